"""The thresholds where the likelihood has two valleys (fitting/valley_law.py): the law of the
local Gaussian model against the laws known exactly (one valley: chi^2_1; one valley on
lambda's bound: bounds.py's q(rho)), and on exact-solution data of the friction regime
(bench/bound_coverage.py's design, lambda = 0.05), draws whose intervals missed the truth
with the single-valley thresholds."""

from __future__ import annotations

import numpy as np
import pytest
from bench.bound_coverage import OUTER, R0, SIGMA, T, data
from scipy import integrate, optimize, stats

from wound_opening.fitting.bounds import (
    GRADIENTS,
    exceedance,
    nuisance_quantile,
    psi_correlations,
)
from wound_opening.fitting.problem import Problem
from wound_opening.fitting.single import fit
from wound_opening.fitting.valley_law import DRAWS as DRAWS_FIT
from wound_opening.fitting.valley_law import ratios, valley_thresholds, whitened

#: Draws of the law in the tests, and the binomial bound on its 95 % point's error: the
#: empirical 95 % point of n draws lies between the law's (95 -+ 4 sd) % points, sd =
#: sqrt(0.05 * 0.95 / n) (a bound that fails once in ~30,000 seeds).
DRAWS = 40_000
SPREAD = 4 * np.sqrt(0.05 * 0.95 / DRAWS)


class Quadratic(Problem):
    """residuals = A (z0, z1, z2^2, z3) - y: linear in psi = lambda^2 >= 0 like the model."""

    def __init__(self, A, y):
        self.A, self.y = A, y

    @property
    def size(self) -> int:
        return self.y.size

    def residuals(self, z):
        return self.A @ np.array([z[0], z[1], z[2] ** 2, z[3]]) - self.y

    def jacobian(self, z, columns=None):
        return self.A * np.array([1.0, 1.0, 2 * z[2], 1.0])

    def bounds(self):
        return np.array([-np.inf, -np.inf, 0.0, -np.inf]), np.full(4, np.inf)


def _between(q, law_ppf):
    """q lies between the law's 95 -+ SPREAD points."""
    assert law_ppf(0.95 - SPREAD) <= q <= law_ppf(0.95 + SPREAD)


def _problem(rho):
    """A 60-point problem whose estimate of z0 has correlation rho with psi's, at z = 0."""
    rng = np.random.default_rng(3)
    A = rng.standard_normal((60, 4))
    # make column 2 (psi) correlated with column 0 so that corr(z0_hat, psi_hat) is rho
    A[:, 2] = A[:, 0] * rho + A[:, 2] * 0.3
    return Quadratic(A, np.zeros(60))


def _alone(problem, z):
    """Draws of the ratio with the valley at z alone (valley_law.ratios)."""
    free = [0, 1, 2, 3]
    local = [(z, *whitened(problem, z, free))]
    return ratios(local, 0, free, GRADIENTS, DRAWS, np.random.default_rng(5))[1]


def test_one_valley_inside_the_bounds_gives_chi2_1():
    problem = _problem(0.5)
    draws = _alone(problem, np.array([0.0, 0.0, 1.0, 0.0]))  # lambda = 1: the bound far away
    for name in GRADIENTS:
        _between(np.quantile(draws[name], 0.95), lambda p: stats.chi2.ppf(p, 1))


@pytest.mark.parametrize("rho", [0.5, 0.95])
def test_one_valley_on_lambdas_bound_gives_the_nuisance_quantile(rho):
    """psi = 0 true, the other parameters' ratio the mixture of bounds.py's four cones, whose
    95 % point q(rho) is an exact integral."""
    problem = _problem(rho)
    z = np.zeros(4)
    draws = _alone(problem, z)
    corr = psi_correlations(problem, z, GRADIENTS)
    for name in GRADIENTS:
        r = corr[name]

        def ppf(p, r=r):
            return optimize.brentq(lambda c: exceedance(c, r) - (1 - p), 0.5, 50.0)

        assert ppf(0.95) == pytest.approx(nuisance_quantile(r), abs=1e-4)
        _between(np.quantile(draws[name], 0.95), ppf)


