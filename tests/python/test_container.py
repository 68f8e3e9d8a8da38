"""The container FMU of python/coupling/container.py (fmpy.container_fmu) built from the
two real FMUs: it validates, and simulate_fmu on it gives what a plain FMU2Slave loop
gives with the same exchange, bit for bit up to rounding, over the worked example.

The container (fmpy 0.3.32, Rust binary) does, with components [wound, purse] and the
connections in the order wound_radius -> purse, edge_stress -> wound:
  instantiate:   set the container's start values (the parameters) in the components
  init mode:     setupExperiment + enterInitializationMode of each component, then
                 the connections, then exitInitializationMode of each
  every step:    doStep(t_n, h) of each component, then the connections; t_n = n h
The plain loop below repeats exactly that.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu
from fmu_harness import record

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT / "python") not in sys.path:
    sys.path.insert(0, str(ROOT / "python"))

from coupling.container import PURSE_PARAMS, WOUND_PARAMS, build_container  # noqa: E402

from wound_opening.coupling.loop import Unit  # noqa: E402

STEP = 0.5
STOP = 300.0
OUTPUTS = ["wound_radius", "edge_velocity", "edge_stress", "line_tension"]
R_START = 10.0 * (1.0 + 1.0 / 6.0)  # R0 (1 + sigma/6): uniform tension at the cut


@pytest.fixture(scope="module")
def container(tmp_path_factory, fmu_path, purse_path):
    path = tmp_path_factory.mktemp("container") / "WoundClosure.fmu"
    build_container(fmu_path, purse_path, path, STEP)
    return str(path)


@pytest.fixture(scope="module")
def container_run(container):
    return simulate_fmu(container, stop_time=STOP, output_interval=STEP, output=OUTPUTS)


def plain_loop(
    wound_path,
    purse_path,
    step,
    stop,
    wound_params=WOUND_PARAMS,
    purse_params=PURSE_PARAMS,
    radius_first=True,
):
    """The container's exchange, written out with two FMU2Slave instances
    (`radius_first=False` swaps the two connections, for the negative check)."""
    n = round(stop / step)
    wound, purse = Unit(wound_path, "wound"), Unit(purse_path, "purse")
    out = {k: np.empty(n + 1) for k in OUTPUTS}

    def exchange():
        if radius_first:
            purse.set(wound_radius=wound.get("wound_radius")[0])
            wound.set(edge_stress=purse.get("edge_stress")[0])
        else:
            wound.set(edge_stress=purse.get("edge_stress")[0])
            purse.set(wound_radius=wound.get("wound_radius")[0])

    def sample(i):
        out["wound_radius"][i], out["edge_velocity"][i] = wound.get("wound_radius", "edge_velocity")
        out["edge_stress"][i], out["line_tension"][i] = purse.get("edge_stress", "line_tension")

    try:
        for unit, params in ((wound, wound_params), (purse, purse_params)):
            unit.set(**params)
        for unit in (wound, purse):
            # simulate_fmu defines no tolerance and passes the stop time; so does the container
            unit.fmu.setupExperiment(tolerance=None, startTime=0.0, stopTime=stop)
            unit.fmu.enterInitializationMode()
        exchange()
        for unit in (wound, purse):
            unit.fmu.exitInitializationMode()
            unit.initialized = True
        sample(0)
        for i in range(n):
            t = i * step
            wound.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=step)
            purse.fmu.doStep(currentCommunicationPoint=t, communicationStepSize=step)
            exchange()
            sample(i + 1)
    finally:
        wound.close()
        purse.close()
    out["time"] = np.arange(n + 1) * step
    return out


def test_container_validates(container):
    problems = validate_fmu(container)
    assert problems == [], "validate_fmu found problems:\n" + "\n".join(problems)


def test_container_lists_only_its_real_platform_and_states_its_step_rule(container):
    """The inner FMUs carry linux64 binaries only: the container must not claim darwin64 or
    win64 (fmpy's template brings them), nor carry the template's stray Container.zip; its
    description says that communication steps are whole multiples of its internal step."""
    import zipfile

    import fmpy

    assert fmpy.supported_platforms(container) == ["linux64"]
    assert "Container.zip" not in zipfile.ZipFile(container).namelist()
    md = read_model_description(container)
    step = float(md.defaultExperiment.stepSize)
    assert f"whole multiple of {step:g} s" in md.description, md.description


def test_container_model_description(container):
    md = read_model_description(container)
    variables = {v.name: v for v in md.modelVariables}
    for name in OUTPUTS:
        assert variables[name].causality == "output", name
    for name, value in {**WOUND_PARAMS, **PURSE_PARAMS}.items():
        assert variables[name].causality == "parameter", name
        assert float(variables[name].start) == value, name
    assert md.coSimulation.modelIdentifier == "container_fmu"


def test_container_matches_plain_loop(container_run, fmu_path, purse_path):
    res = container_run
    ref = plain_loop(fmu_path, purse_path, STEP, STOP)
    assert len(res) == len(ref["time"]) == round(STOP / STEP) + 1
    np.testing.assert_allclose(res["time"], ref["time"], rtol=0, atol=1e-9)
    for name in OUTPUTS:
        a, b = res[name], ref[name]
        assert np.all(np.isfinite(a)), name
        scale = np.max(np.abs(b))
        err = float(np.max(np.abs(a - b)) / scale)
        record(f"container vs plain loop, {name} (max |diff| / max |value|)", err)
        assert err <= 1e-12, f"{name}: container and plain loop differ by {err:.3e} (relative)"

    # the comparison can tell exchanges apart: with the connections swapped (edge stress
    # from the previous radius) the radius moves by far more than the tolerance above
    swapped = plain_loop(fmu_path, purse_path, STEP, STOP, radius_first=False)
    diff = float(np.max(np.abs(res["wound_radius"] - swapped["wound_radius"])))
    assert diff > 1e-6, diff


def test_container_opens_then_closes(container_run):
    r = container_run["wound_radius"]
    t = container_run["time"]
    assert r[0] == pytest.approx(R_START, rel=1e-12)
    k = int(np.argmax(r))
    assert r[k] > R_START + 1.0, f"max radius {r[k]} um at t = {t[k]} s"
    assert r[-1] < r[k] - 3.0, f"R(300) = {r[-1]} um, max {r[k]} um"
    # opening while the purse-string is not yet assembled, closing after
    assert t[k] > PURSE_PARAMS["t_delay"]
    assert np.all(np.diff(r[t <= PURSE_PARAMS["t_delay"]]) > 0)
    assert np.all(np.diff(r[t >= t[k]]) <= 0)


def test_container_purse_string_outputs(container_run):
    """line_tension is the assembly law, edge_stress = T_c / (thickness R) at every point."""
    res = container_run
    t = res["time"]
    p = PURSE_PARAMS
    tc = np.where(
        t > p["t_delay"], p["T_max"] * (1.0 - np.exp(-(t - p["t_delay"]) / p["t_assembly"])), 0.0
    )
    np.testing.assert_allclose(res["line_tension"], tc, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(
        res["edge_stress"],
        res["line_tension"] / (p["thickness"] * res["wound_radius"]),
        rtol=1e-12,
        atol=1e-12,
    )


def test_container_parameters_reach_the_components(container, fmu_path, purse_path):
    """Start values given to simulate_fmu go through the container to the components:
    without the purse-string the wound only opens, here with a doubled time scale T (G
    would not do: with no edge stress it changes nothing)."""
    changed = {"T_max": 0.0, "T": 20.0}
    res = simulate_fmu(
        container, stop_time=100.0, output_interval=STEP, output=OUTPUTS, start_values=changed
    )
    ref = plain_loop(
        fmu_path,
        purse_path,
        STEP,
        100.0,
        wound_params={**WOUND_PARAMS, "T": 20.0},
        purse_params={**PURSE_PARAMS, "T_max": 0.0},
    )
    only_purse = simulate_fmu(
        container,
        stop_time=100.0,
        output_interval=STEP,
        output=OUTPUTS,
        start_values={"T_max": 0.0},
    )
    assert np.all(res["line_tension"] == 0.0)
    assert np.all(np.diff(res["wound_radius"]) > 0)
    assert np.max(np.abs(res["wound_radius"] - only_purse["wound_radius"])) > 0.1  # T arrived
    err = float(
        np.max(np.abs(res["wound_radius"] - ref["wound_radius"])) / np.max(ref["wound_radius"])
    )
    record("container vs plain loop, wound_radius with start_values (relative)", err)
    assert err <= 1e-12
