"""fmi2GetDirectionalDerivative of both FMUs: WoundOpening's against the closed form of the
instantaneous velocity response (docs/model.md, "Exact results", evaluated with SciPy's Bessel
functions in fmu_harness.initial_velocity, independently of the Rust code) and refused at
lambda = 0 where it is infinite; consistency with difference quotients of the outputs;
WoundOpening's physical units against its dimensionless behaviour; the PurseString FMU's
refusals and FMU states."""

import math
import re

import numpy as np
import pytest
from fmu_harness import (
    PARAMS,
    R_INF,
    assert_logged,
    expect_error,
    initial_velocity,
    names_value,
    record,
)

PHYSICAL = {"R0": 10.0, "T": 10.0, "G": 100.0}


def wound_at(make_slave, lam, t_end, p, scales=None):
    """A wound instance stepped to t_end (master time) with edge stress p held."""
    s = make_slave()
    s.initialize({**PARAMS(lam), **(scales or {}), "edge_stress": p})
    for t in np.linspace(0.0, t_end, 6)[1:]:
        s.step_to(t)
    return s


def exact_slope(lam, r_inf=R_INF):
    """d u_t(1) / d p = w(1): the initial velocity for p - sigma = 1."""
    return initial_velocity(lam, p=1.0, sigma=0.0, r_inf=r_inf)


@pytest.mark.parametrize("lam", [0.01, 0.1, 1.0, 10.0, 1e3])
@pytest.mark.parametrize("scales", [None, PHYSICAL], ids=["dimensionless", "physical"])
def test_wound_derivative_is_the_closed_form(make_slave, lam, scales):
    """d edge_velocity / d edge_stress = (R0/T)/G w(1) with w the exact response. Measured
    within 1.2e-15 relative of SciPy's evaluation; asserted at 1e-12. The mesh's own value
    is 17.8 against an exact 25.0 at lambda = 0.01, tolerance 1e-3."""
    k = scales or {"R0": 1.0, "T": 1.0, "G": 1.0}
    s = make_slave()
    s.fmu.setupExperiment(tolerance=1e-3, startTime=0.0)
    s.set({**PARAMS(lam), **(scales or {})})
    s.fmu.enterInitializationMode()
    s.exit_initialization()
    (d_v,) = s.fmu.getDirectionalDerivative([s.vr["edge_velocity"]], [s.vr["edge_stress"]], [1.0])
    want = k["R0"] / k["T"] / k["G"] * exact_slope(lam)
    record(f"directional derivative vs closed form, lambda={lam:g} (relative)", abs(d_v / want - 1))
    assert d_v == pytest.approx(want, rel=1e-12), (d_v, want)


@pytest.mark.parametrize("scales", [None, PHYSICAL], ids=["dimensionless", "physical"])
def test_wound_derivative_is_refused_at_lambda_zero(make_slave, scales):
    """The exact derivative is infinite at lambda = 0: refused with the reason, not a
    mesh artefact (the mesh gives 22.5 to 264 depending on the tolerance)."""
    s = wound_at(make_slave, 0.0, 0.5, 0.2, scales)
    messages = expect_error(
        s, s.fmu.getDirectionalDerivative, [s.vr["edge_velocity"]], [s.vr["edge_stress"]], [1.0]
    )
    assert_logged(messages, re.compile(r"infinite at lambda = 0"), s)


@pytest.mark.parametrize("lam", [0.1, 1.0, 10.0])
@pytest.mark.parametrize("scales", [None, PHYSICAL], ids=["dimensionless", "physical"])
def test_wound_derivatives_match_difference_quotients(make_slave, lam, scales):
    """d wound_radius / d edge_stress = 0; d edge_velocity / d edge_stress is the slope of
    an affine function, so a difference quotient over any dp equals it up to rounding."""
    k = scales or {"R0": 1.0, "T": 1.0, "G": 1.0}
    s = wound_at(make_slave, lam, 0.5 * k["T"], 0.2 * k["G"], scales)
    vr = s.vr
    d_r, d_v = s.fmu.getDirectionalDerivative(
        [vr["wound_radius"], vr["edge_velocity"]], [vr["edge_stress"]], [1.0]
    )
    r0, v0 = s.outputs()
    dp = 0.25 * k["G"]
    s.set({"edge_stress": 0.2 * k["G"] + dp})
    r1, v1 = s.outputs()
    assert d_r == 0.0 and r1 == r0
    fd = (v1 - v0) / dp
    assert d_v < 0.0
    assert d_v == pytest.approx(fd, rel=1e-9), (d_v, fd)
    # Linear in the seed; several knowns are summed.
    (d2,) = s.fmu.getDirectionalDerivative(
        [vr["edge_velocity"]], [vr["edge_stress"], vr["edge_stress"]], [2.0, -0.5]
    )
    assert d2 == pytest.approx(1.5 * d_v, rel=1e-15)


def test_wound_derivative_scales_with_the_units(make_slave):
    """(R0 / T) / G times the dimensionless slope."""
    a = wound_at(make_slave, 1.0, 0.5, 0.2)
    b = wound_at(make_slave, 1.0, 0.5 * PHYSICAL["T"], 0.2 * PHYSICAL["G"], PHYSICAL)
    da = a.fmu.getDirectionalDerivative([a.vr["edge_velocity"]], [a.vr["edge_stress"]], [1.0])[0]
    db = b.fmu.getDirectionalDerivative([b.vr["edge_velocity"]], [b.vr["edge_stress"]], [1.0])[0]
    factor = PHYSICAL["R0"] / PHYSICAL["T"] / PHYSICAL["G"]
    assert db == pytest.approx(factor * da, rel=1e-13)


