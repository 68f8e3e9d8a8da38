"""CPU cost of the FMU driven by fmpy's FMU2Slave: the whole scenario and one fmi2DoStep.

The scenario of `bench.common` (lambda = 0.1, 1, 10; 1000 steps of 0.1) with the FMU's
default settings. Timed with `time.process_time`, best of several repeats:

    fmpy_scenario     FMU2Slave (loads the library), instantiate, set-up, parameters,
                      initialization, 1000 x (doStep + getReal(wound_radius)), terminate,
                      free. The FMU is unzipped once beforehand (not timed).
    fmpy_doStep       one doStep, the mean over the 1000 steps of an initialized instance
    fmpy_getReal      one getReal of wound_radius, likewise

Writes OUT/fmpy_timing.csv with columns what,lambda,seconds,error (error of the
scenario's wound_radius as in `bench.common.error`; empty for the per-call rows).

    python -m bench.fmpy_timing --fmu target/fmu/WoundOpening.fmu --out target/bench
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from bench import common


class Fmu:
    """The unzipped FMU and its value references by name."""

    def __init__(self, path: Path):
        self.md = read_model_description(str(path))
        self.dir = extract(str(path))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}

    def start(self, lam: float) -> FMU2Slave:
        """A new instance of the scenario's case, initialized at t = 0."""
        slave = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=self.dir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName="bench",
        )
        slave.instantiate()
        slave.setupExperiment(startTime=0.0, stopTime=common.T_END)
        slave.setReal(
            [self.vr["lambda"], self.vr["sigma"], self.vr["R_inf"], self.vr["edge_stress"]],
            [lam, common.SIGMA, common.R_INF, 0.0],
        )
        slave.enterInitializationMode()
        slave.exitInitializationMode()
        return slave

    @staticmethod
    def stop(slave: FMU2Slave) -> None:
        slave.terminate()
        slave.freeInstance()

    def scenario(self, lam: float) -> np.ndarray:
        """wound_radius at the 1000 communication points."""
        slave = self.start(lam)
        out = [self.vr["wound_radius"]]
        radius = np.empty(common.STEPS)
        for i in range(common.STEPS):
            slave.doStep(i * common.STEP, common.STEP)
            radius[i] = slave.getReal(out)[0]
        self.stop(slave)
        return radius

    def per_call(self, lam: float, repeats: int) -> tuple[float, float]:
        """Best mean CPU seconds of one doStep and of one getReal over 1000 calls."""
        best_step = best_get = float("inf")
        out = [self.vr["wound_radius"]]
        for _ in range(repeats):
            slave = self.start(lam)
            start = time.process_time()
            for i in range(common.STEPS):
                slave.doStep(i * common.STEP, common.STEP)
            best_step = min(best_step, (time.process_time() - start) / common.STEPS)
            start = time.process_time()
            for _ in range(common.STEPS):
                slave.getReal(out)
            best_get = min(best_get, (time.process_time() - start) / common.STEPS)
            self.stop(slave)
        return best_step, best_get


def measure(fmu_path: Path, repeats: int = 10, log=print) -> list[tuple]:
    fmu = Fmu(fmu_path)
    rows = []
    for lam in common.LAMBDAS:
        label = common.lam_label(lam)
        cpu, radius = common.best_cpu(lambda: fmu.scenario(lam), repeats)
        err = common.error(lam, radius)
        step, get = fmu.per_call(lam, repeats)
        rows += [
            ("fmpy_scenario", label, cpu, err),
            ("fmpy_doStep", label, step, ""),
            ("fmpy_getReal", label, get, ""),
        ]
        log(
            f"fmpy lambda={lam:<4g} scenario {cpu * 1e3:.2f} ms CPU (error {err:.2e}), "
            f"doStep {step * 1e6:.2f} us, getReal {get * 1e6:.2f} us"
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fmu", type=Path, default=Path("target/fmu/WoundOpening.fmu"))
    parser.add_argument("--out", type=Path, default=Path("target/bench"))
    parser.add_argument("--repeats", type=int, default=10)
    args = parser.parse_args()
    rows = measure(args.fmu, args.repeats)
    common.write_rows(args.out / "fmpy_timing.csv", ("what", "lambda", "seconds", "error"), rows)


if __name__ == "__main__":
    main()
