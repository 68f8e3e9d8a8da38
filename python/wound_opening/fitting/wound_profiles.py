"""The profile likelihoods of a several-wound fit (fit_wounds, wounds.py): the shared viscous
length l, tension/G and zeta/G, each wound's R0, and eta/G = l^2 zeta/G / 4 walked in its
own coordinate (EtaCoordinate). Each is walked from every optimum with intervals.hull, as
a single wound's parameters are (intervals.py)."""

from __future__ import annotations

import math

import numpy as np

from ..results.names import ETA, SHARED
from ..results.profiles import Profile
from .intervals import hull
from .objective import LAMBDA_MAX
from .problem import Problem

LN4 = math.log(4.0)


class EtaCoordinate(Problem):
    """The tissue objective with w_2 = ln eta/G = ln zeta/G + 2 ln l - ln 4 in place of
    ln zeta/G (for its profile; needs l > 0)."""

    def __init__(self, tissue: Problem):  # wounds.Tissue
        self.tissue = tissue
        # the user's fixed coordinates other than l and zeta/G are the same in w
        self.fixed = {i: v for i, v in getattr(tissue, "fixed", {}).items() if i not in (0, 2)}

    @property
    def size(self) -> int:
        return self.tissue.size

    @staticmethod
    def to_y(w):
        y = np.array(w, dtype=float)
        y[2] = w[2] - 2 * math.log(max(w[0], 1e-300)) + LN4
        return y

    @staticmethod
    def to_w(y):
        w = np.array(y, dtype=float)
        w[2] = y[2] + 2 * math.log(y[0]) - LN4
        return w

    @staticmethod
    def gradient(y) -> np.ndarray:
        """d w_2 / d y."""
        g = np.zeros(y.size)
        g[0], g[2] = 2 / y[0], 1.0
        return g

    def residuals(self, w):
        return self.tissue.residuals(self.to_y(w))

    def jacobian(self, w, columns=None):
        """dr/dw by the chain rule, every column (`columns` is not used)."""
        dy = np.eye(len(w))
        dy[2, 0] = -2 / w[0]
        return self.tissue.jacobian(self.to_y(w)) @ dy

    def bounds(self):
        lower, upper = self.tissue.bounds()
        lower[0] = 1e-9 * upper[0]
        lower[2], upper[2] = -np.inf, np.inf
        return lower, upper


def _interval(obj, k, centres, chi2_min, threshold, cov, loss, limits, default):
    """One coordinate's profile interval (lower, upper; None where open), points and whether
    each end is a bound the user set, walked by intervals.walk_side from the optimum and from
    every other optimum below the threshold (`centres`: (y, delta chi^2)), as
    intervals.profile_all does; `limits(centre)` gives the search range, `cov` the
    Jacobian's covariance (first step and start prediction)."""
    n = centres[0][0].size
    ok = np.all(np.isfinite(cov[:, k])) and cov[k, k] > 0
    se = math.sqrt(cov[k, k]) if ok else math.nan
    slope = cov[:, k] / cov[k, k] if ok else np.eye(n)[k]
    step = float(np.clip(se if ok else default, default * 0.01, default * 20))
    box = obj.bounds()
    user_bound = getattr(obj, "user_bound", lambda i, side: False)

    def side_limit(centre, direction):
        limit = limits(centre)[0 if direction < 0 else 1]
        edge = box[0 if direction < 0 else 1][k]
        return limit, bool(user_bound(k, direction) and limit == edge)

    lo, hi, points, bounded = hull(
        obj, k, centres, chi2_min, threshold, step, slope, loss, side_limit
    )
    return lo, hi, sorted(points), bounded


def _log_profile(lo, hi, pts, bounded, scale: float = 1.0) -> Profile:
    """A profile walked in a log coordinate, in own units times `scale`."""

    def own(v):
        return None if v is None else scale * math.exp(v)

    return Profile(own(lo), own(hi), False, sorted((own(v), d) for v, d in pts), tuple(bounded))


