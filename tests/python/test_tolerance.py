"""The tolerance chooses the discretization, and the FMU delivers it.

A tolerance is the largest |wound_radius - R_exact| / (R_final - R1) over communication
points t >= 0.01 (the measure of every accuracy claim here).  It comes from
fmi2SetupExperiment when the master defines one, else from the `tolerance` parameter
(default 1e-10).  Checked across lambda in [0, 1000] and R_inf from 2 to 100, against the
exact Laplace-domain solution, on a grid that covers the fast start (steps of 0.01 to t = 1)
and the slow end (to t = 1e7, past the viscous relaxation lambda^2 = 1e6 at lambda = 1000).
"""

import numpy as np
import pytest
import wound_exact
from fmu_harness import record

LAMBDAS = [0.0, 1e-3, 0.1, 1.0, 10.0, 100.0, 1000.0]
R_INFS = [2.0, 10.0, 100.0]
TIMES = np.unique(np.concatenate([np.arange(1, 101) * 0.01, 10 ** np.linspace(0, 7, 71)]))


def run(slave, lam, r_inf, experiment_tolerance=None, parameter_tolerance=None):
    params = {"lambda": lam, "R_inf": r_inf, "sigma": 1.0}
    if parameter_tolerance is not None:
        params["tolerance"] = parameter_tolerance
    slave.fmu.setupExperiment(tolerance=experiment_tolerance, startTime=0.0)
    slave.set(params)
    slave.fmu.enterInitializationMode()
    slave.time = 0.0
    slave.exit_initialization()
    r, _ = slave.run(TIMES)
    exact_r, _ = wound_exact.edge(lam, 1.0, r_inf, TIMES)
    amp = wound_exact.final_radius(1.0, r_inf) - wound_exact.initial_radius(1.0)
    return float(np.max(np.abs(r - exact_r)) / amp)


@pytest.mark.parametrize("tol", [1e-3, 1e-5, 1e-7, 1e-9])
def test_experiment_tolerance_is_met_for_every_regime(make_slave, tol):
    worst = 0.0
    for lam in LAMBDAS:
        for r_inf in R_INFS:
            err = run(make_slave(), lam, r_inf, experiment_tolerance=tol)
            assert err <= tol, f"lambda {lam}, R_inf {r_inf}: error {err:.2e} > tolerance {tol:.0e}"
            worst = max(worst, err)
    record(f"tolerance {tol:.0e} (setupExperiment): worst error", worst)


def test_tolerance_parameter_is_used_when_the_master_defines_none(make_slave):
    loose = run(make_slave(), 0.1, 10.0, parameter_tolerance=1e-3)
    tight = run(make_slave(), 0.1, 10.0, parameter_tolerance=1e-9)
    assert tight <= 1e-9 and loose <= 1e-3
    # A coarser mesh really was used: its error is far above the tight one's.
    assert loose > 100 * tight, (loose, tight)
    # And the experiment's tolerance wins over the parameter.
    assert run(make_slave(), 0.1, 10.0, experiment_tolerance=1e-9, parameter_tolerance=1e-3) <= 1e-9


@pytest.mark.parametrize("r_inf", R_INFS)
def test_default_tolerance_is_met(make_slave, r_inf):
    """The default tolerance 1e-10, asserted at that level, for lambda in {0, 0.1, 1, 10, 100}
    (measured worst 1.5e-11)."""
    worst = 0.0
    for lam in [0.0, 0.1, 1.0, 10.0, 100.0]:
        err = run(make_slave(), lam, r_inf)
        assert err <= 1e-10, f"lambda {lam}: {err:.2e}"
        worst = max(worst, err)
    record(f"default settings R_inf={r_inf:g}: worst error", worst)


def test_invalid_tolerance_is_rejected_by_name(make_slave):
    s = make_slave()
    with pytest.raises(Exception):
        s.set({"tolerance": -1.0})
    assert any("tolerance = -1" in str(m) for m in s.errors()), [str(m) for m in s.log]
