"""target/fmu/WoundClosure.ssp, the coupled system as SSP 1.0: valid against the schema,
the connections and parameters of wound_opening/coupling/loop.py bound where each reader looks
(per component in an .ssv set, and as the system's set), the step in OMSimulator's and
libcosim's annotations, the same file as `python python/coupling/ssp.py build` writes for
PurseString; run with fmpy's SSD reader it agrees with the Python loop at the coupling
accuracy of docs/fmi.md, and with the coupled example within 0.05 um (libcosim and ecos:
test_ssp_readers.py)."""

from __future__ import annotations

import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

import numpy as np
import pytest
from fmpy.ssp.simulation import simulate_ssp
from fmpy.ssp.ssd import read_ssd

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "python"))
from coupling import ssp  # noqa: E402

from wound_opening.coupling.example import STEP  # noqa: E402
from wound_opening.coupling.loop import PURSE_EXAMPLE, WOUND_EXAMPLE, couple  # noqa: E402
from wound_opening.coupling.ssp_file import build  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]

STOP = 300.0
# docs/fmi.md, "Coupling to a closure model" (the SSP file): max |R_ssp(h) - R_loop(h)| over
# 0..300 s is 9.76e-3 um per second of step
# (measured at h = 2, 1, 0.5, 0.25 s: first order, the Jacobi lag of fmpy's stepping).
AGREEMENT_PER_STEP = 0.012  # um / s


@pytest.fixture(scope="module")
def ssp_path(fmu_path):
    path = Path(fmu_path).parent / "WoundClosure.ssp"
    assert path.is_file(), f"{path} missing: cargo run --release -- fmu writes it"
    return str(path)


def test_ssd_is_valid_and_matches_the_loop(ssp_path, fmu_path, purse_path):
    ssd = read_ssd(
        ssp_path, validate=True
    )  # SSP 1.0 SystemStructureDescription.xsd (shipped with fmpy)
    components = {c.name: c.source for c in ssd.system.elements}
    assert components == {
        "wound": "resources/WoundOpening.fmu",
        "purse": "resources/PurseString.fmu",
    }
    connections = {
        (c.startElement, c.startConnector, c.endElement, c.endConnector)
        for c in ssd.system.connections
    }
    assert connections == {
        ("wound", "wound_radius", "purse", "wound_radius"),
        ("purse", "edge_stress", "wound", "edge_stress"),
    }
    values = {p.name: float(p.value) for p in ssp.parameter_set(ssd).parameters}
    expected = {f"wound.{k}": v for k, v in WOUND_EXAMPLE.items()} | {
        f"purse.{k}": v for k, v in PURSE_EXAMPLE.items()
    }
    assert values == pytest.approx(expected, rel=1e-15)
    # The same values per component (resources/<component>.ssv), FMU names, set worked_example.
    for component, example in (("wound", WOUND_EXAMPLE), ("purse", PURSE_EXAMPLE)):
        (element,) = [c for c in ssd.system.elements if c.name == component]
        (binding,) = element.parameterBindings
        assert binding.source == f"resources/{component}.ssv"
        (values,) = binding.parameterValues
        assert values.name == "worked_example"
        own = {p.name: float(p.value) for p in values.parameters}
        assert own == pytest.approx(example, rel=1e-15)
    assert ssp.experiment(ssp_path) == (STEP, STOP)
    with zipfile.ZipFile(ssp_path) as z:
        for name, built in (("WoundOpening.fmu", fmu_path), ("PurseString.fmu", purse_path)):
            assert z.read(f"resources/{name}") == Path(built).read_bytes()


def test_fmpy_simulate_ssp_stops_on_the_zero_radius_it_starts_with(ssp_path, tmp_path, monkeypatch):
    """fmpy 0.3.32 starts the connectors at 0 (python/coupling/ssp.py): the purse-string
    refuses wound_radius = 0 instead of answering with a wrong edge stress. (fmpy does not
    clean up after the failure: its extracted folders go to tmp_path.)"""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    with pytest.raises(Exception, match="fmi2SetReal"):
        simulate_ssp(ssp_path, stop_time=STOP, step_size=0.5)


