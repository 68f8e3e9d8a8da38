#!/usr/bin/env bash
# Every test: Rust unit and integration tests, then the FMU built and driven by fmpy.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/venv.sh
cargo test --release
cargo build --release  # the library the Python package loads
cargo run --release --quiet -- fmu
bash scripts/c_tests.sh
python -m pytest -q tests/python
