"""Masters that stop on any status but OK (fmusim, OMSimulator, PyFMI on fmi2Warning), through
fmpy: the validity crossing of lambda = 0.3, sigma = 2, R_inf = 20 (an edge strain of 1 at
t = 3 s) stops them unless `validity_warning = 0`, which the warning names; then the run
reaches its end on the exact solution. A tolerance of 0 from the master (OMSimulator's SSP
import) is none given. Small sigma (docs/model.md, the accepted domain): refused with the
range where the rounding of R misses the tolerance, else accurate to it, on every path
(FMI 2.0 and 3.0 co-simulation and Model Exchange, the package's simulate).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import wound_exact
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from test_masters import NotOk, strict

CASE = {"lambda": 0.3, "sigma": 2.0, "R_inf": 20.0}
EPS = np.finfo(float).eps


def opening(sigma, r_inf):
    return wound_exact.final_radius(sigma, r_inf) - wound_exact.initial_radius(sigma)


@pytest.mark.parametrize("which", ["fmi2", "fmi3"])
def test_a_strict_master_stops_at_the_crossing_without_validity_warning_0(
    fmu_path, fmu3_path, which
):
    with pytest.raises(NotOk, match="DoStep.*WARNING"):
        simulate_fmu(
            fmu_path if which == "fmi2" else fmu3_path,
            start_values=CASE,
            stop_time=10.0,
            output_interval=0.5,
            output=["wound_radius"],
            fmi_call_logger=strict,
        )


def test_the_warning_names_the_parameter_and_the_value_to_set(make_slave):
    s = make_slave()
    s.initialize(CASE)
    for t in np.arange(1.0, 6.0):
        s.step_to(t)
    warned = [m for m in s.log if m.status == 1]
    assert len(warned) == 1 and warned[0].category == "logStatusWarning", s.log_text()
    text = warned[0].message
    assert "at t = 3 s the run leaves the model's validity: the strain at the wound edge" in text, (
        text
    )
    assert "the parameter validity_warning is set to 0" in text, text


@pytest.mark.parametrize("which", ["fmi2", "fmi3"])
def test_with_validity_warning_0_a_strict_master_runs_to_the_end_on_the_exact_solution(
    fmu_path, fmu3_path, which
):
    r = simulate_fmu(
        fmu_path if which == "fmi2" else fmu3_path,
        start_values={**CASE, "validity_warning": 0},
        stop_time=10.0,
        output_interval=0.5,
        output=["wound_radius"],
        fmi_call_logger=strict,
    )
    assert r["time"][-1] == pytest.approx(10.0)
    t = r["time"][1:]
    exact, _ = wound_exact.edge(CASE["lambda"], CASE["sigma"], CASE["R_inf"], t)
    err = np.max(np.abs(r["wound_radius"][1:] - exact)) / opening(CASE["sigma"], CASE["R_inf"])
    assert err < 1e-10, err
    assert exact[-1] - 1 > 1.0, "the run did leave the validity (edge strain > 1)"


def test_with_validity_warning_0_the_crossing_is_logged_with_status_ok(make_slave):
    s = make_slave()
    s.enter_initialization(CASE)
    s.fmu.setInteger([s.vr["validity_warning"]], [0])
    s.exit_initialization()
    for t in np.arange(1.0, 6.0):
        s.step_to(t)
    noted = [m for m in s.log if m.category == "logStatusWarning"]
    assert [m.status for m in noted] == [0], s.log_text()
    assert (
        "at t = 3 s the run leaves the model's validity: the strain at the wound edge"
        in noted[0].message
    )


def test_a_tolerance_of_0_is_none_given_and_nan_negative_infinite_are_refused(make_slave):
    s = make_slave()
    s.fmu.setupExperiment(tolerance=0.0, startTime=0.0)
    s.fmu.enterInitializationMode()
    s.fmu.exitInitializationMode()
    s.initialized = True
    assert any(
        "tolerance = 0 with toleranceDefined is taken as no tolerance given" in m.message
        and m.status == 0
        for m in s.log
    ), s.log_text()
    s.time = 0.0
    s.step_to(1.0)
    for bad in (math.nan, -1e-6, math.inf):
        t = make_slave()
        with pytest.raises(FMICallException):
            t.fmu.setupExperiment(tolerance=bad, startTime=0.0)
        assert "it must be finite and > 0" in t.log_text()


def test_fmi3_tolerance_0_is_none_given(fmu3_path):
    from fmpy import extract, read_model_description
    from fmpy.fmi3 import FMU3Slave

    md = read_model_description(fmu3_path)
    slave = FMU3Slave(
        guid=md.guid,
        unzipDirectory=extract(fmu3_path),
        modelIdentifier="WoundOpening",
        fmiCallLogger=strict,
    )
    slave.instantiate()
    slave.enterInitializationMode(tolerance=0.0, startTime=0.0)
    slave.exitInitializationMode()
    slave.doStep(0.0, 1.0)
    slave.terminate()
    slave.freeInstance()


# --------------------------------------------------------------------------- small sigma

SIGMAS = [1e-6, 1e-8, 1e-10, -1e-12]
TIMES = np.array([0.01, 0.1, 1.0, 10.0])
LAM, R_INF = 1.0, 10.0


def floor(tol):
    """6 eps / tolerance (src/solver/tolerance.rs, sigma_floor), the tolerance down to 1e-11."""
    return 6 * EPS / max(tol, 1e-11)


def exact_opening_error(sigma, r):
    """max |R - R_exact| / (R_final - R1) over TIMES; R - 1 = sigma (R_ref - 1) exactly (linear)."""
    ref, _ = wound_exact.edge(LAM, 1.0, R_INF, TIMES)
    return float(np.max(np.abs((np.asarray(r) - 1.0) - sigma * (ref - 1.0)))) / abs(
        opening(sigma, R_INF)
    )


def _text(m):
    return m.decode("utf-8", "replace") if isinstance(m, bytes) else str(m)


def refusal_names_the_range(text, tol):
    mantissa, exponent = f"{floor(tol):.2e}".split("e")  # as Rust's {:.2e} writes it: 1.33e-5
    return f"accepted: sigma = 0 or |sigma| >= {mantissa}e{int(exponent)}" in text


@pytest.mark.parametrize("tol", [1e-10, 1e-3])
@pytest.mark.parametrize("which", ["fmi2", "fmi3"])
def test_small_sigma_in_co_simulation_is_refused_with_the_range_or_accurate(
    fmu_path, fmu3_path, which, tol
):
    path = fmu_path if which == "fmi2" else fmu3_path
    outcomes = set()
    for sigma in SIGMAS:
        messages = []
        logger = lambda *args: messages.append(_text(args[-1]))  # noqa: E731
        start = {"lambda": LAM, "sigma": sigma, "R_inf": R_INF, "tolerance": tol}
        try:
            r = simulate_fmu(
                path,
                start_values=start,
                stop_time=10.0,
                output_interval=0.01,
                output=["wound_radius"],
                relative_tolerance=tol,
                logger=logger,
                debug_logging=False,
            )
        except Exception as e:  # fmpy raises on the refused fmi2ExitInitializationMode
            assert abs(sigma) < floor(tol), (sigma, tol, e)
            assert any(refusal_names_the_range(m, tol) for m in messages), messages
            outcomes.add("refused")
            continue
        assert abs(sigma) >= floor(tol)
        keep = np.isin(np.round(r["time"], 9), TIMES)
        assert exact_opening_error(sigma, r["wound_radius"][keep]) <= tol
        outcomes.add("accurate")
    assert outcomes == ({"refused"} if tol == 1e-10 else {"accurate", "refused"})


@pytest.mark.parametrize("which", ["fmi2", "fmi3"])
def test_small_sigma_in_model_exchange_is_refused_with_the_range(fmu_me_path, fmu3_path, which):
    for sigma in SIGMAS:
        messages = []
        with pytest.raises(Exception):
            simulate_fmu(
                fmu_me_path if which == "fmi2" else fmu3_path,
                fmi_type="ModelExchange",
                start_values={"lambda": LAM, "sigma": sigma, "R_inf": R_INF},
                stop_time=1.0,
                logger=lambda *args: messages.append(_text(args[-1])),
            )
        assert any(refusal_names_the_range(m, 1e-10) for m in messages), messages


@pytest.mark.parametrize("tol", [1e-10, 1e-3])
def test_small_sigma_in_the_package_is_refused_with_the_range_or_accurate(tol):
    from wound_opening import simulate

    for sigma in SIGMAS:
        try:
            sim = simulate(
                TIMES,
                R0_um=1.0,
                outer_radius_um=R_INF,
                lam=LAM,
                sigma=sigma,
                T_s=1.0,
                tolerance=tol,
            )
        except Exception as e:
            assert abs(sigma) < floor(tol) and refusal_names_the_range(str(e), tol), (sigma, tol, e)
            continue
        assert abs(sigma) >= floor(tol)
        assert exact_opening_error(sigma, sim.radius_um) <= tol, sigma


def test_sigma_0_is_accepted_and_exact(fmu_path):
    r = simulate_fmu(
        fmu_path,
        start_values={"sigma": 0.0},
        stop_time=10.0,
        output_interval=1.0,
        output=["wound_radius"],
        fmi_call_logger=strict,
    )
    assert np.all(r["wound_radius"] == 1.0)
