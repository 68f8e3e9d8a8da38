"""Is the fitted time scale one the sampling can resolve, and one a laser-ablation recoil has?

The opening after the cut is governed by the slower of two time scales: T = zeta R0^2 / 4G
(friction) and tau = lambda^2 T = eta / G (viscous relaxation of the whole tissue). With
t_c = max(T, tau):

- t_c below the first sampled time after the cut: the opening is over before the first
  sample, the data show only the plateau, and t_c is bounded above rather than measured;
- t_c above EDGE x the last sampled time: the recording ends while the wound is still in its
  early opening, and t_c is extrapolated;
- t_c above LONGEST_S: a recoil of an ablated epithelium relaxes within seconds to minutes;
  an hour or more suggests times in milliseconds read as seconds. A uniform rescaling of every
  time cannot be seen in the sampling itself (t_c scales with it), hence this absolute bound.

Each finding is a warning in FitResult.warnings, not a refusal: the estimate may be right."""

from __future__ import annotations

import numpy as np

#: t_c above this multiple of the last sampled time is outside what the recording resolves.
EDGE = 3.0
#: t_c above this many seconds is implausible for a laser-ablation recoil.
LONGEST_S = 3600.0


def time_scale_warnings(theta, radius, profile=None) -> list[str]:
    """Warnings for the fitted theta = (R0_um, sigma, lambda, T_s) against the sampled times
    [s since the cut] of the radius series and the velocity profile."""
    times_s = np.concatenate([np.asarray(radius.times_s, dtype=float)]
                             + ([] if profile is None else [np.asarray(profile.times_s, dtype=float)]))
    _, _, lam, T = theta
    tau = lam**2 * T
    name, t_c = ("tau = lambda^2 T", tau) if tau > T else ("T", T)
    t = np.asarray(times_s, dtype=float)
    after = t[t > 0]
    out = []
    if after.size and t_c < after.min():
        out.append(f"the fitted time scale {name} = {t_c:.3g} s is shorter than the first sample after the cut "
                   f"({after.min():.3g} s): the opening is over before it is sampled; sample earlier")
    if t.size and t_c > EDGE * t.max():
        out.append(f"the fitted time scale {name} = {t_c:.3g} s is longer than {EDGE:g} x the last sampled time "
                   f"({t.max():.3g} s): the recording ends during the opening and {name} is extrapolated")
    if t_c > LONGEST_S:
        out.append(f"the fitted time scale {name} = {t_c:.3g} s ({t_c / 3600:.3g} h) is long for a laser-ablation "
                   "recoil (seconds to minutes): are the times in milliseconds? (--time-unit ms)")
    return out
