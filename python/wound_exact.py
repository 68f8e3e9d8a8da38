"""Exact wound-opening solution, computed independently of the Rust solver.

Implements docs/model.md, "Exact results": the Laplace-domain
solution of the dimensionless problem, with no spatial or temporal discretization,

    k(s)^2 = s / (1 + lambda^2 s)
    V(r, s) = A I1(k r) + B K1(k r)
    (1 + lambda^2 s) D V(1, s) = (p - sigma) / s,   D V(R_inf, s) = 0
    D I1(k r) =  2 (2 k I0(k r) - I1(k r) / r)
    D K1(k r) = -2 (2 k K0(k r) + K1(k r) / r)

so that R(t) = 1 + sigma/6 + v(1, t) and dR/dt is the inverse transform of s V(1, s).

Two inversions are provided:

* `edge`: double precision, vectorised.  The Bessel functions are SciPy's exponentially
  scaled ones (no overflow at large |k R_inf|) and the Bromwich integral is taken on
  Weideman's optimised Talbot contour (SIAM J. Numer. Anal. 44, 2006)

      z(theta) = (N / t) (-0.6122 + 0.5017 theta cot(0.6407 theta) + 0.2645 i theta),

  trapezoidal rule with N = 24 nodes.  It agrees with the 30-digit mpmath inversion to
  about 1e-14 (checked by tests/python/test_reference.py).
* `edge_mp`: mpmath's fixed Talbot at 30 significant digits; slow (seconds per point),
  used only to validate `edge`.
"""

from __future__ import annotations

import numpy as np
import scipy.special as sp

CONTOUR_NODES = 24


def edge_transform(s, lam, sigma, r_inf, p=0.0):
    """V(1, s), the Laplace transform of v(1, t) = u(1, t) - sigma/6 (numpy, complex s).

    With scaled functions I~ = I e^-Re(z), K~ = K e^z, the common factor e^(k - Re(k) R)
    cancels between numerator and determinant, leaving E = exp((Re k + k)(1 - R_inf)),
    |E| <= 1, so nothing overflows.
    """
    k = np.sqrt(s / (1 + lam**2 * s))
    kr = k * r_inf
    i1a, k1a = sp.ive(1, k), sp.kve(1, k)
    d_ia = 2 * (2 * k * sp.ive(0, k) - i1a)
    d_ka = -2 * (2 * k * sp.kve(0, k) + k1a)
    d_ib = 2 * (2 * k * sp.ive(0, kr) - sp.ive(1, kr) / r_inf)
    d_kb = -2 * (2 * k * sp.kve(0, kr) + sp.kve(1, kr) / r_inf)
    e = np.exp((k.real + k) * (1 - r_inf))
    rhs = (p - sigma) / (s * (1 + lam**2 * s))
    return rhs * (d_kb * i1a * e - d_ib * k1a) / (d_ia * d_kb * e - d_ka * d_ib)


def profile_transform(s, r, lam, sigma, r_inf, p=0.0):
    """V(r, s) = A I1(k r) + B K1(k r), the transform of v(r, t) = u(r, t) - sigma r / 6.

    Same constants as `edge_transform`, whose value is this at r = 1:

        (1 + lambda^2 s) D V(1, s) = (p - sigma) / s,   D V(R_inf, s) = 0,
        A = rhs D_K(R) / det,  B = -rhs D_I(R) / det,  det = D_I(1) D_K(R) - D_K(1) D_I(R).

    With scaled functions I~(z) = I(z) e^-Re(z), K~(z) = K(z) e^z and numerator and
    determinant multiplied by the same factor as in `edge_transform`, the exponentials left
    are exp(Re(k) (r - 1) + (Re(k) + k) (1 - R_inf)), of modulus exp(Re(k) (r + 1 - 2 R_inf))
    <= 1, on the I part and exp(-k (r - 1)), of modulus <= 1, on the K part, for
    1 <= r <= R_inf: nothing overflows.
    """
    k = np.sqrt(s / (1 + lam**2 * s))
    kr, kb = k * r, k * r_inf
    d_ia = 2 * (2 * k * sp.ive(0, k) - sp.ive(1, k))
    d_ka = -2 * (2 * k * sp.kve(0, k) + sp.kve(1, k))
    d_ib = 2 * (2 * k * sp.ive(0, kb) - sp.ive(1, kb) / r_inf)
    d_kb = -2 * (2 * k * sp.kve(0, kb) + sp.kve(1, kb) / r_inf)
    e = np.exp((k.real + k) * (1 - r_inf))
    rhs = (p - sigma) / (s * (1 + lam**2 * s))
    det = d_ia * d_kb * e - d_ka * d_ib
    i_part = d_kb * sp.ive(1, kr) * np.exp(k.real * (r - 1) + (k.real + k) * (1 - r_inf))
    k_part = d_ib * sp.kve(1, kr) * np.exp(-k * (r - 1))
    return rhs * (i_part - k_part) / det


