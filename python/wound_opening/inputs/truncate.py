"""A radius that shrinks again, and the selection of the opening alone.

A passive opening only opens: the model's R(t) rises monotonically from R1 to R_final. A wound
whose radius falls again after its maximum is closing actively (a purse string, cell crawling),
which the model does not describe; fitted whole it gives a negative tension or an opening
larger than the tissue.

The decision is made with the noise s of the radii: 1.4826 x the median absolute deviation
of the second differences / sqrt(6) (var(d2) = 6 s^2), or the noise given (the median of the
per-point uncertainties) where that is larger: a point is "below" when it lies more than

    h = s (sqrt(2 ln n) + 3)

under the running maximum of the points before it (the maximum of n noisy points on a
plateau exceeds the plateau by about s sqrt(2 ln n); 3 s more below that is P = 0.00135 for
one point), and the radius shrinks when RUN = 3 consecutive points are below (P ~ 2.5e-9 per
place on a plateau of pure noise). Both the points and the running maximum are those of the
radius smoothed by a running median of SMOOTH = 5 points, so that one or two outliers (a
segmentation error) neither raise the maximum nor make a decrease. `until_max` keeps the
points up to the maximum of the smoothed radius before the first such run; `until_s` keeps
the points at or before a time. Either says in RadiusSeries.note which file lines (or rows)
were kept and dropped; the fit's warnings repeat it."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from .series import RadiusSeries, VelocityProfile

#: Consecutive points below the running maximum that make a sustained decrease.
RUN = 3
#: Points of the running median that smooths the radius for the maximum `until_max` keeps.
SMOOTH = 5


@dataclass(frozen=True)
class Shrinking:
    """A sustained decrease: rows (0-based, in time order) of the maximum and of the points
    below it after the first run, the largest drop [um], the threshold h and the noise s."""

    peak: int
    below: np.ndarray
    drop_um: float
    threshold_um: float
    noise_um: float


def noise_of(radius: RadiusSeries) -> float:
    """The radii's noise [um]: robust from the second differences, or the noise given (the
    median uncertainty) where that is larger; a given noise smaller than the scatter must
    not turn the scatter of a plateau into a decrease."""
    given = 0.0
    if radius.noise_um is not None:
        given = float(radius.noise_um)
    elif radius.sd_um is not None:
        given = float(np.median(radius.sd_um))
    r = _ordered(radius)[1]
    if r.size < 4:
        return given
    d2 = np.diff(r, 2)
    return max(given, 1.4826 * float(np.median(np.abs(d2 - np.median(d2)))) / math.sqrt(6))


def _ordered(radius: RadiusSeries):
    t = np.asarray(radius.times_s, dtype=float)
    order = np.argsort(t, kind="stable")
    return order, np.asarray(radius.radius_um, dtype=float)[order]


def shrinking(radius: RadiusSeries) -> Shrinking | None:
    """The sustained decrease of the radius after its maximum, or None (module docstring)."""
    order, r = _ordered(radius)
    n = r.size
    s = noise_of(radius)
    h = max(s * (math.sqrt(2 * math.log(max(n, 2))) + 3), 1e-9 * float(np.max(r)))
    half = SMOOTH // 2
    smooth = np.array([np.median(r[max(0, k - half) : k + half + 1]) for k in range(n)])
    running = np.maximum.accumulate(smooth)
    below = np.zeros(n, dtype=bool)
    below[1:] = running[:-1] - smooth[1:] > h
    runs = np.convolve(below.astype(int), np.ones(RUN, dtype=int), "valid") == RUN
    if not runs.any():
        return None
    start = int(np.flatnonzero(runs)[0])
    peak = int(np.argmax(smooth[:start])) if start else 0
    after = np.flatnonzero(below[start:]) + start
    return Shrinking(peak, after, float(running[-1] - smooth[after].min()), h, s)


def _row_names(radius: RadiusSeries, rows_in_order: np.ndarray) -> str:
    """'lines 52-61' (file lines) or 'rows 50-59' (1-based) of the rows given in time order."""
    order = _ordered(radius)[0]
    k = order[rows_in_order]
    if radius.lines is not None:
        numbers, what = np.asarray(radius.lines)[k], "line"
    else:
        numbers, what = k + 1, "row"
    lo, hi = int(numbers.min()), int(numbers.max())
    return f"{what} {lo}" if lo == hi else f"{what}s {lo}-{hi}"


def describe(radius: RadiusSeries, found: Shrinking) -> str:
    """The frames where the radius shrinks, for an error message."""
    t = np.asarray(radius.times_s, dtype=float)[_ordered(radius)[0]]
    r = _ordered(radius)[1]
    return (
        f"the radius shrinks again after its maximum {r[found.peak]:.4g} um at "
        f"{t[found.peak]:.4g} s ({_row_names(radius, np.array([found.peak]))}): "
        f"{found.below.size} later points ({_row_names(radius, found.below)}, "
        f"{t[found.below[0]]:.4g}-{t[found.below[-1]]:.4g} s) lie more than "
        f"{found.threshold_um:.3g} um below the largest radius before them (running medians "
        f"of {SMOOTH}; up to "
        f"{found.drop_um:.3g} um; noise {found.noise_um:.3g} um): the wound closes actively, "
        "which the passive opening the model describes cannot do"
    )


def until_s(
    radius: RadiusSeries, profile: VelocityProfile | None, t_s: float, why: str = "--until-s"
):
    """(radius, profile) at times <= t_s [s since the cut], the radius's note saying which
    rows were kept and dropped."""
    if not (math.isfinite(t_s) and t_s > 0):
        raise ValueError(f"{why} {t_s:g}: the last time to fit must be finite and > 0 s")
    order = _ordered(radius)[0]
    t = np.asarray(radius.times_s, dtype=float)
    keep = np.flatnonzero(t[order] <= t_s)
    drop = np.flatnonzero(t[order] > t_s)
    if keep.size < 5:
        raise ValueError(
            f"{why} {t_s:g} s keeps {keep.size} radius points (the first at "
            f"{t[order][0]:.4g} s): need at least 5"
        )
    note = f"fitted {_row_names(radius, keep)} (t <= {t_s:.4g} s)"
    note += (
        f"; dropped {_row_names(radius, drop)} ({t[order][drop[0]]:.4g}-{t[order][-1]:.4g} s) "
        f"({why})"
        if drop.size
        else f"; nothing dropped ({why})"
    )
    rows = order[keep]
    sd = None if radius.sd_um is None else np.asarray(radius.sd_um)[rows]
    lines = None if radius.lines is None else np.asarray(radius.lines)[rows]
    kept = replace(
        radius,
        times_s=np.asarray(radius.times_s, dtype=float)[rows],
        radius_um=np.asarray(radius.radius_um, dtype=float)[rows],
        sd_um=sd,
        lines=lines,
        note=note,
    )
    if profile is not None:
        total = np.size(profile.r_um)
        sel = np.flatnonzero(np.asarray(profile.times_s, dtype=float) <= t_s)
        if sel.size == 0:
            raise ValueError(f"{why} {t_s:g} s keeps no point of the velocity profile")
        if sel.size < total:
            profile = replace(
                profile,
                times_s=np.asarray(profile.times_s, dtype=float)[sel],
                r_um=np.asarray(profile.r_um, dtype=float)[sel],
                velocity_um_s=np.asarray(profile.velocity_um_s, dtype=float)[sel],
                sd_um_s=None if profile.sd_um_s is None else np.asarray(profile.sd_um_s)[sel],
                lines=None if profile.lines is None else np.asarray(profile.lines)[sel],
            )
            kept = replace(kept, note=note + f"; profile: {sel.size} of {total} points kept")
    return kept, profile


def until_max(radius: RadiusSeries, profile: VelocityProfile | None = None):
    """(radius, profile) up to the maximum radius before a sustained decrease (module
    docstring); unchanged but for a note when the radius does not shrink."""
    found = shrinking(radius)
    t = np.asarray(radius.times_s, dtype=float)[_ordered(radius)[0]]
    if found is None:
        return replace(radius, note="--until-max: the radius does not shrink; every row fitted"), (
            profile
        )
    return until_s(radius, profile, float(t[found.peak]), "--until-max")
