"""A nuisance coordinate joins a one-wound fit by its declaration alone (fitting/objective.py,
NUISANCES): the outline's radial offset, given or fitted, through the whole pipeline (starts,
local fits, verdict, profile intervals, result), against the EXACT solution
(python/wound_exact.py)."""

from __future__ import annotations

import json

import numpy as np
import pytest
import wound_exact as we

import wound_opening as wo
from wound_opening.fitting.objective import Objective, to_z

R0, SIGMA, LAM, T, OUTER = 8.0, 0.5, 2.5, 1.6, 100.0
OFFSET = 0.15  # um: the outline a threshold puts outside the edge
TRUTH = {"R0_um": R0, "sigma": SIGMA, "lambda": LAM, "T_s": T}


def _series(noise: float, seed: int = 3) -> wo.RadiusSeries:
    t = 0.25 * np.arange(1, 121)
    r = R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0] + OFFSET
    r = r + noise * np.random.default_rng(seed).standard_normal(t.size)
    return wo.RadiusSeries(t, r, noise_um=noise if noise else 1e-4)


def test_the_offset_column_is_the_derivative_of_the_residuals():
    """d residuals / d offset = 1 / sd on the radius rows, and the other columns with the
    offset are those without it: a central difference of the model in the offset agrees."""
    radius = _series(0.0)
    plain = Objective(radius, None, OUTER)
    data = Objective(radius, None, OUTER, ["outline_offset_um"])
    z = np.append(to_z((R0, SIGMA, LAM, T)), 0.2)
    jac = data.jacobian(z)
    assert jac.shape == (radius.radius_um.size, 5)
    np.testing.assert_array_equal(jac[:, :4], plain.jacobian(z[:4]))
    e = np.array([0, 0, 0, 0, 1e-3])
    diff = (data.residuals(z + e) - data.residuals(z - e)) / 2e-3
    np.testing.assert_allclose(jac[:, 4], diff, rtol=1e-9)
    np.testing.assert_allclose(jac[:, 4], 1 / data.sd, rtol=1e-12)


def test_a_given_offset_recovers_the_exact_parameters():
    """Exact radii plus the offset, the offset given: every parameter to 1e-6 of the truth;
    without it the same data put R0 off by about the offset (the bias the nuisance removes)."""
    p = wo.Parameters()
    p.add("outline_offset_um", value=OFFSET, vary=False)
    got = wo.fit(_series(0.0), outer_radius_um=OUTER, params=p, intervals=False)
    assert got.converged, got.reasons
    for i, (name, value) in enumerate(TRUTH.items()):
        assert got.theta[i] == pytest.approx(value, rel=1e-6), name
    assert got.reports["outline_offset_um"].estimate == OFFSET
    ignored = wo.fit(_series(0.0), outer_radius_um=OUTER, intervals=False)
    assert abs(ignored.theta[0] - R0) > 0.5 * OFFSET


def test_a_fitted_offset_with_a_prior_is_reported_with_its_interval():
    """Noise 0.06 um, the offset fitted with a prior of 0.1 +- 0.1 um: the offset and every
    parameter covered by its 95 % profile interval, the offset in the summary and the JSON."""
    p = wo.Parameters()
    p.add("outline_offset_um", prior=(0.1, 0.1))
    got = wo.fit(_series(0.06), outer_radius_um=OUTER, params=p, derived=False)
    assert got.converged, got.reasons
    for name, value in TRUTH.items() | {("outline_offset_um", OFFSET)}:
        lo, hi = got.reports[name].ci95
        assert (lo is None or lo <= value) and (hi is None or value <= hi), (name, lo, hi)
    offset = got.reports["outline_offset_um"]
    assert offset.profile is not None and offset.stderr > 0
    assert offset.ci95[0] < offset.estimate < offset.ci95[1], (offset.estimate, offset.ci95)
    assert "outline_offset_um" in got.summary()
    doc = json.loads(got.to_json())
    assert doc["parameters"]["outline_offset_um"]["prior"] == [0.1, 0.1]
    assert doc["correlation"]["order"][-1] == "outline_offset_um"
    assert np.array(doc["correlation"]["matrix"]).shape == (5, 5)


CUT = 0.3  # s after frame N, of a 0.5 s frame interval: the laser fired between frames


def _since_frame(noise: float, seed: int = 4, piv: bool = False):
    """Frames every 0.5 s counted from frame N (the last before the cut), the cut CUT after
    it: the exact radius at t - CUT after the cut (and, for the Jacobian alone, whose
    derivative does not depend on the data, PIV vectors 0.1 R0 / r um/s)."""
    t = 0.5 * np.arange(1, 61)
    r = R0 * we.edge(LAM, SIGMA, OUTER / R0, (t - CUT) / T)[0]
    r = r + noise * np.random.default_rng(seed).standard_normal(t.size)
    radius = wo.RadiusSeries(t, r, noise_um=noise if noise else 1e-4)
    if not piv:
        return radius, None
    pt, pr, pv = [], [], []
    for tk in t[[0, 2, 6]]:
        x = np.linspace(1.3, 4.0, 8)  # current radii in R0, beyond the edge
        pt += [tk] * x.size
        pr += list(x * R0)
        pv += list(0.1 / x)
    return radius, wo.VelocityProfile(np.array(pt), np.array(pr), np.array(pv), noise_um_s=1e-3)


