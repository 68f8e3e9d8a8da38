"""CPU cost of the whole fmpy scenario per archive: parse the model description, extract
the archive, load and instantiate (co-simulation), initialize, 1000 steps of 0.1 at
lambda = 1 with wound_radius read after each, terminate, free. `time.process_time`, best
of `--repeats`; each archive on its own, side by side.

    python -m bench.fmpy_whole target/fmu/WoundOpening.fmu target/fmu/WoundOpening-me.fmu
"""

from __future__ import annotations

import argparse
import shutil
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from bench import common


def whole(path: str, lam: float = 1.0) -> tuple[float, float, int]:
    """CPU seconds of the whole scenario, of its parse alone, and the variable count."""
    start = time.process_time()
    md = read_model_description(path)
    parsed = time.process_time()
    unzipped = extract(path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier,
                      instanceName="whole")
    slave.instantiate()
    slave.setupExperiment(startTime=0.0, stopTime=common.T_END)
    slave.setReal([vr["lambda"], vr["sigma"], vr["R_inf"], vr["edge_stress"]], [lam, common.SIGMA, common.R_INF, 0.0])
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    out = [vr["wound_radius"]]
    for i in range(common.STEPS):
        slave.doStep(i * common.STEP, common.STEP)
        slave.getReal(out)
    slave.terminate()
    slave.freeInstance()
    seconds = time.process_time() - start
    slave.freeLibrary()
    shutil.rmtree(unzipped, ignore_errors=True)
    return seconds, parsed - start, len(md.modelVariables)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fmus", nargs="+")
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    print("| archive | variables | parse | whole scenario (lambda = 1) |")
    print("|---|---|---|---|")
    for path in args.fmus:
        runs = [whole(path) for _ in range(args.repeats)]
        best = min(r[0] for r in runs)
        parse = min(r[1] for r in runs)
        print(f"| {path.rsplit('/', 1)[-1]} | {runs[0][2]} | {parse * 1e3:.2f} ms | {best * 1e3:.2f} ms |", flush=True)


if __name__ == "__main__":
    main()
