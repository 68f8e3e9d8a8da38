"""Model Exchange accuracy over sigma, outputs that are functions of the states, and masters
that abort on any status but OK (FMI 2.0 and 3.0, co-simulation and Model Exchange).

The strict master is fmpy's simulate_fmu with an fmiCallLogger that raises on every FMI
call answering anything but OK (fmusim and PyFMI abort on fmi2Warning the same way).
References: the exact Laplace-domain solution (python/wound_exact.py) and the Bessel closed
form of the initial velocity (fmu_harness.initial_velocity).
"""

from ctypes import POINTER, c_double

import numpy as np
import pytest
import wound_exact
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Model
from fmpy.fmi3 import FMU3Model
from fmu_harness import R_INF, VELOCITY_TOL, initial_velocity

EPS = np.finfo(float).eps


class NotOk(AssertionError):
    pass


def strict(message):
    """fmiCallLogger of a master that aborts on any status but OK."""
    if " -> " in message and message.rsplit(" -> ", 1)[1] in (
        "WARNING",
        "DISCARD",
        "ERROR",
        "FATAL",
    ):
        raise NotOk(message)


def opening_error(lam, sigma, t, r):
    r_exact, _ = wound_exact.edge(lam, sigma, R_INF, t)
    opening = wound_exact.final_radius(sigma, R_INF) - wound_exact.initial_radius(sigma)
    # R itself is rounded to eps R: relative to a tiny opening that is the floor.
    floor = 2 * EPS * np.max(np.abs(r_exact)) / abs(opening)
    return float(np.max(np.abs(r - r_exact)) / abs(opening)), floor


@pytest.mark.parametrize("which", ["WoundOpening", "WoundOpening-fmi3"])
@pytest.mark.parametrize("sigma", [2e-5, 1e-4, 1e-2, 10.0])
def test_model_exchange_error_relative_to_the_opening_does_not_depend_on_sigma(
    fmu_me_path, fmu3_path, which, sigma
):
    """docs/fmi.md: with CVode at rtol (absolute rtol x nominal) the radius is within 100 rtol
    of the opening (plus the rounding of R, 2 eps R / opening) whatever sigma."""
    path = fmu_me_path if which == "WoundOpening" else fmu3_path
    rtol = 1e-10
    r = simulate_fmu(
        path,
        fmi_type="ModelExchange",
        solver="CVode",
        relative_tolerance=rtol,
        start_values={"lambda": 10.0, "sigma": sigma, "R_inf": R_INF},
        stop_time=10.0,
        output_interval=0.01,
        output=["wound_radius"],
    )
    keep = r["time"] >= 0.01 - 1e-12
    err, floor = opening_error(10.0, sigma, r["time"][keep], r["wound_radius"][keep])
    assert err <= 100 * rtol + floor, (sigma, err)


def _vector(get, n):
    v = np.zeros(n)
    get(v.ctypes.data_as(POINTER(c_double)), n)
    return v


