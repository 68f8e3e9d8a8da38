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
    r = simulate_fmu(
        fmu3_path,
        fmi_type="CoSimulation",
        start_values=PARAMS(lam),
        stop_time=10.0,
        step_size=0.01,
        output_interval=0.01,
        output=["wound_radius"],
    )
    keep = r["time"] >= 0.01
    r_exact, _ = exact(lam, r["time"][keep])
    err = radius_error(r["wound_radius"][keep], r_exact).max()
    record(f"FMI 3.0 co-simulation radius error, lambda = {lam}", err)
    assert err < RADIUS_TOL, (lam, err)


@pytest.mark.parametrize("lam", [0.0, 0.1, 1.0, 10.0])
def test_model_exchange_matches_the_exact_opening(fmu3_path, lam):
    r = simulate_fmu(
        fmu3_path,
        fmi_type="ModelExchange",
        solver="CVode",
        relative_tolerance=1e-11,
        start_values=PARAMS(lam),
        stop_time=10.0,
        output_interval=0.01,
        output=["wound_radius"],
    )
    keep = r["time"] >= 0.01
    r_exact, _ = exact(lam, r["time"][keep])
    err = radius_error(r["wound_radius"][keep], r_exact).max()
    record(f"FMI 3.0 Model Exchange CVode radius error, lambda = {lam}", err)
    assert err < ME_RADIUS_TOL, (lam, err)


def test_purse_string_fmi3_both_interfaces(purse3_path):
    for kind in ("CoSimulation", "ModelExchange"):
        r = simulate_fmu(
            purse3_path,
            fmi_type=kind,
            stop_time=100.0,
            output_interval=10.0,
            output=["line_tension"],
        )
        t = r["time"]
        want = np.where(t > 20.0, 6500.0 * (1 - np.exp(-(t - 20.0) / 30.0)), 0.0)
        np.testing.assert_allclose(r["line_tension"], want, rtol=1e-14, atol=1e-9)


# The displacement field (FMI 3.0 arrays): value references from the archive.
PROBE_RADII = [1.0, 1.5, 2.0, 3.0, 5.0, 10.0]
PROFILE_TIMES = [0.01, 0.1, 1.0, 10.0]
# Measured worst errors at these radii and times (lambda = 0.1, 1, 10): displacement
# 1.3e-8 of the opening (the edge alone: 1e-10; between the mesh's nodes the polynomial
# interpolation of the modes adds up to ~1e-8), velocity 4.7e-5 relative (floor AMPLITUDE /
# 100; lambda = 0.1 at t <= 0.1, inside the viscous boundary layer of width lambda),
# 1e-6 at lambda = 1 and 1e-8 at lambda = 10. The tolerances are twice those.
PROFILE_U_TOL = 3e-8
PROFILE_V_TOL = {0.1: 1e-4, 1.0: 2e-6, 10.0: 2e-8}


def _slave3(path):
    from fmpy import extract
    from fmpy.fmi3 import FMU3Slave

    md = read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmu = FMU3Slave(
        guid=md.guid,
        unzipDirectory=extract(path),
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="probes",
    )
    fmu.instantiate()
    return fmu, vr


@pytest.mark.parametrize("lam", [0.1, 1.0, 10.0])
def test_displacement_field_matches_the_exact_profiles(fmu3_path, lam):
    import wound_exact
    from fmu_harness import AMPLITUDE

    fmu, vr = _slave3(fmu3_path)
    fmu.setFloat64([vr["lambda"]], [lam])
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    assert fmu.getFloat64([vr["probe_radii"]], nValues=6) == PROBE_RADII
    u0 = fmu.getFloat64([vr["displacement"]], nValues=6)
    assert u0 == [r / 6 for r in PROBE_RADII], "sigma r / 6 at the cut"
    u_exact, v_exact = wound_exact.profile(lam, 1.0, 10.0, PROBE_RADII, np.array(PROFILE_TIMES))
    t = 0.0
    for k, tk in enumerate(PROFILE_TIMES):
        fmu.doStep(t, tk - t)
        t = tk
        u = np.array(fmu.getFloat64([vr["displacement"]], nValues=6))
        v = np.array(fmu.getFloat64([vr["velocity"]], nValues=6))
        eu = np.max(np.abs(u - u_exact[k])) / AMPLITUDE
        ev = np.max(np.abs(v - v_exact[k]) / np.maximum(np.abs(v_exact[k]), AMPLITUDE / 100))
        record(f"FMI 3.0 displacement field error, lambda = {lam}", eu)
        record(f"FMI 3.0 velocity field error, lambda = {lam}", ev)
        assert eu < PROFILE_U_TOL, (lam, tk, eu)
        assert ev < PROFILE_V_TOL[lam], (lam, tk, ev)
    fmu.terminate()
    fmu.freeInstance()


