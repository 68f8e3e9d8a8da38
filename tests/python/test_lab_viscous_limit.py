"""A radius-only lab fit whose best point sits at the viscous limit lambda = LAMBDA_MAX.

Draw 8 of the coverage study (bench/lab_coverage.py: R0 10.2 um, lambda 2.43, 1 s frames,
the cut 26 ms after frame 5, 256 px at 0.2 um), its outline measured as ImageJ measures it,
fitted without the field by the documented command. Its least-squares optimum has lambda on
its search limit 50, where R(t) depends on lambda^2 T alone: lambda's column of the Jacobian
is T's times 2 T / lambda. Before lambda's limit was counted as a vanishing column
(Objective.vanishing) the fit exited 1, "the Jacobian at the best point is singular", and
published nothing; now it gives numbers. The claim is the fit's own: every interval it
publishes (identified or open) holds the truth, and R0's has an upper end. Its radius noise
is the outline's floor, half of the 0.2 um pixel (inputs/fiji.py: the residuals' 0.039 um
is below it), said in the JSON; at the residuals' noise R0 was identified, [7.45, 10.8] um,
and with the floor its interval is open below. Its cut time sits on
its bound (the end of the frame interval), where its column is nearly R0's and sigma's
(a slow opening is one exponential: a shift in time is a change of amplitude); with it in
the covariance the standard errors of R0 and sigma were printed as 2.6e5 um and 5e4, far
beyond their profile intervals. Held on its bound (stages.reported_cov), the cut's error is
none and each other finite one lies within twice its estimate's distance to its interval's
farther finite end. About 13 s
(render, measure, fit; --durations, 2026-12-07).
"""

from __future__ import annotations

import json
import math
import shlex

import pytest
from bench.lab_coverage import KEYS, movie
from bench.lab_movies import measure, radius_only, run_fit
from bench.lab_render import render

DRAW = 8


def test_radius_fit_at_the_viscous_limit_gives_honest_numbers(tmp_path):
    m = movie(DRAW, 256)
    frames, truth = render(m)
    record = measure(tmp_path, m, frames, truth)
    res = run_fit(tmp_path, record, radius_only(shlex.split(record["fit_command"])), "fit_radius")
    print((tmp_path / "fit_radius.txt").read_text())
    assert res["exit"] == 0, res.get("reasons")
    rows = res["estimates"]
    for key in (*KEYS, "sigma"):
        assert rows[key]["covers"], (key, rows[key])
    assert rows["R0_um"]["ci95"][1] is not None, rows["R0_um"]

    out = json.loads((tmp_path / "fit_radius.json").read_text())
    assert out["noise"]["radius_at_floor_um"] == pytest.approx(0.1, rel=1e-12), out["noise"]
    assert out["noise"]["radius_um"] == pytest.approx(0.1, rel=1e-12), out["noise"]
    fit = out["parameters"]
    cut = fit["cut_s"]
    ends = (0.0, record["frame_interval_s"])
    assert min(abs(cut["estimate"] - e) for e in ends) < 1e-6, cut  # on a bound
    assert cut["stderr"] is None, cut
    for name in ("R0_um", "sigma"):
        est, se = fit[name]["estimate"], fit[name]["stderr"]
        reach = max(abs(end - est) for end in fit[name]["ci95"] if end is not None)
        assert se is not None and math.isfinite(se) and 0 < se < 2 * reach, (name, fit[name])
