"""The thresholds where the likelihood has two valleys (fitting/valley_law.py): the law of the
local Gaussian model against the laws known exactly (one valley: chi^2_1; one valley on
lambda's bound: bounds.py's q(rho)), and on exact-solution data of the friction regime
(bench/bound_coverage.py's design, lambda = 0.05), draws whose intervals missed the truth
with the single-valley thresholds."""

from __future__ import annotations

import numpy as np
import pytest
from bench.bound_coverage import OUTER, R0, SIGMA, T, data
from scipy import optimize, stats

from wound_opening.fitting.bounds import (
    GRADIENTS,
    exceedance,
    nuisance_quantile,
    psi_correlations,
)
from wound_opening.fitting.problem import Problem
from wound_opening.fitting.single import fit
from wound_opening.fitting.valley_law import valley_thresholds

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


def test_one_valley_inside_the_bounds_gives_chi2_1():
    problem = _problem(0.5)
    z = np.array([0.0, 0.0, 1.0, 0.0])  # lambda = 1: psi's bound far away
    law = valley_thresholds(problem, [(z, 0.0)], GRADIENTS, draws=DRAWS)
    for name in GRADIENTS:
        _between(law[name], lambda p: stats.chi2.ppf(p, 1))


@pytest.mark.parametrize("rho", [0.5, 0.95])
def test_one_valley_on_lambdas_bound_gives_the_nuisance_quantile(rho):
    """psi = 0 true, the other parameters' ratio the mixture of bounds.py's four cones, whose
    95 % point q(rho) is an exact integral."""
    problem = _problem(rho)
    z = np.zeros(4)
    law = valley_thresholds(problem, [(z, 0.0)], GRADIENTS, draws=DRAWS)
    corr = psi_correlations(problem, z, GRADIENTS)
    for name in GRADIENTS:
        r = corr[name]

        def ppf(p, r=r):
            return optimize.brentq(lambda c: exceedance(c, r) - (1 - p), 0.5, 50.0)

        assert ppf(0.95) == pytest.approx(nuisance_quantile(r), abs=1e-4)
        _between(law[name], ppf)


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
