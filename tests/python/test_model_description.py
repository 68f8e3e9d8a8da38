"""The FMU archive and its modelDescription.xml: fmpy's validation and the declared interface."""

import zipfile

from fmpy import platform, sharedLibraryExtension
from fmpy.validation import validate_fmu

# name: (valueReference, causality, variability, start)
VARIABLES = {
    "lambda": (0, "parameter", "fixed", 1.0),
    "sigma": (1, "parameter", "fixed", 1.0),
    "R_inf": (2, "parameter", "fixed", 10.0),
    "edge_stress": (3, "input", "continuous", 0.0),
    "wound_radius": (4, "output", "continuous", None),
    "edge_velocity": (5, "output", "continuous", None),
    "tolerance": (6, "parameter", "fixed", 1e-10),
    "method": (7, "parameter", "fixed", 0),
    "grid_points": (8, "parameter", "fixed", 101),
    "internal_step": (9, "parameter", "fixed", 1e-3),
}


def test_validate_fmu_reports_no_problems(fmu_path):
    problems = validate_fmu(fmu_path)
    assert problems == [], "\n".join(problems)


def test_archive_layout(fmu_path):
    with zipfile.ZipFile(fmu_path) as zf:
        names = zf.namelist()
    assert "modelDescription.xml" in names
    assert f"binaries/{platform}/WoundOpening{sharedLibraryExtension}" in names, names


def test_co_simulation_interface(model_description):
    md = model_description
    assert md.fmiVersion == "2.0"
    assert md.modelExchange is None
    cs = md.coSimulation
    assert cs is not None and cs.modelIdentifier == "WoundOpening"
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canGetAndSetFMUstate
    assert cs.canSerializeFMUstate
    assert not cs.canBeInstantiatedOnlyOncePerProcess  # the tests run several instances
    categories = {c.name for c in md.logCategories}
    assert {"logStatusError", "logStatusWarning", "logCalls"} <= categories, categories


def test_variables(model_description):
    found = {v.name: v for v in model_description.modelVariables}
    assert set(found) == set(VARIABLES), sorted(found)
    for name, (vr, causality, variability, start) in VARIABLES.items():
        v = found[name]
        assert v.type == ("Integer" if name in ("method", "grid_points") else "Real"), name
        assert (v.valueReference, v.causality, v.variability) == (vr, causality, variability), name
        if start is not None:
            assert v.start is not None and float(v.start) == start, (name, v.start)


def test_output_dependencies(model_description):
    """edge_velocity is direct feedthrough of edge_stress; wound_radius is not.

    fmpy gives dependencies=None when the attribute is absent (then everything is assumed
    to be a dependency, which is legal but loses the information); check it when declared.
    """
    outputs = {u.variable.name: u for u in model_description.outputs}
    assert set(outputs) == {"wound_radius", "edge_velocity"}
    deps = {n: u.dependencies for n, u in outputs.items()}
    if deps["edge_velocity"] is not None:
        assert "edge_stress" in [d.name for d in deps["edge_velocity"]], deps
    if deps["wound_radius"] is not None:
        assert "edge_stress" not in [d.name for d in deps["wound_radius"]], deps
