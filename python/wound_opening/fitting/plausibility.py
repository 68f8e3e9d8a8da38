"""Is the fitted opening one the sampling resolves, and a time scale a laser-ablation recoil has?

After the cut the wound jumps to R1 = R0 (1 + sigma/6) and opens towards
R_final = R0 (1 + (2 sigma / 3) k), k = R_inf^2 / (R_inf^2 - 1). The fitted model's fraction
of that opening done at time t,

    f(t) = (R(t) - R1) / (R_final - R1),

says what the samples can see:

- f above DONE_AT_FIRST at the first sampled time after the cut: the data show the end of the
  opening only, and its time scale is bounded rather than measured;
- f below DONE_AT_LAST at the last sampled time: the recording ends during the opening, and
  R_final and the time scale are extrapolated.

These name what the data lack; the half-opening time of the fitted curve is quoted with them
only where the slower time scale max(T, tau) is identified (a finite 95 % interval on both
sides): the half-opening time of an estimate the data do not bound says nothing.

A uniform rescaling of every time (milliseconds read as seconds) rescales the fitted time
scales with the sampling and leaves f at the samples unchanged, so the sampling cannot reveal
it. The time scales themselves can: T = zeta R0^2 / 4G (friction) and tau = lambda^2 T = eta / G
(viscous relaxation) of an ablated epithelium are seconds to minutes, so max(T, tau) above
LONGEST_S (one hour) is warned about.

The ms question is asked only of a time scale the data identify (a finite 95 % interval on
both sides); for one they do not, the warning says what the data lack instead (the recording
ends during the opening: bounded below only; the opening is over before the first samples:
bounded above only).

Each finding is a warning in FitResult.warnings, not a refusal: the estimate may be right.
The recording itself is checked before any fit (`check_recording`, recording.py): a span or
frame interval no laser-ablation recoil has in seconds is refused."""

from __future__ import annotations

import numpy as np

from .._native import SolverError
from ..model import simulate
from ..results.names import ETA

#: Fraction of the opening done by the first sample after the cut above which the opening is
#: over before it is sampled.
DONE_AT_FIRST = 0.9
#: Fraction done by the last sample below which the recording ends during the opening.
DONE_AT_LAST = 0.5
#: max(T, tau) above this many seconds is implausible for a laser-ablation recoil.
LONGEST_S = 3600.0
#: max(T, tau) below this many seconds is implausible too (times in s given as ms).
SHORTEST_S = 0.01


def time_scale_warnings(
    theta, outer_radius_um: float, radius, profile=None, intervals: dict | None = None
) -> list[str]:
    """Warnings for the fitted theta = (R0_um, sigma, lambda, T_s) against the sampled times
    [s since the cut] of the radius series and the velocity profile; `intervals` as for
    `unit_warnings` (None: not computed)."""
    R0, sigma, lam, T = (float(x) for x in theta)
    t = np.concatenate(
        [np.asarray(radius.times_s, dtype=float)]
        + ([] if profile is None else [np.asarray(profile.times_s, dtype=float)])
    )
    after = t[t > 0]
    out = []
    k = outer_radius_um**2 / (outer_radius_um**2 - R0**2)
    R1, R_final = R0 * (1 + sigma / 6), R0 * (1 + 2 * sigma / 3 * k)
    if after.size and R_final - R1 > 0:
        first, last = float(after.min()), float(after.max())
        grid = np.geomspace(first * 1e-3, last * 1e3, 121)
        try:
            R = np.asarray(
                simulate(
                    np.concatenate([[0.0], grid]),
                    lam=lam,
                    sigma=sigma,
                    R0_um=R0,
                    T_s=T,
                    outer_radius_um=outer_radius_um,
                ).radius_um
            )[1:]
        except (SolverError, ValueError):
            R = None
        if R is not None:
            done = (R - R1) / (R_final - R1)
            f_first, f_last = np.interp(np.log([first, last]), np.log(grid), done)
            half = (
                f"half-opening time {float(np.exp(np.interp(0.5, done, np.log(grid)))):.3g} s"
                if done[0] < 0.5 < done[-1]
                and np.all(np.diff(done) >= 0)
                and _identified(lam, T, intervals)
                else ""
            )
            if f_first > DONE_AT_FIRST:
                out.append(
                    f"the fitted opening is {100 * f_first:.0f} % done at the first sample after "
                    f"the cut "
                    f"({first:.3g} s{'; ' + half if half else ''}): the data show its end only "
                    f"and its "
                    "time scale is bounded rather than measured; sample earlier"
                )
            if f_last < DONE_AT_LAST:
                out.append(
                    f"the fitted opening is {100 * f_last:.0f} % done at the last sample "
                    f"({last:.3g} s"
                    f"{'; ' + half if half else ''}): the recording ends during the opening and "
                    f"R_final "
                    "and the time scale are extrapolated; record longer"
                )
    return out + unit_warnings(lam, T, intervals)


