"""The package's coupled worked example (`python -m wound_opening.coupling`,
wound_opening/coupling/example.py; the wheel ships it): it writes the closure run the loop
gives, and its convergence table shows the orders of docs/fmi.md (1 with the edge stress
held, 2 with input derivatives). The free opening it writes is the exact solution."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pandas as pd
import wound_exact as we

from wound_opening.coupling.example import STEP, STOP
from wound_opening.coupling.loop import WOUND_EXAMPLE, couple


def test_the_example_writes_the_loops_run_and_its_orders(tmp_path, fmu_path, purse_path):
    done = subprocess.run(
        [sys.executable, "-m", "wound_opening.coupling", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    closure = pd.read_csv(tmp_path / "coupled_closure.csv")
    run = couple(fmu_path, purse_path, step=STEP, stop=STOP, interpolate=True)
    assert np.array_equal(closure["wound_radius_um"].to_numpy(), run.wound_radius)
    w = WOUND_EXAMPLE
    t = closure["time_s"].to_numpy()[1:]
    exact = w["R0"] * we.edge(w["lambda"], w["sigma"], w["R_inf"], t / w["T"])[0]
    opening = w["R0"] * (we.final_radius(w["sigma"], w["R_inf"]) - we.initial_radius(w["sigma"]))
    assert np.abs(closure["free_wound_radius_um"].to_numpy()[1:] - exact).max() <= 1e-10 * opening
    orders = pd.read_csv(tmp_path / "coupled_convergence.csv").iloc[1:]
    assert orders["held_observed_order"].between(0.9, 1.15).all(), orders
    assert orders["interpolated_observed_order"].between(1.8, 2.1).all(), orders
    assert (tmp_path / "coupled_closure.png").stat().st_size > 10_000
