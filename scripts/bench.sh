#!/usr/bin/env bash
# The benchmarks, one command: build the FMU, write the exact references, run the
# Rust benchmark examples, the two Python peers and the fmpy timing (CSVs in target/bench/),
# then every chart and docs/benchmarks.md (docs/). About 10 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/venv.sh
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"
# CPU time is compared with single-threaded Rust: keep BLAS (SciPy's dense LU) on one thread.
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
data=target/bench
mkdir -p "$data"

step() { echo "== $1 ($(date +%T))"; }

step "FMU"
cargo run --release --quiet -- fmu
step "exact references"
python -m bench.reference --out "$data"
for example in work_precision stability_map step_cost fresh_cost profiles; do
    step "cargo run --release --example $example"
    cargo run --release --quiet --example "$example" -- "$data"
done
step "SciPy peer (method of lines + solve_ivp)"
python -m bench.scipy_peer --out "$data"
step "paper's scheme, NumPy/SciPy peer"
python -m bench.paper_peer --out "$data"
step "FMU through fmpy"
python -m bench.fmpy_timing --fmu target/fmu/WoundOpening.fmu --out "$data"
python -m bench.fmpy_whole target/fmu/WoundOpening.fmu --both target/fmu/WoundOpening-me.fmu --out "$data"
step "charts and docs/benchmarks.md"
python -m bench.charts --data "$data" --out docs
step "done"
