"""Run target/fmu/WoundClosure.ssp (written by `cargo run --release -- fmu`) with fmpy's
SSP module (fmpy 0.3.32, `fmpy.ssp`).

fmpy's own `fmpy.ssp.simulation.simulate_ssp` cannot run this system as it stands, for two
reasons of that version (read from its source):

* it starts every connector at 0.0 and reads outputs only after the first `doStep`, so
  PurseString gets `wound_radius = 0` at t = 0, which it refuses (a closed wound;
  accepted [1e-6, 1e9] um): the run stops with fmi2Error;
* it applies only the `parameter_set` argument, not the SSD's ParameterBindings.

`simulate` below uses fmpy's SSD reader and its instantiate / step / free functions and
changes only those two points: the parameter set is the SSD's system-level binding, and the
connectors start from the outputs after initialization. The stepping is fmpy's (Jacobi:
every component steps with the inputs of the last communication point, then the
connections are applied), so the purse-string's edge stress at t_n is computed from the
radius at t_n-1: order 1 in the step, like the Gauss-Seidel loop of loop.py with the
edge stress held, but not the same numbers (tests/python/test_ssp.py, docs/fmi.md).
"""

from __future__ import annotations

import shutil

import numpy as np
from fmpy import extract
from fmpy.ssp.simulation import add_path, do_step, free_fmu, get_value, instantiate_fmu
from fmpy.ssp.ssd import find_components, find_connectors, get_connections, read_ssd


def parameter_set(ssd):
    """The SSD's system-level parameter set (names `<component>.<variable>`)."""
    (binding,) = ssd.system.parameterBindings
    (values,) = binding.parameterValues
    return values


def simulate(ssp_path: str, *, step: float, stop: float) -> dict[str, np.ndarray]:
    """Inputs and outputs at t_0 = 0, ..., t_N = stop by connector path
    (`wound.wound_radius`, ...), plus `time`."""
    ssd = read_ssd(ssp_path)  # validates against SSP 1.0's SystemStructureDescription.xsd
    n = round(stop / step)
    if n < 1 or abs(n * step - stop) > 1e-9 * stop:
        raise ValueError(f"stop = {stop} is not a whole number of steps of {step}")
    add_path(ssd.system)
    components = find_components(ssd.system)
    connectors = [c for c in find_connectors(ssd.system) if c.kind in ("input", "output")]
    connections = get_connections(ssd.system)
    unzipped = extract(ssp_path)
    started = []
    try:
        for component in components:
            instantiate_fmu(component, unzipped, 0.0, stop, parameter_set(ssd))
            started.append(component)
        for connector in connectors:
            if connector.kind == "output":
                connector.value = get_value(connector.parent, connector.name)
        rows = []
        for i in range(n + 1):
            for a, b in connections:
                b.value = a.value
            rows.append([c.value for c in connectors])
            if i == n:
                break
            for component in components:
                do_step(component, i * step, step)
    finally:
        for component in started:
            free_fmu(component)
        shutil.rmtree(unzipped, ignore_errors=True)
    values = np.array(rows, dtype=float)
    out = {"time": np.arange(n + 1) * step}
    out.update({c.path: values[:, k] for k, c in enumerate(connectors)})
    return out
