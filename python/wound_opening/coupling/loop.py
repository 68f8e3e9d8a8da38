"""A co-simulation master for WoundOpening and a closure model, with fmpy's FMU2Slave
(fmpy is needed here only: `pip install fmpy`).

The wound FMU takes the edge stress as input and gives the wound radius; the
PurseString FMU takes the radius and gives the edge stress p = T_c(t) / (h R). The
loop is Gauss-Seidel over communication steps of size `step`:

    at t_n:   R_n = wound.wound_radius            (no direct feedthrough from the input)
              purse.wound_radius <- R_n;  p_n = purse.edge_stress(t_n, R_n)
              wound.edge_stress  <- p_n           (held over [t_n, t_n + step])
              doStep both from t_n to t_n+1

Holding p_n over the step is a zero-order hold, so the coupled solution converges with
order 1 in `step` (measured by `observed_order` and the tests); the wound itself is
exact in time for a held input.

With `interpolate=True` the loop passes the wound FMU a first derivative of the edge
stress (fmi2SetRealInputDerivatives, canInterpolateInputs), extrapolated from the last two
communication points:

    p(t) = p_n + (p_n - p_n-1) / step_n-1 (t - t_n)      on [t_n, t_n+1]   (0 at t_0)

The wound's modal step is exact for an edge stress linear in time, so the only coupling
error is that of the extrapolation, O(step^2) per unit time: order 2. (A derivative from
the closure model's directional derivative d p / d R times the wound's edge velocity, plus
the explicit time dependence of T_c, would do as well; the extrapolation needs nothing of
the closure model.)

Instead of the purse-string, a constant edge stress (`edge_stress=`) can be applied, which
is the case with an exact answer (docs/model.md, superposition).
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass, field

import numpy as np

try:
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
except ImportError as e:  # fmpy is an optional dependency of the package
    raise ImportError(
        "wound_opening.coupling.loop drives the FMUs with fmpy: pip install fmpy "
        "(or the package's extra: pip install 'wound_opening[fmi]')"
    ) from e

from .start import fmu_start_values

# The README's worked example: a wound of R0 = 10 um in a tissue with G = 100 Pa,
# eta = 1000 Pa s (viscous relaxation time eta / G = 10 s) and zeta = 40 Pa s / um^2,
# so lambda = 2 sqrt(eta / zeta) / R0 = 1 and T = zeta R0^2 / (4 G) = 10 s; homeostatic
# tension 100 Pa (sigma = 1), outer radius 100 um (R_inf = 10).
MATERIAL_EXAMPLE = {
    "G_pa": 100.0,
    "eta_pa_s": 1000.0,
    "zeta_pa_s_per_um2": 40.0,
    "tension_pa": 100.0,
    "R0_um": 10.0,
    "outer_radius_um": 100.0,
}
WOUND_EXAMPLE = fmu_start_values(**MATERIAL_EXAMPLE)
# Purse-string: 6.5 nN after a 20 s delay with a 30 s assembly time, 5 um thick sheet
# (the PurseString FMU's defaults, written out).
PURSE_EXAMPLE = {"T_max": 6500.0, "t_assembly": 30.0, "t_delay": 20.0, "thickness": 5.0}


class Unit:
    """One FMU instance driven by the loop: values by name, fmpy's default logger."""

    def __init__(self, path: str, name: str):
        self.md = read_model_description(path)
        self.dir = extract(path)
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=self.dir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate()
        self.initialized = False

    def set(self, **values: float) -> None:
        self.fmu.setReal([self.vr[n] for n in values], [float(x) for x in values.values()])

    def get(self, *names: str) -> list[float]:
        return self.fmu.getReal([self.vr[n] for n in names])

    def initialize(self, params: dict, stop: float) -> None:
        self.fmu.setupExperiment(startTime=0.0, stopTime=stop)
        self.set(**params)
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.initialized = True

    def close(self) -> None:
        """Terminate (if initialized), free, and remove the extracted files; a failure of
        initialization is not hidden by a refused fmi2Terminate."""
        if self.initialized:
            self.fmu.terminate()
        self.fmu.freeInstance()
        shutil.rmtree(self.dir, ignore_errors=True)


@dataclass
class Run:
    """Values at the communication points t_0 = 0, ..., t_N = stop."""

    time: np.ndarray
    wound_radius: np.ndarray  # um
    edge_velocity: np.ndarray  # um/s, under the edge stress held over the step that ends here
    edge_stress: np.ndarray  # Pa, the value set at t_n (held over [t_n, t_n+1]); last: at t_N
    line_tension: np.ndarray = field(default=None)  # pN (purse-string runs only)


def couple(
    wound_fmu: str,
    purse_fmu: str | None,
    *,
    step: float,
    stop: float,
    wound_params: dict = WOUND_EXAMPLE,
    purse_params: dict = PURSE_EXAMPLE,
    edge_stress: float | None = None,
    interpolate: bool = False,
) -> Run:
    """Run the loop from 0 to `stop` with communication step `step` (stop / step must be
    an integer). With `edge_stress` given, that constant is the input and `purse_fmu` is
    not used. With `interpolate`, the edge stress is extrapolated linearly over each step
    (see the module's notes)."""
    n = round(stop / step)
    if n < 1 or abs(n * step - stop) > 1e-9 * stop:
        raise ValueError(f"stop = {stop} is not a whole number of steps of {step}")
    times = np.arange(n + 1) * step
    wound = Unit(wound_fmu, "wound")
    purse = Unit(purse_fmu, "purse") if edge_stress is None else None
    out = {k: np.empty(n + 1) for k in ("r", "v", "p", "tc")}
    try:
        wound.initialize(wound_params, stop)
        if purse is not None:
            purse.initialize(purse_params, stop)
        for i, t in enumerate(times):
            (r,) = wound.get("wound_radius")
            if purse is not None:
                purse.set(wound_radius=r)
                p, tc = purse.get("edge_stress", "line_tension")
            else:
                p, tc = edge_stress, np.nan
            wound.set(edge_stress=p)
            if interpolate and i > 0:
                rate = (p - out["p"][i - 1]) / (t - times[i - 1])
                wound.fmu.setRealInputDerivatives([wound.vr["edge_stress"]], [1], [rate])
            out["r"][i], out["p"][i], out["tc"][i] = r, p, tc
            out["v"][i] = wound.get("edge_velocity")[0]
            if i == n:
                break
            h = times[i + 1] - t
            wound.fmu.doStep(t, h)
            if purse is not None:
                purse.fmu.doStep(t, h)
    finally:
        wound.close()
        if purse is not None:
            purse.close()
    return Run(times, out["r"], out["v"], out["p"], None if purse is None else out["tc"])


def observed_order(wound_fmu: str, purse_fmu: str, steps, stop: float, **kwargs):
    """Max difference in the radius between runs at `steps[k]` and `steps[k+1] = steps[k]/2`
    on the coarse grid, and the observed orders log2(d_k / d_k+1)."""
    runs = [couple(wound_fmu, purse_fmu, step=h, stop=stop, **kwargs) for h in steps]
    diffs = []
    for coarse, fine in zip(runs, runs[1:]):
        stride = round((len(fine.time) - 1) / (len(coarse.time) - 1))
        diffs.append(float(np.max(np.abs(fine.wound_radius[::stride] - coarse.wound_radius))))
    orders = [float(np.log2(a / b)) for a, b in zip(diffs, diffs[1:])]
    return runs, diffs, orders
