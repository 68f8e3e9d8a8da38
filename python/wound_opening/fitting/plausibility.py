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

A uniform rescaling of every time (milliseconds read as seconds) rescales the fitted time
scales with the sampling and leaves f at the samples unchanged, so the sampling cannot reveal
it. The time scales themselves can: T = zeta R0^2 / 4G (friction) and tau = lambda^2 T = eta / G
(viscous relaxation) of an ablated epithelium are seconds to minutes, so max(T, tau) above
LONGEST_S (one hour) is warned about.

Each finding is a warning in FitResult.warnings, not a refusal: the estimate may be right."""

from __future__ import annotations

import numpy as np

from .._native import SolverError
from ..model import simulate

#: Fraction of the opening done by the first sample after the cut above which the opening is
#: over before it is sampled.
DONE_AT_FIRST = 0.9
#: Fraction done by the last sample below which the recording ends during the opening.
DONE_AT_LAST = 0.5
#: max(T, tau) above this many seconds is implausible for a laser-ablation recoil.
LONGEST_S = 3600.0


def time_scale_warnings(theta, outer_radius_um: float, radius, profile=None) -> list[str]:
    """Warnings for the fitted theta = (R0_um, sigma, lambda, T_s) against the sampled times
    [s since the cut] of the radius series and the velocity profile."""
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
                if done[0] < 0.5 < done[-1] and np.all(np.diff(done) >= 0)
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
    tau = lam**2 * T
    name, t_c = ("tau = lambda^2 T", tau) if tau > T else ("T", T)
    if t_c > LONGEST_S:
        out.append(
            f"the fitted time scale {name} = {t_c:.3g} s ({t_c / 3600:.3g} h) is long for a "
            f"laser-ablation "
            "recoil (seconds to minutes): are the times in milliseconds? (--time-unit ms)"
        )
    return out
