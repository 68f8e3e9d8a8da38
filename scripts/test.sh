#!/usr/bin/env bash
# Every test: Rust unit and integration tests, the C programs under valgrind
# (scripts/c_tests.sh), then the FMUs driven by fmpy, the Python package (its Dask tests
# start their own scheduler and workers on 127.0.0.1) and each FMU's documentation page
# rendered in headless Chromium. Installs what it needs: .venv (scripts/venv.sh), and with
# apt-get valgrind (in c_tests.sh) and chromium when they are missing.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/venv.sh
bash scripts/cross.sh  # Rust targets, cross linkers, Wine and qemu: the Windows and aarch64 binaries
if ! command -v chromium >/dev/null; then
    echo "== installing chromium (for tests/python/test_fmu_pages.py)"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium </dev/null
fi
cargo fmt --check  # the crate's format (rustfmt.toml)
cargo test --release
cargo build --release  # the library the Python package loads
cargo run --release --quiet -- fmu
bash scripts/c_tests.sh
bash scripts/cross_tests.sh  # the archives' Windows and aarch64 binaries under Wine and qemu-user
# The Python code's format and lint (ruff, configured in pyproject.toml).
ruff format --check python tests/python setup.py
ruff check python tests/python setup.py
# Two worker processes (pytest-xdist): the Python tests are independent of each other.
python -m pytest -q -n 2 tests/python
