"""Whether a profile's crossing stands: a valley beyond it, on the other branch.

The radius depends on (lambda, T) through two nearly invariant curves: with lambda large
(viscous regime, the tissue moves as one) mostly through tau = lambda^2 T = eta/G, with
lambda small (friction regime) through T = (zeta/G) R0^2 / 4. A profile walked by warm-
started fits stays on the branch it starts on; where the data are short (an opening 5 %
done at the last frame) the other branch can be a valley as low as the optimum, beyond a
barrier that the walk reports as an interval end (data with lambda = 10, T = 10 s: R0
walked down from the small-lambda optimum closed at 3.93 um, where a fit from the other
branch lies at delta chi^2 = 3.05 at 3.53 um; tests/python/test_valleys.py).

A crossing at v (the first profile point above the threshold; z_c the last inside point,
in the parameters z = (ln R0, sigma, lambda, ln T)) stands only if no constrained fit
beyond it, from starts on the other branch, falls back under the threshold. The starts
(`starts`), R0 and sigma those of z_c unless the profiled coordinate moves them:

    at v:     z_c moved to v keeping tau_c = lambda_c^2 T_c (lambda = sqrt(tau_c / T) where
              T moved, T = tau_c / lambda^2 where lambda moved), and keeping zeta_c (T moves
              with R0^2 where R0 moved);
    further:  z_c carried along a curve into the other regime: the viscous point (lambda =
              VISCOUS, T = tau_c / VISCOUS^2; with lambda_c < 1 also at tau = s_c, the time
              scale s_c = T_c (1 + lambda_c^2) the global grid pairs across regimes) and the
              friction point (lambda = 0, T = s_c), fitted at their own value of the
              profiled coordinate where that lies beyond v, else at v (not in lambda's
              own profile: at lambda = v a branch point is no longer on its branch, and
              the viscous point's T there lay orders of magnitude from any valley).

"Beyond" is in the profiled coordinate of the problem walked (ln R0, sigma, lambda, ln T, or
a derived ln q read through its reparametrisation): for R0 and sigma, which neither curve
moves, the other branch is tried at v itself; for lambda, ln T and a derived ratio also
where the curve takes it. A valley further than the walk's search limit (T = 10 s from an
estimate T = 8e4 s, limit x100) leaves that end open: the data do not bound it in the
search range. Each fit has at most BUDGET evaluations, so an ordinary crossing costs at most
five bounded fits, fewer in practice: a fit stops at its first point under the threshold
(that fit is then continued to its minimum, returned, and the walk goes on from it), and
where it comes within local.NEAR of where an earlier start's fit at the same value ended
above it (the same valley). Repeated starts are tried once. Problems without the four
parameters (several wounds) are not checked.

Where lambda's own profile is already walked, at a threshold no lower than the walk's
(`Walk.lambda_range`: its 95 % interval [lo, hi] in lambda, an open end None), no point with
lambda outside it lies under the threshold: the profile is the minimum over all the other
coordinates, and its own crossings passed this test. A start carried into the other regime
(`_other_branches`) at a lambda outside [lo, hi] then tests a regime that holds no valley,
and is skipped; the starts moved along tau or zeta within the branch are kept. A velocity
field pins lambda so: on bench/lab_movies' OpenPIV movie (R0 = 10 um, 24 pairs) lambda's
interval is [0.92, 1.06], the VISCOUS start (10) and the friction one (0) lie outside it,
and the fit's intervals came out the same to the last digit in 11.1 s instead of 15.8 s.
"""

from __future__ import annotations

import math

import numpy as np

from .._native import SolverError
from .local import local_fit

#: lambda of a start on the viscous branch: R depends on tau alone to ~1 / lambda^2.
VISCOUS = 10.0
#: Evaluations of each fit that tests a start (a valley shows within a few steps).
BUDGET = 60
#: A start nearer than this (in z) to the walk's own start at v adds nothing.
SAME = 0.05


def _with(z: np.ndarray, i: int, *values: float) -> np.ndarray:
    """z with coordinates i, i + 1, ... set to `values` (the others, nuisances too, kept)."""
    out = np.array(z, dtype=float)
    out[i : i + len(values)] = values
    return out


def _moved(zc: np.ndarray, z: np.ndarray) -> list[np.ndarray]:
    """z (zc with the profiled value set) with lambda or T moved to keep tau_c, or T to keep
    zeta_c; only those that differ from z."""
    tau = zc[2] ** 2 * math.exp(zc[3])
    out = []
    if abs(z[3] - zc[3]) > 1e-12 and tau > 0:  # T moved: lambda along tau = const
        out.append(_with(z, 2, math.sqrt(tau / math.exp(z[3]))))
    if abs(z[2] - zc[2]) > 1e-12 and z[2] > 0 and tau > 0:  # lambda moved: T along tau
        out.append(_with(z, 3, math.log(tau / z[2] ** 2)))
    if abs(z[0] - zc[0]) > 1e-12:  # R0 moved: T along zeta = 4 T / R0^2
        out.append(_with(z, 3, zc[3] + 2 * (z[0] - zc[0])))
    return [s for s in out if np.max(np.abs(s - z)) > 1e-6]


