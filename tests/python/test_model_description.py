"""The FMU archives and their modelDescription.xml: fmpy's validation and the declared
interface, for both FMUs (WoundOpening and the PurseString closure model)."""

import zipfile

import pytest
from fmpy import platform, read_model_description, sharedLibraryExtension
from fmpy.validation import validate_fmu

# name: (valueReference, causality, variability, start, unit)
WOUND = {
    "lambda": (0, "parameter", "fixed", 1.0, "1"),
    "sigma": (1, "parameter", "fixed", 1.0, "1"),
    "R_inf": (2, "parameter", "fixed", 10.0, "1"),
    "edge_stress": (3, "input", "continuous", 0.0, "Pa"),
    "wound_radius": (4, "output", "continuous", None, "um"),
    "edge_velocity": (5, "output", "continuous", None, "um/s"),
    "tolerance": (6, "parameter", "fixed", 1e-10, "1"),
    "method": (7, "parameter", "fixed", 0, None),
    "grid_points": (8, "parameter", "fixed", 101, None),
    "internal_step": (9, "parameter", "fixed", 1e-3, "s"),
    "R0": (10, "parameter", "fixed", 1.0, "um"),
    "T": (11, "parameter", "fixed", 1.0, "s"),
    "G": (12, "parameter", "fixed", 1.0, "Pa"),
    "validity_warning": (452, "parameter", "fixed", 1, None),
}

PURSE = {
    "T_max": (0, "parameter", "fixed", 6500.0, "pN"),
    "t_assembly": (1, "parameter", "fixed", 30.0, "s"),
    "t_delay": (2, "parameter", "fixed", 20.0, "s"),
    "thickness": (3, "parameter", "fixed", 5.0, "um"),
    "wound_radius": (4, "input", "continuous", 10.0, "um"),
    "edge_stress": (5, "output", "continuous", None, "Pa"),
    "line_tension": (6, "output", "continuous", None, "pN"),
}

# SI exponents (kg, m, s) and factor of each unit used.
SI = {
    "Pa": ((1, -1, -2), 1.0),
    "s": ((0, 0, 1), 1.0),
    "um": ((0, 1, 0), 1e-6),
    "um/s": ((0, 1, -1), 1e-6),
    "pN": ((1, 1, -2), 1e-12),
}

# name: (variables, {output: inputs it depends on directly})
MODELS = {
    "WoundOpening": (WOUND, {"wound_radius": [], "edge_velocity": ["edge_stress"]}),
    "PurseString": (PURSE, {"edge_stress": ["wound_radius"], "line_tension": []}),
}


@pytest.fixture(params=sorted(MODELS))
def fmu(request, fmu_path, purse_path):
    name = request.param
    return name, {"WoundOpening": fmu_path, "PurseString": purse_path}[name]


def test_validate_fmu_reports_no_problems(fmu):
    _, path = fmu
    problems = validate_fmu(path)
    assert problems == [], "\n".join(problems)


def test_archive_layout(fmu):
    name, path = fmu
    with zipfile.ZipFile(path) as zf:
        names = zf.namelist()
    assert "modelDescription.xml" in names
    assert "documentation/index.html" in names
    assert f"binaries/{platform}/{name}{sharedLibraryExtension}" in names, names


def test_co_simulation_interface(fmu):
    name, path = fmu
    md = read_model_description(path)
    assert md.fmiVersion == "2.0"
    if name == "WoundOpening":
        # Co-simulation alone: its Model Exchange (217 states) is WoundOpening-me.fmu.
        # 13 published rows and validity_warning (value reference 452, after every other).
        assert (
            md.modelExchange is None
            and md.numberOfContinuousStates == 0
            and len(md.modelVariables) == 14
        )
        me = read_model_description(path.replace(".fmu", "-me.fmu"))
        assert (
            me.coSimulation is None
            and me.modelExchange.modelIdentifier == name
            and me.guid == md.guid
        )
        named = [(v.name, v.valueReference) for v in me.modelVariables if v.causality != "local"]
        assert named == [(v.name, v.valueReference) for v in md.modelVariables]
    else:
        assert md.modelExchange is not None and md.modelExchange.modelIdentifier == name, (
            "both interfaces, one library"
        )
    cs = md.coSimulation
    assert cs is not None and cs.modelIdentifier == name
    assert cs.canHandleVariableCommunicationStepSize
    assert cs.canGetAndSetFMUstate
    assert cs.canSerializeFMUstate
    assert cs.providesDirectionalDerivative
    assert not cs.canBeInstantiatedOnlyOncePerProcess  # the tests run several instances
    categories = {c.name for c in md.logCategories}
    assert {"logStatusError", "logStatusWarning", "logStatusDiscard", "logCalls"} <= categories, (
        categories
    )