def in_continuous_time(path, params, name):
    """A Model Exchange instance (FMI 2.0 or 3.0, as the archive says) in Continuous-Time
    Mode at t = 0, aborting on any status but OK, with its model description and value
    references by name."""
    md = read_model_description(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmi3 = md.fmiVersion.startswith("3")
    m = (FMU3Model if fmi3 else FMU2Model)(
        guid=md.guid,
        unzipDirectory=extract(path),
        modelIdentifier="WoundOpening",
        instanceName=name,
        fmiCallLogger=strict,
    )
    m.instantiate()
    if fmi3:
        m.setFloat64([vr[k] for k in params], list(params.values()))
        m.enterInitializationMode(startTime=0.0)
    else:
        m.setupExperiment(startTime=0.0)
        m.setReal([vr[k] for k in params], list(params.values()))
        m.enterInitializationMode()
    m.exitInitializationMode()
    if not fmi3:
        m.newDiscreteStates()
    m.enterContinuousTimeMode()
    return m, md, vr


@pytest.mark.parametrize("lam", [1e-4, 1e-3, 0.37])
def test_initial_edge_velocity_is_a_function_of_the_states_fmi2(fmu_me_path, lam):
    """After fmi2SetContinuousStates with the cut's x = 0, edge_velocity at t = 0 is the
    closed-form initial velocity (no stored reference decides it)."""
    params = {"lambda": lam, "sigma": 1.0, "R_inf": R_INF, "edge_stress": 0.0}
    m, md, vr = in_continuous_time(fmu_me_path, params, "x0")
    nx = md.numberOfContinuousStates
    want = initial_velocity(lam)
    for _ in range(2):
        m.setTime(0.0)
        x = np.zeros(nx)
        m.setContinuousStates(x.ctypes.data_as(POINTER(c_double)), nx)
        _vector(m.getDerivatives, nx)
        v = m.getReal([vr["edge_velocity"]])[0]
        assert abs(v - want) <= VELOCITY_TOL * abs(want), (lam, v, want)
    m.terminate()
    m.freeInstance()


def test_initial_edge_velocity_is_a_function_of_the_states_fmi3(fmu3_path):
    params = {"lambda": 1e-4, "sigma": 1.0, "R_inf": R_INF, "edge_stress": 0.0}
    m, md, vr = in_continuous_time(fmu3_path, params, "x0")
    nx = md.numberOfContinuousStates
    m.setTime(0.0)
    x = np.zeros(nx)
    m.setContinuousStates(x.ctypes.data_as(POINTER(c_double)), nx)
    v = m.getFloat64([vr["edge_velocity"]])[0]
    want = initial_velocity(1e-4)
    assert abs(v - want) <= VELOCITY_TOL * abs(want), (v, want)
    m.terminate()
    m.freeInstance()


INTERFACES = [
    ("WoundOpening", "CoSimulation"),
    ("WoundOpening-me", "ModelExchange"),
    ("WoundOpening-fmi3", "CoSimulation"),
    ("WoundOpening-fmi3", "ModelExchange"),
]


@pytest.mark.parametrize("which,interface", INTERFACES)
def test_lambda_zero_runs_in_a_master_that_aborts_on_warnings(
    fmu_path, fmu_me_path, fmu3_path, which, interface
):
    """lambda = 0: the edge velocity is infinite at the cut; the FMU answers the mean over the
    next 0.01 T with OK (said in the log), finite, and within the tolerance of the exact
    mean (R(0.01) - R1) / 0.01."""
    path = {"WoundOpening": fmu_path, "WoundOpening-me": fmu_me_path}.get(which, fmu3_path)
    r = simulate_fmu(
        path,
        fmi_type=interface,
        solver="CVode",
        relative_tolerance=1e-10,
        start_values={"lambda": 0.0, "sigma": 1.0, "R_inf": R_INF},
        stop_time=0.1,
        output_interval=0.01,
        output=["wound_radius", "edge_velocity"],
        fmi_call_logger=strict,
    )
    v0 = r["edge_velocity"][0]
    assert np.all(np.isfinite(r["edge_velocity"]))
    r_01, _ = wound_exact.edge(0.0, 1.0, R_INF, np.array([0.01]))
    mean = (r_01[0] - wound_exact.initial_radius(1.0)) / 0.01
    assert abs(v0 - mean) <= 1e-7 * abs(mean), (v0, mean)


@pytest.mark.parametrize("which,interface", INTERFACES)
def test_a_tolerance_below_the_floor_runs_in_a_master_that_aborts_on_warnings(
    fmu_path, fmu_me_path, fmu3_path, which, interface
):
    """A master handing its integrator's 1e-12 to the FMU gets the floor's accuracy (1e-11
    of the opening in co-simulation) with OK."""
    path = {"WoundOpening": fmu_path, "WoundOpening-me": fmu_me_path}.get(which, fmu3_path)
    r = simulate_fmu(
        path,
        fmi_type=interface,
        solver="CVode",
        relative_tolerance=1e-12,
        start_values={"lambda": 1.0, "sigma": 1.0, "R_inf": R_INF},
        stop_time=1.0,
        output_interval=0.1,
        output=["wound_radius"],
        fmi_call_logger=strict,
    )
    keep = r["time"] >= 0.1 - 1e-12
    err, floor = opening_error(1.0, 1.0, r["time"][keep], r["wound_radius"][keep])
    assert err <= (1e-11 if interface == "CoSimulation" else 1e-9) + floor, err


def test_model_exchange_states_set_one_by_one_are_accepted(fmu_me_path):
    """fmi2SetReal of a continuous state in Continuous-Time Mode (PyFMI's finite-difference
    Jacobian) sets that state: the derivative follows dx_k/dt = (g_k - x_k) / nu_k."""
    m, md, _ = in_continuous_time(fmu_me_path, {"lambda": 1.0, "sigma": 1.0, "R_inf": R_INF}, "fd")
    one_state_moves_only_its_derivative(m, md, m.getReal, m.setReal)


def one_state_moves_only_its_derivative(m, md, get, set_):
    """At t = 0.5 in Continuous-Time Mode: set state 2 alone; states 1 and 3 and their
    derivatives stay, state 2's derivative (g - x) / nu falls."""
    states = [d.variable.derivative.valueReference for d in md.derivatives]
    ders = [d.variable.valueReference for d in md.derivatives]
    m.setTime(0.5)
    d0 = get(ders[:3])
    set_([states[1]], [1e-3])
    assert get(states[:3]) == [0.0, 1e-3, 0.0]
    d1 = get(ders[:3])
    assert d1[0] == d0[0] and d1[2] == d0[2] and d1[1] < d0[1]
    m.terminate()
    m.freeInstance()


def test_model_exchange_states_set_one_by_one_are_accepted_fmi3(fmu3_path):
    """fmi3SetFloat64 of a continuous state in Continuous-Time Mode (FMI 3.0 allows it there)."""
    m, md, _ = in_continuous_time(fmu3_path, {"lambda": 1.0}, "fd")
    one_state_moves_only_its_derivative(m, md, m.getFloat64, m.setFloat64)
