"""The coupled system as an SSP 1.0 file: run one with fmpy's SSD reader, or build one for a
closure model of your own (docs/closure.md).

    python python/coupling/ssp.py run target/fmu/WoundClosure.ssp [--csv out.csv]
    python python/coupling/ssp.py build Ring.fmu --radius radius --edge-stress stress \\
        --set cables=2 --out RingClosure.ssp

`run` reads the file with fmpy's SSD reader (fmpy 0.3.32, `fmpy.ssp.ssd.read_ssd`, which
validates it against SSP 1.0's schema) and steps it with fmpy's FMU classes. fmpy's own
`simulate_ssp` cannot run a wound with a closure model, for two reasons of that version:

* it starts every connector at 0.0 and reads outputs only after the first `doStep`, so the
  closure gets `wound_radius = 0` at t = 0, which PurseString refuses (a closed wound;
  accepted [1e-6, 1e9] um): the run stops with fmi2Error;
* it applies only its `parameter_set` argument, not the SSD's ParameterBindings.

`run` changes only those two points: each component gets its own parameter bindings (or,
without any, the system's set, names `<component>.<variable>`), each value with its type's
setter, and the connectors start from the outputs after initialization. The stepping is
fmpy's (Jacobi: every component steps with the inputs of the last communication point, then
the connections are applied), so the closure's edge stress at t_n is computed from the
radius at t_n-1: order 1 in the step (docs/fmi.md, "The SSP file"). The step and the stop
time are the file's (libcosim's `osp:FixedStepAlgorithm`, the DefaultExperiment) unless
given.

`build` writes an SSP with WoundOpening.fmu (the package's, or --wound-fmu) and a closure
FMU: the same layout as the shipped WoundClosure.ssp (parameters per component in
resources/<component>.ssv and as the system's set, the readers' step annotations), the
connections wound.wound_radius -> closure.<radius>, closure.<edge stress> ->
wound.edge_stress, the wound's parameters those of the worked example unless --wound-set
changes them, the closure's those given with --set (typed by its modelDescription.xml:
Real, Integer, Boolean, String), the others at the FMU's start values.
"""

from __future__ import annotations

import argparse
import csv
import shutil
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.ssp.simulation import add_path, get_value, set_value
from fmpy.ssp.ssd import find_components, find_connectors, get_connections, read_ssd

from wound_opening.coupling.ssp_file import build

NS = {
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "oms": "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd",
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
}
SET = "worked_example"  # the parameter sets' name (ecos applies a set only by name)


def parameter_set(ssd):
    """The SSD's system-level parameter set (names `<component>.<variable>`)."""
    (binding,) = ssd.system.parameterBindings
    (values,) = binding.parameterValues
    return values


def component_parameters(component) -> list:
    """The parameters bound to one component (its own ParameterBindings: inline or .ssv)."""
    return [p for b in component.parameterBindings for s in b.parameterValues for p in s.parameters]


def experiment(ssp_path: str) -> tuple[float | None, float | None]:
    """(step, stop) the file states: libcosim's osp:FixedStepAlgorithm baseStepSize (or
    OMSimulator's oms:FixedStepMaster stepSize) and the DefaultExperiment's stopTime."""
    with zipfile.ZipFile(ssp_path) as z:
        root = ET.fromstring(z.read("SystemStructure.ssd"))
    step = None
    for path, attribute in (
        (".//osp:FixedStepAlgorithm", "baseStepSize"),
        (".//oms:FixedStepMaster", "stepSize"),
    ):
        node = root.find(path, NS)
        if step is None and node is not None and node.get(attribute):
            step = float(node.get(attribute))
    default = root.find("ssd:DefaultExperiment", NS)
    stop = default.get("stopTime") if default is not None else None
    return step, None if stop is None else float(stop)


def _start(component, unzipped: str, stop: float, system_set) -> None:
    """Instantiate, bind the component's parameters (its own, else the system's with
    the `<component>.` prefix), initialize."""
    archive = str(Path(unzipped) / component.source)
    md = read_model_description(archive, validate=False)
    component.unzipdir = extract(archive)
    component.variables = {v.name: v for v in md.modelVariables}
    component.fmu = FMU2Slave(
        guid=md.guid,
        unzipDirectory=component.unzipdir,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName=component.name,
    )
    component.fmu.instantiate()
    component.fmu.setupExperiment(startTime=0.0, stopTime=stop)
    own = component_parameters(component)
    if own:
        values = [(p.name, p) for p in own]
    else:
        prefix = component.name + "."
        values = [(p.name[len(prefix) :], p) for p in system_set if p.name.startswith(prefix)]
    for name, p in values:
        if p.type == "String":
            component.fmu.setString([component.variables[name].valueReference], [p.value])
        elif p.type == "Boolean":
            set_value(component, name, p.value in ("true", "1"))
        else:
            set_value(component, name, p.value)
    component.fmu.enterInitializationMode()
    component.fmu.exitInitializationMode()