@pytest.mark.parametrize("piv", [False, True])
def test_the_cut_column_is_the_derivative_of_the_residuals(piv):
    """d residuals / d cut against a central difference in the cut, radius and PIV rows."""
    radius, profile = _since_frame(0.0, piv=piv)
    data = Objective(radius, profile, OUTER, ["cut_s"])
    z = np.append(to_z((R0, SIGMA, LAM, T)), 0.2)
    jac = data.jacobian(z)
    e = np.array([0, 0, 0, 0, 1e-5])
    diff = (data.residuals(z + e) - data.residuals(z - e)) / 2e-5
    scale = np.max(np.abs(diff))
    np.testing.assert_allclose(jac[:, 4], diff, rtol=0, atol=1e-5 * scale)


def test_a_cut_between_two_frames_is_fitted_with_its_interval():
    """Exact radii, times counted from frame N and the cut 0.3 s after it, the cut fitted
    within the frame interval [0, 0.5] s: the cut and the parameters to 1e-5; at noise 0.06
    um each is covered by its 95 % interval, the cut's inside the frame interval."""
    p = wo.Parameters()
    p.add("cut_s", min=0.0, max=0.5)
    exact = wo.fit(_since_frame(0.0)[0], outer_radius_um=OUTER, params=p, intervals=False)
    assert exact.converged, exact.reasons
    assert exact.reports["cut_s"].estimate == pytest.approx(CUT, abs=1e-5)
    for i, (name, value) in enumerate(TRUTH.items()):
        assert exact.theta[i] == pytest.approx(value, rel=1e-5), name
    noisy = wo.fit(_since_frame(0.06)[0], outer_radius_um=OUTER, params=p, derived=False)
    assert noisy.converged, noisy.reasons
    for name, value in TRUTH.items() | {("cut_s", CUT)}:
        lo, hi = noisy.reports[name].ci95
        assert (lo is None or lo <= value) and (hi is None or value <= hi), (name, lo, hi)
    cut = noisy.reports["cut_s"]
    lo, hi = cut.ci95
    assert 0.0 <= (lo or 0.0) <= cut.estimate and (hi is None or cut.estimate <= hi <= 0.5)


def test_the_command_line_names_a_nuisance_by_its_options(tmp_path, capsys):
    """--bound cut_s=0:0.5 joins the cut to the fit of a radius file counted from frame N;
    its estimate lies in the frame interval and its interval holds the truth; an unknown
    name is refused naming the accepted ones, the nuisances among them."""
    from wound_opening.cli import main

    radius, _ = _since_frame(0.06)
    path = tmp_path / "radius.csv"
    rows = "\n".join(f"{t:.17g},{r:.17g}" for t, r in zip(radius.times_s, radius.radius_um))
    path.write_text("time_s,radius_um\n" + rows + "\n")
    out = tmp_path / "fit.json"
    argv = ["fit", str(path), "--outer-radius-um", "100", "--radius-noise-um", "0.06"]
    assert main([*argv, "--bound", "cut_s=0:0.5", "--json", str(out)]) == 0
    cut = json.loads(out.read_text())["parameters"]["cut_s"]
    lo, hi = cut["ci95"]  # None: open (the data allow the cut up to the first frame)
    assert cut["bounds"] == [0.0, 0.5] and 0.0 <= lo <= CUT and (hi is None or CUT <= hi), cut
    assert 0.0 <= cut["estimate"] <= 0.5, cut
    assert main([*argv, "--fix", "cut=0.3"]) == 2
    assert (
        "expected one of R0_um, sigma, lambda, T_s, outline_offset_um, cut_s, piv_gain, G_pa"
        in (capsys.readouterr().err)
    )


def test_the_gain_column_is_the_derivative_of_the_residuals():
    """The PIV field's gain: with the gain g every PIV row of the model and of the other
    columns is g times the one without it, its own column the model's value; central
    differences of the residuals agree, with the pairs' measurement model and the cut."""
    radius, profile = _since_frame(0.0, piv=True)
    profile = wo.VelocityProfile(
        profile.times_s, profile.r_um, profile.velocity_um_s, sd_um_s=np.full(24, 1e-3),
        interval_s=0.5, window_um=2.0,
    )  # fmt: skip
    plain = Objective(radius, profile, OUTER, ["cut_s"])
    data = Objective(radius, profile, OUTER, ["cut_s", "piv_gain"])
    z = np.append(to_z((R0, SIGMA, LAM, T)), [0.2, 1.3])
    n = radius.radius_um.size
    np.testing.assert_allclose(data.model(z)[n:], 1.3 * plain.model(z[:5])[n:], rtol=1e-14)
    jac, ref = data.jacobian(z), plain.jacobian(z[:5])
    np.testing.assert_allclose(jac[:n, :5], ref[:n], rtol=1e-12)
    np.testing.assert_allclose(jac[n:, :5], 1.3 * ref[n:], rtol=1e-12)
    e = np.array([0, 0, 0, 0, 0, 1e-4])
    diff = (data.residuals(z + e) - data.residuals(z - e)) / 2e-4
    np.testing.assert_allclose(jac[:, 5], diff, rtol=1e-8, atol=1e-8 * np.abs(diff).max())
