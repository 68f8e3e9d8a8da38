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

In the model the motion is radial and a material point keeps its reference radius rho,
being at rho + u(rho, t). The point at current radius x at t_a has rho solving
rho + u(rho, t_a) = x, and its displacement over the pair is exactly

    d = u(rho, t_b) - u(rho, t_a),

which the native library computes for every node of every pair of a field in one call
(`wo_pair_displacement`: the solver built once, advanced through the pairs' distinct times,
rho found at t_a as for `wo_profile_series`). The window mean is a 3 x 3 Gauss-Legendre
product rule over a square of side w aligned with the radial direction, each node's radial
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


def window_nodes(x: np.ndarray, half: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(distances (n, 6), cosines (n, 6), weights (6,)) of the 3 x 3 Gauss-Legendre nodes of
    windows of half-side `half` centred at distances `x` (same units), the cosine of each
    node's radial direction with the window centre's, the weights summing to 1. Nodes
    mirrored across the radial line (tangential offsets -+ g) lie at the same distance with
    the same cosine, so each pair is one node of twice the weight: 6 nodes, the same rule."""
    px = x[:, None] + half * _NODE_X[None, :]
    rho = np.hypot(px, half * _NODE_Y[None, :])
    return rho, px / rho, _NODE_W


_G, _W = np.polynomial.legendre.leggauss(GAUSS)
_MIRROR = _G >= 0  # tangential nodes 0 and +g, standing for -g too
#: The window's nodes in units of its half-side (radial x, tangential y >= 0) and weights.
_NODE_X, _NODE_Y = (a.ravel() for a in np.meshgrid(_G, _G[_MIRROR], indexing="ij"))
_NODE_W = np.outer(_W, np.where(_G[_MIRROR] > 0, 2.0, 1.0) * _W[_MIRROR]).ravel() / 4


def displacement(lam, sigma, r_inf, tau_a, tau_b, x, edge, *, tolerance) -> np.ndarray:
    """The displacement over [tau_a, tau_b] (in T) of the material points at current radii
    `x` (in R0) at tau_a; `edge` = (R(tau_a), R(tau_b)) of the model: points at or inside
    the wound edge at tau_a move with it."""
    return displacements(lam, sigma, r_inf, [(tau_a, tau_b)], [x], [edge], tolerance=tolerance)[0]


def displacements(lam, sigma, r_inf, pairs, xs, edges, *, tolerance) -> list[np.ndarray]:
    """`displacement` for many pairs at once, pair k's points `xs[k]` and edges `edges[k]`:
    one native call for all of them (module docstring)."""
    out = [np.full(np.size(x), e[1] - e[0]) for x, e in zip(xs, edges)]
    masks = [np.asarray(x) > e[0] * (1 + 1e-12) for x, e in zip(xs, edges)]
    counts = [int(np.count_nonzero(m)) for m in masks]
    if sum(counts) == 0:
        return out
    r = np.concatenate([np.asarray(x)[m] for x, m in zip(xs, masks)])
    t_a = np.repeat([p[0] for p in pairs], counts)
    t_b = np.repeat([p[1] for p in pairs], counts)
    d = _native.pair_displacement(lam, sigma, r_inf, t_a, t_b, r, tolerance=tolerance)
    at = np.cumsum([0] + counts)
    for k, m in enumerate(masks):
        out[k][m] = d[at[k] : at[k + 1]]
    return out


def window_velocities(lam, sigma, r_inf, pairs, xs, half, edges, *, tolerance):
    """Per pair k (times `pairs[k]` in T), the mean radial displacement over the pair of
    windows of half-side `half` at distances `xs[k]` (in R0), divided by the pair's interval:
    the PIV vectors' radial components in R0 / T (module docstring), in one native call.
    `half` = 0: the window's centre alone."""
    xs = [np.asarray(x, float).ravel() for x in xs]
    counts = [x.size for x in xs]
    tau_a, tau_b = np.array(pairs, float).reshape(-1, 2).T
    edge_a, edge_b = np.array(edges, float).reshape(-1, 2).T
    group = np.repeat(np.arange(len(xs)), counts)
    x = np.concatenate(xs) if xs else np.empty(0)
    v = flat_window_velocities(
        lam, sigma, r_inf, tau_a, tau_b, x, group, half, edge_a, edge_b, tolerance=tolerance
    )
    return np.split(v, np.cumsum(counts)[:-1])


def flat_window_velocities(
    lam, sigma, r_inf, tau_a, tau_b, x, group, half, edge_a, edge_b, *, tolerance
) -> np.ndarray:
    """`window_velocities` of rows at distances `x` (in R0), row j of pair `group[j]`, the
    pairs' times `tau_a`, `tau_b` and model edges `edge_a`, `edge_b` as arrays: the rows'
    velocities in R0 / T in one native call, with no loop over the pairs (a fit's model
    evaluation; `displacements`' rule for nodes at or inside the edge)."""
    if half <= 0:
        nodes, cos, weights = x[:, None], np.ones((x.size, 1)), np.ones(1)
    else:
        nodes, cos, weights = window_nodes(x, half)
        # a corner past the outer radius (in the data, a window at the outer radius's
        # edge): held at the window's own distance or the outer radius, the larger
        nodes = np.minimum(nodes, np.maximum(x[:, None], r_inf * (1 - 1e-9)))
    at = np.repeat(group, nodes.shape[1])  # each node's pair
    flat = nodes.ravel()
    d = (edge_b - edge_a)[at]
    tissue = flat > edge_a[at] * (1 + 1e-12)
    if np.any(tissue):
        d[tissue] = _native.pair_displacement(
            lam, sigma, r_inf, tau_a[at][tissue], tau_b[at][tissue], flat[tissue],
            tolerance=tolerance,
        )  # fmt: skip
    return (d.reshape(nodes.shape) * cos) @ weights / (tau_b - tau_a)[group]


def window_velocity(lam, sigma, r_inf, tau_a, tau_b, x, half, edge, *, tolerance):
    """`window_velocities` of one pair."""
    return window_velocities(
        lam, sigma, r_inf, [(tau_a, tau_b)], [x], half, [edge], tolerance=tolerance
    )[0]