def _other_branches(zc: np.ndarray) -> list[np.ndarray]:
    """zc carried into the other regime: the viscous point at tau_c and, where lambda_c is
    small (tau_c says little), at the time scale s_c = T_c (1 + lambda_c^2) as its tau; the
    friction point (lambda = 0) at s_c."""
    lam, T = zc[2], math.exp(zc[3])
    s = T * (1 + lam**2)
    taus = [lam**2 * T] if lam >= 1 else [lam**2 * T, s]
    out = []
    if lam < VISCOUS:
        for k, tau in enumerate(taus):
            if tau > 0 and all(o <= 0 or abs(math.log(tau / o)) > math.log(2) for o in taus[:k]):
                out.append(_with(zc, 2, VISCOUS, math.log(tau / VISCOUS**2)))
    if lam > 0:
        out.append(_with(zc, 2, 0.0, math.log(s)))
    return out


def _excluded(s: np.ndarray, lambda_range) -> bool:
    """Whether the start s (in z) lies at a lambda outside lambda's interval (module docstring)."""
    if lambda_range is None:
        return False
    lo, hi = lambda_range
    return (lo is not None and s[2] < lo) or (hi is not None and s[2] > hi)


def starts(problem, i: int, w_in, v: float, direction: int, lambda_range=None):
    """(value, start) pairs in the problem's coordinates for a crossing at v of coordinate
    i, w_in the last point inside the threshold; [] for a problem without the four
    parameters. A value may lie beyond the walk's limit (the caller's to judge). The other
    regime's starts outside `lambda_range` (lambda's interval, or None) are left out."""
    if problem.wound_maps is None:
        return []
    to_z, to_w, plain = problem.wound_maps
    lower, upper = problem.bounds()
    w_in = np.asarray(w_in, dtype=float)
    at_v = w_in.copy()
    at_v[i] = v
    out = []
    try:
        zc, z_v = to_z(w_in), to_z(at_v)
        candidates = [(v, s) for s in _moved(zc, z_v)]
        for s in _other_branches(zc):
            if _excluded(s, lambda_range):
                continue  # a regime lambda's own profile excludes
            w = to_w(s)
            if direction * (w[i] - v) > 0:  # the other branch lies beyond the crossing
                candidates.append((w[i], s))
            elif not (plain and i == 2):  # lambda itself tells the branches apart
                w[i] = v
                if not _excluded(moved := to_z(w), lambda_range):
                    candidates.append((v, moved))
        for u, s in candidates:
            if u == v and np.max(np.abs(s - z_v)) < SAME:
                continue  # the walk's own start, near enough
            w = to_w(s)
            if np.all(np.isfinite(w)) and lower[i] <= u <= upper[i]:
                w = np.clip(w, lower, upper)
                if not any(u == o and np.array_equal(w, ow) for o, ow in out):  # no repeats
                    out.append((u, w))
    except (ValueError, OverflowError, ZeroDivisionError):
        pass
    return out


def beyond(walk, w_in, v, direction, w_v=None):
    """For the profile `walk` (intervals.Walk) crossing at v from w_in: the first start of
    `starts` whose constrained fit (at most BUDGET evaluations) falls below its chi^2 at the
    threshold, chi2_max: (value, w, chi^2) of the fit continued from its first point below, or
    None (the crossing stands). A fit stops at its first point below chi2_max, and where it
    comes near where an earlier fit at the same value ended above it (local.py): an earlier
    start's, or at v the walk's own (`w_v`)."""
    problem, i, loss = walk.problem, walk.i, walk.loss
    chi2_max = walk.chi2_min + walk.threshold
    ends: dict[float, list] = {v: [] if w_v is None else [w_v]}
    for u, w0 in starts(problem, i, w_in, v, direction, walk.lambda_range):
        known = ends.setdefault(u, [])
        try:
            w, chi2, res = local_fit(
                problem,
                w0,
                fixed=i,
                value=u,
                loss=loss,
                tol=1e-7,
                max_nfev=BUDGET,
                below=chi2_max,
                ends=known,
            )
            if chi2 < chi2_max:
                w, chi2, _ = local_fit(problem, w, fixed=i, value=u, loss=loss, tol=1e-7)
                return u, w, chi2
        except SolverError:
            continue
        if res.status > 0:  # converged above the threshold: a later start reaching it stops
            known.append(w)
    return None
