"""The verdict's runs test of the residuals (fitting/gof.py) and the interval threshold where
lambda sits on its bound (fitting/bounds.py), on exact-solution data (bench/fit_designs.py)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest
from bench.fit_designs import clean, draw
from scipy import stats
from test_cli import run

from wound_opening.fitting.parameters import Parameters
from wound_opening.fitting.single import fit
from wound_opening.inputs.series import RadiusSeries, VelocityProfile


def _noise_estimated(radius, profile):
    return (
        RadiusSeries(radius.times_s, radius.radius_um),
        VelocityProfile(profile.times_s, profile.r_um, profile.velocity_um_s),
    )


def test_a_wrong_fixed_R0_fails_by_its_systematic_residuals_with_the_noise_estimated():
    """Radius + PIV (lambda 0.5, noise 1 % of the opening, not given), R0 fixed at
    10.5 um where the truth is 10: sigma and T came out "identified" and wrong, exit 0. The
    radius residuals run in a few long blocks of one sign."""
    params = Parameters()
    params.add("R0_um", value=10.5, vary=False)
    radius, profile = _noise_estimated(*draw("piv", 0.5, 0.01, 0, clean("piv", 0.5)))
    result = fit(radius, profile, outer_radius_um=100.0, params=params, intervals=False)
    assert not result.converged
    (reason,) = [r for r in result.reasons if "runs of residual signs" in r]
    assert reason.startswith("radius: ") and "a wrong fixed value" in reason
    assert "FIT FAILED" in result.summary() and "radius:" in result.summary()
    runs = {r["series"]: r for r in result.residual_runs}
    assert runs["radius"]["level"] == "fail" and runs["radius"]["p_value"] < 1e-5


def test_the_command_line_exits_1_and_says_why(tmp_path):
    """The same case through `wound-opening fit --fix R0_um=10.5`: exit 1 (a failed fit),
    the summary and the JSON naming the series and its runs test."""
    radius, profile = draw("piv", 0.5, 0.01, 0, clean("piv", 0.5))
    pd.DataFrame({"time_s": radius.times_s, "radius_um": radius.radius_um}).to_csv(
        tmp_path / "r.csv", index=False
    )
    pd.DataFrame(
        {"time_s": profile.times_s, "r_um": profile.r_um, "velocity_um_s": profile.velocity_um_s}
    ).to_csv(tmp_path / "p.csv", index=False)
    radius_csv, profile_csv, out_json = (tmp_path / f for f in ("r.csv", "p.csv", "fit.json"))
    args = ["--outer-radius-um", 100, "--fix", "R0_um=10.5", "--json", out_json]
    done = run("fit", radius_csv, "--profile", profile_csv, *args)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "FIT FAILED" in done.stdout and "radius: " in done.stdout
    assert "runs of residual signs" in done.stdout
    out = json.loads(out_json.read_text())
    assert out["converged"] is False
    assert [r["level"] for r in out["residual_runs"] if r["series"] == "radius"] == ["fail"]


@pytest.mark.parametrize("seed", [0, 1])
def test_a_correct_fit_passes_the_runs_test(seed):
    radius, profile = _noise_estimated(*draw("piv", 0.5, 0.01, seed, clean("piv", 0.5)))
    result = fit(radius, profile, outer_radius_um=100.0, intervals=False)
    assert result.converged, result.reasons
    assert [r["series"] for r in result.residual_runs] == ["radius", "PIV profile"]
    assert all(r["level"] == "ok" for r in result.residual_runs)


def test_the_runs_law_is_exact_and_the_durbin_watson_tail_matches_a_monte_carlo():
    from wound_opening.fitting.gof import durbin_watson_p, runs_law, runs_test

    rng = np.random.default_rng(0)
    n1, n2 = 7, 9
    signs = np.r_[np.ones(n1), -np.ones(n2)]
    sims = [1 + np.sum(np.diff(rng.permutation(signs)) != 0) for _ in range(20000)]
    freq = np.bincount(sims, minlength=n1 + n2 + 1) / 20000
    assert np.max(np.abs(freq - runs_law(n1, n2))) < 0.01
    # six points in two runs (the fewest possible for three of each sign): p = 0.1, so a
    # short series alone cannot make the runs test alarm
    assert runs_test("x", [np.array([1, 2, 3, -1, -2, -3.0])]).p_runs == pytest.approx(0.1)
    e = rng.standard_normal((200_000, 40))  # Durbin-Watson of independent noise, 40 points
    d = np.sum(np.diff(e, axis=1) ** 2, axis=1) / np.sum(e**2, axis=1)
    for d0 in (1.0, 1.3):
        assert durbin_watson_p(d0, [40]) == pytest.approx(np.mean(d <= d0), rel=0.1)


def test_lambda_on_its_bound_gets_the_mixture_threshold():
    """Radius data with lambda = 0 whose fit puts lambda on its bound 0: the likelihood ratio
    at the truth is 1/2 chi^2_0 + 1/2 chi^2_1, so lambda's interval [0, hi] ends where delta
    chi^2 = 2.71 (chi^2_1's 90 % point), not 3.84."""
    radius, _ = draw("radius", 0.0, 0.01, 9, clean("radius", 0.0))
    result = fit(radius, outer_radius_um=100.0, derived=False)
    assert result.theta[2] < 1e-8  # on the bound (the fit and the verdict use this tolerance)
    lo, hi = result.reports["lambda"].ci95
    assert lo == 0.0 and hi is not None
    mixture = stats.chi2.ppf(0.90, 1)
    assert result.profile_at("lambda", [hi])[0] == pytest.approx(mixture, rel=0.02)
    assert result.reports["lambda"].profile.threshold == pytest.approx(mixture)


def test_several_wounds_name_the_wound_whose_residuals_are_systematic():
    """Three wounds of one tissue (bench/tissue_designs.py), the noise estimated, wound 2's
    R0 fixed 5 % above its truth: the fit fails, each reason naming a wound's radius series
    (the shared material bends to wound 2 and leaves the misfit in another wound too)."""
    from bench.tissue_designs import draw as tissue_draw

    from wound_opening.fitting.wounds import Wound, fit_wounds

    wounds = [
        Wound(RadiusSeries(w.radius.times_s, w.radius.radius_um), w.outer_radius_um, name=w.name)
        for w in tissue_draw(1e-2, 100)
    ]
    params = Parameters()
    params.add("R0_um[2]", value=10.5, vary=False)
    result = fit_wounds(wounds, params=params, intervals=False)
    assert not result.converged
    named = [r for r in result.reasons if "runs of residual signs" in r]
    names = tuple(f"wound {w.name}: radius: " for w in wounds)
    assert named and all(r.startswith(names) for r in named), named


def test_the_nuisance_quantile_matches_a_monte_carlo_of_its_model():
    """q(rho) (bounds.py): chi^2_1's 3.84 at rho = 0; at rho = 0.95 the 95 % point of the
    likelihood ratio of the local Gaussian model with psi >= 0 true at 0, simulated."""
    from wound_opening.fitting.bounds import nuisance_quantile

    assert nuisance_quantile(0.0) == pytest.approx(stats.chi2.ppf(0.95, 1), rel=1e-4)
    rho, n = 0.95, 400_000
    x, y = np.random.default_rng(1).standard_normal((2, n))
    psi = rho * x + np.sqrt(1 - rho**2) * y  # (theta_hat, psi_hat), unit variances
    star = np.maximum(psi - rho * x, 0.0)  # psi fitted at theta = its truth 0, psi >= 0
    null = (x**2 - 2 * rho * x * (psi - star) + (psi - star) ** 2) / (1 - rho**2)
    lr = null - np.where(psi >= 0, 0.0, psi**2)
    assert nuisance_quantile(rho) == pytest.approx(np.quantile(lr, 0.95), rel=0.01)
