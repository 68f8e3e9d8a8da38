"""Model Exchange cost: derivative evaluations, wall time and radius error of outside
integrators on WoundOpening's FMI 2.0 Model Exchange archive, for one or more archives
(e.g. before and after a change, in the same run).

    defaults   fmpy simulate_fmu(fmi_type="ModelExchange") at its defaults, stop_time 1000
               (CVode, the DefaultExperiment's rtol 1e-10, output interval 1)
    accuracy   fmpy's CVode at rtol 1e-10, output interval 0.01, t in [0, 10]
               (bench.me_accuracy's case)
    varying    SciPy's BDF at rtol 1e-8 (finite-difference Jacobian) with the edge stress
               p(t) = 0.5 (1 - exp(-t)) set at every right-hand side, t in [0, 10]
               (exact: python/exact_input.py)

Case: sigma = 1, R_inf = 10; error = max over the output times t >= 0.01 of
|R - R_exact| / |R_final - R1|. Wall time: best of `--repeat`.

    python -m bench.me_cost --fmu before.fmu after.fmu
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import exact_input
import numpy as np
import wound_exact
from fmpy import extract, read_model_description, simulate_fmu
from scipy.integrate import solve_ivp

from bench import common  # noqa: F401  (puts python/ on sys.path)
from bench.me_accuracy import Model

SIGMA, R_INF = 1.0, 10.0
LAMBDAS = (0.0, 0.1, 1.0, 10.0)
OPENING = wound_exact.final_radius(SIGMA, R_INF) - wound_exact.initial_radius(SIGMA)
AMPLITUDE, TAU = 0.5, 1.0


def error(t, radius, exact):
    keep = t >= 0.01 - 1e-12
    return float(np.max(np.abs(np.asarray(radius)[keep] - exact(t[keep]))) / OPENING)


def fmpy_run(path: Path, lam: float, **options):
    """(derivative calls, seconds of one run without the call logger, error or the failure)."""
    calls = [0]

    def count(*args):
        calls[0] += "GetDerivatives" in args[-1] or "GetContinuousStateDerivatives" in args[-1]

    def run(**extra):
        return simulate_fmu(
            str(path),
            fmi_type="ModelExchange",
            start_values={"lambda": lam},
            output=["wound_radius"],
            **options,
            **extra,
        )

    try:
        run(fmi_call_logger=lambda msg: count(msg))
        start = time.perf_counter()
        r = run()
        seconds = time.perf_counter() - start
    except Exception as e:  # noqa: BLE001  (the integrator's failure is the result)
        return calls[0], None, str(e).split(": ")[-1][:60]
    return (
        calls[0],
        seconds,
        error(r["time"], r["wound_radius"], lambda t: wound_exact.edge(lam, SIGMA, R_INF, t)[0]),
    )


def varying(path: Path, lam: float):
    edge = {v.name: v.valueReference for v in read_model_description(str(path)).modelVariables}[
        "edge_stress"
    ]
    m = Model(path, extract(str(path)), lam, SIGMA)
    calls = [0]

    def rhs(t, x):
        calls[0] += 1
        m.fmu.setReal([edge], [float(exact_input.edge_stress(t, AMPLITUDE, TAU))])
        return m.rhs(t, x)

    try:
        start = time.perf_counter()
        sol = solve_ivp(
            rhs,
            (0.0, 10.0),
            m.x0,
            method="BDF",
            rtol=1e-8,
            atol=1e-8 * m.nominals,
            t_eval=np.arange(1, 1001) * 0.01,
        )
        seconds = time.perf_counter() - start
        radius = []
        for t, x in zip(sol.t, sol.y.T):
            m.fmu.setReal([edge], [float(exact_input.edge_stress(t, AMPLITUDE, TAU))])
            radius.append(m.radius(t, x))
    finally:
        m.close()
    return (
        calls[0],
        seconds,
        error(sol.t, radius, lambda t: exact_input.edge(lam, SIGMA, R_INF, t, AMPLITUDE, TAU)),
    )


def best(run, repeat):
    results = [run() for _ in range(repeat)]
    times = [r[1] for r in results if r[1] is not None]
    return results[0][0], min(times) if times else None, results[0][2]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--fmu", type=Path, nargs="+", default=[Path("target/fmu/WoundOpening-me.fmu")]
    )
    parser.add_argument("--lambdas", type=float, nargs="*", default=LAMBDAS)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    cases = {
        "defaults": lambda p, lam: fmpy_run(p, lam, stop_time=1000.0),
        "accuracy": lambda p, lam: fmpy_run(
            p, lam, relative_tolerance=1e-10, output_interval=0.01, stop_time=10.0
        ),
        "varying": varying,
    }
    print("| case | lambda | archive | derivative calls | seconds | radius error |")
    print("|---|---|---|---|---|---|")
    for name, case in cases.items():
        for lam in args.lambdas:
            for path in args.fmu:
                calls, seconds, err = best(lambda: case(path, lam), args.repeat)
                shown = f"{err:.1e}" if isinstance(err, float) else f"fails: {err}"
                secs = f"{seconds:.3f}" if seconds is not None else "-"
                print(
                    f"| {name} | {lam:g} | {path.name} | {calls} | {secs} | {shown} |", flush=True
                )


if __name__ == "__main__":
    main()