class TwoValleys(Quadratic):
    """The 60-point problem (its columns times 3: standard errors of ~0.05) with a second
    valley where z0 > 0.25: the same model moved to the optimum `other`, plus a vector w
    outside the model's columns, |w|^2 = `gap` (the second valley's chi^2 above the
    first's, whose optimum is (0, 0, 1, 0) with residuals 0)."""

    def __init__(self, other, gap):
        A = 3 * _problem(0.5).A
        super().__init__(A, A @ _f(INNER))
        w = np.random.default_rng(7).standard_normal(A.shape[0])
        w -= A @ np.linalg.lstsq(A, w, rcond=None)[0]
        self.shift = A @ (_f(INNER) - _f(other)) + w * np.sqrt(gap / (w @ w))

    def residuals(self, z):
        return super().residuals(z) + (self.shift if z[0] > 0.25 else 0.0)


INNER = np.array([0.0, 0.0, 1.0, 0.0])


def _f(z):
    return np.array([z[0], z[1], z[2] ** 2, z[3]])


def _two_valley_ppf(p, gap):
    """The p point of X^2 + max(0, 2 sqrt(gap) Z - gap), X, Z independent N(0, 1)."""

    def sf(c):
        def inner(z):
            m = max(0.0, 2 * np.sqrt(gap) * z - gap)
            return stats.chi2.sf(max(c - m, 0.0), 1) * stats.norm.pdf(z)

        return integrate.quad(inner, -10, 10, points=[np.sqrt(gap) / 2], limit=200)[0]

    return optimize.brentq(lambda c: sf(c) - (1 - p), 0.1, 50.0)


@pytest.mark.parametrize("gap", [900.0, 0.4])
def test_a_second_valley_gives_the_law_of_its_gap(gap):
    """The second valley is the first moved by 0.5 in R0, sigma and T (10 standard errors:
    held at the truth it never holds the constrained minimum) with the same Jacobian, so
    with the truth in either valley the ratio at the truth is X^2 + max(0, f1 - f2) with
    f1 - f2 = 2 sqrt(gap) Z - gap, the other valley's advantage: an exact law. 900 above it
    never holds the minimum, and the threshold is chi^2_1's to the last digits (the control
    variate); 0.4 above it does in 38 % of the draws, and the threshold is that law's
    95 % point, 4.33: 0.49 above chi^2_1's."""
    other = np.array([0.5, -0.5, 1.0, 0.5])
    problem = TwoValleys(other, gap)
    d = float(np.sum(problem.residuals(other) ** 2) - np.sum(problem.residuals(INNER) ** 2))
    assert d == pytest.approx(gap)
    law = valley_thresholds(problem, [(INNER, 0.0), (other, d)], GRADIENTS, nuisance_quantile)
    for name in ("R0_um", "sigma", "T_s"):
        if gap > 100:
            assert law[name] == pytest.approx(stats.chi2.ppf(0.95, 1), abs=1e-9)
        else:
            spread = 4 * np.sqrt(0.05 * 0.95 / DRAWS_FIT)
            lo, hi = (_two_valley_ppf(0.95 + k * spread, gap) for k in (-1, 1))
            assert lo <= law[name] <= hi, (name, lo, law[name], hi)


# Draws of bench/bound_coverage.py (lambda = 0.05) whose 95 % interval missed the truth with
# the single-valley thresholds (sigma [0.4248, 0.4994], T [10.01, 12.34] s): the fit's
# minimum lies in the valley at lambda ~ 0.4, the truth in the one at lambda = 0.
@pytest.mark.parametrize(("seed", "name"), [(7005, "sigma"), (7018, "T_s")])
def test_intervals_hold_the_truth_of_a_draw_whose_minimum_is_in_the_other_valley(seed, name):
    result = fit(data(0.05, seed), outer_radius_um=OUTER, derived=False)
    truth = {"R0_um": R0, "sigma": SIGMA, "T_s": T}
    report = result.reports[name]
    lo, hi = report.ci95
    assert lo <= truth[name] <= hi, (name, lo, hi)
    assert report.profile.threshold > stats.chi2.ppf(0.95, 1) + 0.5  # the valleys' law's
