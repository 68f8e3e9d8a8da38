"""wound_opening: simulate, fit and sweep the wound-opening model of an epithelium, in the
units of a laser-ablation experiment (um, s, Pa), through the project's native library
(the direct C API of include/wound_opening.h, loaded with ctypes; no FMU per run).

    simulate(times_s, lam=, sigma=, R0_um=, T_s=, outer_radius_um=, radii_um=None)
    fit(radius data, profile data=None, outer_radius_um=) -> FitResult (estimates, profile
        likelihood intervals, identifiability, derived quantities; to_json())
    sweep(grid or list of parameter sets, times) -> pandas DataFrame (local or Dask)

See docs/fitting.md.
"""

from ._native import NativeLibraryMissing, SolverError, library_path
from .data import RadiusSeries, VelocityProfile
from .fit import fit
from .model import Simulation, simulate
from .result import FitResult
from .sweep import sweep

__all__ = ["FitResult", "NativeLibraryMissing", "RadiusSeries", "Simulation", "SolverError", "VelocityProfile",
           "fit", "library_path", "simulate", "sweep"]
