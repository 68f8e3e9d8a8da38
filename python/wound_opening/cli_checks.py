"""The command line's checks of a recording against the units it was given, and the choice of
the frames to fit (--until-max, --until-s); hooked into cli.py's `fit` by one line each.

- The cut time (--cut-time, in the files' time unit) against the file's own times: after
  every time, or more than CUT_FRAMES frame intervals before the first while the same number
  in another unit falls within CUT_FRAMES frame intervals before it (a cut time in s with the
  times in ms): refused, exit 2, naming the cut time to give.
- The recording in seconds (fitting/recording.py), with the unit named in the message.
- --until-max / --until-s T: fit the opening alone (inputs/truncate.py); the result's
  warnings say which lines were fitted and which dropped."""

from __future__ import annotations

import math

import numpy as np

from .inputs.columns import InputError, read_columns
from .inputs.lab_files import TIME_UNITS

#: A cut time this many frame intervals before the first time is "at the start".
CUT_FRAMES = 3


def add_arguments(group) -> None:
    """--until-max and --until-s on the fit's parser (or one of its groups)."""
    group.add_argument(
        "--until-max",
        action="store_true",
        help="fit the radius only up to its maximum before a sustained decrease (a wound that "
        "closes again after opening; the decrease decided with the noise, docs/fitting.md)",
    )
    group.add_argument(
        "--until-s",
        type=float,
        metavar="T",
        help="fit only the times up to T (s) after the cut, radius and profile",
    )


def check_cut(path: str, args) -> None:
    """Refuse a cut time after every recorded time, or one in another unit than the times."""
    table = read_columns(path, (args.time_col,), cut_time=-math.inf, ascending=False, min_rows=0)
    t = np.unique(table.columns[args.time_col])
    if t.size < 2:
        return
    unit, cut = args.time_unit, float(args.cut_time)
    dt = float(np.median(np.diff(t)))
    near = [
        (u, cut * TIME_UNITS[u] / TIME_UNITS[unit])
        for u in TIME_UNITS
        if u != unit and t[0] - CUT_FRAMES * dt <= cut * TIME_UNITS[u] / TIME_UNITS[unit] <= t[0]
    ]
    where = f"{path}: the cut at {cut:g} {unit} (--cut-time, in the times' unit {unit})"
    span = f"the times run from {t[0]:g} to {t[-1]:g} {unit}, frames {dt:g} {unit} apart"
    hint = "".join(
        f"; {cut:g} {u} = {c:g} {unit} is where the recording starts: is the cut time in {u}? "
        f"(give --cut-time {c:g})"
        for u, c in near
    )
    if cut > t[-1]:
        raise InputError(f"{where} is after every recorded time ({span}): all data before it{hint}")
    if t[0] - cut > CUT_FRAMES * dt and near:
        raise InputError(
            f"{where} is {(t[0] - cut) / dt:.0f} frame intervals before the first time ({span})"
            f"{hint}"
        )


def prepare(args, radius, profile=None):
    """(radius, profile) of the frames to fit (--until-max, --until-s), the recording checked
    in the unit given (InputError: a unit mistake, a radius that shrinks again)."""
    from .fitting.recording import check_recording
    from .inputs.truncate import until_max, until_s

    if args.until_max and args.until_s is not None:
        raise InputError("--until-max and --until-s choose the frames both: give one")
    try:
        if args.until_s is not None:
            radius, profile = until_s(radius, profile, args.until_s)
        elif args.until_max:
            radius, profile = until_max(radius, profile)
        if getattr(args, "area_col", None):
            check_frame_interval(radius, args.frame_interval_s)
        check_recording(radius, profile, time_unit=args.time_unit)
    except ValueError as e:
        raise InputError(f"{radius.source or 'radius'}: {e}") from None
    return radius, profile


def prepare_wounds(args, series: dict, profiles: list):
    """`prepare` for each wound of a several-wound fit: ({name: radius}, [profile])."""
    out, kept = {}, []
    for k, (name, radius) in enumerate(series.items()):
        try:
            out[name], p = prepare(args, radius, profiles[k] if k < len(profiles) else None)
        except InputError as e:
            raise InputError(f"wound {name}: {e}") from None
        kept.append(p)
    return out, kept[: len(profiles)]


#: A frame interval typed in another unit than s: (factor to seconds, what was typed).
INTERVAL_MISTAKES = (
    (1e-3, "the interval in ms typed as s"),
    (1e3, "the interval divided by 1000 once too often"),
    (60.0, "the interval in min typed as s"),
)


def check_frame_interval(radius, frame_interval_s: float) -> None:
    """Refuse (ValueError) a Fiji table whose times, made from its frames and
    --frame-interval-s, are no recording of a passive opening (fitting/recording.py's bounds),
    naming the option and the interval in s that makes it a usual one (not --time-unit: a
    Fiji table has no time column)."""
    from .fitting.recording import FRAME_S, LAST_S, QUIET_FRAME_S, QUIET_LAST_S, sampling
    from .fitting.recording import duration as _s

    dt, _, last = sampling(radius.times_s)
    if (dt is None or FRAME_S[0] <= dt <= FRAME_S[1]) and LAST_S[0] <= last <= LAST_S[1]:
        return
    fixes = [
        f"{what}? (--frame-interval-s {frame_interval_s * f:.6g}: frames {_s(dt * f)} apart)"
        for f, what in INTERVAL_MISTAKES
        if dt is not None
        and QUIET_FRAME_S[0] <= dt * f <= QUIET_FRAME_S[1]
        and QUIET_LAST_S[0] <= last * f <= QUIET_LAST_S[1]
    ]
    raise ValueError(
        f"--frame-interval-s {frame_interval_s:g} makes the frames {_s(dt)} apart and the last "
        f"{_s(last)} after the cut: a passive opening after a laser cut is recorded over "
        f"seconds to minutes (accepted: frame interval {_s(FRAME_S[0])} to {_s(FRAME_S[1])}, "
        f"last time {_s(LAST_S[0])} to {_s(LAST_S[1])}); give the time between two frames in s"
        + (": " + " or ".join(fixes) if fixes else "")
    )