def simulate(ssp_path: str, *, step: float | None = None, stop: float | None = None):
    """Inputs and outputs at t_0 = 0, ..., t_N = stop by connector path
    (`wound.wound_radius`, ...), plus `time`; step and stop default to the file's."""
    file_step, file_stop = experiment(ssp_path)
    step = file_step if step is None else step
    stop = file_stop if stop is None else stop
    if step is None or stop is None:
        raise ValueError(f"{ssp_path} states no step or stop time: give them")
    ssd = read_ssd(ssp_path)  # validates against SSP 1.0's SystemStructureDescription.xsd
    n = round(stop / step)
    if n < 1 or abs(n * step - stop) > 1e-9 * stop:
        raise ValueError(f"stop = {stop} is not a whole number of steps of {step}")
    add_path(ssd.system)
    system_set = [
        p for b in ssd.system.parameterBindings for s in b.parameterValues for p in s.parameters
    ]
    components = find_components(ssd.system)
    connectors = [c for c in find_connectors(ssd.system) if c.kind in ("input", "output")]
    connections = get_connections(ssd.system)
    unzipped = extract(ssp_path)
    started = []
    try:
        for component in components:
            _start(component, unzipped, stop, system_set)
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
                for c in component.connectors:
                    if c.kind == "input":
                        set_value(component, c.name, c.value)
                component.fmu.doStep(currentCommunicationPoint=i * step, communicationStepSize=step)
                for c in component.connectors:
                    if c.kind == "output":
                        c.value = get_value(component, c.name)
    finally:
        for component in started:
            component.fmu.terminate()
            component.fmu.freeInstance()
            shutil.rmtree(component.unzipdir, ignore_errors=True)
        shutil.rmtree(unzipped, ignore_errors=True)
    values = np.array(rows, dtype=float)
    out = {"time": np.arange(n + 1) * step}
    out.update({c.path: values[:, k] for k, c in enumerate(connectors)})
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(
        prog="python python/coupling/ssp.py",
        description=__doc__,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    sub = ap.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run an SSP with fmpy's SSD reader")
    run.add_argument("ssp", help="the .ssp file (e.g. target/fmu/WoundClosure.ssp)")
    run.add_argument("--step", type=float, help="communication step [s] (default: the file's)")
    run.add_argument("--stop", type=float, help="stop time [s] (default: the file's)")
    run.add_argument("--csv", help="write every connector at every communication point here")
    b = sub.add_parser("build", help="write an SSP of WoundOpening and a closure FMU")
    b.add_argument("closure", help="the closure FMU (FMI 2.0 co-simulation)")
    b.add_argument("--out", required=True, help="the .ssp file to write")
    b.add_argument(
        "--radius", default="wound_radius", help="its input set to the wound radius [um]"
    )
    b.add_argument(
        "--edge-stress", default="edge_stress", help="its output read as the edge stress [Pa]"
    )
    b.add_argument(
        "--record", action="append", default=[], help="a further output to connect out (repeatable)"
    )
    b.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a closure parameter (repeatable)",
    )
    b.add_argument(
        "--wound-set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="a WoundOpening parameter",
    )
    b.add_argument("--wound-fmu", help="WoundOpening.fmu (default: the package's)")
    b.add_argument(
        "--step",
        type=float,
        default=0.5,
        help="communication step for the readers [s] (%(default)s)",
    )
    b.add_argument("--stop", type=float, default=300.0, help="stop time [s] (%(default)s)")
    args = ap.parse_args(argv)
    if args.command == "run":
        out = simulate(args.ssp, step=args.step, stop=args.stop)
        r = out.get("wound.wound_radius")
        if r is not None:
            i = int(np.argmax(r))
            t = out["time"]
            print(
                f"wound radius: {r[0]:.4f} um at t = 0, max {r[i]:.4f} um at t = {t[i]:g} s, "
                f"{r[-1]:.4f} um at t = {t[-1]:g} s"
            )
        if args.csv:
            with open(args.csv, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(list(out))
                w.writerows(zip(*(v.tolist() for v in out.values())))
            print(f"wrote {args.csv}")
    else:
        try:
            path = build(
                args.closure,
                args.out,
                radius=args.radius,
                edge_stress=args.edge_stress,
                record=args.record,
                closure_values=args.set,
                wound_values=args.wound_set,
                wound_fmu=args.wound_fmu,
                step=args.step,
                stop=args.stop,
            )
        except ValueError as e:
            raise SystemExit(f"error: {e}") from None
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
