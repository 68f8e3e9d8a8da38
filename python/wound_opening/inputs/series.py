"""Measurements to fit: a wound radius series and, optionally, a PIV velocity profile, and
the checks that refuse data no parameter value can describe (ValueError naming the row,
1 = the first row as given, or the file line when read from a file, and the reason)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class RadiusSeries:
    """Wound radius [um] at times [s since the cut]. `noise_um`: the standard deviation of
    every radius; `sd_um`: one per point instead; neither: estimated from the residuals."""

    times_s: np.ndarray
    radius_um: np.ndarray
    noise_um: float | None = None
    sd_um: np.ndarray | None = None
    #: The file read (lab_files.read_radius) and the file line of each row, for messages.
    source: str | None = None
    lines: np.ndarray | None = None
    #: The raw files read for it (provenance.RawFile: hash, counts, notes), e.g. a Fiji table.
    files: tuple = ()
    #: What a selection of the recording kept and dropped (truncate.py), said in the result.
    note: str | None = None
    #: Errors serially correlated (an outline frame after frame: fitting/serial.py); with
    #: the noise estimated, their lag-1 correlation is estimated too.
    serial: bool = False
    #: What the reader found doubtful in the measurement (fiji.outline_warnings), said with
    #: the fit's warnings.
    warnings: tuple = ()
    #: With the noise estimated: the least noise the fit takes [um] (an outline's error is
    #: half a pixel at least: fiji.OUTLINE_FLOOR_PX); None: the residuals' scale alone.
    noise_floor_um: float | None = None
    #: How the floor was set, for the summary and report ("half a pixel": the readers'
    #: outline floor); "" for a floor given by hand.
    noise_floor_said: str = ""

    def __post_init__(self):
        _check_columns("radius", self.times_s, self.radius_um)
        _check_noise(self, "radius", self.noise_um, self.sd_um, np.size(self.radius_um))
        floor = self.noise_floor_um
        if floor is not None and not (math.isfinite(floor) and floor > 0):
            raise ValueError(f"radius noise floor {floor!r} um: expected finite and > 0")
        bad = np.flatnonzero(~(np.asarray(self.radius_um, dtype=float) > 0))
        if bad.size:
            raise ValueError(
                f"{where(self, 'radius', bad[0])}: radius_um = {self.radius_um[bad[0]]:g}: a "
                f"wound radius must be > 0"
            )


@dataclass(frozen=True)
class VelocityProfile:
    """Tissue velocity [um/s] at CURRENT distances r [um] from the wound centre, at times
    [s]; `noise_um_s` its standard deviation, or `sd_um_s` one per point (neither: estimated
    from the residuals)."""

    times_s: np.ndarray
    r_um: np.ndarray
    velocity_um_s: np.ndarray
    noise_um_s: float | None = None
    sd_um_s: np.ndarray | None = None
    source: str | None = None
    lines: np.ndarray | None = None
    #: The raw files read for it (provenance.RawFile), e.g. one PIVlab file per frame pair.
    files: tuple = ()
    #: PIV: the frame pair's interval [s], each point then the displacement over
    #: [t - interval/2, t + interval/2] divided by it (fitting/piv_measure.py), and the
    #: interrogation window's side [um] it is the mean over (None: a point's velocity).
    interval_s: float | None = None
    window_um: float | None = None
    #: The points' covariance [(um/s)^2] (inputs/piv_errors.py), when their errors are
    #: correlated; its diagonal is sd_um_s squared.
    covariance: np.ndarray | None = None
    #: What the reading found doubtful but used (a given wound centre the flow disagrees
    #: with): the fit's warnings.
    warnings: tuple = ()

    def __post_init__(self):
        _check_columns("profile", self.times_s, self.r_um, self.velocity_um_s)
        _check_noise(self, "profile", self.noise_um_s, self.sd_um_s, np.size(self.r_um))
        n = np.size(self.r_um)
        if self.covariance is not None and (
            np.shape(self.covariance) != (n, n) or self.sd_um_s is None
        ):
            raise ValueError(f"profile: a covariance of {n} x {n} goes with sd_um_s")
        for name in ("interval_s", "window_um"):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0):
                raise ValueError(f"profile: {name} = {v:g}: must be finite and > 0")
        bad = np.flatnonzero(~(np.asarray(self.r_um, dtype=float) > 0))
        if bad.size:
            raise ValueError(
                f"{where(self, 'profile', bad[0])}: r_um = {self.r_um[bad[0]]:g}: a distance from "
                f"the centre must be > 0"
            )


def where(data, what: str, k: int) -> str:
    """Where row k (0-based) of `data` is: its file and line when read from a file."""
    if getattr(data, "lines", None) is not None:
        return f"{data.source}: line {int(data.lines[k])}"
    return f"{what}: row {k + 1}"


def _check_columns(what: str, times, *columns) -> None:
    arrays = [np.asarray(times, dtype=float), *(np.asarray(c, dtype=float) for c in columns)]
    if any(a.ndim != 1 or a.size != arrays[0].size for a in arrays):
        raise ValueError(f"{what}: every column must be 1-D with the same length")
    if not all(np.all(np.isfinite(a)) for a in arrays):
        raise ValueError(f"{what}: every value must be finite")
    if np.any(arrays[0] < 0):
        raise ValueError(f"{what}: times must be >= 0 (seconds since the cut)")


def _check_noise(data, what: str, noise, sd, n: int) -> None:
    if noise is not None and not (math.isfinite(noise) and noise > 0):
        raise ValueError(f"{what}: noise = {noise:g}: a standard deviation must be finite and > 0")
    if sd is not None:
        sd = np.asarray(sd, dtype=float)
        if sd.shape != (n,):
            raise ValueError(f"{what}: {sd.size} uncertainties for {n} points")
        bad = np.flatnonzero(~(np.isfinite(sd) & (sd > 0)))
        if bad.size:
            raise ValueError(
                f"{where(data, what, bad[0])}: uncertainty {sd[bad[0]]:g}: must be finite and > 0"
            )
        if noise is not None:
            raise ValueError(
                f"{what}: give either one noise level or per-point uncertainties, not both"
            )


#: A data set whose noise is estimated from its residuals needs this many points: with
#: fewer, the estimate is too uncertain (relative error ~ 1 / sqrt(2 n)) to weigh it.
MIN_POINTS_FOR_NOISE = 10


def check_against(radius: RadiusSeries, profile: VelocityProfile | None, outer_um: float) -> None:
    """Refuse data that contradict each other or the tissue's size."""
    if not (math.isfinite(outer_um) and outer_um > 0):
        raise ValueError(f"outer_radius_um = {outer_um:g}: must be finite and > 0")
    r = np.asarray(radius.radius_um, dtype=float)
    if not outer_um > r.max():
        raise ValueError(
            f"outer_radius_um = {outer_um:g} is not larger than the largest wound radius "
            f"{r.max():g} um ({where(radius, 'radius', int(np.argmax(r)))})"
        )
    for what, noise, sd, n in (
        ("radius", radius.noise_um, radius.sd_um, r.size),
        (
            "profile",
            None if profile is None else profile.noise_um_s,
            None if profile is None else profile.sd_um_s,
            0 if profile is None else np.size(profile.r_um),
        ),
    ):
        if (
            (what == "radius" or profile is not None)
            and noise is None
            and sd is None
            and n < MIN_POINTS_FOR_NOISE
        ):
            raise ValueError(
                f"{what}: {n} points are too few to estimate their own noise (need "
                f"{MIN_POINTS_FOR_NOISE}): give the noise"
            )
    if profile is None:
        return
    t = np.asarray(radius.times_s, dtype=float)
    order = np.argsort(t, kind="stable")
    pt, pr = np.asarray(profile.times_s, dtype=float), np.asarray(profile.r_um, dtype=float)
    edge = np.interp(pt, t[order], r[order])
    if radius.sd_um is not None:
        slack = 3 * np.interp(pt, t[order], np.asarray(radius.sd_um, float)[order])
    else:
        slack = 3 * (radius.noise_um if radius.noise_um is not None else _roughness(r[order]))
    inside = np.flatnonzero(pr < edge - slack)
    if inside.size:
        k = inside[0]
        raise ValueError(
            f"{where(profile, 'profile', k)}: r_um = {pr[k]:g} is inside the measured wound "
            f"(radius {edge[k]:.4g} um "
            f"at {pt[k]:g} s, less 3 noise = {slack if np.isscalar(slack) else slack[k]:.3g} um)"
        )
    beyond = np.flatnonzero(pr >= outer_um)
    if beyond.size:
        k = beyond[0]
        raise ValueError(
            f"{where(profile, 'profile', k)}: r_um = {pr[k]:g} is beyond the tissue (outer radius "
            f"{outer_um:g} um)"
        )


def _roughness(r: np.ndarray) -> float:
    """Noise of a smooth series from its second differences (var(d2) = 6 noise^2)."""
    if r.size < 4:
        return 0.01 * float(np.mean(r))
    return max(float(np.std(np.diff(r, 2))) / math.sqrt(6), 1e-3 * float(np.mean(r)))
