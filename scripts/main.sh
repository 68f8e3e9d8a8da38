#!/usr/bin/env bash
# The main job: build both FMUs, simulate the paper's cases (lambda = 0.1, 1, 10) with
# fmpy, then the coupled worked example (wound opening, purse-string closure, in um and s)
# by an fmpy loop and as a container FMU (target/fmu/WoundClosure.fmu); CSV and PNG plots
# go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/venv.sh
cargo run --release --quiet -- fmu
python python/run_paper_cases.py --fmu target/fmu/WoundOpening.fmu --out out
python python/coupled_example.py --fmu-dir target/fmu --out out
python python/coupling/container.py
