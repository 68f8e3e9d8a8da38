#!/usr/bin/env bash
# The C programs of the test suite (tests/c), built with the system C compiler with
# -Wall -Wextra -Werror and run under valgrind: any memory error or any leak (of any
# kind, reachable included) fails. Builds what it needs: the release library and
# target/fmu/WoundOpening.fmu and WoundOpening-fmi3.fmu.
#
#   fmi2_signatures  every exported FMI function has the standard's type (compile time)
#   direct_api       the wo_* API, linked: lambda = 1 against the exact solution, bad input
#   fmu_master       a minimal FMI 2.0 master, dlopen of the FMU's .so: same, through FMI
#   fmu_misuse       a master that misbehaves: freed, NULL and forged instances, double
#                    free, another instance's FMU states
#   fmu3_master      an FMI 3.0 master, dlopen of WoundOpening-fmi3.fmu's .so: all 75
#                    functions exported, co-simulation and Model Exchange against the exact
#                    solution, every function it uses on NULL, made-up and freed instances
#   strict_master    a master that stops on any status but fmi2OK (as fmusim, OMSimulator,
#                    PyFMI): sigma = 2 stops at the validity warning, runs to the exact end
#                    with validity_warning = 0; tolerance 0 is none given
#   two_libraries    WoundOpening and PurseString (FMI 2.0 and 3.0), two copies of the
#                    library in one process: each copy's instances, FMU states and wo_*
#                    solvers and states are unknown to the other
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v valgrind >/dev/null; then
    echo "== installing valgrind"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq valgrind </dev/null
fi
CC="${CC:-cc}"
CFLAGS=(-std=c11 -O1 -g -Wall -Wextra -Werror -Wincompatible-pointer-types)
out=target/c_tests
mkdir -p "$out"

cargo build --release --quiet
cargo run --release --quiet -- fmu >/dev/null
rm -rf "$out/fmu"
mkdir -p "$out/fmu"
if command -v unzip >/dev/null; then
    unzip -q -o target/fmu/WoundOpening.fmu -d "$out/fmu"
else
    python3 -m zipfile -e target/fmu/WoundOpening.fmu "$out/fmu"
fi

rm -rf "$out/fmu3"
mkdir -p "$out/fmu3"
if command -v unzip >/dev/null; then
    unzip -q -o target/fmu/WoundOpening-fmi3.fmu -d "$out/fmu3"
else
    python3 -m zipfile -e target/fmu/WoundOpening-fmi3.fmu "$out/fmu3"
fi

# Extract target/fmu/$1.fmu into $out/$1 (for the programs that load several FMUs).
extract() {
    rm -rf "${out:?}/$1"
    mkdir -p "$out/$1"
    python3 -m zipfile -e "target/fmu/$1.fmu" "$out/$1"
}
for name in WoundOpening PurseString WoundOpening-fmi3 PurseString-fmi3; do extract "$name"; done

lib="$PWD/target/release"
"$CC" "${CFLAGS[@]}" -Iinclude -Itests/c tests/c/fmi2_signatures.c -L"$lib" -lwound_opening -Wl,-rpath,"$lib" -o "$out/fmi2_signatures"
"$CC" "${CFLAGS[@]}" -Iinclude -Itests/c tests/c/direct_api.c -L"$lib" -lwound_opening -lm -Wl,-rpath,"$lib" -o "$out/direct_api"
"$CC" "${CFLAGS[@]}" -Itests/c tests/c/fmu_master.c -ldl -lm -o "$out/fmu_master"
"$CC" "${CFLAGS[@]}" -Itests/c tests/c/fmu_misuse.c -ldl -lm -o "$out/fmu_misuse"
"$CC" "${CFLAGS[@]}" -Itests/c tests/c/strict_master.c -ldl -lm -o "$out/strict_master"
"$CC" "${CFLAGS[@]}" -Itests/c tests/c/fmu3_master.c -ldl -lm -o "$out/fmu3_master"
"$CC" "${CFLAGS[@]}" -Itests/c tests/c/two_libraries.c -ldl -lm -o "$out/two_libraries"

memcheck=(valgrind -q --error-exitcode=1 --leak-check=full --show-leak-kinds=all --errors-for-leak-kinds=all
          --suppressions=tests/c/valgrind.supp)
failed=0
run() {
    echo "== valgrind $*"
    if ! "${memcheck[@]}" "$@"; then
        echo "FAILED: $*"
        failed=1
    fi
}
run "$out/fmi2_signatures"
run "$out/direct_api"
run "$out/fmu_master" "$out/fmu"
run "$out/fmu_misuse" "$out/fmu"
run "$out/strict_master" "$out/fmu"
run "$out/fmu3_master" "$out/fmu3"
run "$out/two_libraries" "$out/WoundOpening" "$out/PurseString" "$out/WoundOpening-fmi3" "$out/PurseString-fmi3"
exit "$failed"
