"""Rejected values and illegal call sequences.

Each must return fmi2Error (fmpy raises fmpy.fmi1.FMICallException with .status == 3 for
any status above fmi2Warning), log a message through the logger callback (errors are
logged whatever loggingOn says; all instances here have loggingOn=False), and leave the
instance as it was: the tests go on with the same instance in the same process and check
its outputs against the exact solution (the promise of the default tolerance, 1e-10).  Reaching
those checks is
also the proof that the process did not crash.
"""

import math
import re

import pytest
from fmpy.fmi2 import fmi2Error, fmi2Terminated
from fmu_harness import (
    PARAMS,
    InstantiateFailed,
    assert_logged,
    check_free_opening,
    communication_grid,
    expect_error,
    names_value,
    value_regex,
)

NAN, INF = math.nan, math.inf

INVALID_PARAMETERS = [
    ("lambda", -1.0),
    ("lambda", NAN),
    ("lambda", INF),
    ("R_inf", 1.0),
    ("R_inf", 0.5),
    ("R_inf", NAN),
    ("sigma", INF),
    ("sigma", -INF),
    ("sigma", NAN),
]


def continues_correctly(slave, lam, label, t_end=2.0, p=0.0):
    """Initialize if needed, step on to t_end, compare with the exact solution."""
    if not slave.initialized:
        slave.initialize({**PARAMS(lam), "edge_stress": p})
        t = communication_grid(t_end)
    else:
        t = communication_grid(t_end)
        t = t[t > slave.time + 1e-12]
    r, v = slave.run(t)
    check_free_opening(label, lam, t, r, v, p=p, keep=False)


@pytest.mark.parametrize("name, bad", INVALID_PARAMETERS, ids=lambda x: str(x))
def test_invalid_parameter_rejected_at_set_real(make_slave, name, bad):
    s = make_slave()
    good = PARAMS(0.1)
    s.set(good)
    new = expect_error(s, s.set, {name: bad})  # instantiated state
    # names the variable and the value, e.g. "lambda = -1 is invalid: ..."
    assert_logged(new, names_value(name, bad), s)
    s.enter_initialization()
    assert s.get(name) == [good[name]]  # unchanged
    new = expect_error(s, s.set, {name: bad})  # initialization mode
    assert_logged(new, names_value(name, bad), s)
    assert s.get(name) == [good[name]]
    s.exit_initialization()
    continues_correctly(s, 0.1, f"after rejected {name}={bad}")


def test_rejected_set_real_changes_nothing(make_slave):
    """One fmi2SetReal with a valid and an invalid value: the call is rejected as a whole
    ("a rejected call leaves the instance unchanged"), so the valid value is not taken."""
    s = make_slave()
    s.set(PARAMS(0.1))
    new = expect_error(s, s.set, {"lambda": 3.0, "R_inf": 0.5})
    assert_logged(new, names_value("R_inf", 0.5), s)
    s.enter_initialization()
    assert s.get("lambda", "R_inf") == [0.1, 10.0]
    s.exit_initialization()
    continues_correctly(s, 0.1, "after rejected multi-value fmi2SetReal")


@pytest.mark.parametrize("bad", [NAN, INF, -INF], ids=str)
def test_invalid_edge_stress_rejected_while_stepping(make_slave, bad):
    s = make_slave()
    s.initialize({**PARAMS(1.0), "edge_stress": 0.2})
    s.run(communication_grid(0.5))
    before = s.outputs()
    new = expect_error(s, s.set, {"edge_stress": bad})
    assert_logged(new, names_value("edge_stress", bad), s)
    assert s.get("edge_stress") == [0.2]
    assert s.outputs() == before  # exact: nothing changed
    continues_correctly(s, 1.0, f"after rejected edge_stress={bad}", p=0.2)


def test_fixed_parameter_cannot_change_after_initialization(make_slave):
    s = make_slave()
    s.initialize(PARAMS(1.0))
    s.run(communication_grid(0.5))
    new = expect_error(s, s.set, {"lambda": 2.0})
    assert_logged(new, re.compile(r"\blambda\b"), s)
    assert s.get("lambda") == [1.0]
    continues_correctly(s, 1.0, "after rejected change of a fixed parameter")


