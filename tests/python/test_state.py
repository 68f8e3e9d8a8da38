"""FMU state (get/set, serialize), reset, and independence of instances.

All comparisons here are exact (==): the FMU is deterministic, so re-running the same
calls from the same state must reproduce the outputs bit for bit.
"""

import numpy as np
import pytest
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated
from fmu_harness import PARAMS

T1 = 0.5
# from T1: fine steps, an odd one, then coarser ones (variable step size)
CONTINUATION = np.concatenate([np.arange(51, 101) / 100.0, [1.037], np.arange(11, 51) / 10.0])


def edge_stress_schedule(t):
    """A piecewise-constant input that changes during the continuation."""
    return 0.1 if t < 1.0 else 0.25


def started(make_slave, lam=1.0, **kwargs):
    """An instance at T1 with edge_stress = 0.1 set (part of the state to be captured)."""
    s = make_slave(**kwargs)
    s.initialize({**PARAMS(lam), "edge_stress": 0.1})
    s.run(np.arange(1, 11) / 20.0)  # 0.05 ... 0.5
    assert s.time == T1
    return s


def assert_same(a, b):
    np.testing.assert_array_equal(a[0], b[0], err_msg="wound_radius")
    np.testing.assert_array_equal(a[1], b[1], err_msg="edge_velocity")


def test_get_and_set_fmu_state(make_slave):
    s = started(make_slave)
    at_t1 = s.outputs()
    state = s.fmu.getFMUstate()

    first = s.run(CONTINUATION, edge_stress_schedule)
    assert s.outputs() != at_t1

    s.fmu.setFMUstate(state)
    s.time = T1
    # The state includes the input value (edge_stress = 0.1) and the time.
    assert s.outputs() == at_t1
    assert s.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(T1, rel=1e-13)
    second = s.run(CONTINUATION, edge_stress_schedule)
    assert_same(first, second)

    # The state can be set again (it is not consumed) and then freed.
    s.fmu.setFMUstate(state)
    s.time = T1
    assert_same(first, s.run(CONTINUATION, edge_stress_schedule))
    s.fmu.freeFMUstate(state)


def test_serialized_state_round_trip(make_slave):
    s = started(make_slave, instance_name="original")
    state = s.fmu.getFMUstate()
    data = s.fmu.serializeFMUstate(state)
    s.fmu.freeFMUstate(state)
    assert isinstance(data, bytes) and len(data) > 0

    first = s.run(CONTINUATION, edge_stress_schedule)

    # back into the same instance
    restored = s.fmu.deSerializeFMUstate(data)
    s.fmu.setFMUstate(restored)
    s.fmu.freeFMUstate(restored)
    s.time = T1
    assert_same(first, s.run(CONTINUATION, edge_stress_schedule))

    # into a fresh instance: instantiated, same parameters, never initialized or stepped
    # (FMI 2.0 allows fmi2SetFMUstate in the instantiated state)
    fresh = make_slave(instance_name="fresh")
    fresh.set(PARAMS(1.0))
    restored = fresh.fmu.deSerializeFMUstate(data)
    fresh.fmu.setFMUstate(restored)
    fresh.fmu.freeFMUstate(restored)
    fresh.time = T1
    fresh.initialized = True  # it is in the stepping state now (for terminate at close)
    assert fresh.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(T1, rel=1e-13)
    assert_same(first, fresh.run(CONTINUATION, edge_stress_schedule))


def test_serialized_state_into_initialized_instance(make_slave):
    """The same into a second instance that is initialized and has stepped elsewhere."""
    s = started(make_slave, instance_name="original")
    state = s.fmu.getFMUstate()
    data = s.fmu.serializeFMUstate(state)
    s.fmu.freeFMUstate(state)
    first = s.run(CONTINUATION, edge_stress_schedule)

    other = make_slave(instance_name="other")
    other.initialize(PARAMS(1.0))
    other.run([0.3, 2.0])
    restored = other.fmu.deSerializeFMUstate(data)
    other.fmu.setFMUstate(restored)
    other.fmu.freeFMUstate(restored)
    other.time = T1
    assert_same(first, other.run(CONTINUATION, edge_stress_schedule))


def test_reset_then_rerun(make_slave):
    s = make_slave()
    times = np.concatenate([np.arange(1, 51) / 50.0, [1.3, 2.9, 7.0]])
    s.initialize(PARAMS(0.1))
    first = s.run(times, edge_stress_schedule)

    s.reset()
    # fmi2Reset: back to the state after fmi2Instantiate, every variable at its start value
    # (read in initialization mode: FMI 2.0 has no fmi2GetReal in the instantiated state)
    s.enter_initialization()
    assert s.get("lambda", "sigma", "R_inf", "edge_stress") == [1.0, 1.0, 10.0, 0.0]
    s.fmu.reset()
    s.initialize(PARAMS(0.1))
    assert s.fmu.getBooleanStatus(fmi2Terminated) is False
    assert_same(first, s.run(times, edge_stress_schedule))


def test_terminate_then_reset(make_slave):
    s = make_slave()
    s.initialize(PARAMS(10.0))
    first = s.run([0.1, 0.2, 5.0])
    s.fmu.terminate()
    s.reset()
    s.initialize(PARAMS(10.0))
    assert_same(first, s.run([0.1, 0.2, 5.0]))


def test_two_instances_stepped_alternately(make_slave):
    """Two instances of the same loaded library, different lambda, stepped in turn,
    give exactly what each gives alone: no state shared between instances."""
    times = np.concatenate([np.arange(1, 101) / 100.0, np.arange(11, 101) / 10.0])

    def alone(lam):
        s = make_slave(instance_name=f"alone{lam:g}")
        s.initialize(PARAMS(lam))
        return s.run(times)

    ref_a, ref_b = alone(0.1), alone(10.0)

    a = make_slave(instance_name="a")
    b = make_slave(instance_name="b")
    a.initialize(PARAMS(0.1))
    b.initialize(PARAMS(10.0))
    out_a = (np.empty(len(times)), np.empty(len(times)))
    out_b = (np.empty(len(times)), np.empty(len(times)))
    for i, t in enumerate(times):
        a.step_to(t)
        b.step_to(t)
        out_a[0][i], out_a[1][i] = a.outputs()
        out_b[0][i], out_b[1][i] = b.outputs()
    assert_same(ref_a, out_a)
    assert_same(ref_b, out_b)
    assert not np.array_equal(out_a[0], out_b[0])  # the two really differ
