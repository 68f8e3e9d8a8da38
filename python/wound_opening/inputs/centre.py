"""The wound centre of a PIV field, and the field seen from it: the distance r of each vector
from the centre and its radial component.

Estimate. An opening wound moves the tissue radially away from its centre c: the velocity at
position p_i in frame pair k is w_i = g_k(|p_i - c|) e_i + noise, e_i = (p_i - c) / |p_i - c|,
with g_k a smooth radial speed, here g_k(r) = a/r + b/r^2 + c/r^3 + d (per pair). The centre
is the least-squares fit of this model to both components of every vector of every pair: for
a trial c, each g_k is the linear least-squares fit of the radial components, and the
residuals are the tangential components and the radial ones less g_k (variable projection; c
by scipy.optimize.least_squares from the mean position weighted by speed). Fitting the
tangential components alone is biased where the vectors are mostly noise: moving c lines
noise up with the radial direction at no cost, while in the full fit a noise vector costs its
length whatever c is.

Uncertainty: the larger of (a) the curvature of the cost, s^2 2 H^-1 (H by central
differences; s^2 the residual variance), and (b) the jackknife over tiles of the field
(TILES x TILES squares of its extent, every frame pair's vectors of a tile left out
together). A PIV error is mostly the texture in its window, so it persists from pair to
pair at one grid point and is shared by overlapping windows: frame pairs are not
independent (a jackknife over them stated 0.05-0.3 um where the estimate on a rendered movie
measured by OpenPIV was 1.8 um off), tiles several windows wide are. Leaving tile g out
moves the optimum by (H - H_g)^-1 g_g, g_g and H_g the gradient and Hessian of the tile's
part of the cost and H the whole cost's Hessian, all by central differences (nine
evaluations of the residuals serve every tile). This is the leverage correction that makes
leave-one-out exact for linear least squares; H^-1 g_g alone (first order) understated the
spread (rms z 1.54 on the OpenPIV fields of docs/fitting.md's coverage study, 1.30 with the
correction). Where the corrected step differs from the first-order one by more than a
quarter of its length, or H - H_g is not positive definite, the cost is not quadratic over
the step and the tile is truly refitted (tolerance 1e-8, from the first-order step). The
Gauss-Newton J^T J in H's place understated the spread 6-fold (the far field's noise
vectors turn with the centre: the cost's curvature is not J^T J's).
docs/fitting.md gives its calibration on noisy fields of the exact solution."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .columns import InputError


@dataclass(frozen=True)
class Centre:
    """The centre [um] in the files' axes, with its standard errors (0 when given)."""

    x_um: float
    y_um: float
    sd_x_um: float = 0.0
    sd_y_um: float = 0.0
    estimated: bool = False
    tangential_rms_um_s: float | None = None

    def describe(self) -> str:
        if not self.estimated:
            return f"wound centre given: ({self.x_um:.6g}, {self.y_um:.6g}) um"
        return (
            f"wound centre estimated from the flow: ({self.x_um:.6g} +- {self.sd_x_um:.2g}, "
            f"{self.y_um:.6g} +- {self.sd_y_um:.2g}) um (tangential velocity rms "
            f"{self.tangential_rms_um_s:.3g} um/s)"
        )


def parse_point(text: str, option: str) -> tuple[float, float]:
    try:
        x, y = (float(v) for v in text.split(","))
    except ValueError:
        raise InputError(f"{option} {text!r}: expected X,Y (two numbers)") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise InputError(f"{option} {text!r}: must be finite")
    return x, y


def _basis(r):
    return np.column_stack([1 / r, r**-2, r**-3, np.ones_like(r)])


def _residuals(c, x, y, u, v, groups):
    dx, dy = x - c[0], y - c[1]
    r = np.hypot(dx, dy)
    ex, ey = dx / r, dy / r
    radial = u * ex + v * ey
    out = [u * ey - v * ex]
    for rows in groups:
        b = _basis(r[rows])
        coef, *_ = np.linalg.lstsq(b, radial[rows], rcond=None)
        out.append(radial[rows] - b @ coef)
    return np.concatenate(out)


def _fit(x, y, u, v, groups, start, scale, robust: bool = False, tol: float = 1e-14):
    """The least-squares centre from `start`; `robust`: with the soft-L1 loss at the scale of
    the residuals' median absolute value there (a first look, which vectors reading the
    wound's dark, moving edge would otherwise pull)."""
    from scipy.optimize import least_squares

    args = (x, y, u, v, groups)
    f_scale = 1.0
    if robust:
        f_scale = max(1.4826 * float(np.median(np.abs(_residuals(start, *args)))), 1e-300)
    return least_squares(
        _residuals,
        start,
        args=args,
        x_scale=scale,
        loss="soft_l1" if robust else "linear",
        f_scale=f_scale,
        ftol=tol,
        xtol=max(tol, 1e-10),
        gtol=tol,
    )


