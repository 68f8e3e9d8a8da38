"""wo_series_sensitivities (through `_native.series_sensitivities`) against the EXACT solution:
dR/dlambda and dR/dR_inf of the solver's R(t) at tolerance 1e-11 compared with fourth-order
central differences (steps 1e-3 relative: truncation ~1e-12, rounding ~1e-14 / 1e-3) of the
Laplace-domain solution (python/wound_exact.py), for lambda in [0, 50], R_inf in [1.01, 1000]
and times from 1e-3 to 20 (R_inf^2 + lambda^2) (late: the last mode relaxed).

Errors are relative to the opening R_final - R1; the R_inf column is taken as d R / d ln R_inf
(as the fit uses it). Measured worst (2026-12-03): lambda column 1.2e-9 (R_inf = 1.01,
lambda = 0.05; 1e-10 elsewhere, 1e-11 before t = 0.01), ln R_inf column 2.0e-8 (R_inf = 1.01;
1e-10 from R_inf = 1.1 on, 6e-11 before t = 0.01)."""

from __future__ import annotations

import numpy as np
import pytest
import wound_exact as we

from wound_opening import _native

LAMBDAS = (0.0, 0.05, 0.3, 1.0, 4.0, 50.0)
R_INFS = (1.01, 1.1, 1.5, 2.9, 3.1, 10.0, 87.0, 1000.0)


def d4(f, x, h):
    """Fourth-order central difference of f at x, step h."""
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


@pytest.mark.parametrize("r_inf", R_INFS)
def test_radius_derivatives_match_differences_of_the_exact_solution(r_inf):
    sigma = 0.8
    opening = we.final_radius(sigma, r_inf) - we.initial_radius(sigma)
    thin = r_inf < 1.05
    for lam in LAMBDAS:
        t = np.geomspace(1e-3, 20 * (r_inf**2 + lam**2), 9)
        r, v, d_lam, d_r_inf = _native.series_sensitivities(lam, sigma, r_inf, t, tolerance=1e-11)
        ref_r, ref_v = _native.series(lam, sigma, r_inf, t, tolerance=1e-11)
        assert np.array_equal(r, ref_r) and np.array_equal(v, ref_v)  # the very wo_series values
        exact_lam = d4(lambda x: we.edge(abs(x), sigma, r_inf, t)[0], lam, 1e-3 * max(lam, 0.1))
        exact_r = d4(lambda x: we.edge(lam, sigma, x, t)[0], r_inf, 1e-3 * (r_inf - 1))
        err_lam = np.abs(d_lam - exact_lam) / opening
        err_ln_r = np.abs(r_inf * (d_r_inf - exact_r)) / opening
        early = t < 0.01
        what = (r_inf, lam, err_lam.max(), err_ln_r.max())
        assert err_lam[early].max() < 1e-10 and err_ln_r[early].max() < 3e-10, what
        assert err_lam.max() < (5e-9 if thin else 1e-9), what
        assert err_ln_r.max() < (5e-8 if thin else 1e-9), what
        if lam == 0.0:
            assert np.all(d_lam == 0.0)  # R depends on lambda^2 only


def test_bad_times_and_parameters_are_refused_with_the_function_named():
    with pytest.raises(_native.SolverError, match="expected ascending times"):
        _native.series_sensitivities(1.0, 1.0, 10.0, [2.0, 1.0])
    with pytest.raises(_native.SolverError, match="wo_series_sensitivities: R_inf"):
        _native.series_sensitivities(1.0, 1.0, 0.5, [1.0])
