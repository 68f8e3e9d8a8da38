"""Is the recording one of a passive opening after a laser cut, in seconds? Checked before
any fit, by `fit` and `fit_wounds` (and by the command line with the unit it was given).

A laser-ablation recoil is imaged over seconds to minutes at frame intervals of about
0.05-30 s (a spinning-disc or confocal microscope, 20 frames/s to one frame every half
minute), and the model's time scales of an epithelium, T = zeta R0^2 / 4G and tau = eta / G,
are seconds to minutes. Times in milliseconds read as seconds multiply every time by 1000
(frames 50 s to 8 h apart), times in seconds read as milliseconds divide them by 1000
(frames 50 us to 30 ms apart, a recording of 5 ms to a few s). Hence, in seconds:

- refused (ValueError; exit 2 from the command line): a median frame interval outside
  FRAME_S = [0.5 ms, 40 s] or a last time after the cut outside LAST_S = [0.5 s, 2 h]: a
  recording no passive opening has, in the unit given;
- warned about: a frame interval outside QUIET_FRAME_S = [2 ms, 30 s] or a last time outside
  QUIET_LAST_S = [2 s, 1 h] (rare but possible, or a unit mistake the bounds above cannot
  tell from a real recording); a first sample more than GAP_FRAMES frame intervals after the
  cut (the start of the opening unsampled: a cut time in another unit or wrong);
- refused: a radius that shrinks again (truncate.py): offer --until-max or --until-s.

The bounds leave a factor of at least 1.25 between a real recording and its unit mistake
on the side where they overlap least (30 s frames against 50 s from 0.05 s frames in ms);
a recording at 20-30 frames/s read 1000x too slow is told apart only by the fitted time
scale (plausibility.py), which is then identified and warned about."""

from __future__ import annotations

import numpy as np

from ..inputs.lab_files import TIME_UNITS
from ..inputs.truncate import describe, shrinking

#: Accepted median frame interval [s] and last time after the cut [s] (refused outside).
FRAME_S = (5e-4, 40.0)
LAST_S = (0.5, 7200.0)
#: No warning inside these.
QUIET_FRAME_S = (2e-3, 30.0)
QUIET_LAST_S = (2.0, 3600.0)
#: A first sample later than this many frame intervals after the cut is warned about.
GAP_FRAMES = 10


def sampling(times) -> tuple[float | None, float, float]:
    """(median frame interval or None with fewer than 2 distinct times, first, last) [s]."""
    t = np.unique(np.asarray(times, dtype=float))
    dt = float(np.median(np.diff(t))) if t.size > 1 else None
    return dt, float(t[0]), float(t[-1])


def check_recording(radius, profile=None, *, time_unit: str | None = None) -> list[str]:
    """Refuse (ValueError) a recording no passive opening has in seconds, or a radius that
    shrinks again; the warnings of the module docstring (and the note of a selection)."""
    dt, first, last = sampling(radius.times_s)
    unit = time_unit or "s"
    given = f"(times read in {unit}, --time-unit {unit})" if time_unit else "(times_s in seconds)"
    setting = (
        f"frames {_s(dt)} apart (median), the last {_s(last)} after the cut"
        if dt is not None
        else f"the last sample {_s(last)} after the cut"
    )
    ranges = (
        f"a passive opening after a laser cut is recorded over seconds to minutes (accepted: "
        f"frame interval {_s(FRAME_S[0])} to {_s(FRAME_S[1])}, last time {_s(LAST_S[0])} to "
        f"{_s(LAST_S[1])})"
    )
    out = []
    if (dt is not None and not FRAME_S[0] <= dt <= FRAME_S[1]) or not (
        LAST_S[0] <= last <= LAST_S[1]
    ):
        raise ValueError(
            f"{setting} {given}: {ranges}{_suggest(dt, last, unit, time_unit is None)}"
        )
    if (dt is not None and not QUIET_FRAME_S[0] <= dt <= QUIET_FRAME_S[1]) or not (
        QUIET_LAST_S[0] <= last <= QUIET_LAST_S[1]
    ):
        out.append(
            f"{setting} {given}: {'long' if _long(dt, last) else 'short'}"
            f" for a laser-ablation recoil (usually frames {_s(QUIET_FRAME_S[0])} to "
            f"{_s(QUIET_FRAME_S[1])} apart over {_s(QUIET_LAST_S[0])} to {_s(QUIET_LAST_S[1])})"
            f"{_suggest(dt, last, unit, time_unit is None)}"
        )
    if dt is not None and first > GAP_FRAMES * dt:
        out.append(
            f"the first radius is {_s(first)} after the cut, {first / dt:.0f} frame intervals: "
            "the start of the opening is not sampled; if the cut time is wrong or in another "
            "unit than the times (--cut-time is in the files' unit), R0 and sigma are biased"
        )
    found = shrinking(radius)
    if found is not None:
        t_peak = float(np.sort(np.asarray(radius.times_s, dtype=float))[found.peak])
        raise ValueError(
            f"{describe(radius, found)}. Fit the opening alone: --until-max (up to "
            f"{t_peak:.4g} s) or --until-s T (in Python: wound_opening.inputs.truncate."
            "until_max or until_s)"
        )
    if getattr(radius, "note", None):
        out.append(radius.note)
    out += list(getattr(radius, "warnings", ()) or ())
    out += list(getattr(profile, "warnings", ()) or ())
    return out


def _long(dt, last) -> bool:
    return last > QUIET_LAST_S[1] or (dt is not None and dt > QUIET_FRAME_S[1])


#: The units' names in messages.
NAMES = {"ms": "milliseconds", "s": "seconds", "min": "minutes"}


def _suggest(dt, last, unit: str, api: bool = False) -> str:
    """': milliseconds read as seconds? (--time-unit ms: ...)' for each other unit (and, from
    the API, seconds divided by 1000) that makes the recording a usual one."""
    sec = TIME_UNITS.get(unit, 1.0)
    mistakes = [
        (TIME_UNITS[u] / sec, f"{NAMES[u]} read as {NAMES.get(unit, unit)}", f"--time-unit {u}")
        for u in TIME_UNITS
        if u != unit
    ] + ([(1e3, "seconds divided by 1000 as if milliseconds", "times_s x 1000")] if api else [])
    found = []
    for f, mistake, fix in mistakes:
        if not QUIET_LAST_S[0] <= last * f <= QUIET_LAST_S[1]:
            continue
        if dt is not None and not QUIET_FRAME_S[0] <= dt * f <= QUIET_FRAME_S[1]:
            continue
        frames = f"frames {_s(dt * f)} apart" if dt is not None else f"the last {_s(last * f)}"
        found.append(f"{mistake} ({fix}: {frames})")
    return (": " + " or ".join(found) + "?") if found else ""


def duration(x: float) -> str:
    """A duration in s, ms or h as reads best."""
    if x < 1:
        return f"{x * 1e3:.3g} ms"
    if x >= 7200:
        return f"{x:.3g} s ({x / 3600:.3g} h)"
    return f"{x:.3g} s"


_s = duration  # the messages' short name