def _curvature_cov(c, args, h):
    """2 (d^2 cost / dc^2)^-1 by central differences of the cost."""

    def cost(p):
        r = _residuals(np.asarray(p), *args)
        return float(r @ r)

    e = np.eye(2) * h
    hess = np.empty((2, 2))
    for i in range(2):
        for j in range(2):
            hess[i, j] = (
                cost(c + e[i] + e[j])
                - cost(c + e[i] - e[j])
                - cost(c - e[i] + e[j])
                + cost(c - e[i] - e[j])
            ) / (4 * h * h)
    try:
        return 2 * np.linalg.inv(hess)
    except np.linalg.LinAlgError:
        return np.full((2, 2), np.inf)


#: The jackknife's tiles per side of the field's extent (module docstring).
TILES = 6


def tiles(x, y, extent: float) -> np.ndarray:
    """The jackknife's tile of each vector (TILES x TILES squares of side extent / TILES from
    the field's lowest x and y), numbered 0.. over the tiles that hold vectors."""
    tile_x = np.minimum(((x - x.min()) / extent * TILES).astype(int), TILES - 1)
    tile_y = np.minimum(((y - y.min()) / extent * TILES).astype(int), TILES - 1)
    return np.unique(tile_x * TILES + tile_y, return_inverse=True)[1]


def _tile_jackknife(fit, args, extent: float, h: float):
    """The jackknife variance of the centre over tiles (module docstring): leaving tile g out
    moves the optimum by (H - H_g)^-1 g_g, g_g and H_g the gradient and Hessian of the tile's
    own part of the cost and H the whole cost's Hessian (central differences of step h: nine
    evaluations of the residuals, the cost summed per tile, serve every tile); a tile whose
    step is not that of a quadratic cost (module docstring) is refitted. None with fewer
    than 3 tiles holding vectors."""
    x, y = args[0], args[1]
    tile = np.tile(tiles(x, y, extent), 2)  # both residuals of a vector
    m = int(tile.max()) + 1
    if m < 3:
        return None

    def per_tile(c):
        r = _residuals(np.asarray(c), *args)
        return np.bincount(tile, r * r, minlength=m)

    e = np.eye(2) * h
    fp, fm = [per_tile(fit.x + d) for d in e], [per_tile(fit.x - d) for d in e]
    grad = np.stack([(fp[i] - fm[i]) / (2 * h) for i in range(2)], axis=1)
    c0 = per_tile(fit.x)
    hess = np.empty((m, 2, 2))  # each tile's own part of the Hessian
    for i in range(2):
        hess[:, i, i] = (fp[i] - 2 * c0 + fm[i]) / h**2
    hess[:, 0, 1] = hess[:, 1, 0] = (
        per_tile(fit.x + e[0] + e[1])
        - per_tile(fit.x + e[0] - e[1])
        - per_tile(fit.x - e[0] + e[1])
        + per_tile(fit.x - e[0] - e[1])
    ) / (4 * h * h)
    whole = hess.sum(0)
    rest = whole - hess  # the Hessian of the cost without tile g
    try:
        first = np.linalg.solve(whole, grad.T).T
    except np.linalg.LinAlgError:
        return np.full(2, np.inf)
    steps = first.copy()
    good = np.linalg.eigvalsh(rest)[:, 0] > 0
    steps[good] = np.linalg.solve(rest[good], grad[good][:, :, None])[:, :, 0]
    far = ~good | (np.hypot(*(steps - first).T) > 0.25 * np.hypot(*first.T))
    for g in np.flatnonzero(far):
        steps[g] = _refit_without(fit, args, tile[: x.size] == g, first[g], extent)
    return (m - 1) / m * np.sum((steps - steps.mean(0)) ** 2, axis=0)


def _refit_without(fit, args, out, step, extent: float, tol: float = 1e-8):
    """The step of the centre refitted without the vectors `out` (a tile), from `step`."""
    x, y, u, v, groups = args
    keep = ~out
    index = np.cumsum(keep) - 1
    sub = [index[rows[keep[rows]]] for rows in groups]
    sub = [rows for rows in sub if rows.size > 4]
    got = _fit(x[keep], y[keep], u[keep], v[keep], sub, fit.x + step, extent / 100, tol=tol)
    return got.x - fit.x


