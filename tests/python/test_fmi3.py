"""The FMI 3.0 archives (WoundOpening-fmi3.fmu, PurseString-fmi3.fmu: the same shared
object as the FMI 2.0 ones, in binaries/x86_64-linux): fmpy's validation, the declared
interfaces, and both interface types run by fmpy against the exact solution.

Measured (when this was written): co-simulation at steps of 0.01, radius errors 1.1e-11,
7.8e-12, 1.1e-12, 1.3e-13 of the opening for lambda = 0, 0.1, 1, 10 (the FMI 2.0 numbers:
the same code); Model Exchange with CVode at relative tolerance 1e-11, 3.5e-10, 3.5e-10,
8.4e-10, 7.9e-10.
"""

import zipfile

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from fmu_harness import PARAMS, RADIUS_TOL, exact, radius_error, record

ME_RADIUS_TOL = 1e-8


@pytest.fixture(params=["WoundOpening", "PurseString"])
def fmu3(request, fmu3_path, purse3_path):
    return request.param, {"WoundOpening": fmu3_path, "PurseString": purse3_path}[request.param]


def test_validate_fmu_reports_no_problems(fmu3):
    _, path = fmu3
    problems = validate_fmu(path)
    assert problems == [], "\n".join(problems)


def test_archive_and_interfaces(fmu3):
    name, path = fmu3
    with zipfile.ZipFile(path) as zf:
        names = zf.namelist()
    assert f"binaries/x86_64-linux/{name}.so" in names, names
    assert "documentation/index.html" in names
    assert "extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml" in names
    md = read_model_description(path)
    assert md.fmiVersion == "3.0"
    assert md.coSimulation.modelIdentifier == name and md.modelExchange.modelIdentifier == name
    assert not md.coSimulation.hasEventMode
    independent = [v for v in md.modelVariables if v.causality == "independent"]
    assert [v.name for v in independent] == ["time"]


@pytest.mark.parametrize("lam", [0.0, 0.1, 1.0, 10.0])
def test_co_simulation_matches_the_exact_opening(fmu3_path, lam):
    r = simulate_fmu(fmu3_path, fmi_type="CoSimulation", start_values=PARAMS(lam), stop_time=10.0,
                     step_size=0.01, output_interval=0.01, output=["wound_radius"])
    keep = r["time"] >= 0.01
    r_exact, _ = exact(lam, r["time"][keep])
    err = radius_error(r["wound_radius"][keep], r_exact).max()
    record(f"FMI 3.0 co-simulation radius error, lambda = {lam}", err)
    assert err < RADIUS_TOL, (lam, err)


@pytest.mark.parametrize("lam", [0.0, 0.1, 1.0, 10.0])
def test_model_exchange_matches_the_exact_opening(fmu3_path, lam):
    r = simulate_fmu(fmu3_path, fmi_type="ModelExchange", solver="CVode", relative_tolerance=1e-11,
                     start_values=PARAMS(lam), stop_time=10.0, output_interval=0.01, output=["wound_radius"])
    keep = r["time"] >= 0.01
    r_exact, _ = exact(lam, r["time"][keep])
    err = radius_error(r["wound_radius"][keep], r_exact).max()
    record(f"FMI 3.0 Model Exchange CVode radius error, lambda = {lam}", err)
    assert err < ME_RADIUS_TOL, (lam, err)


def test_purse_string_fmi3_both_interfaces(purse3_path):
    for kind in ("CoSimulation", "ModelExchange"):
        r = simulate_fmu(purse3_path, fmi_type=kind, stop_time=100.0, output_interval=10.0, output=["line_tension"])
        t = r["time"]
        want = np.where(t > 20.0, 6500.0 * (1 - np.exp(-(t - 20.0) / 30.0)), 0.0)
        np.testing.assert_allclose(r["line_tension"], want, rtol=1e-14, atol=1e-9)
