"""The double-precision exact reference (python/wound_exact.py) checked on its own.

The FMU tests measure the FMU against `wound_exact.edge`; this file makes sure that
reference deserves the trust: against mpmath's 30-digit fixed-Talbot inversion (3 points,
~15 s in total), and against closed-form limits from docs/model.md ("Exact results").
No FMU needed.
"""

import numpy as np
import pytest
import scipy.special as sp
import wound_exact
from fmu_harness import AMPLITUDE, R_FINAL, R_INF, SIGMA, record


@pytest.mark.parametrize(
    "lam, t",
    [
        (1.0, 0.01),  # early, steep part
        (1.0, 100.0),  # late, velocity down to ~6e-5
        (10.0, 10.0),  # viscous regime, mid-relaxation
    ],
)
def test_edge_agrees_with_mpmath(lam, t):
    """Double precision vs 30 digits: 1e-12 bounds the ~1e-14 measured agreement with room
    for libm/SciPy differences between platforms, and is 1e6 times below the FMU budget."""
    r_mp, v_mp = wound_exact.edge_mp(lam, SIGMA, R_INF, t)
    r, v = wound_exact.edge(lam, SIGMA, R_INF, [t])
    err_r = abs(r[0] - r_mp) / AMPLITUDE
    err_v = abs(v[0] - v_mp) / max(abs(v_mp), 1e-3)
    record("reference vs mpmath radius", err_r)
    record("reference vs mpmath velocity", err_v)
    assert err_r <= 1e-12, (r[0], r_mp)
    assert err_v <= 1e-12, (v[0], v_mp)


@pytest.mark.parametrize("lam, t", [(0.0, 5000.0), (0.1, 5000.0), (1.0, 5000.0), (10.0, 50000.0)])
def test_edge_reaches_final_radius(lam, t):
    """Long after the cut (slowest mode decayed by > e^-30) R = R_final = 1 + (2 sigma/3) k
    and dR/dt = 0; 1e-12 again covers the rounding of the inversion (~1e-14 measured)."""
    r, v = wound_exact.edge(lam, SIGMA, R_INF, [t])
    assert abs(r[0] - R_FINAL) <= 1e-12 * AMPLITUDE, r[0] - R_FINAL
    assert abs(v[0]) <= 1e-12, v[0]


def test_edge_initial_velocity_bessel_formula():
    """u_t(1, 0+) = (sigma - p) K1(1/l) / (2 l^2 [K1(1/l) + (2/l) K0(1/l)]) for R_inf -> oo.

    lambda = 0.1: the outer edge at R_inf = 10 is 90 viscous lengths away, so the finite
    R_inf changes this by ~e^-180, nothing.  At t = 1e-10 the velocity has decayed from
    its t = 0+ value by a relative ~5e-9 (measured: it is linear in t), hence 1e-7.
    With p = 0.3 the formula scales by (1 - p/sigma).
    """
    lam, t = 0.1, 1e-10
    x = 1.0 / lam
    v0 = SIGMA * sp.k1(x) / (2 * lam**2 * (sp.k1(x) + 2 / lam * sp.k0(x)))
    for p in (0.0, 0.3):
        _, v = wound_exact.edge(lam, SIGMA, R_INF, [t], p=p)
        assert v[0] == pytest.approx((1 - p / SIGMA) * v0, rel=1e-7)


def test_edge_superposition_in_p():
    """R_p - R1 = (1 - p/sigma)(R_0 - R1): the transform is linear in (p - sigma), so this
    holds to rounding (1e-13 of the amplitude)."""
    t = np.array([0.01, 0.3, 3.0, 30.0])
    r0, v0 = wound_exact.edge(1.0, SIGMA, R_INF, t)
    rp, vp = wound_exact.edge(1.0, SIGMA, R_INF, t, p=0.3)
    r1 = wound_exact.initial_radius(SIGMA)
    np.testing.assert_allclose(rp - r1, 0.7 * (r0 - r1), rtol=0, atol=1e-13 * AMPLITUDE)
    np.testing.assert_allclose(vp, 0.7 * v0, rtol=1e-13, atol=1e-16)


def test_profile_reduces_to_the_edge_and_relaxes_to_the_final_state():
    """u(1, t) is the wound radius minus 1 (same transform at r = 1), and u(r, t -> inf)
    = a r + b / r with a = sigma k / 6, b = sigma k / 2, k = R^2 / (R^2 - 1)."""
    t = np.array([0.01, 1.0, 100.0])
    for lam in [0.0, 0.1, 1.0, 10.0]:
        for r_inf in [10.0, 1e6]:
            u, v = wound_exact.profile(lam, 1.0, r_inf, [1.0], t)
            radius, velocity = wound_exact.edge(lam, 1.0, r_inf, t)
            assert np.max(np.abs(1 + u[:, 0] - radius)) < 1e-14
            assert np.max(np.abs(v[:, 0] - velocity)) < 1e-14
    r = np.array([1.0, 2.0, 5.0, 10.0])
    u, v = wound_exact.profile(1.0, 1.0, 10.0, r, [1e9])
    k = 100.0 / 99.0
    assert np.max(np.abs(u[0] - (k / 6 * r + k / 2 / r))) < 1e-12
    assert np.max(np.abs(v[0])) < 1e-12
