"""CPU cost of the whole fmpy scenario per archive: parse the model description, extract
the archive, load and instantiate (co-simulation), initialize, 1000 steps of 0.1 at
lambda = 1 with wound_radius read after each, terminate, free. `time.process_time` of the
whole and of each phase, best of `--repeats`; each archive on its own, side by side. `--both` adds
the single archive
that declares both FMI 2.0 interfaces (the Model Exchange archive's description with the
co-simulation element added, the library deflated), the layout the two archives replace.
Prints a Markdown table; with `--out`, writes OUT/fmpy_whole.csv for docs/benchmarks.md.

    python -m bench.fmpy_whole target/fmu/WoundOpening.fmu --both target/fmu/WoundOpening-me.fmu
    --out target/bench
"""

from __future__ import annotations

import argparse
import re
import shutil
import tempfile
import time
import zipfile
from pathlib import Path

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from bench import common

#: The scenario's phases, in order (CPU seconds of each are measured).
PHASES = ("parse", "extract", "instantiate", "initialize", "steps", "free")


def whole(path: str, lam: float = 1.0) -> tuple[dict, int]:
    """CPU seconds of each phase of the scenario (`PHASES`) and the variable count."""
    marks = [time.process_time()]
    md = read_model_description(path)
    marks.append(time.process_time())
    unzipped = extract(path)
    marks.append(time.process_time())
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(
        guid=md.guid,
        unzipDirectory=unzipped,
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="whole",
    )
    slave.instantiate()
    marks.append(time.process_time())
    slave.setupExperiment(startTime=0.0, stopTime=common.T_END)
    slave.setReal(
        [vr["lambda"], vr["sigma"], vr["R_inf"], vr["edge_stress"]],
        [lam, common.SIGMA, common.R_INF, 0.0],
    )
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    marks.append(time.process_time())
    out = [vr["wound_radius"]]
    for i in range(common.STEPS):
        slave.doStep(i * common.STEP, common.STEP)
        slave.getReal(out)
    marks.append(time.process_time())
    slave.terminate()
    slave.freeInstance()
    slave.freeLibrary()
    shutil.rmtree(unzipped, ignore_errors=True)
    marks.append(time.process_time())
    return {name: b - a for name, a, b in zip(PHASES, marks, marks[1:])}, len(md.modelVariables)


def both_interfaces(cs_path: str, me_path: str, out: Path) -> str:
    """One archive declaring co-simulation and Model Exchange, from the two archives."""
    cs, me = zipfile.ZipFile(cs_path), zipfile.ZipFile(me_path)
    cs_xml, me_xml = (
        cs.read("modelDescription.xml").decode(),
        me.read("modelDescription.xml").decode(),
    )
    element = re.search(r"  <CoSimulation.*?/>\n\n", cs_xml, re.S).group(0)
    end = re.search(r"  <ModelExchange.*?/>\n\n", me_xml, re.S).end()
    path = out / (Path(cs_path).stem + "-both.fmu")
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for name in me.namelist():
            z.writestr(
                name,
                me_xml[:end] + element + me_xml[end:]
                if name == "modelDescription.xml"
                else me.read(name),
            )
    return str(path)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fmu", help="a co-simulation archive")
    parser.add_argument(
        "--both",
        metavar="ME_FMU",
        help="also time one archive with both interfaces, made from this one",
    )
    parser.add_argument("--repeats", type=int, default=20)
    parser.add_argument("--out", type=Path)
    args = parser.parse_args()
    scratch = Path(tempfile.mkdtemp())
    paths = [args.fmu] + ([both_interfaces(args.fmu, args.both, scratch)] if args.both else [])
    columns = ("archive", "variables", "seconds") + tuple(f"{p}_seconds" for p in PHASES)
    print("| " + " | ".join(columns) + " |")
    print("|---" * len(columns) + "|")
    rows = []
    for path in paths:
        runs = [whole(path) for _ in range(args.repeats)]
        best = min(sum(r[0].values()) for r in runs)
        phases = [min(r[0][p] for r in runs) for p in PHASES]  # each phase's best, over all runs
        rows.append((Path(path).name, runs[0][1], best, *phases))
        print(
            "| "
            + " | ".join(
                [Path(path).name, str(runs[0][1])] + [f"{x * 1e3:.2f} ms" for x in (best, *phases)]
            )
            + " |",
            flush=True,
        )
    shutil.rmtree(scratch, ignore_errors=True)
    if args.out:
        common.write_rows(args.out / "fmpy_whole.csv", columns, rows)


if __name__ == "__main__":
    main()
