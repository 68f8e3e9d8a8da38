"""Likelihood profiles of derived quantities: the fit reparametrised so that the quantity
is one coordinate, then profiled like a parameter (intervals.py).

Each quantity is a monomial of the parameters, linear in the log coordinates
y = (ln R0, -, ln lambda, ln T):

    quantity                       ln q = c + sum_i a_i y_i         replaces (else)
    tau = eta/G = lambda^2 T [s]   2 y2 + y3                         ln T (lambda)
    zeta/G = 4 T / R0^2 [s/um^2]   ln 4 - 2 y0 + y3                  ln T (ln R0)
    viscous length lambda R0 [um]  y0 + y2                           lambda (ln R0)

The coordinate k it replaces becomes w_k = ln q, the others stay (w_i = z_i), and

    y_k = (w_k - c - sum_{i != k} a_i y_i) / a_k,
    d z_k / d w_k = (d z_k / d y_k) / a_k,
    d z_k / d w_i = -(a_i / a_k) (d y_i / d w_i) (d z_k / d y_k),
    d w_k / d z_i = a_i d y_i / d z_i,

with d z / d y = 1 for ln R0, ln T and lambda for lambda (d y2 / d z2 = 1 / lambda). The
replaced coordinate is the first of the two that the user does not hold fixed (parameters.py);
with both held the quantity is fixed itself. A user's bound on the replaced coordinate is
a box in w only when the other coordinates of the monomial are fixed (it is then mapped to
w_k); otherwise an unbounded coordinate is replaced where there is one, and failing that the
quantity is not profiled. tension/G is sigma (its own profile). A
quantity needing lambda > 0 is not profiled when lambda's estimate is 0 (its interval then
reaches 0: not identified).
"""

from __future__ import annotations

import math

import numpy as np

from ..results.profiles import Profile
from .optimum import Optimum, Target
from .parameters import Coordinate, Coordinates, factor
from .problem import Problem

#: kind -> (c, {i: a_i}, the coordinates it may replace, in order of preference)
MONOMIALS = {
    "tau_s": (0.0, {2: 2.0, 3: 1.0}, (3, 2)),
    "zeta_over_G_s_per_um2": (math.log(4.0), {0: -2.0, 3: 1.0}, (3, 0)),
    "viscous_length_um": (0.0, {0: 1.0, 2: 1.0}, (2, 0)),
}
UNITS = {"tau_s": "s", "zeta_over_G_s_per_um2": "s/um^2", "viscous_length_um": "um"}


def _y(i: int, z_i: float) -> float:
    return math.log(max(z_i, 1e-300)) if i == 2 else z_i


