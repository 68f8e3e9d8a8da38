"""Model Exchange at fmpy's defaults and the exact Jacobian through fmpy.

* fmpy's `simulate_fmu(..., fmi_type="ModelExchange")` at its defaults (CVode, the
  DefaultExperiment's tolerance 1e-10, output interval 1 for stop_time 1000, at most 500
  steps per interval) runs lambda = 0 to t = 1000, FMI 2.0 and 3.0, within the accuracy
  docs/fmi.md states for CVode (100 rtol of the opening), against python/wound_exact.py.
  Before the states were the departure from the held response it stopped at t = 0.45
  ("mxstep steps taken before reaching tout").
* fmi2GetDirectionalDerivative (providesDirectionalDerivative) of the state derivatives in
  the states equals finite differences of fmi2GetDerivatives along the same direction (the
  system is linear: exact up to rounding), and each state's column has one entry, its
  own rate.
* A smooth edge stress p(t) = P (1 - exp(-t)), set at every right-hand side, integrated
  by SciPy's BDF with the FMU's Jacobian at lambda = 0, against the exact solution of
  python/exact_input.py: the states follow the input's changes, within 100 rtol.
"""

from ctypes import POINTER, c_double, c_uint

import exact_input
import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Model
from fmu_harness import AMPLITUDE, PARAMS, R_INF, SIGMA, exact, radius_error, record
from scipy.integrate import solve_ivp

DEFAULT_RTOL = 1e-10  # the DefaultExperiment's tolerance, which fmpy takes
CVODE_FACTOR = 100  # docs/fmi.md: within 100 rtol of the opening with CVode and BDF


@pytest.mark.parametrize("which", ["fmi2", "fmi3"])
def test_cvode_at_fmpys_defaults_runs_lambda_zero_to_1000(fmu_me_path, fmu3_path, which):
    path = fmu_me_path if which == "fmi2" else fmu3_path
    r = simulate_fmu(
        path,
        fmi_type="ModelExchange",
        start_values=PARAMS(0.0),
        stop_time=1000.0,
        output=["wound_radius"],
    )
    assert r["time"][-1] == 1000.0
    keep = r["time"] > 0
    err = radius_error(r["wound_radius"][keep], exact(0.0, r["time"][keep])[0]).max()
    record(f"ME CVode at fmpy's defaults to t = 1000, lambda = 0, {which}", err)
    assert err < CVODE_FACTOR * DEFAULT_RTOL, err


class Me:
    """One FMI 2.0 Model Exchange instance in continuous-time mode, through fmpy."""

    def __init__(self, path, lam):
        md = read_model_description(path)
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.nx = md.numberOfContinuousStates
        self.fmu = FMU2Model(
            guid=md.guid,
            unzipDirectory=extract(path),
            modelIdentifier=md.modelExchange.modelIdentifier,
            instanceName="jacobian",
        )
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.setReal([self.vr["lambda"]], [lam])
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.fmu.newDiscreteStates()
        self.fmu.enterContinuousTimeMode()
        self.states = (c_uint * self.nx)(
            *[self.vr[f"modal_coordinate[{k + 1}]"] for k in range(self.nx)]
        )
        self.ders = (c_uint * self.nx)(
            *[self.vr[f"der(modal_coordinate[{k + 1}])"] for k in range(self.nx)]
        )

    def vector(self, get):
        v = np.zeros(self.nx)
        get(v.ctypes.data_as(POINTER(c_double)), self.nx)
        return v

    def set(self, t, x, p=0.0):
        self.fmu.setTime(t)
        self.fmu.setReal([self.vr["edge_stress"]], [float(p)])
        x = np.ascontiguousarray(x, dtype=float)
        self.fmu.setContinuousStates(x.ctypes.data_as(POINTER(c_double)), self.nx)

    def rhs(self, t, x, p=0.0):
        self.set(t, x, p)
        return self.vector(self.fmu.getDerivatives)

    def jv(self, knowns, v):
        out = (c_double * self.nx)()
        seed = (c_double * len(v))(*v)
        self.fmu.fmi2GetDirectionalDerivative(
            self.fmu.component, self.ders, self.nx, knowns, len(v), seed, out
        )
        return np.array(out[:])

    def close(self):
        self.fmu.terminate()
        self.fmu.freeInstance()


def test_directional_derivative_is_the_jacobian_of_the_derivatives(fmu_me_path):
    m = Me(fmu_me_path, 0.0)
    try:
        rng = np.random.default_rng(7)
        x, v = 1e-3 * rng.standard_normal(m.nx), rng.standard_normal(m.nx)
        f0 = m.rhs(0.2, x)
        jv = m.jv(m.states, v)
        e = 1e-6
        fd = (m.rhs(0.2, x + e * v) - f0) / e
        scale = np.abs(jv).max()
        assert np.abs(fd - jv).max() < 1e-6 * scale, np.abs(fd - jv).max() / scale
        m.set(0.2, x)
        for k in (0, 5, 40):  # a column: the state's own rate only (uncoupled modes)
            col = m.jv((c_uint * 1)(m.states[k]), [1.0])
            assert col[k] < 0 and np.count_nonzero(col) == 1, (k, np.flatnonzero(col))
    finally:
        m.close()


def test_bdf_with_the_fmus_jacobian_follows_a_varying_edge_stress(fmu_me_path):
    lam, rtol, amplitude, tau = 0.0, 1e-8, 0.5, 1.0
    m = Me(fmu_me_path, lam)
    try:
        nominals = m.vector(m.fmu.getNominalsOfContinuousStates)
        p = lambda t: exact_input.edge_stress(t, amplitude, tau)  # noqa: E731

        def jac(t, x):
            m.set(t, x, p(t))
            return np.diag([m.jv((c_uint * 1)(m.states[k]), [1.0])[k] for k in range(m.nx)])

        times = np.arange(1, 1001) * 0.01
        sol = solve_ivp(
            lambda t, x: m.rhs(t, x, p(t)),
            (0.0, 10.0),
            m.vector(m.fmu.getContinuousStates),
            method="BDF",
            rtol=rtol,
            atol=rtol * nominals,
            t_eval=times,
            jac=jac,
        )
        assert sol.status == 0, sol.message
        radius = []
        for t, x in zip(sol.t, sol.y.T):
            m.set(t, x, p(t))
            radius.append(m.fmu.getReal([m.vr["wound_radius"]])[0])
    finally:
        m.close()
    r_exact = exact_input.edge(lam, SIGMA, R_INF, sol.t, amplitude, tau)
    err = radius_error(radius, r_exact).max()
    record("ME BDF with the FMU's Jacobian, varying edge stress, lambda = 0", err)
    assert err < CVODE_FACTOR * rtol, err
    assert np.abs(r_exact - exact(lam, sol.t)[0]).max() > 0.1 * AMPLITUDE, (
        "the input moves the radius"
    )
