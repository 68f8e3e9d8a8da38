"""Model Exchange accuracy for a given integrator tolerance, over sigma from 2e-5 (above the
small-sigma floor at 1e-10, docs/model.md) to 10.

The FMI 2.0 Model Exchange interface of WoundOpening.fmu integrated by three outside
integrators, each with relative tolerance `rtol` and absolute tolerance `rtol x nominal`
(the nominals of `fmi2GetNominalsOfContinuousStates`):

    CVode   fmpy's simulate_fmu (SUNDIALS CVode, BDF, Newton), output interval 0.01
    BDF     SciPy solve_ivp(method="BDF") on fmi2SetContinuousStates / fmi2GetDerivatives
    Radau   SciPy solve_ivp(method="Radau"), likewise

Case: R_inf = 10, edge stress 0, t in [0, 10] (T = 1), error = max over t in [0.01, 10] of
|R - R_exact| / |R_final - R1| (the opening), R_exact from `wound_exact.edge`.

    python -m bench.me_accuracy --fmu target/fmu/WoundOpening.fmu
"""

from __future__ import annotations

import argparse
from ctypes import POINTER, c_double
from pathlib import Path

import numpy as np
import wound_exact
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Model
from scipy.integrate import solve_ivp

from bench import common  # noqa: F401  (puts python/ on sys.path for wound_exact)

R_INF, T_END, DT = 10.0, 10.0, 0.01
SIGMAS = (2e-5, 1e-4, 1e-2, 1.0, 10.0)
RTOLS = (1e-6, 1e-8, 1e-10)
LAMBDAS = (0.1, 1.0, 10.0)
TIMES = np.arange(1, int(round(T_END / DT)) + 1) * DT


def relative_error(lam: float, sigma: float, t: np.ndarray, radius: np.ndarray) -> float:
    r_exact, _ = wound_exact.edge(lam, sigma, R_INF, t)
    opening = wound_exact.final_radius(sigma, R_INF) - wound_exact.initial_radius(sigma)
    return float(np.max(np.abs(radius - r_exact)) / abs(opening))


def cvode(path: Path, lam: float, sigma: float, rtol: float) -> float:
    r = simulate_fmu(
        str(path),
        fmi_type="ModelExchange",
        solver="CVode",
        relative_tolerance=rtol,
        start_values={"lambda": lam, "sigma": sigma, "R_inf": R_INF},
        stop_time=T_END,
        output_interval=DT,
        output=["wound_radius"],
    )
    keep = r["time"] >= DT - 1e-12
    return relative_error(lam, sigma, r["time"][keep], r["wound_radius"][keep])


class Model:
    """One initialized FMI 2.0 Model Exchange instance in continuous-time mode."""

    def __init__(self, path: Path, unzipped: str, lam: float, sigma: float):
        md = read_model_description(str(path))
        vr = {v.name: v.valueReference for v in md.modelVariables}
        self.nx = md.numberOfContinuousStates
        self.radius_vr = [vr["wound_radius"]]
        self.fmu = FMU2Model(
            guid=md.guid,
            unzipDirectory=unzipped,
            modelIdentifier=md.modelExchange.modelIdentifier,
            instanceName="me",
        )
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        self.fmu.setReal(
            [vr["lambda"], vr["sigma"], vr["R_inf"], vr["edge_stress"]], [lam, sigma, R_INF, 0.0]
        )
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.fmu.newDiscreteStates()
        self.fmu.enterContinuousTimeMode()
        self.x0 = self.vector(self.fmu.getContinuousStates)
        self.nominals = self.vector(self.fmu.getNominalsOfContinuousStates)

    def vector(self, get) -> np.ndarray:
        v = np.zeros(self.nx)
        get(v.ctypes.data_as(POINTER(c_double)), self.nx)
        return v

    def set_state(self, t: float, x: np.ndarray) -> None:
        self.fmu.setTime(t)
        x = np.ascontiguousarray(x, dtype=float)
        self.fmu.setContinuousStates(x.ctypes.data_as(POINTER(c_double)), self.nx)

    def rhs(self, t: float, x: np.ndarray) -> np.ndarray:
        self.set_state(t, x)
        return self.vector(self.fmu.getDerivatives)

    def radius(self, t: float, x: np.ndarray) -> float:
        self.set_state(t, x)
        return self.fmu.getReal(self.radius_vr)[0]

    def close(self) -> None:
        self.fmu.terminate()
        self.fmu.freeInstance()


def scipy_method(
    path: Path, unzipped: str, method: str, lam: float, sigma: float, rtol: float
) -> float:
    m = Model(path, unzipped, lam, sigma)
    try:
        sol = solve_ivp(
            m.rhs,
            (0.0, T_END),
            m.x0,
            method=method,
            rtol=rtol,
            atol=rtol * m.nominals,
            t_eval=TIMES,
            jac=lambda t, x: np.diag(jacobian_diagonal(m, t, x)),
        )
        radius = np.array([m.radius(t, x) for t, x in zip(sol.t, sol.y.T)])
    finally:
        m.close()
    return relative_error(lam, sigma, sol.t, radius)


def jacobian_diagonal(m: Model, t: float, x: np.ndarray) -> np.ndarray:
    """The modes are uncoupled and linear: d(dx_k)/dx_k = f_k(x + e) - f_k(x) for any
    e (one perturbation of every state at once, exact for a diagonal linear system)."""
    f0 = m.rhs(t, x)
    e = np.maximum(m.nominals, 1e-300)
    return (m.rhs(t, x + e) - f0) / e


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmu", type=Path, default=Path("target/fmu/WoundOpening.fmu"))
    parser.add_argument("--lambdas", type=float, nargs="*", default=LAMBDAS)
    parser.add_argument("--rtols", type=float, nargs="*", default=RTOLS)
    parser.add_argument("--sigmas", type=float, nargs="*", default=SIGMAS)
    args = parser.parse_args()
    unzipped = extract(str(args.fmu))
    print(
        "| rtol | integrator | lambda | " + " | ".join(f"sigma = {s:g}" for s in args.sigmas) + " |"
    )
    print("|---|---|---|" + "---|" * len(args.sigmas))
    for rtol in args.rtols:
        for name in ("CVode", "BDF", "Radau"):
            for lam in args.lambdas:
                errs = []
                for sigma in args.sigmas:
                    if name == "CVode":
                        errs.append(cvode(args.fmu, lam, sigma, rtol))
                    else:
                        errs.append(scipy_method(args.fmu, unzipped, name, lam, sigma, rtol))
                print(
                    f"| {rtol:g} | {name} | {lam:g} | "
                    + " | ".join(f"{e:.1e}" for e in errs)
                    + " |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
