#!/usr/bin/env bash
# The archives' Windows and aarch64 Linux binaries, run by real programs: the C masters of
# tests/c (fmu_master: FMI 2.0, fmu3_master: FMI 3.0, direct_api: the wo_* API linked
# against the archived library) cross-compiled with MinGW-w64 and GCC for aarch64, run
# under Wine and qemu-user against the binaries extracted from target/fmu/WoundOpening.fmu
# and WoundOpening-fmi3.fmu. Each program checks the paper's lambda = 1 case against the
# exact solution (tests/c/reference.h) and its bad-input cases; then every radius and
# velocity printed on Windows and aarch64 is compared with the same program's on Linux
# (tests/c/compare_runs.py). Installs what it needs with scripts/cross.sh.
#
# Wine 8 has no bcryptprimitives.dll, whose ProcessPrng Rust's standard library imports:
# tests/c/wine/bcryptprimitives.c stands in for it, beside the test programs only.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/cross.sh --tests
out=target/cross_tests
CFLAGS=(-std=c11 -O1 -Wall -Wextra -Werror -Wincompatible-pointer-types -Iinclude -Itests/c)
cargo run --release --quiet -- fmu >/dev/null
rm -rf "$out"
mkdir -p "$out"/{linux,win,arm}
python3 -m zipfile -e target/fmu/WoundOpening.fmu "$out/fmu"
python3 -m zipfile -e target/fmu/WoundOpening-fmi3.fmu "$out/fmu3"

# The programs, for each platform: fmu_master, fmu3_master (dynamic loading), direct_api
# (linked against the archive's library itself).
build() { # build <dir> <compiler> <library of direct_api> <exe suffix> <extra flags...>
    local dir=$1 cc=$2 library=$3 exe=$4
    shift 4
    "$cc" "${CFLAGS[@]}" tests/c/fmu_master.c -o "$out/$dir/fmu_master$exe" "$@"
    "$cc" "${CFLAGS[@]}" tests/c/fmu3_master.c -o "$out/$dir/fmu3_master$exe" "$@"
    "$cc" "${CFLAGS[@]}" tests/c/direct_api.c "$PWD/$library" -o "$out/$dir/direct_api$exe" "$@"
}
build linux cc "$out/fmu/binaries/linux64/WoundOpening.so" "" -ldl -lm
build arm aarch64-linux-gnu-gcc "$out/fmu/binaries/aarch64-linux/WoundOpening.so" "" -ldl -lm
build win x86_64-w64-mingw32-gcc "$out/fmu/binaries/win64/WoundOpening.dll" .exe
x86_64-w64-mingw32-gcc -std=c11 -O2 -Wall -Wextra -Werror -shared tests/c/wine/bcryptprimitives.c -ladvapi32 \
    -o "$out/win/bcryptprimitives.dll"
# direct_api.exe imports the DLL by the name inside it (wound_opening.dll): the archived
# file, under that name, beside the program.
dll_name=$(x86_64-w64-mingw32-objdump -p "$out/win/direct_api.exe" | sed -n 's/^\s*DLL Name: \(wound_opening.dll\)$/\1/ip')
cp "$out/fmu/binaries/win64/WoundOpening.dll" "$out/win/$dll_name"

export WINEPREFIX="$PWD/target/wine" WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="
wine=(wine)
[ -x /usr/lib/wine/wine64 ] && wine=(/usr/lib/wine/wine64)  # the 64-bit loader itself: no wine32 warning
failed=0
run() { # run <platform> <program> <argument>: its output into $out/<platform>/<program>.txt
    local platform=$1 program=$2 argument=${3:-}
    local cmd=("./$platform/$program")
    case $platform in
        win) cmd=("${wine[@]}" "$platform/$program.exe") ;;
        arm) cmd=(qemu-aarch64 -L /usr/aarch64-linux-gnu "$platform/$program") ;;
    esac
    echo "== $platform: $program"
    if ! (cd "$out" && "${cmd[@]}" $argument >"$platform/$program.txt"); then
        echo "FAILED: $platform $program"
        failed=1
    fi
    tail -n 1 "$out/$platform/$program.txt"
}
for platform in linux arm win; do
    run "$platform" fmu_master fmu
    run "$platform" fmu3_master fmu3
    run "$platform" direct_api
done
for platform in arm win; do
    for program in fmu_master fmu3_master direct_api; do
        python3 tests/c/compare_runs.py "$out/linux/$program.txt" "$out/$platform/$program.txt" || failed=1
    done
done
exit "$failed"
