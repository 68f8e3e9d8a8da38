"""A lab's own files: a radius series and a PIV profile read from CSV files with their own
column names and units, converted to the fit's units (um, s, um/s, times since the cut).

    t [s]       = (t_file - cut_time) x TIME_UNITS[time_unit]
    length [um] = length_file x (1 for um, pixel_size_um for px)
    v [um/s]    = v_file x length factor / time factor      (velocity in length unit per time unit)

Uncertainty columns are in the unit of their column. Errors name the file line (columns.py)."""

from __future__ import annotations

import math

import numpy as np

from .columns import MIN_POINTS, InputError, read_columns
from .series import RadiusSeries, VelocityProfile

#: Seconds per time unit.
TIME_UNITS = {"ms": 1e-3, "s": 1.0, "min": 60.0}
LENGTH_UNITS = ("um", "px")
#: A laser-cut wound is microns to tens of microns wide: a median radius outside this range
#: [um] with a pixel size is a pixel size in nm (over) or in mm or m (under).
RADIUS_UM = (1.5, 1000.0)


def check_pixel_size(path, what: str, radius_px: float, pixel_size_um: float) -> None:
    """Refuse a pixel size that makes a median radius of `radius_px` px no laser wound's."""
    r = radius_px * pixel_size_um
    if RADIUS_UM[0] <= r <= RADIUS_UM[1]:
        return
    raise InputError(
        f"{path}: {what} with --pixel-size-um {pixel_size_um:g} is a radius of {r:.4g} um, "
        + (
            f"over {RADIUS_UM[1]:g} um: is the pixel size in nm? (--pixel-size-um "
            f"{pixel_size_um / 1000:g})"
            if r > RADIUS_UM[1]
            else f"under {RADIUS_UM[0]:g} um: is the pixel size in mm or m? (give it in um)"
        )
    )


def _factors(
    path, time_unit: str, length_unit: str, pixel_size_um: float | None
) -> tuple[float, float]:
    """(seconds per time unit, um per length unit), the units checked."""
    if time_unit not in TIME_UNITS:
        raise InputError(
            f"{path}: time unit {time_unit!r}: expected one of {', '.join(TIME_UNITS)}"
        )
    if length_unit not in LENGTH_UNITS:
        raise InputError(
            f"{path}: length unit {length_unit!r}: expected one of {', '.join(LENGTH_UNITS)}"
        )
    if length_unit == "um":
        if pixel_size_um is not None:
            raise InputError(
                f"{path}: a pixel size is given but the length unit is um: give the length unit px"
            )
        return TIME_UNITS[time_unit], 1.0
    if pixel_size_um is None or not (math.isfinite(pixel_size_um) and pixel_size_um > 0):
        raise InputError(
            f"{path}: length unit px needs the pixel size in um (finite, > 0), got {pixel_size_um}"
        )
    return TIME_UNITS[time_unit], float(pixel_size_um)


#: A cut time this many frame intervals before the first time is "at the start".
CUT_FRAMES = 3


def check_cut(path: str, times, unit: str, cut: float) -> None:
    """Refuse a cut time after every recorded time (`times`, in the file's unit), or more
    than CUT_FRAMES frame intervals before the first while the same number in another unit
    falls within CUT_FRAMES frame intervals before it (a cut time in s with the times in ms),
    naming the cut time to give."""
    t = np.unique(times)
    if t.size < 2:
        return
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


def _cut(cut_time: float) -> float:
    if not math.isfinite(cut_time):
        raise InputError(f"cut time {cut_time}: must be finite")
    return float(cut_time)


def read_radius(
    path: str,
    *,
    time_col: str = "time_s",
    radius_col: str = "radius_um",
    sd_col: str | None = None,
    time_unit: str = "s",
    length_unit: str = "um",
    pixel_size_um: float | None = None,
    cut_time: float = 0.0,
    noise_um: float | None = None,
) -> RadiusSeries:
    """The wound radius series of a CSV file. `cut_time`: the time of the cut in the file's
    time unit (subtracted). `sd_col`: per-point standard deviations (in the length unit;
    default: the column radius_sd_um if present). `noise_um`: one noise level in um."""
    return _radius_series(
        path,
        time_col,
        radius_col,
        sd_col,
        time_unit,
        length_unit,
        pixel_size_um,
        cut_time,
        noise_um,
    )[None]