def _slower(lam: float, T: float) -> tuple[str, str, float]:
    """(interval key, name, value) of the slower time scale max(T, tau)."""
    tau = lam**2 * T
    return ("tau_s", "tau = lambda^2 T", tau) if tau > T else ("T_s", "T", T)


def _identified(lam: float, T: float, intervals: dict | None) -> bool:
    """Whether the slower time scale's 95 % interval is finite on both sides."""
    ends = (intervals or {}).get(_slower(lam, T)[0])
    return ends is not None and None not in ends


def unit_warnings(lam: float, T: float, intervals: dict | None) -> list[str]:
    """The unit question about the slower time scale max(T, tau) out of (SHORTEST_S,
    LONGEST_S), asked only where its 95 % interval is finite on both sides. `intervals`:
    {"T_s": (lower, upper), "tau_s": (lower, upper)}, None for an open end (a lower end on
    lambda's bound 0 counts as open); None (or the pair None): not computed."""
    key, name, t_c = _slower(lam, T)
    if SHORTEST_S <= t_c <= LONGEST_S:
        return []
    long = t_c > LONGEST_S
    what = (
        f"the fitted time scale {name} = {t_c:.3g} s"
        + (f" ({t_c / 3600:.3g} h) is long" if long else " is short")
        + " for a laser-ablation recoil (seconds to minutes)"
    )
    question = (
        "are the times in milliseconds? (--time-unit ms)"
        if long
        else "are the times in seconds, given as milliseconds? (--time-unit s)"
    )
    if intervals is None or intervals.get(key) is None:
        return [
            f"{what}; its interval was not computed, so whether the data measure it is not "
            f"known: if they do, {question}"
        ]
    lo, hi = intervals[key]
    if lo is not None and hi is not None:
        return [f"{what} and the data identify it ([{lo:.4g}, {hi:.4g}] s): {question}"]
    return [
        f"{name} = {t_c:.3g} s is {'long' if long else 'short'} for a laser-ablation recoil "
        f"but not identified ({_lack(name, lo, hi)}): a time scale the data do not measure "
        "says nothing about the unit of the times"
    ]


def _lack(name: str, lo, hi) -> str:
    """What the data lack, from the open ends of the interval."""
    interval = f"95 % interval [{'open' if lo is None else f'{lo:.4g}'}, " + (
        f"{'open' if hi is None else f'{hi:.4g}'}] s"
    )
    if lo is not None:
        return f"{interval}: the recording ends during the opening: {name} is bounded below only"
    if hi is not None:
        return (
            f"{interval}: the opening is mostly over before the first samples: {name} is "
            "bounded above only"
        )
    return f"{interval}: the data bound it on neither side"


def intervals_of(reports: dict, derived: dict) -> dict | None:
    """{"T_s": (lo, hi), "tau_s": (lo, hi)} of a fit's profiles (None for an open end or a
    lower end on lambda's bound, or for the pair of a profile not computed), or None when no
    interval was computed."""
    T = reports["T_s"].profile
    tau = derived.get("tau_s")
    if T is None and tau is None:
        return None
    out = {}
    for key, p in (("T_s", T), ("tau_s", tau)):
        if p is None:
            out[key] = None  # not computed
        else:
            lo = None if (p.at_bound or p.bounded[0]) else p.lower
            out[key] = (lo, None if p.bounded[1] else p.upper)
    return out


def tissue_intervals(shared: dict, r0, profiles: dict) -> dict | None:
    """`intervals_of` for one wound of a several-wound fit: tau = eta/G shared; T = (zeta/G)
    R0^2 / 4 from the shared zeta/G's ends at the wound's R0 where R0 is identified (else
    not known). `shared`: name -> ParameterReport; `r0`: the wound's R0 report."""
    if not profiles:
        return None

    def ends(rep):
        p = rep.profile
        if p is None:
            return None
        return (
            None if (p.at_bound or p.bounded[0]) else p.lower,
            None if p.bounded[1] else p.upper,
        )

    zeta, scale = ends(shared["zeta_over_G_s_per_um2"]), r0.estimate**2 / 4
    T = None
    if zeta is not None and r0.identifiable:
        T = tuple(None if v is None else v * scale for v in zeta)
    return {"T_s": T, "tau_s": ends(shared[ETA])}
