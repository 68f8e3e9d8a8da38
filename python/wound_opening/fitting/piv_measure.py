"""What a PIV vector measures: the displacement of the texture in its interrogation window
between the two frames of its pair, divided by the frame interval.

A PIV program correlates the image of a window of side w at frame a with frame b = a + 1 and
reports the shift of the correlation peak. For a smooth flow that shift is the mean
displacement of the material in the window over [t_a, t_b] (Lagrangian: the same material
points, followed from t_a to t_b), so the vector is

    v_PIV(c) = (1 / dt) mean over the window W(c) of [ X(t_b; p) - p ],   dt = t_b - t_a,

with X(t; p) the position at t of the material point at p at t_a. It is not the velocity at
the window's centre c at the pair's middle: the two differ at second order in dt / T (the
velocity decays within the interval when the time scale T is close to the frame interval)
and in the displacement over the interval relative to the distance from the wound.

In the model the motion is radial, a material point at reference radius rho being at
rho + u(rho, t). With the solver's displacement at CURRENT radii x, u_c(x, t) (the
displacement of the material point now at x), a point at x at t_a has rho = x - u_c(x, t_a)
and reaches the radius X that solves

    X - u_c(X, t_b) = rho,

found by the secant method from the first-order guess X0 = x + dt v(x, t_a) (the residual's
derivative 1 - du_c/dx is the inverse of the radial stretch, near 1; a handful of native
calls per pair, the solver's accuracy). The window mean is a 3 x 3 Gauss-Legendre product
rule over a square of side w aligned with the radial direction, each node's radial
displacement projected onto the radial direction through the window's centre: exact for
fields of degree 5 across the window (against a 6 x 6 rule: 1e-5 of the velocity for a
window as wide as two thirds of its distance from the centre).

Nodes at or inside the model's wound edge at t_a move with the edge (R(t_b) - R(t_a)):
the data's windows that touch the wound are dropped before the fit (inputs/rings.py), so
these occur only at parameters far from the data's own edge."""

from __future__ import annotations

import numpy as np

from .. import _native

#: Gauss-Legendre points per side of a window (3: exact for fields of degree 5 across it).
GAUSS = 3
#: Secant iterations at most, and the residual (relative to the radius) they stop at.
ITERATIONS, CHANGE = 12, 1e-13
#: Chebyshev points of a pair's displacement interpolant (_smooth_displacement), and the
#: interpolant's accuracy relative to the largest displacement (measured with 20 points:
#: 3e-7 on most spans, 9e-6 at worst, from the wound to 0.9 R_inf at sigma = -0.5).
CHEBYSHEV, INTERPOLATION = 20, 1e-5