def test_do_step_before_initialization(make_slave):
    s = make_slave()
    expect_error(s, s.fmu.doStep, 0.0, 0.1)  # instantiated
    s.fmu.setupExperiment(startTime=0.0)
    s.set(PARAMS(10.0))
    s.fmu.enterInitializationMode()
    expect_error(s, s.fmu.doStep, 0.0, 0.1)  # initialization mode
    s.fmu.exitInitializationMode()
    s.initialized, s.time = True, 0.0
    continues_correctly(s, 10.0, "after doStep before initialization")


def test_do_step_at_wrong_communication_point(make_slave):
    s = make_slave()
    s.initialize(PARAMS(1.0))
    s.run([0.125, 0.25])
    for wrong in (0.5, 0.125, 0.0):  # ahead, behind, back at the start
        new = expect_error(s, s.fmu.doStep, wrong, 0.1)
        # the message gives the time the FMU is at, 0.25
        assert_logged(new, re.compile(value_regex(0.25)), s)
    continues_correctly(s, 1.0, "after doStep at a wrong communication point")


@pytest.mark.parametrize("h", [0.0, -0.1, NAN], ids=str)
def test_do_step_with_non_positive_step(make_slave, h):
    s = make_slave()
    s.initialize(PARAMS(0.0))
    s.run([0.125, 0.25])
    before = s.outputs()
    expect_error(s, s.fmu.doStep, 0.25, h)
    assert s.outputs() == before
    continues_correctly(s, 0.0, f"after doStep with step {h}")


def test_do_step_past_stop_time(make_slave):
    """With stopTime = 1 a step beyond it is rejected; stepping to exactly 1 is fine and
    then fmi2GetBooleanStatus(fmi2Terminated) says the slave is done."""
    s = make_slave()
    s.initialize(PARAMS(1.0), stop_time=1.0)
    s.run([0.5])
    new = expect_error(s, s.fmu.doStep, 0.5, 0.6)
    assert_logged(new, re.compile(r"stopTime"), s)
    assert s.fmu.getBooleanStatus(fmi2Terminated) is False
    continues_correctly(s, 1.0, "after a step past stopTime", t_end=1.0)
    assert s.fmu.getBooleanStatus(fmi2Terminated) is True


def test_wrong_guid_fails_to_instantiate(make_slave):
    with pytest.raises(InstantiateFailed) as info:
        make_slave(guid="{00000000-0000-0000-0000-000000000000}")
    assert any(m.status >= fmi2Error for m in info.value.log), info.value.log
    # and the library still serves a correct instance afterwards
    continues_correctly(make_slave(), 1.0, "after a failed instantiate")


def test_log_categories(make_slave, model_description):
    declared = {c.name for c in model_description.logCategories}

    quiet = make_slave(instance_name="quiet", logging_on=False)
    quiet.initialize(PARAMS(1.0))
    quiet.run([0.1, 0.2])
    expect_error(quiet, quiet.fmu.doStep, 0.0, 0.1)
    assert not [m for m in quiet.log if m.category == "logCalls"], quiet.log_text()
    errors = quiet.errors()
    assert errors and all(m.category == "logStatusError" for m in errors), quiet.log_text()
    assert all(m.instance == "quiet" for m in quiet.log), quiet.log_text()

    loud = make_slave(instance_name="loud", logging_on=True)
    loud.initialize(PARAMS(1.0))
    loud.run([0.1, 0.2])
    assert any(m.category == "logCalls" for m in loud.log), loud.log_text()
    assert {m.category for m in loud.log} <= declared, loud.log_text()

    # switched off again: no more call logging, errors still logged
    loud.fmu.setDebugLogging(False, [])
    n = len(loud.log)
    loud.run([0.3])
    assert loud.log[n:] == [], loud.log_text()
    expect_error(loud, loud.fmu.doStep, 0.0, 0.1)
