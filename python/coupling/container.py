"""WoundOpening + PurseString wrapped into one FMI 2.0 co-simulation FMU with fmpy's
container FMU (`fmpy.container_fmu`, fmpy 0.3.32).

The container steps both FMUs with a fixed step and, after every step (and once at the
end of initialization), copies WoundOpening.wound_radius -> PurseString.wound_radius and
then PurseString.edge_stress -> WoundOpening.edge_stress. It exposes the physical
parameters of both FMUs (start values: the README's worked example) and the outputs
wound_radius, edge_velocity, edge_stress and line_tension.

    python python/coupling/container.py   # writes target/fmu/WoundClosure.fmu and runs it
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import uuid
import zipfile
from pathlib import Path

from fmpy import read_model_description
from fmpy.container_fmu.cli import create_container_fmu
from fmpy.container_fmu.config import Component, Configuration, Connection
from fmpy.model_description import (
    CoSimulation,
    DefaultExperiment,
    ModelDescription,
    ModelVariable,
    Unknown,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
# The worked example (its origin is explained in wound_opening/coupling/loop.py).
from wound_opening.coupling.loop import PURSE_EXAMPLE as PURSE_PARAMS  # noqa: E402
from wound_opening.coupling.loop import WOUND_EXAMPLE as WOUND_PARAMS  # noqa: E402

# container output name -> (component, variable of that component)
OUTPUTS = {
    "wound_radius": ("wound", "wound_radius"),
    "edge_velocity": ("wound", "edge_velocity"),
    "edge_stress": ("purse", "edge_stress"),
    "line_tension": ("purse", "line_tension"),
}

# Applied in this order after every step: the radius first, so that the edge stress the
# wound receives is computed from the radius of the same instant.
CONNECTIONS = [
    ("wound", "wound_radius", "purse", "wound_radius"),
    ("purse", "edge_stress", "wound", "edge_stress"),
]


def _connector(variable: ModelVariable) -> ModelVariable:
    """The connection's variableType is written from the component's variable type, which
    is "Real" for FMI 2.0, but the container binary only knows the FMI 3.0 names
    ("Float64"). Hand it a copy that differs only in the type."""
    return ModelVariable(
        name=variable.name,
        valueReference=variable.valueReference,
        type="Float64" if variable.type == "Real" else variable.type,
    )


def build_container(
    wound_fmu,
    purse_fmu,
    out_path,
    step_size: float,
    wound_params: dict = WOUND_PARAMS,
    purse_params: dict = PURSE_PARAMS,
    stop_time: float = 300.0,
) -> Path:
    """Write the container FMU to `out_path`; `step_size` is its fixed internal step
    (every communication step must be a whole multiple of it). Returns `out_path`."""
    paths = {"wound": Path(wound_fmu).resolve(), "purse": Path(purse_fmu).resolve()}
    if paths["wound"].stem == paths["purse"].stem:
        raise ValueError(
            "the two FMUs are extracted to resources/<file stem>: the stems must differ"
        )
    mds = {k: read_model_description(str(p)) for k, p in paths.items()}
    comps = {k: Component(name=k, filename=paths[k], modelDescription=mds[k]) for k in paths}
    var = {k: {v.name: v for v in md.modelVariables} for k, md in mds.items()}

    variables = [
        ModelVariable(
            name="time",
            type="Real",
            causality="independent",
            variability="continuous",
            description="Simulation time",
        )
    ]
    mappings = {}

    for key, params in (("wound", wound_params), ("purse", purse_params)):
        for name, value in params.items():
            inner = var[key][name]
            v = ModelVariable(
                name=name,
                type="Real",
                causality="parameter",
                variability="fixed",
                initial="exact",
                start=repr(float(value)),
                unit=inner.unit,
                description=f"{inner.description} [{key}]",
            )
            variables.append(v)
            mappings[v] = [(comps[key], inner)]

    outputs = []
    for name, (key, inner_name) in OUTPUTS.items():
        inner = var[key][inner_name]
        v = ModelVariable(
            name=name,
            type="Real",
            causality="output",
            variability="continuous",
            initial="calculated",
            unit=inner.unit,
            description=f"{inner.description} [{key}]",
        )
        variables.append(v)
        outputs.append(v)
        mappings[v] = [(comps[key], inner)]

    # the units used by the exposed variables, taken from the components
    used = {v.unit for v in variables if v.unit}
    units = {}
    for md in mds.values():
        for unit in md.unitDefinitions:
            if unit.name in used:
                units.setdefault(unit.name, unit)

    md = ModelDescription(
        fmiVersion="2.0",
        modelName="WoundClosure",
        instantiationToken="{" + str(uuid.uuid4()) + "}",
        description=(
            "WoundOpening and PurseString coupled in an fmpy container FMU; it steps with a fixed "
            f"internal step of {step_size:g} s, so every communication step must be a whole "
            f"multiple of {step_size:g} s (others are refused); linux64 only"
        ),
        generationTool="fmpy.container_fmu (python/coupling/container.py)",
        defaultExperiment=DefaultExperiment(
            startTime="0", stopTime=repr(float(stop_time)), stepSize=repr(float(step_size))
        ),
        coSimulation=CoSimulation(fixedInternalStepSize=step_size),
        unitDefinitions=list(units.values()),
        modelVariables=variables,
        # no container inputs, so no output depends on one; initially they depend on the
        # parameters (no dependency list = all of them)
        outputs=[Unknown(variable=v, dependencies=[]) for v in outputs],
        initialUnknowns=[Unknown(variable=v) for v in outputs],
    )

    connections = [
        Connection(comps[src], [_connector(var[src][sv])], comps[dst], [_connector(var[dst][dv])])
        for src, sv, dst, dv in CONNECTIONS
    ]
    # The binary addresses container variable k + 1 as variableMappings[k] (0 is time),
    # and create_container_fmu numbers modelVariables 0, 1, ...: keep the orders equal.
    assert list(mappings) == variables[1:]
    config = Configuration(
        parallelDoStep=False,
        modelDescription=md,
        components=[comps["wound"], comps["purse"]],
        connections=connections,
        variableMappings=mappings,
    )

    out_path = Path(out_path)
    staging = Path(tempfile.mkdtemp(prefix="container_"))
    try:
        # create_container_fmu deletes and refills its directory, and leaves the archive
        # there under the given name; build outside the target directory and move it.
        work = staging / "unzipped"
        work.mkdir()
        archive = staging / "container.fmu"
        create_container_fmu(config, work, archive)
        out_path.parent.mkdir(parents=True, exist_ok=True)
        _keep_real_platforms(archive, out_path)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return out_path


# What fmpy 0.3.32's container template carries that this container does not use: its
# binaries for win64 (the inner FMUs have Windows binaries, but the template's own DLL was
# never run here: the container stays linux64 only) and darwin64, and a stray, empty
# template archive.
_UNUSED = ("binaries/win64/", "binaries/darwin64/", "Container.zip")


def _keep_real_platforms(archive: Path, out_path: Path) -> None:
    """Copy `archive` to `out_path` without the entries of _UNUSED."""
    with (
        zipfile.ZipFile(archive) as src,
        zipfile.ZipFile(out_path, "w", zipfile.ZIP_DEFLATED) as dst,
    ):
        for item in src.infolist():
            if not item.filename.startswith(_UNUSED):
                dst.writestr(item, src.read(item.filename))


if __name__ == "__main__":
    import argparse

    import numpy as np
    from fmpy import simulate_fmu

    root = Path(__file__).resolve().parents[2]
    parser = argparse.ArgumentParser(
        description="Build WoundClosure.fmu, an fmpy container of WoundOpening.fmu and "
        "PurseString.fmu "
        "coupled by wound_radius and edge_stress, then simulate it for 300 s and print a table."
    )
    parser.add_argument(
        "--fmu-dir",
        type=Path,
        default=root / "target" / "fmu",
        help="folder with the two FMUs; the container is written there (default: %(default)s)",
    )
    parser.add_argument(
        "--step",
        type=float,
        default=0.5,
        help="the container's fixed internal step in s; communication steps must be whole "
        "multiples of it (default: %(default)s)",
    )
    args = parser.parse_args()
    fmu_dir, step = args.fmu_dir, args.step
    path = build_container(
        fmu_dir / "WoundOpening.fmu",
        fmu_dir / "PurseString.fmu",
        fmu_dir / "WoundClosure.fmu",
        step,
    )
    print(f"wrote {path}")
    res = simulate_fmu(str(path), stop_time=300.0, output_interval=step)
    r = res["wound_radius"]
    print(f"{'t [s]':>6} {'R [um]':>10} {'v [um/s]':>10} {'p [Pa]':>10} {'T_c [pN]':>10}")
    for t in (0.0, 10.0, 20.0, 50.0, 100.0, 200.0, 300.0):
        i = int(np.argmin(np.abs(res["time"] - t)))
        print(
            f"{res['time'][i]:6.1f} {r[i]:10.5f} {res['edge_velocity'][i]:10.5f} "
            f"{res['edge_stress'][i]:10.4f} {res['line_tension'][i]:10.2f}"
        )
    k = int(np.argmax(r))
    print(f"max radius {r[k]:.5f} um at t = {res['time'][k]:g} s; at t = 300 s: {r[-1]:.5f} um")