def test_number_of_probes_is_a_structural_parameter(fmu3_path):
    """Set in Configuration Mode; the radii then have that many values; a radius outside
    the tissue is refused when the field is read (R_inf may be set after the radii)."""
    from fmpy.fmi1 import FMICallException

    fmu, vr = _slave3(fmu3_path)
    with pytest.raises(FMICallException):
        fmu.setUInt64([vr["n_probes"]], [3])  # not in Configuration Mode
    fmu.enterConfigurationMode()
    fmu.setUInt64([vr["n_probes"]], [3])
    fmu.exitConfigurationMode()
    fmu.setFloat64([vr["probe_radii"]], [1.0, 4.0, 10.0])
    with pytest.raises(FMICallException):
        fmu.setFloat64([vr["probe_radii"]], [1.0, 4.0])  # two values for three probes
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    fmu.doStep(0.0, 1.0)
    u = fmu.getFloat64([vr["displacement"]], nValues=3)
    assert len(u) == 3 and u[0] == pytest.approx(
        fmu.getFloat64([vr["wound_radius"]])[0] - 1.0, abs=1e-15
    )
    fmu.terminate()
    fmu.freeInstance()
    fmu, vr = _slave3(fmu3_path)
    fmu.setFloat64([vr["probe_radii"]], [1.0, 2.0, 3.0, 4.0, 5.0, 11.0])  # R_inf = 10
    fmu.enterInitializationMode(startTime=0.0)
    fmu.exitInitializationMode()
    with pytest.raises(FMICallException):
        fmu.getFloat64([vr["displacement"]], nValues=6)
    assert fmu.getFloat64([vr["wound_radius"]]) == [1 + 1 / 6], "the scalars are unaffected"
    fmu.terminate()
    fmu.freeInstance()


def _couple3(wound_path, purse_path, step, stop):
    """The purse-string loop of wound_opening/coupling/loop.py with the FMI 3.0 archives: the wound
    asks for its edge stress at the end of each step (Intermediate Update Mode) and gets the
    linear extrapolation from the last two communication points."""
    from fmpy import extract
    from fmpy.fmi3 import FMU3Slave

    from wound_opening.coupling.loop import PURSE_EXAMPLE, WOUND_EXAMPLE

    md_w, md_p = read_model_description(wound_path), read_model_description(purse_path)
    vw = {v.name: v.valueReference for v in md_w.modelVariables}
    vp = {v.name: v.valueReference for v in md_p.modelVariables}
    wound = FMU3Slave(
        guid=md_w.guid,
        unzipDirectory=extract(wound_path),
        modelIdentifier="WoundOpening",
        instanceName="w",
    )
    purse = FMU3Slave(
        guid=md_p.guid,
        unzipDirectory=extract(purse_path),
        modelIdentifier="PurseString",
        instanceName="p",
    )
    ramp = {"t": 0.0, "p": 0.0, "slope": 0.0}

    def update(
        env,
        time,
        set_requested,
        get_allowed,
        finished,
        can_return_early,
        early_requested,
        early_time,
    ):
        if set_requested:
            wound.setFloat64([vw["edge_stress"]], [ramp["p"] + ramp["slope"] * (time - ramp["t"])])

    wound.instantiate(intermediateUpdate=update, requiredIntermediateVariables=[vw["edge_stress"]])
    purse.instantiate()
    for fmu, vr, params in ((wound, vw, WOUND_EXAMPLE), (purse, vp, PURSE_EXAMPLE)):
        fmu.setFloat64([vr[k] for k in params], list(params.values()))
        fmu.enterInitializationMode(startTime=0.0, stopTime=stop)
        fmu.exitInitializationMode()
    n = round(stop / step)
    radii, previous = [], None
    for k in range(n + 1):
        t = k * step
        (r,) = wound.getFloat64([vw["wound_radius"]])
        purse.setFloat64([vp["wound_radius"]], [r])
        (p,) = purse.getFloat64([vp["edge_stress"]])
        wound.setFloat64([vw["edge_stress"]], [p])
        ramp.update(t=t, p=p, slope=0.0 if previous is None else (p - previous) / step)
        previous = p
        radii.append(r)
        if k < n:
            wound.doStep(t, step)
            purse.doStep(t, step)
    for fmu in (wound, purse):
        fmu.terminate()
        fmu.freeInstance()
    return np.array(radii)


def test_intermediate_update_gives_second_order_coupling(fmu3_path, purse3_path):
    """FMI 3.0 has no input derivatives; setting the input in Intermediate Update Mode is
    its replacement. Measured orders (steps 4, 2, 1, 0.5 s; 300 s): 1.930 and 1.965, those
    of the FMI 2.0 loop with fmi2SetRealInputDerivatives."""
    steps = [4.0, 2.0, 1.0, 0.5]
    runs = [_couple3(fmu3_path, purse3_path, h, 300.0) for h in steps]
    diffs = [np.max(np.abs(fine[::2] - coarse)) for coarse, fine in zip(runs, runs[1:])]
    orders = [np.log2(a / b) for a, b in zip(diffs, diffs[1:])]
    for h, o in zip(steps[1:], orders):
        record(f"FMI 3.0 intermediate update coupled order, h = {h} s", o)
    assert all(1.85 < o < 2.1 for o in orders), orders
