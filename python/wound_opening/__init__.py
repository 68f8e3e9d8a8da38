"""wound_opening: simulate, fit and sweep the wound-opening model of an epithelium
(G. M. Carvalho, N. A. M. Araujo, P. Patricio, "Wound opening in a thin incompressible
viscoelastic tissue") in the units of a laser-ablation experiment (um, s, Pa), through the
project's native library (the C API of include/wound_opening.h, loaded with ctypes).

Public names (`__all__`; each imported on first use; see docs/fitting.md, docs/fmi.md):

    simulate(times_s, R0_um=, outer_radius_um=, lam=, sigma=, T_s=, radii_um=None) -> Simulation
        (or G_pa=, eta_pa_s=, zeta_pa_s_per_um2=, tension_pa= for lam, sigma, T_s)
    Simulation          the radius, edge velocity and field of one run (a dataclass)
    sweep(grid or parameter sets, times) -> a pandas DataFrame (local or Dask)
    from_material(G_pa=, eta_pa_s=, zeta_pa_s_per_um2=, tension_pa=, R0_um=)
        -> {lam, sigma, T_s, R0_um}, simulate's keywords
    to_material(lam=, sigma=, T_s=, R0_um=, G_pa=) -> {G_pa, eta_pa_s, zeta_pa_s_per_um2, ...}
    read_radius(path, time_col=, radius_col=, time_unit=, ...) -> RadiusSeries (a lab's CSV)
    read_profile(path, ...) -> VelocityProfile (PIV velocities against the distance)
    read_wounds(path, wound_col=, ...) -> {wound: RadiusSeries}, several wounds from one file
    RadiusSeries        wound radius [um] against time since the cut [s], with its noise
    VelocityProfile     radial velocity [um/s] at (time, distance from the centre)
    Parameters          fixed values, bounds, Gaussian priors and G for a fit
    fit(radius, profile=None, outer_radius_um=, params=Parameters()) -> FitResult
    FitResult           estimates, profile intervals, identifiability, material values
    Wound               one wound of a tissue: Wound(radius, outer_radius_um, profile, name)
    fit_wounds([Wound, ...]) -> TissueFitResult (shared material, each wound's R0)
    TissueFitResult     the fit of several wounds: shared material values, each R0
    write_report(path, result, radius, profile=None): a self-contained HTML report
    fmu_start_values(result or G_pa=, eta_pa_s=, ..., outer_radius_um=) -> the WoundOpening
        FMU's start values {lambda, sigma, R_inf, R0, T, G}, for fmpy.simulate_fmu
    fmu_path(name="WoundOpening.fmu") -> the path of a shipped FMU archive
    library_path() -> the path of the native library in use
    NativeLibraryMissing  raised when the native library is not found
    SolverError         raised when the native solver refuses a value or fails

Subpackage wound_opening.coupling: the FMU master that couples WoundOpening to the
PurseString closure (`python -m wound_opening.coupling --out out`, needs fmpy).
"""

import importlib

#: Where each public name lives; imported on first use, so that `wound-opening --help`
#: starts without numpy, scipy or pandas.
_HOME = {
    "NativeLibraryMissing": "_native",
    "SolverError": "_native",
    "library_path": "_native",
    "Simulation": "model",
    "simulate": "model",
    "from_material": "material",
    "to_material": "material",
    "sweep": "sweeping",
    "fmu_path": "shipped",
    "fmu_start_values": "coupling.start",
    "RadiusSeries": "inputs.series",
    "VelocityProfile": "inputs.series",
    "read_radius": "inputs.lab_files",
    "read_profile": "inputs.lab_files",
    "read_wounds": "inputs.lab_files",
    "Parameters": "fitting.parameters",
    "fit": "fitting.single",
    "Wound": "fitting.wounds",
    "fit_wounds": "fitting.wounds",
    "FitResult": "results.result",
    "TissueFitResult": "results.wounds",
    "write_report": "results.report",
}
__all__ = sorted(_HOME)


def __getattr__(name):
    if name == "__version__":  # the installed distribution's (pyproject.toml)
        from importlib.metadata import PackageNotFoundError, version

        try:
            return version(__name__)
        except PackageNotFoundError:
            return "unknown (not installed)"
    if name in _HOME:
        value = getattr(importlib.import_module(f".{_HOME[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    """The public names and the module's dunder attributes (not its helpers)."""
    return sorted(set(__all__) | {"__version__"} | {k for k in globals() if k.startswith("__")})
