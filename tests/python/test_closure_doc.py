"""docs/closure.md as written: its pythonfmu closure model (taken from the page) is built
with pythonfmu, coupled through `couple()` by its own names (an Integer parameter, the
edge stress or the line tension read), and agrees with PurseString.fmu, the package's
closure with the same law; the SSP that `python python/coupling/ssp.py build` writes for it
runs in libcosim within 0.05 um of the loop; the fold's numbers of the page are those of
the equilibrium condition, and past the fold the wound closes through zero."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from wound_opening.coupling.loop import (
    PURSE_EXAMPLE,
    WOUND_EXAMPLE,
    Closure,
    couple,
)

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "closure.md"
RING = Closure(radius="radius", edge_stress="stress", record=("tension",))
RING_PARAMS = {"cables": 2, "cable_tension": 3250.0}


@pytest.fixture(scope="module")
def ring_fmu(tmp_path_factory):
    """RingClosure.fmu, built by pythonfmu from the page's code block."""
    text = DOC.read_text()
    block = re.search(r"<!-- closure example:[^\n]*\n```python\n(.*?)```", text, re.S)
    assert block, "docs/closure.md lost its marked example"
    folder = tmp_path_factory.mktemp("ring")
    (folder / "ring.py").write_text(block.group(1))
    done = subprocess.run(
        [sys.executable, "-m", "pythonfmu", "build", "-f", "ring.py", "-d", str(folder)],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    return str(folder / "RingClosure.fmu")


def test_the_ring_couples_by_its_own_names_as_purse_string_does(ring_fmu, fmu_path, purse_path):
    kw = {"step": 0.5, "stop": 300.0, "interpolate": True}
    ring = couple(fmu_path, ring_fmu, closure=RING, purse_params=RING_PARAMS, **kw)
    purse = couple(fmu_path, purse_path, **kw)
    scale = np.max(purse.wound_radius)
    assert np.max(np.abs(ring.wound_radius - purse.wound_radius)) <= 1e-12 * scale
    assert np.max(np.abs(ring.closure["tension"] - purse.line_tension)) <= 1e-12 * 6500
    assert purse.wound_radius.max() - purse.wound_radius[-1] > 3.0  # a live coupling
    # Read through its line tension, with Laplace's law applied by the loop: the same run.
    by_tension = Closure(radius="radius", edge_stress=None, line_tension="tension", thickness_um=5)
    again = couple(fmu_path, ring_fmu, closure=by_tension, purse_params=RING_PARAMS, **kw)
    assert np.max(np.abs(again.wound_radius - ring.wound_radius)) <= 1e-12 * scale


def test_the_pages_couple_block_prints_what_it_says(ring_fmu, monkeypatch, capsys):
    block = re.search(r"<!-- couple example:[^\n]*\n```python\n(.*?)```", DOC.read_text(), re.S)
    assert block, "docs/closure.md lost its marked couple() example"
    monkeypatch.chdir(Path(ring_fmu).parent)
    exec(compile(block.group(1), str(DOC), "exec"), {})
    printed = capsys.readouterr().out.strip()
    assert re.match(r"\d+\.\d{4} um, \d+\.\d pN$", printed), printed
    assert f"# {printed}" in block.group(1)  # the value the page states


def test_a_wrong_name_or_type_is_refused_with_what_the_fmu_has(ring_fmu, fmu_path):
    kw = {"step": 1.0, "stop": 2.0, "closure": RING}
    with pytest.raises(ValueError, match=r"cables is a Integer parameter: 2\.5"):
        couple(fmu_path, ring_fmu, purse_params={"cables": 2.5}, **kw)
    with pytest.raises(ValueError, match="no parameter named 'T_max'.*cable_tension"):
        couple(fmu_path, ring_fmu, purse_params=PURSE_EXAMPLE, **kw)
    with pytest.raises(ValueError, match="no output named 'edge_stress'.*stress"):
        couple(fmu_path, ring_fmu, closure=Closure(radius="radius"), step=1.0, stop=2.0)
    with pytest.raises(ValueError, match="thickness_um"):
        Closure(radius="radius", edge_stress=None, line_tension="tension")


def test_the_ssp_built_for_the_ring_runs_in_libcosim(ring_fmu, fmu_path, tmp_path):
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    ssp = tmp_path / "RingClosure.ssp"
    build = [sys.executable, str(ROOT / "python" / "coupling" / "ssp.py"), "build", ring_fmu]
    # docs/closure.md's command (the wound: the package's archive, the one built here).
    build += ["--radius", "radius", "--edge-stress", "stress"]
    build += ["--set", "cables=2", "--set", "cable_tension=3250", "--out", str(ssp)]
    done = subprocess.run(build, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    log_output_level(CosimLogLevel.WARNING)
    execution = CosimExecution.from_ssp_file(str(ssp))
    wound = {s.name.decode(): s.index for s in execution.slave_infos()}["wound"]
    ref = {v.name.decode(): v.reference for v in execution.slave_variables(wound)}
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    radius = []
    for _ in range(600):
        assert execution.step()
        radius.append(observer.last_real_values(wound, [ref["wound_radius"]])[0])
    loop = couple(fmu_path, ring_fmu, closure=RING, purse_params=RING_PARAMS, step=0.5, stop=300)
    assert np.max(np.abs(np.array(radius) - loop.wound_radius[1:])) <= 0.05


def fold():
    """(c, c*, T_max*, R_stable, R_unstable, R_fold) of the worked example, um and pN."""
    w, pe = WOUND_EXAMPLE, PURSE_EXAMPLE
    k = w["R_inf"] ** 2 / (w["R_inf"] ** 2 - 1)
    r1, rf = 1 + w["sigma"] / 6, 1 + 2 * w["sigma"] / 3 * k
    scale = pe["thickness"] * w["R0"] * w["sigma"] * w["G"]
    c, c_star = pe["T_max"] / scale, rf**2 / (4 * (rf - r1))
    root = math.sqrt(rf * rf - 4 * c * (rf - r1))
    r0 = w["R0"]
    return c, c_star, c_star * scale, r0 * (rf + root) / 2, r0 * (rf - root) / 2, r0 * rf / 2


def test_the_pages_fold_numbers():
    c, c_star, t_star, stable, unstable, at_fold = fold()
    text = DOC.read_text()
    for number in (
        f"R_final = {2 * at_fold / WOUND_EXAMPLE['R0']:.5f}, c = {c:g} and c* = {c_star:.5f}",
        f"R1 = {1 + WOUND_EXAMPLE['sigma'] / 6:.5f}",
        f"{100 * (c_star / c - 1):.1f} % more tension",
        f"T_max* = c* h R0 sigma G = {t_star:.1f} pN",
        f"{100 * (1 - c / c_star):.1f} % below it",
        f"{stable:.4f} um",
        f"unstable one\n{unstable:.4f} um",
        f"fold's radius {at_fold:.4f} um",
    ):
        assert number in text, number


def test_past_the_fold_the_wound_closes_through_zero(fmu_path, purse_path):
    """T_max 10 % above the fold: no equilibrium; the radius falls until PurseString
    refuses it (a closed wound) and the run stops with that error."""
    t_max = 1.1 * fold()[2]
    with pytest.raises(Exception, match="fmi2SetReal"):
        couple(
            fmu_path,
            purse_path,
            step=1.0,
            stop=2000.0,
            purse_params=PURSE_EXAMPLE | {"T_max": t_max},
        )
