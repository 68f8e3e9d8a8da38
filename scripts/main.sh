#!/usr/bin/env bash
# The main job: build both FMUs, simulate the paper's cases (lambda = 0.1, 1, 10) with
# fmpy, then the coupled worked example (wound opening, purse-string closure, in um and s)
# by an fmpy loop and as a container FMU (target/fmu/WoundClosure.fmu); CSV and PNG plots
# go to out/. Then the wound_opening package: a synthetic experiment (exact solution plus
# noise) fitted by `wound-opening fit`, and a lambda x sigma sweep by `wound-opening sweep`.
set -euo pipefail
cd "$(dirname "$0")/.."
step() { echo "== $1"; }
mkdir -p target
# The venv waits on the network, the builds on the CPU: the venv is made (scripts/venv.sh,
# its log target/setup_venv.log) while the linkers are installed and the archives built.
step "Python environment (.venv, created on first use), in the background"
bash scripts/venv.sh >target/setup_venv.log 2>&1 &
venv=$!
trap 'kill "$venv" 2>/dev/null || true' EXIT  # a failed build ends the set-up too
bash scripts/cross.sh  # the linkers of the archives' five platforms (no emulator: tests only)
step "building the library and the five FMU archives (cargo, release; a few minutes the first time)"
cargo run --release --quiet -- fmu
cargo build --release --quiet
status=0
wait "$venv" || status=$?
cat target/setup_venv.log
((status == 0)) || { echo "error: the venv (target/setup_venv.log) failed: $status" >&2; exit "$status"; }
source scripts/venv.sh  # made: this only activates it
step "the paper's cases through fmpy"
python python/run_paper_cases.py --fmu target/fmu/WoundOpening.fmu --out out
step "the coupled worked example: opening, then purse-string closure"
python -m wound_opening.coupling --fmu-dir target/fmu --out out
step "the same coupling as a container FMU"
python python/coupling/container.py
step "a synthetic experiment, fitted with wound-opening fit"
python python/fitting_figures.py --data-only --out out
wound-opening fit out/experiment_radius.csv --profile out/experiment_profile.csv --outer-radius-um 100 \
    --json out/fit.json --plot out/fit.png --export out/fit --report out/fit.html
step "a lambda x sigma sweep with wound-opening sweep"
wound-opening sweep --lambda 0,0.1,0.3,1,3,10 --sigma 0.25,0.5,1,2 --R-inf 10 --times 0,1,10,100 \
    --csv out/sweep.csv --parquet out/sweep.parquet --plot out/sweep.png
step "wrote:"
ls -1 out/* target/fmu/*.fmu | sed 's/^/  /'
