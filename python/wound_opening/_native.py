"""ctypes binding of the series functions of the direct C API (include/wound_opening.h).

Everything here is dimensionless (lengths in R0, time in T, stresses in G); `model.py`
converts. The library is loaded once per process: from `$WOUND_OPENING_LIB` when it is set
(an explicit choice, and the only place then looked at), else from the first of the
installed package (a wheel carries `wound_opening/libwound_opening.so`, or the `.dylib` or
`wound_opening.dll` of macOS and Windows) and
`target/release/libwound_opening.so` of the checkout (built by `cargo build --release`;
editable install).
Each worker process of a sweep loads it itself (nothing native crosses a pickle).
"""

from __future__ import annotations

import ctypes
import os
import sys
from pathlib import Path

import numpy as np

from .shipped import candidates, first_file

ENV_VAR = "WOUND_OPENING_LIB"
#: The file name cargo gives the library on this platform (a wheel keeps it).
LIB_NAME = {"win32": "wound_opening.dll", "darwin": "libwound_opening.dylib"}.get(
    sys.platform, "libwound_opening.so"
)

#: Grid accuracy asked of the solver (relative to the opening amplitude R_final - R1).
TOLERANCE = 1e-10

WO_OK, WO_UNDEFINED, WO_OUTSIDE_VALIDITY = 0, 7, 8


class NativeLibraryMissing(RuntimeError):
    """The native library was not found where it was looked for."""


class SolverError(ValueError):
    """A call refused by the native library; the message is wo_last_error()'s."""

    def __init__(self, status: int, message: str):
        super().__init__(message)
        self.status = status


class _Problem(ctypes.Structure):
    _fields_ = [
        (name, ctypes.c_double)
        for name in ("lambda_", "sigma", "r_inf", "tolerance", "edge_stress")
    ]


_DOUBLES = ctypes.c_void_p  # float64 arrays, passed by address
_lib = None


def library_paths() -> list[Path]:
    """Where the native library is looked for: $WOUND_OPENING_LIB alone when it is set, else
    the package, then the checkout."""
    override = os.environ.get(ENV_VAR)
    return [Path(override)] if override else candidates(LIB_NAME, f"release/{LIB_NAME}")


def library_path() -> Path:
    """The native library that is (or will be) loaded: the first of library_paths() that exists."""
    paths = library_paths()
    if path := first_file(paths):
        return path
    raise NativeLibraryMissing(
        f"wound_opening: native library not found at {' or '.join(map(str, paths))}; build it with "
        f"`cargo build --release` in the repository (editable install), install the wheel, or set "
        f"{ENV_VAR} to its path"
    )


def _load():
    global _lib
    if _lib is None:
        lib = ctypes.CDLL(str(library_path()))
        lib.wo_series.argtypes = [_Problem, _DOUBLES, ctypes.c_size_t, _DOUBLES, _DOUBLES]
        lib.wo_profile_series.argtypes = [
            _Problem,
            _DOUBLES,
            ctypes.c_size_t,
            _DOUBLES,
            ctypes.c_size_t,
            _DOUBLES,
            _DOUBLES,
        ]
        lib.wo_series_sensitivities.argtypes = [_Problem, _DOUBLES, ctypes.c_size_t] + [
            _DOUBLES
        ] * 4
        lib.wo_profile_rates.argtypes = lib.wo_profile_series.argtypes
        lib.wo_pair_displacement.argtypes = (
            [_Problem]
            + [_DOUBLES] * 3
            + [
                ctypes.c_size_t,
                _DOUBLES,
            ]
        )
        lib.wo_point_rates.argtypes = [_Problem, _DOUBLES, _DOUBLES, ctypes.c_size_t, _DOUBLES]
        for f in (
            lib.wo_series,
            lib.wo_profile_series,
            lib.wo_series_sensitivities,
            lib.wo_profile_rates,
            lib.wo_pair_displacement,
            lib.wo_point_rates,
        ):
            f.restype = ctypes.c_int
        lib.wo_last_error.restype = ctypes.c_char_p
        lib.wo_last_error.argtypes = []
        _lib = lib
    return _lib


def _ptr(a: np.ndarray | None):
    """The address of a contiguous float64 array (argtypes c_void_p: no ctypes object per call)."""
    return None if a is None else a.__array_interface__["data"][0]


def _check(lib, status: int) -> None:
    """Raise on a refusal; WO_OUTSIDE_VALIDITY is a warning with every output written (the
    package checks the validity where it reports it)."""
    if status not in (WO_OK, WO_OUTSIDE_VALIDITY):
        raise SolverError(status, lib.wo_last_error().decode("utf-8", "replace"))


def _doubles(x) -> np.ndarray:
    return np.ascontiguousarray(x, dtype=np.float64)


