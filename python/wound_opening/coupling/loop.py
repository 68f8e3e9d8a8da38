"""A co-simulation master for WoundOpening and a closure model, with fmpy's FMU2Slave
(fmpy is needed here only: `pip install fmpy`).

The wound FMU takes the edge stress as input and gives the wound radius; the closure FMU
takes the radius and gives the edge stress, PurseString's p = T_c(t) / (h R). Any FMI 2.0
co-simulation closure fits: a `Closure` names its radius input and its edge-stress output,
or a line-tension output from which the loop computes p = T_c / (h R) (docs/closure.md).
The loop is Gauss-Seidel over communication steps of size `step`:

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

import math
import shutil
from dataclasses import dataclass, field
from pathlib import Path

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


@dataclass(frozen=True)
class Closure:
    """Which variables of a closure FMU the loop uses (names as in its modelDescription.xml).

    radius:        the input set to the wound radius R [um] at every communication point;
    edge_stress:   the output read as the edge stress p [Pa] given to WoundOpening; or None
                   when the closure gives a line tension instead:
    line_tension:  an output read as a line tension T_c [pN]; with edge_stress None the loop
                   applies Laplace's law for a line, p = T_c / (thickness_um R);
    thickness_um:  the sheet thickness h of that law [um] (only with edge_stress None);
    record:        further outputs kept in `Run.closure` (by name).

    `PURSE_STRING` is PurseString.fmu's mapping.
    """

    radius: str = "wound_radius"
    edge_stress: str | None = "edge_stress"
    line_tension: str | None = None
    thickness_um: float | None = None
    record: tuple[str, ...] = ()

    def __post_init__(self):
        if self.edge_stress is None:
            h = self.thickness_um
            if self.line_tension is None or h is None or not (math.isfinite(h) and h > 0):
                raise ValueError(
                    "a closure without an edge_stress output needs line_tension= (the output "
                    f"read as T_c [pN]) and thickness_um > 0 (p = T_c / (h R)); got "
                    f"line_tension={self.line_tension!r}, thickness_um={h!r}"
                )
        elif self.thickness_um is not None:
            raise ValueError("thickness_um is used only with edge_stress=None (a line tension)")

    def outputs(self) -> list[str]:
        """The outputs read at each communication point, edge stress (or tension) first."""
        names = [self.edge_stress or self.line_tension]
        if self.edge_stress is not None and self.line_tension is not None:
            names.append(self.line_tension)
        return names + [n for n in self.record if n not in names]


PURSE_STRING = Closure(line_tension="line_tension")

# FMI 2.0 types by the setter that takes them; Enumeration values are Integers.
_SETTERS = {"Real": "setReal", "Integer": "setInteger", "Enumeration": "setInteger"}


class Unit:
    """One FMU instance driven by the loop: values by name, fmpy's default logger."""

    def __init__(self, path: str, name: str):
        self.md = read_model_description(path)
        if self.md.fmiVersion != "2.0" or self.md.coSimulation is None:
            raise ValueError(
                f"{path}: the loop drives FMI 2.0 co-simulation archives; this one is FMI "
                f"{self.md.fmiVersion}{'' if self.md.coSimulation else ' without co-simulation'}"
            )
        self.path = path
        self.dir = extract(path)
        self.var = {v.name: v for v in self.md.modelVariables}
        self.vr = {n: v.valueReference for n, v in self.var.items()}
        self.fmu = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=self.dir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.fmu.instantiate()
        self.initialized = False

    def require(self, names, causalities, what: str, real: bool = False) -> None:
        """ValueError unless every name is a variable of one of `causalities` (and a Real
        with `real`: the loop exchanges Reals)."""
        for name in names:
            v = self.var.get(name)
            if v is not None and v.causality in causalities and real and v.type != "Real":
                raise ValueError(f"{name} is a {v.type} {what}: the loop exchanges Reals")
            if v is None or v.causality not in causalities:
                have = sorted(n for n, v in self.var.items() if v.causality in causalities)
                raise ValueError(
                    f"{Path(self.path).name} has no {what} named {name!r}; its "
                    f"{what}s: {', '.join(have) or 'none'}"
                )

    def set(self, **values: float) -> None:
        self.fmu.setReal([self.vr[n] for n in values], [float(x) for x in values.values()])

    def set_typed(self, values: dict) -> None:
        """Sets each value with the setter of its variable's type (Real, Integer,
        Enumeration, Boolean, String); ValueError for an unknown name or a value the type
        cannot hold exactly (2.5 for an Integer, 1 for a Boolean)."""
        self.require(values, ("parameter", "input"), "parameter")
        for name, value in values.items():
            kind = self.var[name].type
            if kind == "Real" and isinstance(value, (int, float)) and not isinstance(value, bool):
                self.fmu.setReal([self.vr[name]], [float(value)])
            elif kind in ("Integer", "Enumeration") and _is_integer(value):
                self.fmu.setInteger([self.vr[name]], [int(value)])
            elif kind == "Boolean" and isinstance(value, bool):
                self.fmu.setBoolean([self.vr[name]], [value])
            elif kind == "String" and isinstance(value, str):
                self.fmu.setString([self.vr[name]], [value])
            else:
                raise ValueError(f"{name} is a {kind} parameter: {value!r} is not one")

    def get(self, *names: str) -> list[float]:
        return self.fmu.getReal([self.vr[n] for n in names])

    def initialize(self, params: dict, stop: float) -> None:
        self.fmu.setupExperiment(startTime=0.0, stopTime=stop)
        self.set_typed(params)
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


