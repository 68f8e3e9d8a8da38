"""The FMI 3.0 field arrays meet the contract docs/fmi.md states for them, at random radii
anywhere in the tissue (not only at the default probes), against the exact profiles. The
bounds are read from the page, so the page cannot claim more than the arrays deliver."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import wound_exact as we
from fmpy import extract, read_model_description
from fmpy.fmi3 import FMU3Slave

DOC = Path(__file__).resolve().parents[2] / "docs" / "fmi.md"
TIMES = np.array([0.01, 0.1, 1.0, 10.0, 100.0])


def stated_contract():
    text = " ".join(DOC.read_text().split())
    m = re.search(
        r"\*\*displacement within (\S+) of the opening R_final - R1; velocity within (\S+) / "
        r"(\S+) / (\S+) "
        r"\(relative to \|u_t\|, floored at the opening / 100 per T\) at lambda = 0.1 / 1 / 10\*\*",
        text,
    )
    assert m, "docs/fmi.md states the field contract"
    return float(m.group(1)), dict(zip([0.1, 1.0, 10.0], map(float, m.groups()[1:])))


@pytest.fixture(scope="module")
def fmu3(fmu3_path):
    md = read_model_description(fmu3_path)
    return md, {v.name: v.valueReference for v in md.modelVariables}, extract(fmu3_path)


def field(fmu3, lam, r_inf, radii):
    md, vr, unzipped = fmu3
    f = FMU3Slave(
        guid=md.guid, unzipDirectory=unzipped, modelIdentifier="WoundOpening", instanceName="field"
    )
    f.instantiate()
    f.enterConfigurationMode()
    f.setUInt64([vr["n_probes"]], [len(radii)])
    f.exitConfigurationMode()
    f.setFloat64([vr["lambda"], vr["R_inf"], vr["sigma"]], [lam, r_inf, 0.8])
    f.setFloat64([vr["probe_radii"]], list(radii))
    f.enterInitializationMode(startTime=0.0)
    f.exitInitializationMode()
    u, v, t = [], [], 0.0
    for tk in TIMES:
        f.doStep(t, tk - t)
        t = tk
        u.append(f.getFloat64([vr["displacement"]], nValues=len(radii)))
        v.append(f.getFloat64([vr["velocity"]], nValues=len(radii)))
    f.terminate()
    f.freeInstance()
    return np.array(u), np.array(v)


@pytest.mark.parametrize("lam", [0.1, 1.0, 10.0])
@pytest.mark.parametrize("seed", range(3))
def test_the_arrays_meet_the_stated_contract_at_random_radii(fmu3, lam, seed):
    u_max, v_max = stated_contract()
    rng = np.random.default_rng(100 * seed + int(10 * lam))
    r_inf = 10 ** rng.uniform(0.5, 2.2)
    radii = np.sort(np.exp(rng.uniform(0, np.log(r_inf), 16)))
    u, v = field(fmu3, lam, r_inf, radii)
    u_exact, v_exact = we.profile(lam, 0.8, r_inf, radii, TIMES)
    amplitude = we.final_radius(0.8, r_inf) - we.initial_radius(0.8)
    eu = np.max(np.abs(u - u_exact)) / amplitude
    ev = np.max(np.abs(v - v_exact) / np.maximum(np.abs(v_exact), amplitude / 100))
    assert eu <= u_max, (r_inf, eu)
    assert ev <= v_max[lam], (r_inf, ev)
