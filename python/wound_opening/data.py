"""Measurements to fit: a wound radius series and, optionally, a PIV velocity profile."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class RadiusSeries:
    """Wound radius [um] at times [s since the cut]; `noise_um` is its standard deviation
    (None: estimated from the residuals)."""

    times_s: np.ndarray
    radius_um: np.ndarray
    noise_um: float | None = None

    def __post_init__(self):
        _check_columns("radius", self.times_s, self.radius_um)


@dataclass(frozen=True)
class VelocityProfile:
    """Tissue velocity [um/s] at CURRENT distances r [um] from the wound centre, at times
    [s]; `noise_um_s` its standard deviation (None: estimated from the residuals)."""

    times_s: np.ndarray
    r_um: np.ndarray
    velocity_um_s: np.ndarray
    noise_um_s: float | None = None

    def __post_init__(self):
        _check_columns("profile", self.times_s, self.r_um, self.velocity_um_s)


def _check_columns(what: str, times, *columns) -> None:
    arrays = [np.asarray(times, dtype=float), *(np.asarray(c, dtype=float) for c in columns)]
    if any(a.ndim != 1 or a.size != arrays[0].size for a in arrays):
        raise ValueError(f"{what}: every column must be 1-D with the same length")
    if not all(np.all(np.isfinite(a)) for a in arrays):
        raise ValueError(f"{what}: every value must be finite")
    if np.any(arrays[0] < 0):
        raise ValueError(f"{what}: times must be >= 0 (seconds since the cut)")
