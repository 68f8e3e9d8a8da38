"""The profile walker: for one coordinate of a problem (a `Walk`, which optimum.Optimum.profile
builds), chi^2 minimised over the other coordinates at fixed values of it, walked outward
from the estimate on both sides until it rises by the threshold (3.84, or the F quantile
with an estimated noise) or a search limit is reached.

```text
delta(v) = min over the others of chi^2 - chi^2_min,   95 % interval = { v : delta(v) < threshold }
```

sqrt(delta) is close to linear in the parameter near the optimum: the first point is aimed
at the crossing a quadratic profile with the Jacobian's standard error has (sqrt(threshold)
standard errors), each next one just beyond the crossing predicted by the line through the
last two (a move between 1/100 and 4 times the previous one), and the bracketed crossing is
refined by regula falsi on sqrt(delta) (`crossing`: each refining fit starts from the
interpolation of the fits at the bracket's ends, which lie in the same valley). Each point
is a fit of the other three from a predicted start, at tolerances 1e-7: a looser relative
cost change (1e-5) lets fits on the flat, curved valleys of plateau-only data stop short
and report false crossings.
The search limits are the coordinate's window (parameters.py; one wound: lambda from its
bound 0, where an interval [0, hi] is closed, to LAMBDA_MAX, ln T and ln R0 a factor 100 and
3, sigma 10 |sigma| + 1 from the estimate). An end that reaches such a search limit is open
(None): the data do not bound it.
An end that reaches a bound of the user's (parameters.py) is that bound (`bounded`), as an
estimate on such a bound gives that end. Parameters the user holds fixed are not profiled.
A crossing stands only if no fit beyond it from the other branch (valleys.py: along
lambda^2 T = const and zeta = const) falls back under the threshold; else the walk goes on
from that fit.
A walk's fit that lands BETTER or more below the optimum's chi^2 has found a better optimum:
where the fit allows it (`Walk.restart`) the walk stops with BetterOptimum, and the fit
settles again from there (optimum.profiled) rather than measure the intervals against a
minimum that is not one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._native import SolverError
from .local import local_fit
from .problem import Problem
from .valleys import beyond

#: An interval end is located to where sqrt(delta chi^2) is within this fraction of the
#: threshold's square root (delta within ~2e-3 of the threshold, relative).
ROOT_TOL = 1e-3
#: ... or to a bracket across which sqrt(delta) changes by less than this fraction of it.
BRACKET = 0.05
#: A fit confirming a crossing (tolerances 1e-10, rounds of 400 evaluations) stops once a
#: round lowers chi^2 by less than this: the end then moves by a negligible ~CONFIRM / 3.84
#: of the threshold.
CONFIRM = 0.01
#: Refining steps of a bracketed end at most (regula falsi, bisection where it creeps).
REFINE = 16
#: A walk's point whose fit is unsure (it ran out of evaluations, or put R0 or T on a search
#: bound) ends the side open; before that, the step is cut to a tenth this many times: a
#: first step aimed by a standard error that a coordinate at its bound inflates (the cut
#: of a fit whose cut sits at frame N) can land far beyond the crossing, where the fits
#: are unsure though the data are not.
UNSURE_RETRIES = 3
#: A walk's fit whose chi^2 lies this far or more below the optimum's found a better optimum
#: than the fit's (a start in another valley, a fit that stopped short): the intervals are
#: then walked again from it (BetterOptimum), not measured against a minimum that is not one.
BETTER = 0.05


class BetterOptimum(Exception):
    """A profile walk's fit below the optimum's chi^2 by BETTER or more: `z` (in the walked
    problem's coordinates) and its `chi2`. Raised where the walk allows it (Walk.restart)."""

    def __init__(self, z: np.ndarray, chi2: float):
        super().__init__(f"a profile fit reached chi^2 {chi2:.6g}, below the optimum's")
        self.z, self.chi2 = np.asarray(z, dtype=float), float(chi2)


def _on_search_bound(obj, z: np.ndarray, fixed: int) -> bool:
    """Whether ln R0 or ln T (coordinates 0 and 3, other than the profiled one) lies on its
    search bound (Objective.bounds: R0 from 1 % of the smallest radius to the outer radius /
    1.001, T within 1e-6 .. 1e6 of the last time). Those bounds are not physical: a profile
    fit held there rises because of the bound (plateau-only data with R0 -> 0 and
    sigma -> infinity at fixed R0 sigma), so the rise does not bound the parameter."""
    lower, upper = obj.bounds()
    return any(k != fixed and not (lower[k] + 1e-6 < z[k] < upper[k] - 1e-6) for k in (0, 3))


@dataclass(frozen=True)
class Walk:
    """What one profile walk holds fixed: coordinate `i` of `problem` profiled against the
    optimum's chi^2 (`chi2_min`) up to `threshold`, its first move `step` (times the
    threshold's square root) and the other coordinates' prediction `slope` (d z / d z_i, the
    Jacobian's regression line), fits under `loss`; `lambda_range`: lambda's own interval
    where it is walked already at a threshold no lower (valleys.py), else None. Built by
    optimum.Optimum.profile."""

    problem: Problem
    i: int
    chi2_min: float
    threshold: float
    step: float
    slope: np.ndarray
    loss: str = "linear"
    lambda_range: tuple | None = None
    #: raise BetterOptimum where a fit falls BETTER below chi2_min (else it counts as 0)
    restart: bool = False

    def below(self, z, chi2: float) -> None:
        """Raise BetterOptimum if the fit at z lies BETTER or more below the optimum."""
        if self.restart and chi2 < self.chi2_min - BETTER:
            raise BetterOptimum(z, chi2)


def walk_side(walk: Walk, z_hat, direction: int, limit: float, delta0: float = 0.0):
    """Walk one side from the optimum z_hat (delta chi^2 `delta0` above the best) towards
    `limit`; return (end in z coordinates or None, at limit, points).

    Each constrained fit starts from a prediction of the other parameters: along the
    Jacobian's regression line `slope` (d z / d z_i) for the first step, then extrapolated
    from the last two profile points (the profile of lambda at fixed tau = lambda^2 T bends
    T strongly: a start at the previous point alone can end in a worse local minimum)."""

    obj, i, chi2_min, threshold = walk.problem, walk.i, walk.chi2_min, walk.threshold
    loss, slope = walk.loss, walk.slope
    root = math.sqrt(threshold)
    path = [(z_hat[i], z_hat)]

    def start(v):
        (v1, z1) = path[-1]
        if len(path) >= 2 and path[-2][0] != v1:
            v0, z0 = path[-2]
            move = (z1 - z0) * (v - v1) / (v1 - v0)
        else:
            move = slope * (v - v1)
        return z1 + np.clip(move, -1.0, 1.0)  # at most a factor e in R0, T; 1 in sigma, lambda

    def constrained(v, bracket=None):
        """chi^2 at fixed v from the predicted start; where that looks like a crossing, also
        from the last profile point, keeping the lower (a false crossing would shorten the
        interval; the second fit stops where it reaches the first one's end if that one
        converged, local.py).
        Inside a bracket being refined (`bracket`: the fitted points (za, zb) at its ends,
        za inside) the start is their interpolation at v and the second start za. A
        crossing found by fits that ran out of evaluations (a flat, curved valley they
        crawl along) is not trusted: `unsure` ends the walk with an open end.
        The fits at tolerances 1e-7 can stop short on such a valley with a converged status
        (early-time data: Delta chi^2 = 5.7 where the minimum is 0.02), so a crossing is
        confirmed by fits at 1e-10 continued while they lower chi^2 by CONFIRM or more.
        Neither is a point whose fit puts R0 or T on a search bound (`_on_search_bound`):
        the bound, not the data, then holds the profile."""
        if bracket is None:
            first, second = start(v), path[-1][1]
        else:
            (a, za), (b, zb) = bracket
            first, second = za + (zb - za) * (v - a) / (b - a), za
        z, chi2, res = local_fit(obj, first, fixed=i, value=v, loss=loss, tol=1e-7)
        unsure = False
        if chi2 - chi2_min >= threshold:
            z2, chi2b, res2 = local_fit(
                obj,
                second,
                fixed=i,
                value=v,
                loss=loss,
                tol=1e-7,
                ends=[z] if res.status > 0 else [],
            )
            if chi2b < chi2:
                z, chi2, res = z2, chi2b, res2
            for _ in range(3):  # a crossing stands only where a fit at tolerances 1e-10 confirms it
                z3, chi2c, res3 = local_fit(
                    obj, z, fixed=i, value=v, loss=loss, tol=1e-10, max_nfev=400
                )
                drop = chi2 - chi2c
                if chi2c < chi2:
                    z, chi2, res = z3, chi2c, res3
                if chi2 - chi2_min < threshold or res3.status > 0 or drop < CONFIRM:
                    break
            unsure = res.status == 0
        walk.below(z, chi2)
        return z, max(chi2 - chi2_min, 0.0), unsure or _on_search_bound(obj, z, i)

    def refused_open(v, bracket=None):  # a point the solver refuses ends the walk, open
        try:
            return constrained(v, bracket)
        except SolverError:
            return path[-1][1], math.inf, True

    prev_v, prev_s = z_hat[i], math.sqrt(delta0)
    move = (
        walk.step * root
    )  # aimed at the crossing of a quadratic profile with the Jacobian's error
    points, retries = [], 0
    for _ in range(16 + UNSURE_RETRIES):
        v = prev_v + direction * move
        v = min(v, limit) if direction > 0 else max(v, limit)
        z, delta, unsure = refused_open(v)
        points.append((v, delta))
        if unsure and retries < UNSURE_RETRIES:  # too far to be sure: a tenth of the step
            retries += 1
            move *= 0.1
            continue
        if unsure:
            return None, True, points
        if delta >= threshold:  # a crossing stands if no valley lies beyond it (valleys.py)
            found = beyond(walk, path[-1][1], v, direction, z)
            if found is None:
                s = math.sqrt(delta)
                ends = (path[-1][1], z)
                return crossing(
                    refused_open, points, prev_v, prev_s - root, v, s - root, root, ends
                )
            walk.below(found[1], found[2])
            v, z, delta = found[0], found[1], max(found[2] - chi2_min, 0.0)
            points.append((v, delta))
            if direction * (v - limit) >= 0:  # a valley at or past the search limit: open
                return None, True, points
            path[:], slope = [], np.eye(len(z))[i]  # from there, moving coordinate i alone
        s = math.sqrt(delta)
        if v == limit:
            return None, True, points
        rate = (s - prev_s) / abs(v - prev_v)
        # just beyond the crossing predicted by the line through the last two points
        want = ((1 + 5 * ROOT_TOL) * root - s) / rate if rate > 0 else 4 * move
        move = min(max(want, 0.01 * move), 4 * move)
        prev_v, prev_s = v, s
        path.append((v, z))
    return None, True, points


def crossing(constrained, points, a, fa, b, fb, root, ends=(None, None)):
    """The end between a (inside, fa = sqrt(delta) - root < 0) and b (outside, fb >= 0):
    regula falsi with the Illinois modification on sqrt(delta), which is close to linear in
    the parameter, until sqrt(delta) is within ROOT_TOL of the threshold's (delta within
    2 ROOT_TOL of it, relative) or the bracket spans less than BRACKET of it; then the line
    through the bracket (for sqrt(delta) = |v - v0| (1 + c (v - v0)) / se its error is
    ~ c (b - a)^2 / 4, below 1e-3 se for a bracket of 5 % and a skewness c se < 1).
    Where the profile is far from linear (a wall: delta rising from ~0 to 1e3 within the
    bracket, as where R0 passes the first measured radius) the secant creeps from the inside
    end: after two steps that keep the same end the next bisects, so the bracket at least
    halves every third step. A bracket not located within REFINE steps ends at its
    outside end b (delta >= threshold there: the interval is never cut inside the region the
    data allow). `ends`: the fitted points at a and b; each refining fit starts from their
    interpolation (`constrained(c, bracket)`), and its point becomes the new end's. Returns
    (end, False, points) or (None, True, points) if a refining fit is unsure."""
    last, repeat, wa, wb = 0, 0, fa, fb  # wa, wb: the Illinois-weighted values the secant uses
    za, zb = ends
    for _ in range(REFINE):
        if min(-fa, fb) < ROOT_TOL * root or fb - fa < BRACKET * root:
            return a + (b - a) * (-fa) / (fb - fa), False, points
        c = 0.5 * (a + b) if repeat >= 2 else a + (b - a) * (-wa) / (wb - wa)
        zc, dc, unsure = constrained(c, None if za is None else ((a, za), (b, zb)))
        if unsure:
            return None, True, points
        points.append((c, dc))
        fc = math.sqrt(dc) - root
        side = -1 if fc < 0 else 1
        repeat = repeat + 1 if side == last else 0
        last = side
        if side < 0:
            a, fa, wa, za = c, fc, fc, zc
            wb *= 0.5 if repeat == 1 else 1.0
        else:
            b, fb, wb, zb = c, fc, fc, zc
            wa *= 0.5 if repeat == 1 else 1.0
    return b, False, points


def hull(walk: Walk, centres, side_limit):
    """The profile interval of `walk`'s coordinate k, walked by walk_side down and up from
    every optimum of `centres` ((coordinates, delta chi^2), the best first; another optimum
    below the threshold may lie in a second valley, past a barrier above it): an optimum
    inside the interval found so far adds nothing, and the hull of the ends is reported.
    `side_limit(centre, direction)` gives the search limit of that side and whether it is
    the user's bound (an end there is the user's, not the data's).

    Returns (lower, upper, points, (lower end by the user's bound, upper end by it)); an
    end is None where that side is open."""
    k = walk.i
    ends = {-1: [], 1: []}
    bounded = {-1: False, 1: False}
    points = []
    for centre, delta0 in centres:
        for direction in (-1, 1):
            got = ends[direction]
            if got and (got[0] is None or direction * (centre[k] - got[0]) <= 0):
                continue  # an optimum inside the interval found (or an open end)
            limit, mine = side_limit(centre, direction)
            if direction * (limit - centre[k]) <= 0:  # the optimum on its limit
                got.append(limit if mine else None)
                bounded[direction] |= mine
                continue
            end, _, pts = walk_side(walk, centre, direction, limit, delta0)
            if mine and end is None and pts and pts[-1][0] == limit and pts[-1][1] < walk.threshold:
                end = limit  # the walk reached the user's bound inside the threshold
                bounded[direction] = True
            got.append(end)
            points += pts
    lower = None if None in ends[-1] else min(ends[-1])
    upper = None if None in ends[1] else max(ends[1])
    return lower, upper, points, (bounded[-1], bounded[1])


#: A rise of delta chi^2 between neighbouring values of profile_at beyond which the value is
#: also fitted from the estimate (a start in a higher valley gives such jumps).
JUMP = 1.0


def profile_at(
    obj: Problem,
    z_hat: np.ndarray,
    chi2_min: float,
    i: int,
    values,
    loss: str = "linear",
    max_nfev: int = 100,
) -> np.ndarray:
    """delta chi^2 at the given values of coordinate i of z (ln R0, sigma, lambda, ln T):
    each a fit of the other three with coordinate i fixed, as the walks above make them.
    The values are visited outward from the estimate on each side; each is fitted from the
    previous value's optimum moved along the line through the last two (as `walk_side`
    predicts), and where that fit does not converge or delta jumps by more than JUMP from the
    previous value, also from the previous optimum itself and then from the estimate,
    keeping the lowest (a start equal to one tried is not fitted again, and one whose fit
    reaches where an earlier one at that value ended stops there): one start alone can
    end in a higher valley and draw a spike. A value
    whose fits all stop without converging within `max_nfev` evaluations, or that the solver
    refuses, gives nan (its chi^2 would only bound the profile from above). For drawing a
    profile finely; the intervals come from `optimum.Optimum.profile`."""

    values = np.asarray(values, dtype=float)
    out = np.full(values.size, np.nan)
    for side in (np.flatnonzero(values >= z_hat[i]), np.flatnonzero(values < z_hat[i])):
        side = side[np.argsort(np.abs(values[side] - z_hat[i]), kind="stable")]
        path = [(z_hat[i], np.asarray(z_hat, dtype=float))]
        prev = -1
        for k in side:
            v = values[k]
            (v1, z1) = path[-1]
            move = (
                (z1 - path[-2][1]) * (v - v1) / (v1 - path[-2][0])
                if len(path) >= 2 and path[-2][0] != v1
                else 0
            )
            best, tried, ended = None, [], []
            for start in (z1 + np.clip(move, -1.0, 1.0), z1, z_hat):
                if best is not None and best[1] - chi2_min < JUMP + (out[prev] if prev >= 0 else 0):
                    break
                if any(np.array_equal(start, s) for s in tried):
                    continue  # the same start gives the same fit
                tried.append(start)
                try:
                    z, chi2, res = local_fit(
                        obj,
                        start,
                        fixed=i,
                        value=v,
                        loss=loss,
                        tol=1e-7,
                        max_nfev=max_nfev,
                        ends=ended,
                    )
                except SolverError:
                    continue
                if res.status > 0:
                    ended.append(z)  # a later start that reaches it ends there (local.py)
                    if best is None or chi2 < best[1]:
                        best = (z, chi2)
            if best is not None:
                out[k] = max(best[1] - chi2_min, 0.0)
                path.append((v, best[0]))
                prev = k
    return out
