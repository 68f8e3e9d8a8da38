"""What importers and saved files rely on stays as it was: the exported symbols of the
shared object, every archive's GUID / instantiation token and the variables an importer
names (name, value reference, causality, variability, type), and the serialized FMU-state format
(a state
saved by an earlier build restores and continues on the exact solution; a state saved now
has the same layout).

tests/python/pinned/interface.json was written from the archives of the release before
the source tree was reorganised (`python tests/python/test_pinned_interface.py OUT.json
DIR_WITH_FMUS` writes it; run it only when an interface change is deliberate, and say so).
"""

from __future__ import annotations

import json
import struct
import subprocess
import sys
import tempfile
import zipfile
from pathlib import Path
from xml.etree import ElementTree

import macho
import numpy as np
import pytest
import wound_exact

ROOT = Path(__file__).resolve().parents[2]
PINNED = Path(__file__).resolve().parent / "pinned" / "interface.json"
ARCHIVES = ("WoundOpening.fmu", "WoundOpening-fmi3.fmu", "PurseString.fmu", "PurseString-fmi3.fmu")
# The saved state: lambda = 0.5, sigma = 1, R_inf = 10, default tolerance, one step to t = 1.
STATE_CASE = {"lambda": 0.5, "sigma": 1.0, "R_inf": 10.0}
STATE_TIME = 1.0


# Every platform folder of the archives (src/package/platforms.rs), with the command that
# lists a binary's exported functions (the cross binutils of scripts/cross.sh).
PLATFORMS = {
    "WoundOpening.fmu": ("linux64", "aarch64-linux", "win64", "darwin64"),
    "WoundOpening-fmi3.fmu": (
        "x86_64-linux",
        "aarch64-linux",
        "x86_64-windows",
        "x86_64-darwin",
        "aarch64-darwin",
    ),
}


def exported_symbols(fmu: Path, folder: str = "linux64") -> list[str]:
    with zipfile.ZipFile(fmu) as z:
        name = next(n for n in z.namelist() if n.startswith(f"binaries/{folder}/"))
        data = z.read(name)
    with tempfile.TemporaryDirectory() as tmp:
        library = Path(tmp) / Path(name).name
        library.write_bytes(data)
        if library.suffix == ".dylib":  # dyld's export trie, of each architecture
            exports = {tuple(s.exports) for s in macho.read(library)}
            assert len(exports) == 1, exports
            return [name.removeprefix("_") for name in exports.pop()]
        if library.suffix == ".dll":  # the PE export table: "[   0] name" lines
            out = subprocess.run(
                ["x86_64-w64-mingw32-objdump", "-p", str(library)],
                capture_output=True,
                text=True,
                check=True,
            ).stdout
            table = out.split("[Ordinal/Name Pointer] Table", 1)[1].split("\n\n", 1)[0]
            return sorted(
                line.split("]", 1)[1].strip() for line in table.splitlines() if "]" in line
            )
        nm = "aarch64-linux-gnu-nm" if folder.startswith("aarch64") else "nm"
        out = subprocess.run(
            [nm, "-D", "--defined-only", str(library)], capture_output=True, text=True, check=True
        ).stdout
    return sorted(line.split()[-1] for line in out.splitlines() if line.strip())


def variables(fmu: Path) -> dict:
    """Token, model name and the variables an importer names (the Model Exchange states and
    derivatives, causality local, are the integrator's, counted by the archive itself)."""
    with zipfile.ZipFile(fmu) as z:
        root = ElementTree.fromstring(z.read("modelDescription.xml"))
    token = root.get("guid") or root.get("instantiationToken")
    rows = []
    if root.get("fmiVersion", "").startswith("2"):
        for v in root.iter("ScalarVariable"):
            kind = next(iter(v)).tag
            rows.append(
                [
                    v.get("name"),
                    int(v.get("valueReference")),
                    v.get("causality", "local"),
                    v.get("variability", "continuous"),
                    kind,
                ]
            )
    else:
        for v in root.find("ModelVariables"):
            rows.append(
                [
                    v.get("name"),
                    int(v.get("valueReference")),
                    v.get("causality", "local"),
                    v.get("variability", "continuous"),
                    v.tag,
                ]
            )
    rows = [r for r in rows if r[2] != "local"]
    return {"token": token, "model_identifier": root.get("modelName"), "variables": rows}