def read_wounds(
    path: str,
    *,
    wound_col: str,
    time_col: str = "time_s",
    radius_col: str = "radius_um",
    sd_col: str | None = None,
    time_unit: str = "s",
    length_unit: str = "um",
    pixel_size_um: float | None = None,
    cut_time: float = 0.0,
    noise_um: float | None = None,
) -> dict:
    """Several wounds' radius series from one long table with a wound id column `wound_col`:
    {id: RadiusSeries} in the order the ids first appear; times ascend within each wound, each
    wound has at least MIN_POINTS rows. The other arguments as for `read_radius`."""
    return _radius_series(
        path,
        time_col,
        radius_col,
        sd_col,
        time_unit,
        length_unit,
        pixel_size_um,
        cut_time,
        noise_um,
        wound_col,
    )


def _radius_series(
    path,
    time_col,
    radius_col,
    sd_col,
    time_unit,
    length_unit,
    pixel_size_um,
    cut_time,
    noise_um,
    wound_col=None,
) -> dict:
    """{wound id: RadiusSeries} of a file ({None: ...} without a wound column)."""
    sec, um = _factors(path, time_unit, length_unit, pixel_size_um)
    cut = _cut(cut_time)
    table = read_columns(
        path,
        (time_col, radius_col) + ((sd_col,) if sd_col else ()),
        cut_time=cut,
        min_rows=MIN_POINTS,
        optional=() if sd_col else ("radius_sd_um",),
        label=wound_col,
        check_times=lambda t: check_cut(path, t, time_unit, cut),
    )
    c = table.columns
    sd = c.get(sd_col or "radius_sd_um")
    ids = c[wound_col] if wound_col else np.full(table.lines.size, None)
    if length_unit == "px" and c[radius_col].size:
        median = float(np.median(c[radius_col]))
        check_pixel_size(path, f"{radius_col} median {median:.4g} px", median, um)
    out = {}
    for name in dict.fromkeys(ids.tolist()):  # the wound ids as Python str, in order of appearance
        rows = np.flatnonzero(ids == name) if wound_col else np.arange(ids.size)
        if rows.size < MIN_POINTS:
            raise InputError(
                f"{path}: {wound_col} {name!r} (lines "
                f"{table.lines[rows[0]]}-{table.lines[rows[-1]]}): "
                f"{rows.size} rows: too few points, need at least {MIN_POINTS} per wound"
            )
        out[name] = RadiusSeries(
            (c[time_col][rows] - cut) * sec,
            c[radius_col][rows] * um,
            noise_um,
            None if sd is None else sd[rows] * um,
            source=path,
            lines=table.lines[rows],
        )
    return out


def read_profile(
    path: str,
    *,
    time_col: str = "time_s",
    r_col: str = "r_um",
    velocity_col: str = "velocity_um_s",
    sd_col: str | None = None,
    time_unit: str = "s",
    length_unit: str = "um",
    pixel_size_um: float | None = None,
    cut_time: float = 0.0,
    noise_um_s: float | None = None,
) -> VelocityProfile:
    """The PIV velocity profile of a CSV file: r the CURRENT distance from the wound centre,
    the velocity in length unit per time unit. `sd_col`: per-point standard deviations of the
    velocity (default: the column velocity_sd_um_s if present). `noise_um_s`: one level in um/s."""
    sec, um = _factors(path, time_unit, length_unit, pixel_size_um)
    cut = _cut(cut_time)
    table = read_columns(
        path,
        (time_col, r_col, velocity_col) + ((sd_col,) if sd_col else ()),
        cut_time=cut,
        min_rows=1,
        optional=() if sd_col else ("velocity_sd_um_s",),
    )
    c = table.columns
    sd = c.get(sd_col or "velocity_sd_um_s")
    return VelocityProfile(
        (c[time_col] - cut) * sec,
        c[r_col] * um,
        c[velocity_col] * (um / sec),
        noise_um_s,
        None if sd is None else sd * (um / sec),
        source=path,
        lines=table.lines,
    )