def window_nodes(x: np.ndarray, half: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(distances (n, 9), cosines (n, 9), weights (9,)) of the 3 x 3 Gauss-Legendre nodes of
    windows of half-side `half` centred at distances `x` (same units), the cosine of each
    node's radial direction with the window centre's, the weights summing to 1."""
    px = x[:, None] + half * _NODE_X[None, :]
    rho = np.hypot(px, half * _NODE_Y[None, :])
    return rho, px / rho, _NODE_W


_G, _W = np.polynomial.legendre.leggauss(GAUSS)
#: The window's nodes in units of its half-side (radial x, tangential y) and their weights.
_NODE_X, _NODE_Y = (a.ravel() for a in np.meshgrid(_G, _G, indexing="ij"))
_NODE_W = np.outer(_W, _W).ravel() / 4


def displacement(lam, sigma, r_inf, tau_a, tau_b, x, edge, *, tolerance) -> np.ndarray:
    """X(t_b) - x for the material points at current radii `x` (in R0) at tau_a (in T);
    `edge` = (R(tau_a), R(tau_b)) of the model: points at or inside the wound edge at tau_a
    move with it."""
    out = np.full(x.size, edge[1] - edge[0])
    tissue = x > edge[0] * (1 + 1e-12)
    if not np.any(tissue):
        return out
    p = x[tissue]
    u_a, v_a = _native.profile_series(lam, sigma, r_inf, [tau_a], p, tolerance=tolerance)
    rho = p - u_a[0]
    low = edge[1] * (1 + 1e-12)

    def residual(X):
        u_b, _ = _native.profile_series(
            lam, sigma, r_inf, [tau_b], X, velocity=False, tolerance=tolerance
        )
        return X - u_b[0] - rho

    x0 = np.maximum(p + (tau_b - tau_a) * v_a[0], low)
    g0 = residual(x0)
    x1 = np.maximum(x0 - g0, low)  # one fixed-point step: X = rho + u_c(X)
    for _ in range(ITERATIONS):
        g1 = residual(x1)
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = (g1 - g0) / (x1 - x0)
        slope = np.where(np.isfinite(slope) & (slope > 0.05), slope, 1.0)
        x0, g0, x1 = x1, g1, np.maximum(x1 - g1 / slope, low)
        if np.all(np.abs(g1) <= CHANGE * np.maximum(np.abs(x0), 1.0)):
            break  # x1, a step past a residual this small, is at the root to rounding
    out[tissue] = x1 - p
    return out


def window_velocity(lam, sigma, r_inf, tau_a, tau_b, x, half, edge, *, tolerance):
    """The mean radial displacement over [tau_a, tau_b] of windows of half-side `half` at
    distances `x` (all in R0, times in T), divided by tau_b - tau_a: the PIV vector's radial
    component in R0 / T (module docstring). `half` = 0: the window's centre alone."""
    if half <= 0:
        nodes, cos, weights = x[:, None], np.ones((x.size, 1)), np.ones(1)
    else:
        nodes, cos, weights = window_nodes(x, half)
        # a corner past the outer radius (in the data, a window at the outer radius's edge):
        # held at the window's own distance or the outer radius, whichever is larger
        nodes = np.minimum(nodes, np.maximum(x[:, None], r_inf * (1 - 1e-9)))
    d = _smooth_displacement(lam, sigma, r_inf, (tau_a, tau_b), nodes.ravel(), edge, tolerance)
    return (d.reshape(nodes.shape) * cos) @ weights / (tau_b - tau_a)


def _smooth_displacement(lam, sigma, r_inf, taus, x, edge, tolerance) -> np.ndarray:
    """`displacement` at many points `x` through its values at CHEBYSHEV points: in the
    tissue the displacement over a pair is a smooth function of 1 / x (a sum of decaying
    Bessel modes), so its polynomial interpolant in 1 / x at Chebyshev points of the span
    (barycentric form) holds it to INTERPOLATION relative to the largest
    (tests/python/test_piv_measure.py) with the solver called at CHEBYSHEV points only.
    Points at or inside the edge move with it; fewer points than CHEBYSHEV are computed
    directly."""
    tissue = x > edge[0] * (1 + 1e-12)
    if np.count_nonzero(tissue) <= CHEBYSHEV:
        return displacement(lam, sigma, r_inf, *taus, x, edge, tolerance=tolerance)
    out = np.full(x.size, edge[1] - edge[0])
    w = 1.0 / x[tissue]
    lo, hi = float(w.min()), float(w.max())
    nodes = 0.5 * (lo + hi) + 0.5 * (hi - lo) * _COS
    d = displacement(lam, sigma, r_inf, *taus, 1.0 / nodes, edge, tolerance=tolerance)
    out[tissue] = _barycentric(nodes, d, w, _WEIGHTS)
    return out


_ANGLES = (2 * np.arange(CHEBYSHEV) + 1) * np.pi / (2 * CHEBYSHEV)
_COS = np.cos(_ANGLES)
#: The barycentric weights of Chebyshev points of the first kind, (-1)^k sin(angle_k).
_WEIGHTS = (-1.0) ** np.arange(CHEBYSHEV) * np.sin(_ANGLES)


def _barycentric(nodes, values, at, weights) -> np.ndarray:
    """The interpolant through (nodes, values) at `at`, in the second barycentric form."""
    diff = at[:, None] - nodes[None, :]
    exact = diff == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        c = weights / diff
        out = (c @ values) / c.sum(axis=1)
    hit = exact.any(axis=1)
    out[hit] = values[np.argmax(exact[hit], axis=1)]
    return out