def series(
    lam: float,
    sigma: float,
    r_inf: float,
    times,
    edge_stress: float = 0.0,
    *,
    velocity: bool = True,
    tolerance: float = TOLERANCE,
):
    """R(t) and (if `velocity`) dR/dt at ascending dimensionless `times`, in one C call.
    Returns (radius, velocity or None)."""
    lib = _load()
    t = _doubles(times)
    r = np.empty_like(t)
    v = np.empty_like(t) if velocity else None
    problem = _Problem(lam, sigma, r_inf, tolerance, edge_stress)
    _check(lib, lib.wo_series(problem, _ptr(t), t.size, _ptr(r), _ptr(v)))
    return r, v


def series_sensitivities(
    lam: float,
    sigma: float,
    r_inf: float,
    times,
    edge_stress: float = 0.0,
    *,
    tolerance: float = TOLERANCE,
):
    """R(t), dR/dt, dR/dlambda and dR/dR_inf at ascending dimensionless `times`, in one C
    call: the derivatives are exact for the solver's own R(t) (its grid held fixed), through
    its modal basis (wo_series_sensitivities). Returns the four arrays."""
    lib = _load()
    t = _doubles(times)
    r, v, d_lam, d_r_inf = (np.empty_like(t) for _ in range(4))
    problem = _Problem(lam, sigma, r_inf, tolerance, edge_stress)
    status = lib.wo_series_sensitivities(
        problem, _ptr(t), t.size, _ptr(r), _ptr(v), _ptr(d_lam), _ptr(d_r_inf)
    )
    _check(lib, status)
    return r, v, d_lam, d_r_inf


def profile_series(
    lam: float,
    sigma: float,
    r_inf: float,
    times,
    radii,
    edge_stress: float = 0.0,
    *,
    velocity: bool = True,
    tolerance: float = TOLERANCE,
):
    """u and (if `velocity`) u_t of the material points at CURRENT radii `radii`, at each
    ascending time: arrays (len(times), len(radii)), in one C call."""
    lib = _load()
    t, r = _doubles(times), _doubles(radii)
    u = np.empty((t.size, r.size))
    v = np.empty((t.size, r.size)) if velocity else None
    problem = _Problem(lam, sigma, r_inf, tolerance, edge_stress)
    _check(lib, lib.wo_profile_series(problem, _ptr(t), t.size, _ptr(r), r.size, _ptr(u), _ptr(v)))
    return u, v


def pair_displacement(
    lam: float,
    sigma: float,
    r_inf: float,
    t_a,
    t_b,
    radii,
    *,
    tolerance: float = TOLERANCE,
) -> np.ndarray:
    """u(X, t_b) - u(X, t_a) of the material points at CURRENT radii `radii` at times `t_a`
    (X + u(X, t_a) = r), each point with its own pair of times (t_a <= t_b), in one C call
    (wo_pair_displacement): the displacement a PIV vector measures over its frame pair."""
    lib = _load()
    a, b, r = np.broadcast_arrays(_doubles(t_a), _doubles(t_b), _doubles(radii))
    a, b, r = (np.ascontiguousarray(v) for v in (a, b, r))
    out = np.empty(r.size)
    problem = _Problem(lam, sigma, r_inf, tolerance, 0.0)
    _check(lib, lib.wo_pair_displacement(problem, _ptr(a), _ptr(b), _ptr(r), r.size, _ptr(out)))
    return out.reshape(r.shape)


def profile_rates(lam: float, sigma: float, r_inf: float, times, radii, *, tolerance=TOLERANCE):
    """Velocities u_t at CURRENT radii and at the wound edge, with their exact derivatives in
    sigma, lambda, the dimensionless time, R_inf (the current radius held) and the current
    radius (free edge, times > 0; wo_profile_rates, src/solver/profile_rates.rs). Returns
    `(points, edge)`: arrays (len(times), len(radii), 6) and (len(times), 2, 6), last axis
    (u_t, d/dsigma, d/dlambda, d/dt, d/dR_inf, d/dr); edge[:, 0] the edge's own (material
    point held: d/dr = 0), edge[:, 1] their limit from the tissue (a current radius coming
    down to the edge)."""
    lib = _load()
    t, r = _doubles(times), _doubles(radii)
    points = np.empty((t.size, r.size, 6))
    edge = np.empty((t.size, 2, 6))
    problem = _Problem(lam, sigma, r_inf, tolerance, 0.0)
    status = lib.wo_profile_rates(
        problem, _ptr(t), t.size, _ptr(r), r.size, _ptr(points), _ptr(edge)
    )
    _check(lib, status)
    return points, edge


def point_rates(lam: float, sigma: float, r_inf: float, times, radii, *, tolerance=TOLERANCE):
    """`profile_rates` with a time of its own for each point (wo_point_rates): the rates of
    the material point at CURRENT radius radii[i] at times[i] (> 0, any order), an array
    (len(radii), 6), last axis as profile_rates'."""
    lib = _load()
    t, r = np.broadcast_arrays(_doubles(times), _doubles(radii))
    t, r = np.ascontiguousarray(t), np.ascontiguousarray(r)
    out = np.empty((r.size, 6))
    problem = _Problem(lam, sigma, r_inf, tolerance, 0.0)
    _check(lib, lib.wo_point_rates(problem, _ptr(t), _ptr(r), r.size, _ptr(out)))
    return out
