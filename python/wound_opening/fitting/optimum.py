"""The optimum of a fit, and every profile interval walked from it.

An `Optimum` holds what the intervals need of a finished fit: the (constrained) problem
with its named coordinates, the best point z, its chi^2 and loss, the interval threshold
(and the thresholds of their own that lambda's bound gives some quantities: bounds.py), the
Jacobian's covariance in z, and the other local optima a profile may reach (alternates).
Its one `profile(target)` walks every interval, one wound's or several's, of a parameter or
of a derived quantity:

    target                                walked
    Target(k)                             coordinate k of the optimum's problem
    Target(k, problem=reparametrisation)  coordinate k of a problem in which a derived
                                          quantity is a coordinate (derived.py: tau, zeta/G,
                                          the viscous length; wound_profiles.py: eta/G)

For the target's coordinate w_k (with A = d w / d z, identity but for row k):

    cov_w = A cov A^T,    first step = se(w_k) (the coordinate's own step where the Jacobian
                          gives none), clipped to 1/100 .. 20 times that step,
    slope = cov_w[:, k] / cov_w[k, k]   (the other coordinates' start prediction)

and the walk (intervals.walk_side) runs from the optimum and from every alternate below the
threshold to the search window the coordinate declares (parameters.py), narrowed to the
problem's bounds; an end on a bound of the user's is that bound. Once lambda's own profile
is walked, its interval (`lambda_range`, in z) goes with every later walk whose threshold is
no higher than lambda's: the valley search then skips the regimes it excludes (valleys.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..results.profiles import Profile
from .intervals import BetterOptimum, Walk, hull, profile_at
from .problem import Problem

#: Times a fit settles again from a better optimum its walks found, at most.
RESTARTS = 2


def profiled(settle_at, profile_all, starts):
    """(optimum, verdict, profiles) of a fit: `settle_at(starts)` gives (Optimum, Verdict)
    (stages.settle), `profile_all(optimum, verdict)` the profiles. Where a walk finds a fit
    below the optimum (intervals.BetterOptimum), the fit settles again from that point and the
    previous optimum, and every interval is walked again from the new optimum, at most
    RESTARTS times; the last round's walks count a lower fit as delta chi^2 = 0. The previous
    optimum's other local optima (alternates) are starts again too, so that a valley the first
    starts found stays one the walks start from."""
    for left in range(RESTARTS, -1, -1):
        optimum, judged = settle_at(starts)
        optimum.restart = left > 0
        try:
            return optimum, judged, profile_all(optimum, judged)
        except BetterOptimum as better:
            starts = [better.z, optimum.z, *(a for a, _ in optimum.alternates)]
    raise AssertionError("unreachable: the last round does not restart")


@dataclass(frozen=True)
class Target:
    """What a profile walks: coordinate `k` of `problem` (a reparametrisation of the
    optimum's problem with `to_w` and `gradient`), or of the optimum's own problem."""

    k: int
    problem: Problem | None = None


@dataclass
class Optimum:
    """A fit's optimum (module docstring): `problem` (its `coordinates` by name), `z`,
    `chi2`, `loss`, `threshold`, `cov` (the Jacobian's covariance in z, rows and columns
    of held coordinates 0), `alternates` ((z, delta chi^2) of other local optima) and
    `thresholds` (name -> a threshold of its own)."""

    problem: Problem
    z: np.ndarray
    chi2: float
    loss: str
    threshold: float
    cov: np.ndarray
    alternates: list = field(default_factory=list)
    thresholds: dict = field(default_factory=dict)
    #: lambda's interval (lo, hi) in z and its threshold, once its profile is walked
    lambda_walked: tuple | None = None
    #: a walk's fit below chi2 (intervals.BETTER) raises BetterOptimum (z in this problem's
    #: coordinates): the fit settles again from there (`profiled`)
    restart: bool = False

    def target(self, name: str) -> Target:
        """The optimum's own coordinate `name`."""
        return Target(self.problem.coordinates.index(name))

    def threshold_of(self, name: str) -> float:
        return self.thresholds.get(name) or self.threshold

    def centres(self, threshold: float) -> list:
        """The optimum and the alternates below `threshold`, (z, delta chi^2)."""
        return [(self.z, 0.0)] + [(a, d) for a, d in self.alternates if d < threshold]

    def profile(self, target: Target) -> Profile:
        """The profile interval of `target` in its own units (module docstring); a
        coordinate the user holds fixed is its value."""
        problem = target.problem or self.problem
        k = target.k
        coordinate = problem.coordinates[k]
        if target.problem is None and k in problem.fixed:
            v = problem.spec.fixed[k]  # as given
            return Profile(v, v, False, [(v, 0.0)])
        own = self.thresholds.get(coordinate.name)
        threshold = own or self.threshold
        mapped = target.problem is not None
        centres = [(problem.to_w(c) if mapped else c, d) for c, d in self.centres(threshold)]
        w_hat = centres[0][0]
        a = np.eye(self.z.size)
        if mapped:
            a[k] = problem.gradient(self.z)
        cov = a @ self.cov @ a.T
        default = coordinate.first_step(w_hat)
        se = math.sqrt(max(cov[k, k], 0.0))
        slope = np.nan_to_num(cov[:, k] / cov[k, k]) if cov[k, k] > 0 else np.zeros(self.z.size)
        slope[k] = 1.0
        step = float(
            np.clip(se if math.isfinite(se) and se > 0 else default, default * 0.01, default * 20)
        )
        box = problem.bounds()

        def side_limit(centre, direction):
            side = 0 if direction < 0 else 1
            lo, hi = coordinate.window(centre, w_hat, k)
            limit = max(lo, box[0][k]) if side == 0 else min(hi, box[1][k])
            return limit, bool(problem.user_bound(k, direction) and limit == box[side][k])

        known = self.lambda_walked
        lambda_range = known[0] if known is not None and known[1] >= threshold else None
        walk = Walk(
            problem, k, self.chi2, threshold, step, slope, self.loss, lambda_range, self.restart
        )
        try:
            lo, hi, walked, bounded = hull(walk, centres, side_limit)
        except BetterOptimum as better:
            if mapped:
                better.z = problem.from_w(better.z)
            raise
        if target.problem is None and coordinate.name == "lambda" and problem.wound_maps:
            self.lambda_walked = ((lo, hi), threshold)
        at_bound = coordinate.closed and lo is None  # lambda, l: the interval reaches 0
        points = [(w_hat[k], 0.0)] + walked
        return Profile(
            coordinate.lower if at_bound else None if lo is None else coordinate.own(lo),
            None if hi is None else coordinate.own(hi),
            at_bound,
            sorted((coordinate.own(v), d) for v, d in points),
            tuple(bounded),
            own,
        )

    def profile_at(self, i: int, values, max_nfev: int = 100) -> np.ndarray:
        """delta chi^2 at `values` of coordinate i (in z), each a fit of the others
        (intervals.profile_at): the figure's profile panels."""
        return profile_at(self.problem, self.z, self.chi2, i, values, self.loss, max_nfev)
