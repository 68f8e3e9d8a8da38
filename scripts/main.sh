#!/usr/bin/env bash
# The main job: build the FMU, simulate the paper's cases (lambda = 0.1, 1, 10) with fmpy,
# write CSV and PNG plots to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/venv.sh
cargo run --release --quiet -- fmu
python python/run_paper_cases.py --fmu target/fmu/WoundOpening.fmu --out out