def initialized(fmu: Path):
    """An fmpy co-simulation instance of `fmu` at t = 0 with STATE_CASE set, and its value
    references by name."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(fmu))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(
        guid=md.guid,
        unzipDirectory=extract(str(fmu)),
        modelIdentifier=md.coSimulation.modelIdentifier,
    )
    slave.instantiate()
    slave.setupExperiment(startTime=0.0)
    slave.setReal([vr[k] for k in STATE_CASE], list(STATE_CASE.values()))
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    return slave, vr


def saved_state(fmu: Path) -> bytes:
    slave, _ = initialized(fmu)
    slave.doStep(0.0, STATE_TIME)
    blob = bytes(slave.serializeFMUstate(slave.getFMUstate()))
    slave.terminate()
    slave.freeInstance()
    return blob


def layout(blob: bytes) -> tuple[bytes, np.ndarray]:
    """(every byte but the modal coefficients and the checksum, the coefficients). Envelope:
    16 bytes, then the model identifier, machine state, start time, time, stop time; the
    wound model: parameters and scales, mesh, tolerances, scheme, then the solver state
    (time, n, n coefficients) and the input rate (src/models/wound/codec.rs)."""
    name_len = blob[16]
    model = 17 + name_len + 1 + 8 + 8 + 1 + 8
    solver = model + 6 * 8 + 2 * 4 + 3 * 8 + 1 + 8 + 2 * 4 + 8
    assert blob[solver] == 1, "the state holds a solver"
    n = struct.unpack_from("<I", blob, solver + 1 + 8)[0]
    coeffs = solver + 1 + 8 + 4
    values = np.frombuffer(blob, dtype="<f8", count=n, offset=coeffs)
    return blob[:coeffs] + blob[coeffs + 8 * n : -4], values


@pytest.fixture(scope="module")
def pinned() -> dict:
    return json.loads(PINNED.read_text())


@pytest.fixture(scope="module")
def fmu_dir(fmu_path, fmu3_path, purse_path, purse3_path) -> Path:
    return Path(fmu_path).parent


def test_exported_symbols_are_the_pinned_ones(pinned, fmu_dir):
    assert exported_symbols(fmu_dir / "WoundOpening.fmu") == pinned["symbols"]


@pytest.mark.parametrize(
    "archive, folder", [(a, f) for a, folders in PLATFORMS.items() for f in folders]
)
def test_every_platform_binary_exports_the_pinned_symbols(pinned, fmu_dir, archive, folder):
    with zipfile.ZipFile(fmu_dir / archive) as z:
        binaries = sorted({n.split("/")[1] for n in z.namelist() if n.startswith("binaries/")})
    assert binaries == sorted(PLATFORMS[archive]), binaries
    assert exported_symbols(fmu_dir / archive, folder) == pinned["symbols"]


@pytest.mark.parametrize("archive", ARCHIVES)
def test_tokens_and_value_references_are_the_pinned_ones(pinned, fmu_dir, archive):
    assert variables(fmu_dir / archive) == pinned["archives"][archive]


def test_a_state_saved_by_the_pinned_build_restores_and_continues_exactly(pinned, fmu_dir):
    slave, vr = initialized(fmu_dir / "WoundOpening.fmu")
    blob = bytes.fromhex(pinned["state"])
    slave.setFMUstate(slave.deSerializeFMUstate(blob))
    lam, sigma, r_inf = STATE_CASE.values()
    amplitude = wound_exact.final_radius(sigma, r_inf) - wound_exact.initial_radius(sigma)
    slave_time = STATE_TIME
    for t in (STATE_TIME, 2.5, 10.0):
        if t > STATE_TIME:
            slave.doStep(slave_time, t - slave_time)
        slave_time = t
        radius = slave.getReal([vr["wound_radius"]])[0]
        exact = float(wound_exact.edge(lam, sigma, r_inf, np.array([t]))[0][0])
        assert abs(radius - exact) <= 1e-10 * amplitude, (t, radius, exact)
    slave.terminate()
    slave.freeInstance()


def test_a_state_saved_now_has_the_pinned_layout(pinned, fmu_dir):
    fixed_now, coeffs_now = layout(saved_state(fmu_dir / "WoundOpening.fmu"))
    fixed_then, coeffs_then = layout(bytes.fromhex(pinned["state"]))
    assert fixed_now == fixed_then
    assert coeffs_now.size == coeffs_then.size
    # The modal coefficients are results of floating-point work: equal to rounding.
    assert np.allclose(coeffs_now, coeffs_then, rtol=1e-9, atol=1e-14 * np.abs(coeffs_then).max())


def write(out: Path, fmu_dir: Path) -> None:
    data = {
        "symbols": exported_symbols(fmu_dir / "WoundOpening.fmu"),
        "archives": {a: variables(fmu_dir / a) for a in ARCHIVES},
        "state": saved_state(fmu_dir / "WoundOpening.fmu").hex(),
    }
    out.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    write(Path(sys.argv[1]), Path(sys.argv[2]))