class Reparametrised(Problem):
    """The objective in coordinates w (one coordinate replaced), for local_fit; `fixed` are
    the user's held coordinates (unchanged by the reparametrisation)."""

    def __init__(self, obj, kind: str):
        self.obj, self.kind = obj, kind
        self.c, self.a, choices = MONOMIALS[kind]
        self.fixed = dict(obj.fixed)
        bounded = obj.user_bounded
        free = [k for k in choices if k not in self.fixed]
        # The user's bound on the replaced coordinate would not be a box in w: prefer an unbounded
        # one.
        free.sort(key=lambda k: k in bounded)
        self.k = free[0] if free else None  # None: the quantity is held fixed
        self.stretched = obj.stretched if self.k != 2 else ()
        if self.k is not None:  # w_k = ln q, searched a factor 100 either way
            own = Coordinate(kind, UNITS[kind], log=True, lower=0.0, window=factor(1e2), step=0.05)
            self.coordinates = Coordinates(
                tuple(own if i == self.k else c for i, c in enumerate(obj.coordinates))
            )
        if obj.wound_maps is not None:  # the wound's z through w (valleys.py)
            self.wound_maps = (self.to_z, self.to_w, False)
        #: The replaced coordinate carries a bound of the user's that is not a box in w (the
        #: others it depends on are not all fixed): the walk could not honour it.
        self.unenforceable = (
            bool(free)
            and free[0] in bounded
            and any(i not in self.fixed for i in self.a if i != free[0])
        )

    @property
    def size(self) -> int:
        return self.obj.size

    def value(self, z) -> float:
        return math.exp(self.c + sum(a * _y(i, z[i]) for i, a in self.a.items()))

    def to_z(self, w):
        z = np.array(w, dtype=float)
        k = self.k
        y = (w[k] - self.c - sum(a * _y(i, w[i]) for i, a in self.a.items() if i != k)) / self.a[k]
        z[k] = math.exp(y) if k == 2 else y
        return z

    def from_w(self, w):
        """The objective's z of w (optimum.profile maps a walk's point back with it)."""
        return self.to_z(w)

    def to_w(self, z):
        w = np.array(z, dtype=float)
        w[self.k] = math.log(self.value(z))
        return w

    def residuals(self, w):
        return self.obj.residuals(self.to_z(w))

    def jacobian(self, w, columns=None):
        """dr/dw by the chain rule, every column (`columns` is not used)."""
        z = self.to_z(w)
        k, dz = self.k, np.eye(len(w))
        dzk_dyk = z[k] if k == 2 else 1.0
        dz[k, k] = dzk_dyk / self.a[k]
        for i, a in self.a.items():
            if i != k:
                dz[k, i] = -(a / self.a[k]) * (1 / w[i] if i == 2 else 1.0) * dzk_dyk
        return self.obj.jacobian(z) @ dz

    def user_bound(self, i: int, side: int) -> bool:
        """The user's bound of the objective's coordinate i (mapped to w_k where it is a box
        in w: `bounds`)."""
        return self.obj.user_bound(i, side)

    def gradient(self, z) -> np.ndarray:
        """d w_k / d z: the row of dw/dz that differs from the identity."""
        g = np.zeros(len(z))
        for i, a in self.a.items():
            g[i] = a / z[i] if i == 2 else a
        return g

    def bounds(self):
        """The objective's bounds, w_k free; lambda > 0 where ln lambda enters (k != 2)."""
        lower, upper = self.obj.bounds()
        k = self.k
        if all(i in self.fixed for i in self.a if i != k):  # w_k = const + a_k y_k: a box in w too
            ends = []
            for zk in (lower[k], upper[k]):
                yk = (math.log(zk) if zk > 0 else -np.inf) if k == 2 else zk
                ends.append(
                    self.c
                    + sum(a * _y(i, self.fixed[i]) for i, a in self.a.items() if i != k)
                    + self.a[k] * yk
                    if math.isfinite(yk)
                    else math.copysign(np.inf, self.a[k] * yk)
                )
            lower[k], upper[k] = min(ends), max(ends)
        else:
            lower[k], upper[k] = -np.inf, np.inf
        if 2 in self.a and self.k != 2:
            lower[2] = max(lower[2], 1e-6)
        return lower, upper


def derived_profiles(optimum: Optimum) -> dict:
    """Profile (interval in the quantity's units) of tau, zeta/G and the viscous length,
    each walked by `optimum.profile` in the reparametrisation where it is a coordinate;
    with other optima below the threshold, the hull of the intervals walked from each."""
    obj = optimum.problem
    out = {}
    for kind in ("tau_s", "zeta_over_G_s_per_um2", "viscous_length_um"):
        centres = optimum.centres(optimum.threshold_of(kind))
        if kind != "zeta_over_G_s_per_um2" and obj.fixed.get(2) == 0.0:
            out[kind] = Profile(
                0.0, 0.0, False, [(0.0, 0.0)]
            )  # lambda held at 0: the quantity is 0
            continue
        if kind != "zeta_over_G_s_per_um2" and any(c[2] <= 1e-6 for c, _ in centres):
            out[kind] = Profile(0.0, None, True)
            continue
        rep = Reparametrised(obj, kind)
        if rep.k is None:  # every coordinate it depends on is fixed
            q = rep.value(optimum.z)
            out[kind] = Profile(q, q, False, [(q, 0.0)])
            continue
        if rep.unenforceable:  # not computed: the walk would leave the user's bounds
            continue
        out[kind] = optimum.profile(Target(rep.k, rep))
    return out