def shared_profiles(tissue, y_hat, chi2_min, threshold, cov, loss, alternates) -> dict:
    """Profiles of l, sigma, zeta/G, eta/G and each R0_k, with the single fit's search limits
    (intervals.py): l from 0 to LAMBDA_MAX times the largest R0 (an interval reaching 0 is
    closed there but does not identify l, as lambda's), sigma within 10 |sigma| + 1, zeta/G
    and eta/G within a factor 100, R0 within a factor 3. A coordinate the user holds fixed
    is its value; eta/G with l or zeta/G fixed is the other one's profile carried over."""

    lower, upper = tissue.bounds()
    fixed = tissue.fixed
    centres = [(y_hat, 0.0)] + [(a, d) for a, d in alternates if d < threshold]
    out = {}

    def clipped(i, lo, hi):
        return lambda c: (max(lo(c), lower[i]), min(hi(c), upper[i]))

    l_max = LAMBDA_MAX * math.exp(max(y_hat[3:]))
    limits = {
        0: clipped(0, lambda c: 0.0, lambda c: min(l_max, upper[0])),
        1: clipped(1, lambda c: c[1] - 10 * abs(c[1]) - 1, lambda c: c[1] + 10 * abs(c[1]) + 1),
        2: clipped(2, lambda c: c[2] - math.log(100.0), lambda c: c[2] + math.log(100.0)),
    }
    walked = {}
    for i in range(tissue.n):
        key = SHARED[i] if i < 3 else ("R0_um", i - 3)
        if i in fixed:
            v = float(y_hat[i] if i < 2 else math.exp(y_hat[i]))
            out[key] = Profile(v, v, False, [(v, 0.0)])
            continue
        lim = limits.get(i) or clipped(
            i, lambda c, i=i: c[i] - math.log(3.0), lambda c, i=i: c[i] + math.log(3.0)
        )
        default = (
            (0.1 * math.exp(float(np.median(y_hat[3:]))), 0.05 * abs(y_hat[1]) + 0.01, 0.1)[i]
            if i < 3
            else 0.05
        )
        lo, hi, pts, bounded = _interval(
            tissue, i, centres, chi2_min, threshold, cov, loss, lim, default
        )
        walked[i] = (lo, hi, pts, bounded)
        if i < 2:
            at_bound = i == 0 and lo is None
            out[key] = Profile(0.0 if at_bound else lo, hi, at_bound, pts, tuple(bounded))
        else:
            out[key] = _log_profile(lo, hi, pts, bounded)
    out[ETA] = _eta_profile(tissue, y_hat, centres, chi2_min, threshold, cov, loss, walked, l_max)
    return out


def _eta_profile(tissue, y_hat, centres, chi2_min, threshold, cov, loss, walked, l_max):
    """eta/G = l^2 zeta/G / 4: walked in its own coordinate (EtaCoordinate), or, with l or
    zeta/G held fixed, the other one's profile carried over (eta/G is monotonic in it)."""
    fixed = tissue.fixed
    zg, l_hat = math.exp(y_hat[2]), y_hat[0]
    if 0 in fixed and 2 in fixed:
        v = l_hat**2 * zg / 4
        return Profile(v, v, False, [(v, 0.0)])
    if 0 in fixed:  # eta/G = (l^2 / 4) zeta/G
        lo, hi, pts, bounded = walked[2]
        return _log_profile(lo, hi, pts, bounded, scale=l_hat**2 / 4)
    if 2 in fixed:  # eta/G = (zeta/G / 4) l^2, l >= 0
        lo, hi, pts, bounded = walked[0]
        sq = [(zg * v * v / 4, d) for v, d in pts]
        return Profile(
            0.0 if lo is None else zg * lo * lo / 4,
            None if hi is None else zg * hi * hi / 4,
            lo is None,
            sorted(sq),
            tuple(bounded),
        )
    if any(c[0] <= 1e-8 * l_max for c, _ in centres):
        return Profile(0.0, None, True)  # eta/G = 0 is allowed: not identified
    rep = EtaCoordinate(tissue)
    a = np.eye(tissue.n)
    a[2] = rep.gradient(y_hat)
    eta_centres = [(rep.to_w(c), d) for c, d in centres]
    lo, hi, pts, _ = _interval(
        rep,
        2,
        eta_centres,
        chi2_min,
        threshold,
        a @ cov @ a.T,
        loss,
        lambda c: (c[2] - math.log(100.0), c[2] + math.log(100.0)),
        0.1,
    )
    return _log_profile(lo, hi, pts, (False, False))