def _is_integer(value) -> bool:
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, np.integer)):
        return True
    return isinstance(value, float) and value.is_integer()


@dataclass
class Run:
    """Values at the communication points t_0 = 0, ..., t_N = stop."""

    time: np.ndarray
    wound_radius: np.ndarray  # um
    edge_velocity: np.ndarray  # um/s, under the edge stress held over the step that ends here
    edge_stress: np.ndarray  # Pa, the value set at t_n (held over [t_n, t_n+1]); last: at t_N
    line_tension: np.ndarray = field(default=None)  # pN (a closure with a line tension only)
    closure: dict = field(default_factory=dict)  # Closure.record outputs by name


def couple(
    wound_fmu: str,
    purse_fmu: str | None,
    *,
    step: float,
    stop: float,
    wound_params: dict = WOUND_EXAMPLE,
    purse_params: dict | None = None,
    closure: Closure = PURSE_STRING,
    edge_stress: float | None = None,
    interpolate: bool = False,
) -> Run:
    """Run the loop from 0 to `stop` with communication step `step` (stop / step must be
    an integer). `purse_fmu` is the closure FMU (any FMI 2.0 co-simulation archive) and
    `closure` says which of its variables are the radius input and the edge stress or
    line tension output (`Closure`; default: PurseString.fmu's names). `purse_params` are
    its parameters by name, each set with its type's setter (Real, Integer, Enumeration,
    Boolean, String); default: the worked example's with PurseString's mapping, else none
    (the FMU's start values). With `edge_stress` given, that constant is the input and
    `purse_fmu` is not used. With `interpolate`, the edge stress is extrapolated linearly
    over each step (see the module's notes)."""
    n = round(stop / step)
    if n < 1 or abs(n * step - stop) > 1e-9 * stop:
        raise ValueError(f"stop = {stop} is not a whole number of steps of {step}")
    if purse_params is None:
        purse_params = PURSE_EXAMPLE if closure == PURSE_STRING else {}
    times = np.arange(n + 1) * step
    wound = Unit(wound_fmu, "wound")
    purse = None
    out = {k: np.empty(n + 1) for k in ("r", "v", "p", "tc")}
    kept = {name: np.empty(n + 1) for name in closure.record}
    try:
        if edge_stress is None:
            purse = Unit(purse_fmu, "purse")
            purse.require([closure.radius], ("input",), "input", real=True)
            purse.require(closure.outputs(), ("output",), "output", real=True)
        wound.initialize(wound_params, stop)
        if purse is not None:
            purse.initialize(purse_params, stop)
            reads = closure.outputs()
        for i, t in enumerate(times):
            (r,) = wound.get("wound_radius")
            if purse is not None:
                purse.set(**{closure.radius: r})
                values = dict(zip(reads, purse.get(*reads)))
                if closure.edge_stress is None:
                    p = values[closure.line_tension] / (closure.thickness_um * r)
                else:
                    p = values[closure.edge_stress]
                tc = values.get(closure.line_tension, np.nan)
                for name in kept:
                    kept[name][i] = values[name]
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
    tension = None if purse is None or closure.line_tension is None else out["tc"]
    return Run(times, out["r"], out["v"], out["p"], tension, kept)


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