def test_physical_units_scale_the_dimensionless_run(make_slave):
    """Same trajectory: radius x R0, velocity x R0 / T, at master times x T, input x G."""
    a = wound_at(make_slave, 0.1, 3.0, 0.3)
    b = wound_at(make_slave, 0.1, 3.0 * PHYSICAL["T"], 0.3 * PHYSICAL["G"], PHYSICAL)
    (ra, va), (rb, vb) = a.outputs(), b.outputs()
    assert rb == pytest.approx(PHYSICAL["R0"] * ra, rel=1e-13)
    assert vb == pytest.approx(PHYSICAL["R0"] / PHYSICAL["T"] * va, rel=1e-12)


def test_derivative_refuses_wrong_roles(make_slave):
    s = wound_at(make_slave, 1.0, 0.5, 0.0)
    vr = s.vr
    new = expect_error(
        s, s.fmu.getDirectionalDerivative, [vr["wound_radius"]], [vr["lambda"]], [1.0]
    )
    assert any("must be a Real input" in m.message for m in new), s.log_text()
    new = expect_error(
        s, s.fmu.getDirectionalDerivative, [vr["edge_stress"]], [vr["edge_stress"]], [1.0]
    )
    assert any("must be a Real output" in m.message for m in new), s.log_text()
    new = expect_error(
        s, s.fmu.getDirectionalDerivative, [vr["edge_velocity"]], [vr["edge_stress"]], [math.nan]
    )
    assert_logged(new, names_value("dvKnown", math.nan), s)
    # The instance goes on.
    s.step_to(1.0)
    assert np.isfinite(s.outputs()).all()


@pytest.mark.parametrize(
    "name, bad", [("R0", 0.0), ("T", -1.0), ("G", math.inf), ("R0", -2.5)], ids=str
)
def test_invalid_scale_is_refused(make_slave, name, bad):
    s = make_slave()
    new = expect_error(s, s.set, {name: bad})
    assert_logged(new, names_value(name, bad), s)
    s.initialize(PARAMS(1.0))
    assert s.get(name) == [1.0]


# --------------------------------------------------------------------------- PurseString


def purse_at(make_purse, t_end, radius, params=None):
    s = make_purse()
    s.initialize({**(params or {}), "wound_radius": radius})
    for t in np.linspace(0.0, t_end, 4)[1:]:
        s.step_to(t)
    return s


def test_purse_string_outputs_and_derivative(make_purse):
    s = purse_at(make_purse, 50.0, 12.0)
    p, tc = s.get("edge_stress", "line_tension")
    want_tc = 6500.0 * -math.expm1(-(50.0 - 20.0) / 30.0)
    assert tc == pytest.approx(want_tc, rel=1e-14)
    assert p == pytest.approx(want_tc / (5.0 * 12.0), rel=1e-14)
    (dp,) = s.fmu.getDirectionalDerivative([s.vr["edge_stress"]], [s.vr["wound_radius"]], [1.0])
    h = 1e-5
    s.set({"wound_radius": 12.0 + h})
    (p_plus,) = s.get("edge_stress")
    s.set({"wound_radius": 12.0 - h})
    (p_minus,) = s.get("edge_stress")
    fd = (p_plus - p_minus) / (2 * h)
    assert dp == pytest.approx(-p / 12.0, rel=1e-14)
    assert dp == pytest.approx(fd, rel=1e-8), (dp, fd)  # central difference, O(h^2) + rounding
    (dt,) = s.fmu.getDirectionalDerivative([s.vr["line_tension"]], [s.vr["wound_radius"]], [1.0])
    assert dt == 0.0


def test_purse_string_before_its_delay_pulls_nothing(make_purse):
    s = purse_at(make_purse, 19.5, 11.0)
    assert s.get("edge_stress", "line_tension") == [0.0, 0.0]


@pytest.mark.parametrize("bad", [0.0, -3.0, math.nan, math.inf], ids=str)
def test_purse_string_refuses_a_closed_or_invalid_radius(make_purse, bad):
    s = purse_at(make_purse, 40.0, 12.0)
    before = s.get("edge_stress")
    new = expect_error(s, s.set, {"wound_radius": bad})
    assert_logged(new, names_value("wound_radius", bad), s)
    assert s.get("wound_radius") == [12.0]
    assert s.get("edge_stress") == before
    s.step_to(60.0)  # and goes on


@pytest.mark.parametrize(
    "name, bad",
    [("thickness", 0.0), ("T_max", -1.0), ("t_assembly", math.nan), ("t_delay", -0.5)],
    ids=str,
)
def test_purse_string_refuses_invalid_parameters(make_purse, name, bad):
    s = make_purse()
    new = expect_error(s, s.set, {name: bad})
    assert_logged(new, names_value(name, bad), s)


def test_purse_string_state_round_trip_and_foreign_state(make_purse, make_slave):
    s = purse_at(make_purse, 30.0, 12.0)
    state = s.fmu.getFMUstate()
    data = s.fmu.serializeFMUstate(state)
    s.fmu.freeFMUstate(state)
    p30 = s.get("edge_stress")
    s.step_to(80.0)
    s.set({"wound_radius": 9.0})
    restored = s.fmu.deSerializeFMUstate(data)
    s.fmu.setFMUstate(restored)
    s.fmu.freeFMUstate(restored)
    s.time = 30.0
    assert s.get("wound_radius", "edge_stress") == [12.0, *p30]
    # A WoundOpening state is refused by name.
    w = wound_at(make_slave, 1.0, 0.5, 0.0)
    ws = w.fmu.getFMUstate()
    wdata = w.fmu.serializeFMUstate(ws)
    w.fmu.freeFMUstate(ws)
    new = expect_error(s, s.fmu.deSerializeFMUstate, wdata)
    assert any(
        'of model "WoundOpening" but this instance is "PurseString"' in m.message for m in new
    ), s.log_text()