@pytest.mark.parametrize("step", [1.0, 0.5])
def test_ssp_run_agrees_with_the_python_loop_at_the_coupling_accuracy(
    ssp_path, fmu_path, purse_path, step
):
    run = ssp.simulate(ssp_path, step=step, stop=STOP)
    loop = couple(fmu_path, purse_path, step=step, stop=STOP)
    np.testing.assert_array_equal(run["time"], loop.time)
    assert run["wound.wound_radius"][0] == pytest.approx(loop.wound_radius[0], rel=1e-15)
    gap = np.max(np.abs(run["wound.wound_radius"] - loop.wound_radius))
    assert gap <= AGREEMENT_PER_STEP * step, f"step {step} s: {gap:.3e} um"
    assert (
        np.max(loop.wound_radius) - loop.wound_radius[-1] > 3.0
    )  # it opens and closes: the coupling is live


def annotations(ssp_path) -> dict:
    """The step annotations and the stop time, as OMSimulator and libcosim read them."""
    with zipfile.ZipFile(ssp_path) as z:
        root = ET.fromstring(z.read("SystemStructure.ssd"))
    system = root.find("ssd:System", ssp.NS)
    oms = system.find("ssd:Annotations/ssc:Annotation[@type='org.openmodelica']", ssp.NS)
    master = oms.find("oms:Annotations/oms:SimulationInformation/oms:FixedStepMaster", ssp.NS)
    default = root.find("ssd:DefaultExperiment", ssp.NS)
    osp = default.find(
        "ssd:Annotations/ssc:Annotation[@type='com.opensimulationplatform']/osp:Algorithm", ssp.NS
    )
    (algorithm,) = list(osp)  # libcosim reads every child of osp:Algorithm as an algorithm
    return {
        "oms": master.attrib,
        "osp": (algorithm.tag, algorithm.attrib),
        "stop": default.get("stopTime"),
    }


def test_the_readers_annotations(ssp_path):
    got = annotations(ssp_path)
    # No tolerance: OMSimulator then passes none and WoundOpening keeps its own.
    assert got["oms"] == {"description": "oms-ma", "stepSize": "0.5"}
    assert got["osp"] == (f"{{{ssp.NS['osp']}}}FixedStepAlgorithm", {"baseStepSize": "0.5"})
    assert float(got["stop"]) == STOP


def test_the_builder_writes_the_shipped_file_for_purse_string(
    ssp_path, fmu_path, purse_path, tmp_path
):
    """`ssp.py build` (wound_opening/coupling/ssp_file.py) with PurseString and the worked
    example says what src/package/ssp.rs writes: the same parameters (types and values),
    connections and annotations, under the closure's component name."""
    built = build(
        purse_path,
        tmp_path / "built.ssp",
        closure_values=PURSE_EXAMPLE,
        wound_fmu=fmu_path,
        record=["line_tension"],
        name="purse",
    )
    shipped, mine = read_ssd(ssp_path, validate=True), read_ssd(str(built), validate=True)

    def summary(ssd):
        out = {
            "system": [(p.name, p.type, float(p.value)) for p in ssp.parameter_set(ssd).parameters]
        }
        for c in ssd.system.elements:
            out[c.name] = [(p.name, p.type, float(p.value)) for p in ssp.component_parameters(c)]
            out[c.name + " connectors"] = sorted((k.name, k.kind) for k in c.connectors)
        out["connections"] = sorted(
            (c.startElement, c.startConnector, c.endElement, c.endConnector)
            for c in ssd.system.connections
        )
        return out

    assert summary(mine) == summary(shipped)
    assert annotations(str(built)) == annotations(ssp_path)


def test_the_command_has_help_and_runs_the_file(ssp_path, capsys):
    script = str(ROOT / "python" / "coupling" / "ssp.py")
    done = subprocess.run([sys.executable, script, "--help"], capture_output=True, text=True)
    assert done.returncode == 0 and "usage: python python/coupling/ssp.py" in done.stdout
    assert "build" in done.stdout and "run" in done.stdout
    with pytest.raises(SystemExit) as stop:
        ssp.main([])  # no command: the usage and status 2
    assert stop.value.code == 2 and "required" in capsys.readouterr().err
    ssp.main(["run", ssp_path])
    assert "at t = 300 s" in capsys.readouterr().out


def test_fmpys_reader_runs_the_file_within_the_readers_claim_of_the_example(
    ssp_path, fmu_path, purse_path
):
    """docs/fmi.md's claim for every reader: within 0.05 um of the coupled example."""
    run = ssp.simulate(ssp_path)  # the file's step (0.5 s) and stop time (300 s)
    example = couple(fmu_path, purse_path, step=STEP, stop=STOP, interpolate=True)
    np.testing.assert_array_equal(run["time"], example.time)
    assert np.max(np.abs(run["wound.wound_radius"] - example.wound_radius)) <= 0.05
