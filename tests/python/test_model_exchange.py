"""FMI 2.0 Model Exchange of both FMUs, integrated by fmpy's CVode (BDF, dense Newton),
against the exact Laplace-domain solution (python/wound_exact.py).

WoundOpening's continuous states are the modal coordinates of the spectral-element mesh;
CVode integrates the same ODE that the co-simulation step solves exactly, so its error is
CVode's own plus the mesh's (1e-10 of the opening at the default tolerance). At
relative_tolerance 1e-11 (absolute 1e-11: the nominals are max(|sigma|, |edge_stress|/G) = 1) the
measured worst radius
errors over t in [0.01, 10] are 3.5e-10, 3.5e-10, 8.4e-10, 7.9e-10 of the opening for
lambda = 0, 0.1, 1, 10 (2.5e-9 to 8.5e-9 at 1e-10), against the promised 1e-8.
"""

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmu_harness import AMPLITUDE, PARAMS, exact, radius_error, record

ME_RADIUS_TOL = 1e-8


@pytest.mark.parametrize("lam", [0.0, 0.1, 1.0, 10.0])
def test_cvode_matches_the_exact_opening(fmu_me_path, lam):
    r = simulate_fmu(
        fmu_me_path,
        fmi_type="ModelExchange",
        solver="CVode",
        relative_tolerance=1e-11,
        start_values=PARAMS(lam),
        stop_time=10.0,
        output_interval=0.01,
        output=["wound_radius", "edge_velocity"],
    )
    keep = r["time"] >= 0.01
    t = r["time"][keep]
    r_exact, _ = exact(lam, t)
    err = radius_error(r["wound_radius"][keep], r_exact).max()
    record(f"ME CVode radius error, lambda = {lam}", err)
    assert err < ME_RADIUS_TOL, (lam, err)
    assert r["wound_radius"][0] == 1 + 1 / 6, "R1 at the cut, exactly"
    assert AMPLITUDE > 0


def test_purse_string_model_exchange_follows_time(purse_path):
    r = simulate_fmu(
        purse_path,
        fmi_type="ModelExchange",
        solver="CVode",
        stop_time=100.0,
        output_interval=10.0,
        output=["line_tension", "edge_stress"],
    )
    t = r["time"]
    want = np.where(t > 20.0, 6500.0 * (1 - np.exp(-(t - 20.0) / 30.0)), 0.0)
    np.testing.assert_allclose(r["line_tension"], want, rtol=1e-14, atol=1e-9)


def test_model_exchange_declares_the_states(fmu_me_path):
    md = read_model_description(fmu_me_path)
    me = md.modelExchange
    assert me is not None and me.modelIdentifier == "WoundOpening"
    assert len(md.derivatives) == 217
    states = [d.variable.derivative for d in md.derivatives]
    assert [s.name for s in states[:2]] == ["modal_coordinate[1]", "modal_coordinate[2]"]
    assert md.numberOfEventIndicators == 0
