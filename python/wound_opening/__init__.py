"""wound_opening: simulate, fit and sweep the wound-opening model of an epithelium, in the
units of a laser-ablation experiment (um, s, Pa), through the project's native library
(the direct C API of include/wound_opening.h, loaded with ctypes; no FMU per run).

    simulate(times_s, lam=, sigma=, R0_um=, T_s=, outer_radius_um=, radii_um=None), or with
        G_pa=, eta_pa_s=, zeta_pa_s_per_um2=, tension_pa= instead of lam, sigma, T_s
    from_material(...) -> {lam, sigma, T_s, R0_um}; to_material(...) -> G, eta, zeta, tension
    read_radius(path, time_col=, radius_col=, time_unit=, length_unit=, pixel_size_um=,
        cut_time=) -> RadiusSeries; read_profile(...) -> VelocityProfile (a lab's CSV files)
    fit(radius data, profile data=None, outer_radius_um=, params=Parameters()) -> FitResult
        (estimates, profile likelihood intervals, identifiability, derived quantities and
        material values; to_json(), tables(), export(stem)); Parameters: fixed, bounded,
        Gaussian priors, G
    write_report(path, result, radius, profile=None) -> a self-contained HTML report of a fit
    fit_wounds([Wound(radius, outer_radius_um, profile=None, name=None), ...]) -> TissueFitResult
        (several wounds of one tissue: shared material, each R0); read_wounds(path, wound_col=)
    sweep(grid or list of parameter sets, times) -> pandas DataFrame (local or Dask)
    fmu_path(name) -> the path of a shipped FMU archive, for fmpy or another FMI master

See docs/fitting.md.
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
    return sorted(set(globals()) | set(__all__))