def test_variables_and_units(fmu):
    name, path = fmu
    md = read_model_description(path)
    table, _ = MODELS[name]
    found = {v.name: v for v in md.modelVariables if v.causality != "local"}
    assert set(found) == set(table), sorted(found)
    units = {u.name: u for u in md.unitDefinitions}
    for var, (vr, causality, variability, start, unit) in table.items():
        v = found[var]
        assert v.type == (
            "Integer" if var in ("method", "grid_points", "validity_warning") else "Real"
        ), var
        assert (v.valueReference, v.causality, v.variability) == (vr, causality, variability), var
        if start is not None:
            assert v.start is not None and float(v.start) == start, (var, v.start)
        assert v.unit == unit, (var, v.unit)
        if unit in SI:
            base = units[unit].baseUnit
            (kg, m, s), factor = SI[unit]
            assert (base.kg, base.m, base.s, float(base.factor)) == (kg, m, s, factor), (var, unit)


def test_output_dependencies(fmu):
    """Direct feedthrough as declared: WoundOpening's edge_velocity on edge_stress (and
    not its radius, so a loop with PurseString has no algebraic loop); PurseString's
    edge_stress on wound_radius."""
    name, path = fmu
    md = read_model_description(path)
    _, want = MODELS[name]
    outputs = {u.variable.name: u for u in md.outputs}
    assert set(outputs) == set(want)
    for out, inputs in want.items():
        deps = outputs[out].dependencies
        assert deps is not None, f"{out}: dependencies are declared"
        # The outputs depend on the continuous states (Model Exchange) and on these inputs.
        assert [d.name for d in deps if d.causality == "input"] == inputs, (out, deps)


def test_reference_results_are_declared_and_start_at_the_start_values(fmu):
    """FMI-LS-REF: the manifest names the CSV as the result, the CSV has time and every
    output as columns, over the DefaultExperiment; WoundOpening starts at R1 = 1 + 1/6
    (sigma = 1, R0 = 1) to the last bit, PurseString with no tension (t < t_delay)."""
    import csv
    import io
    import xml.etree.ElementTree as ET

    name, path = fmu
    folder = "extra/org.fmi-standard.fmi-ls-ref"
    with zipfile.ZipFile(path) as zf:
        manifest = ET.fromstring(zf.read(f"{folder}/fmi-ls-manifest.xml"))
        ns = "{http://fmi-standard.org/fmi-ls-manifest}"
        assert manifest.tag == "fmiReferences"
        assert manifest.get(f"{ns}fmi-ls-name") == "org.fmi-standard.fmi-ls-ref"
        # The default experiment's first; the paper's cases follow (test_reference_cases.py).
        related = manifest.findall("Related")[0]
        assert related.get("source") == f"{name}_out.csv"
        assert related.get("role") == "result" and related.get("type") == "text/csv"
        rows = list(csv.reader(io.StringIO(zf.read(f"{folder}/{related.get('source')}").decode())))
    md = read_model_description(path)
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    assert rows[0] == ["time"] + outputs
    first, last = [float(x) for x in rows[1]], [float(x) for x in rows[-1]]
    experiment = md.defaultExperiment
    assert first[0] == float(experiment.startTime) and last[0] == float(experiment.stopTime)
    if name == "WoundOpening":
        assert first[1] == 1 + 1 / 6
    else:
        assert first[1:] == [0.0, 0.0]
