"""The PIV measurement model (fitting/piv_measure.py) against the exact solution, and the
ring means' correlated errors (inputs/piv_errors.py) against draws of known correlation."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we

from wound_opening import _native
from wound_opening.fitting import piv_measure as pm
from wound_opening.inputs import piv_errors

TOL = 1e-11
CASES = [(2.5, 0.5, 12.5), (0.3, 1.0, 10.0), (0.0, 2.0, 5.0), (1.0, -0.5, 10.0)]
PAIRS = [(0.1, 0.25), (1.0, 1.5), (5.0, 5.3)]


def _edges(lam, sigma, r_inf, ta, tb):
    r, _ = _native.series(lam, sigma, r_inf, [ta, tb], tolerance=TOL)
    return float(r[0]), float(r[1])


@pytest.mark.parametrize("lam,sigma,r_inf", CASES)
def test_displacement_follows_the_material_points_of_the_exact_solution(lam, sigma, r_inf):
    """The material point at reference radius rho is at rho + u(rho, t): from its current
    radius at t_a the model must find u(rho, t_b) - u(rho, t_a), to 1e-7 of the largest; the
    points of several pairs in one call as each pair alone (to rounding: the solver is
    advanced through other times)."""
    rho = np.array([1.6, 2.5, 0.5 * r_inf, 0.9 * r_inf])
    for ta, tb in PAIRS:
        u, _ = we.profile(lam, sigma, r_inf, rho, np.array([ta, tb]))
        exact = u[1] - u[0]
        got = pm.displacement(
            lam, sigma, r_inf, ta, tb, rho + u[0], _edges(lam, sigma, r_inf, ta, tb), tolerance=TOL
        )
        assert np.max(np.abs(got - exact)) <= 1e-7 * np.max(np.abs(exact)), (ta, tb)
    pairs = PAIRS[::-1]
    xs = [rho + we.profile(lam, sigma, r_inf, rho, np.array([ta]))[0][0] for ta, _ in pairs]
    edges = [_edges(lam, sigma, r_inf, *p) for p in pairs]
    together = pm.displacements(lam, sigma, r_inf, pairs, xs, edges, tolerance=TOL)
    for p, x, e, d in zip(pairs, xs, edges, together):
        alone = pm.displacement(lam, sigma, r_inf, *p, x, e, tolerance=TOL)
        assert np.max(np.abs(d - alone)) <= 1e-13 * np.max(np.abs(alone))  # rounding


def test_a_pair_as_long_as_half_the_time_scale_is_not_the_velocity_at_its_middle():
    """What the model is for: early on, with the frame interval T / 2, the measurement and
    the velocity at the pair's middle differ near the wound by more than a percent (a ring
    mean's error in a lab's field)."""
    lam, sigma, r_inf, ta, tb = 1.0, 1.0, 10.0, 0.25, 0.75
    x = np.array([1.8, 2.2])
    edges = _edges(lam, sigma, r_inf, ta, tb)
    measured = pm.window_velocity(lam, sigma, r_inf, ta, tb, x, 0.0, edges, tolerance=TOL)
    _, mid = _native.profile_series(lam, sigma, r_inf, [0.5 * (ta + tb)], x, tolerance=TOL)
    assert np.all(np.abs(measured / mid[0] - 1) > 0.01)


def test_the_window_mean_is_the_mean_over_the_square():
    """The 3 x 3 Gauss rule against a 6 x 6 rule of the same displacement, for windows from a
    tenth to two thirds of their distance: within 2e-5 of the velocity."""
    lam, sigma, r_inf, ta, tb = 1.0, 1.0, 10.0, 1.0, 1.25
    edges = _edges(lam, sigma, r_inf, ta, tb)
    x = np.array([2.5, 4.0, 6.0])
    g, w = np.polynomial.legendre.leggauss(6)
    for half in (0.125, 0.5, 0.8):
        fine = []
        for c in x:
            px, py = np.meshgrid(c + half * g, half * g, indexing="ij")
            rho = np.hypot(px, py).ravel()
            d = pm.displacement(lam, sigma, r_inf, ta, tb, rho, edges, tolerance=TOL)
            weight = np.outer(w, w).ravel() / 4
            fine.append(np.sum(weight * d * px.ravel() / rho) / (tb - ta))
        got = pm.window_velocity(lam, sigma, r_inf, ta, tb, x, half, edges, tolerance=TOL)
        assert np.max(np.abs(got - fine)) <= 2e-5 * np.max(np.abs(fine)), half


def _draw(rng, shape, pairs, rho_t):
    """Errors of unit variance: a grid point's persistent part (correlation rho_t between
    pairs) and each pair's own, both 3 x 3 moving averages of white noise (correlation
    (1 - |dx| / 3)(1 - |dy| / 3) between windows)."""

    def smooth(a):
        k = np.ones((1, 3, 3)) / 3.0
        from scipy.signal import fftconvolve

        return fftconvolve(np.pad(a, ((0, 0), (1, 1), (1, 1)), mode="wrap"), k, mode="valid")

    persistent = smooth(rng.standard_normal((1, shape[0] + 2, shape[1] + 2)))[:, 1:-1, 1:-1]
    own = smooth(rng.standard_normal((pairs, shape[0] + 2, shape[1] + 2)))[:, 1:-1, 1:-1]
    return np.sqrt(rho_t) * persistent + np.sqrt(1 - rho_t) * own


def test_ring_means_covariance_matches_draws_of_known_correlation():
    """Estimated from single fields, rho_t and the neighbour correlation come out as drawn,
    and the ring means' covariance (averaged over 40 fields' estimates: one field's varies by
    some 15 %, its persistent texture being one draw) matches that of 800 draws: the
    variances of each band's rings (averaged over the pairs) within 10 % (over 1,500 draws
    they are 6 to 10 % low), the
    correlations of each band's rings across pairs within 0.05."""
    rng = np.random.default_rng(7)
    shape, pairs, rho_t = (30, 30), 8, 0.8
    iy, ix = np.meshgrid(np.arange(shape[0]), np.arange(shape[1]), indexing="ij")
    ix, iy = np.tile(ix.ravel(), pairs), np.tile(iy.ravel(), pairs)
    pair = np.repeat(np.arange(pairs), shape[0] * shape[1])
    r = np.hypot(ix - 14.5, iy - 14.5)
    band = np.minimum((r // 4).astype(int), 3)
    ring = pair * 4 + band
    grid = piv_errors.Grid(ix, iy, shape)
    n = np.bincount(ring)
    means, estimates, rhos = [], [], []
    for k in range(800):
        e = _draw(rng, shape, pairs, rho_t)[pair, iy, ix]
        means.append(np.bincount(ring, e) / n)
        if k < 40:
            d, s2 = piv_errors.deviations(r, e, pair)
            rho, got_t = piv_errors.correlations(d, pair, grid, 2, s2)
            estimates.append(piv_errors.ring_covariance(ring, pair, grid, rho, got_t, s2))
            rhos.append((np.mean(got_t[1:]), rho[2, 3]))
    got_t, step = np.mean(rhos, axis=0)
    assert got_t == pytest.approx(rho_t, abs=0.03)
    assert step == pytest.approx(2 / 3, abs=0.05)
    cov, empirical = np.mean(estimates, axis=0), np.cov(np.array(means).T)
    bands = [np.diag(c).reshape(pairs, 4).mean(axis=0) for c in (cov, empirical)]
    assert bands[0] == pytest.approx(bands[1], rel=0.1)

    def across(c):  # per band, the mean correlation of its rings in different pairs
        r = (c / np.sqrt(np.outer(np.diag(c), np.diag(c)))).reshape(pairs, 4, pairs, 4)
        off = ~np.eye(pairs, dtype=bool)
        return np.array([r[:, b, :, b][off].mean() for b in range(4)])

    assert np.max(np.abs(across(cov) - across(empirical))) <= 0.05
