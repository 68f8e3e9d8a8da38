#!/usr/bin/env bash
# Every test: Rust unit and integration tests, the C programs under valgrind
# (scripts/c_tests.sh) and, cross-built, under Wine and qemu-user (scripts/cross_tests.sh),
# then the FMUs driven by fmpy, the Python package (its Dask tests start their own scheduler
# and workers on 127.0.0.1) and each FMU's documentation page rendered in headless Chromium.
# Installs what it needs: .venv (scripts/venv.sh), zig (the Linux linker, first: every
# cargo build links with it), the Rust cross targets, and with apt-get the cross linkers,
# Wine, qemu-user, valgrind and chromium when they are missing (scripts/cross.sh --tests),
# and libtbb12 (ecospy's library, for the SSP readers' tests).
#
# The set-up waits on the network and dpkg, the Rust build on the CPU: the venv and the
# Debian packages are installed in the background while the host's crate compiles and its
# tests run; their output follows.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p target
bash scripts/cross.sh --zig  # the Linux linker (.cargo/config.toml): every host build links with it
bash scripts/venv.sh >target/setup_venv.log 2>&1 &
venv=$!
# ecospy (tests/python/test_ssp_readers.py) loads libtbb.so.12: a library, so dpkg, not a command, says it is there.
{ bash scripts/cross.sh --tests valgrind chromium && { dpkg -s libtbb12 >/dev/null 2>&1 ||
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libtbb12 </dev/null; }; }; } \
    >target/setup_debian.log 2>&1 &
debian=$!
trap 'kill "$venv" "$debian" 2>/dev/null || true' EXIT  # a failed step ends the set-up too
cargo fmt --check  # the crate's format (rustfmt.toml)
cargo test --release
# Lints with warnings as errors, on the test build's dependencies (checked, not rebuilt).
cargo clippy --version >/dev/null 2>&1 || rustup component add clippy
cargo clippy --release --all-targets --quiet -- -D warnings
cargo build --release  # the library the Python package loads
for job in "venv $venv" "debian $debian"; do
    read -r name pid <<<"$job"
    status=0
    wait "$pid" || status=$?
    cat "target/setup_$name.log"
    if ((status)); then
        echo "error: the set-up (target/setup_$name.log) failed with status $status" >&2
        exit "$status"
    fi
done
source scripts/venv.sh
cargo run --release --quiet -- fmu  # the archives, with their Windows, aarch64 Linux and macOS binaries
# The Python code's format and lint (ruff, configured in pyproject.toml).
ruff format --check python tests/python setup.py
ruff check python tests/python setup.py
# Two worker processes (pytest-xdist): the Python tests are independent of each other. They
# run beside the C programs under valgrind and the cross binaries under Wine and qemu (one
# process at a time, ~30 s), their output kept in target/pytest.log and shown after, with
# the 20 slowest tests (the command's 8-minute budget: tests/python/conftest.py LONG_FIRST).
python -m pytest -q -n 2 --durations=20 tests/python >target/pytest.log 2>&1 &
pytest=$!
trap 'kill "$venv" "$debian" "$pytest" 2>/dev/null || true' EXIT
bash scripts/c_tests.sh
bash scripts/cross_tests.sh  # the archives' Windows and aarch64 binaries under Wine and qemu
status=0
wait "$pytest" || status=$?
cat target/pytest.log
if ((status)); then
    echo "error: the Python tests (target/pytest.log) failed with status $status" >&2
    exit "$status"
fi