def profile(lam, sigma, r_inf, r, t, p=0.0):
    """Exact (u(r, t), u_t(r, t)) at radii r (1 <= r <= R_inf, reference positions) and
    times t > 0, for a constant edge stress p from t = 0: arrays of shape (len(t), len(r))."""
    r = np.atleast_1d(np.asarray(r, dtype=float))
    u = np.empty((np.size(t), r.size))
    v = np.empty_like(u)
    for j, rj in enumerate(r):
        f = lambda s: profile_transform(s, rj, lam, sigma, r_inf, p)  # noqa: E731
        u[:, j] = sigma * rj / 6 + _invert(f, t)
        v[:, j] = _invert(lambda s: s * f(s), t)
    return u, v


def _invert(transform, t, n=CONTOUR_NODES):
    """Inverse Laplace transform at each t > 0 on Weideman's contour."""
    t = np.atleast_1d(np.asarray(t, dtype=float))[:, None]
    theta = -np.pi + (np.arange(n) + 0.5) * 2 * np.pi / n
    a, mu, nu, shift = 0.6407, 0.5017, 0.2645, -0.6122
    z = n / t * (shift + mu * theta / np.tan(a * theta) + 1j * nu * theta)
    dz = n / t * (mu / np.tan(a * theta) - mu * a * theta / np.sin(a * theta) ** 2 + 1j * nu)
    return (np.sum(np.exp(z * t) * transform(z) * dz, axis=1) / (1j * n)).real


def edge(lam, sigma, r_inf, t, p=0.0):
    """Exact (R(t), dR/dt) arrays for a constant edge stress p applied from t = 0 (t > 0)."""

    def f(s):
        return edge_transform(s, lam, sigma, r_inf, p)

    radius = 1 + sigma / 6 + _invert(f, t)
    velocity = _invert(lambda s: s * f(s), t)
    return radius, velocity


def edge_mp(lam, sigma, r_inf, t, p=0.0, dps=30):
    """The same at one t, with mpmath (30 digits, fixed Talbot): slow, for validation."""
    import mpmath as mp

    with mp.workdps(dps):
        lam, sigma, r_inf, p = (mp.mpf(x) for x in (lam, sigma, r_inf, p))

        def f(s):
            k = mp.sqrt(s / (1 + lam**2 * s))
            kr = k * r_inf
            d_ia = 2 * (2 * k * mp.besseli(0, k) - mp.besseli(1, k))
            d_ka = -2 * (2 * k * mp.besselk(0, k) + mp.besselk(1, k))
            d_ib = 2 * (2 * k * mp.besseli(0, kr) - mp.besseli(1, kr) / r_inf)
            d_kb = -2 * (2 * k * mp.besselk(0, kr) + mp.besselk(1, kr) / r_inf)
            rhs = (p - sigma) / (s * (1 + lam**2 * s))
            det = d_ia * d_kb - d_ka * d_ib
            return rhs * (d_kb * mp.besseli(1, k) - d_ib * mp.besselk(1, k)) / det

        radius = 1 + sigma / 6 + mp.invertlaplace(f, t, method="talbot")
        velocity = mp.invertlaplace(lambda s: s * f(s), t, method="talbot")
        return float(radius), float(velocity)


def final_radius(sigma, r_inf):
    """R_final = 1 + (2 sigma / 3) R_inf^2 / (R_inf^2 - 1)."""
    return 1.0 + 2.0 * sigma / 3.0 * r_inf**2 / (r_inf**2 - 1.0)


def initial_radius(sigma):
    """R1 = 1 + sigma / 6, the wound radius at the moment of the cut."""
    return 1.0 + sigma / 6.0