def estimate_centre(x, y, u, v, pair=None, *, check: bool = True, start=None) -> Centre:
    """The centre of the radial flow (module docstring). `pair`: the frame pair of each
    vector (one radial profile each). `check`: refuse a field that does not point away from
    one centre (else return the best estimate, for a first look)."""
    x, y, u, v = (np.asarray(a, dtype=float) for a in (x, y, u, v))
    if x.size < 10:
        raise InputError(f"{x.size} PIV vectors: too few to estimate the wound centre, give it")
    pair = np.zeros(x.size, int) if pair is None else np.asarray(pair)
    groups = [np.flatnonzero(pair == k) for k in np.unique(pair)]
    extent = max(float(np.ptp(x)), float(np.ptp(y)), 1e-12)
    speed = np.hypot(u, v)
    if start is None:
        start = np.array([np.average(x, weights=speed), np.average(y, weights=speed)])
    fit = _fit(x, y, u, v, groups, start, extent / 100, robust=not check)
    dof = max(2 * x.size - 2 - 4 * len(groups), 1)
    s2 = float(fit.fun @ fit.fun) / dof
    var = np.diag(s2 * _curvature_cov(fit.x, (x, y, u, v, groups), extent / 200)).copy()
    jack = _tile_jackknife(fit, (x, y, u, v, groups), extent, extent / 200)
    if jack is not None:
        var = np.maximum(var, jack)
    tangential = fit.fun[: x.size]
    rms = math.sqrt(float(tangential @ tangential) / x.size)
    if check and (
        not fit.success or not np.all(np.isfinite(var)) or var.max() > (extent / 10) ** 2
    ):
        raise InputError(
            f"the PIV field does not point away from one centre (tangential velocity rms "
            f"{rms:.3g} um/s, median speed {float(np.median(speed)):.3g} um/s): give the "
            "centre (--centre-um or --centre-px)"
        )
    return Centre(float(fit.x[0]), float(fit.x[1]), math.sqrt(var[0]), math.sqrt(var[1]), True, rms)


def radial(centre: Centre, x, y, u, v) -> tuple[np.ndarray, np.ndarray]:
    """(r [um], radial velocity [um/s]) of each vector seen from `centre`."""
    dx, dy = np.asarray(x) - centre.x_um, np.asarray(y) - centre.y_um
    r = np.hypot(dx, dy)
    with np.errstate(invalid="ignore", divide="ignore"):
        vr = (dx * np.asarray(u) + dy * np.asarray(v)) / r
    return r, vr


def ring_sensitivity(centre: Centre, x, y, r, vr, group, pair) -> np.ndarray:
    """(rings, 2): how far each ring's residual (its mean radial velocity less the model's
    at its harmonic mean distance H) moves per um of the centre in x and y, so that an
    estimated centre's uncertainty enters the rings' covariance (inputs/rings.py).

    Seen from c = c* + delta, a vector of a radial flow keeps its radial component to
    first order (the change is the tangential component, noise, over r) while its distance
    becomes r_i - e_i . delta; H = n / sum(1 / r_i) then moves by
    -(H^2 / n) sum(e_i / r_i^2) . delta and the model's value at H with it, so

        d residual / d c = M'(H) (H^2 / n) sum_i e_i / r_i^2,

    zero for a full ring, not for one the image's border or the left-out windows cut. M'
    is the slope of each pair's smooth radial profile (the estimate's a/r + b/r^2 + c/r^3 +
    d, fitted to the ring's vectors' pair) at H."""
    x, y, r, vr = (np.asarray(a, float) for a in (x, y, r, vr))
    group, pair = np.asarray(group), np.asarray(pair)
    ex, ey = (x - centre.x_um) / r, (y - centre.y_um) / r
    n = np.bincount(group)
    h = n / np.bincount(group, 1.0 / r)
    slope = np.zeros(n.size)
    ring_pair = np.zeros(n.size, dtype=pair.dtype)
    ring_pair[group] = pair
    for k in np.unique(pair):
        rows = pair == k
        coef, *_ = np.linalg.lstsq(_basis(r[rows]), vr[rows], rcond=None)
        mine = ring_pair == k
        hk = h[mine]
        slope[mine] = np.column_stack([-(hk**-2), -2 * hk**-3, -3 * hk**-4, 0 * hk]) @ coef
    w = r**-2
    moved = np.column_stack([np.bincount(group, ex * w), np.bincount(group, ey * w)])
    return (slope * h**2 / n)[:, None] * moved
