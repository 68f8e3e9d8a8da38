"""Rings or every vector: the PIV field in the fit's likelihood, measured on the same data.

Each draw writes a Fiji table (0.3 px noise) and six PIVlab frame pairs (0.05 um/s per
component, 3470 vectors used) of the exact solution (make_lab_examples.py, R0 = 8 um), reads
them with the estimated centre, and fits (a) the ring profile (ring means, the pooled scatter
within rings as the noise) and (b) every vector (one noise level, estimated from the
residuals). Prints per draw and likelihood: CPU seconds of the fit, each parameter's error
against the truth in units of its standard error, and whether the 95 % intervals cover.

    PYTHONPATH=python python python/bench/piv_likelihood.py [--draws 3] [--vector-draws 1]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import make_lab_examples as lab

from wound_opening.fitting.single import fit
from wound_opening.inputs.fiji import read_fiji
from wound_opening.inputs.piv import Frames, read_field
from wound_opening.inputs.rings import field_profile

R0 = 8.0


def draw(seed: int, folder: Path):
    lab.write_fiji(folder / "Results.csv", R0, noise_px=lab.NOISE_PX, seed=seed)
    lab.write_pivlab(folder / "piv", R0, noise=lab.NOISE_UM_S, seed=seed)
    radius = read_fiji(
        str(folder / "Results.csv"),
        area_col="Area",
        frame_interval_s=lab.FRAME_S,
        cut_after_frame=lab.CUT_AFTER,
        length_unit="px",
        pixel_size_um=lab.PIXEL_UM,
    )
    field = read_field(
        str(folder / "piv"), Frames(lab.FRAME_S, lab.CUT_AFTER, lab.PIV_FIRST, lab.PIV_STEP)
    )
    return radius, field


def run(radius, field, likelihood: str) -> str:
    profile, _ = field_profile(
        field, radius, lab.OUTER_UM, likelihood=likelihood, window_um=lab.WINDOW_PX * lab.PIXEL_UM
    )
    t0 = time.process_time()
    result = fit(radius, profile, outer_radius_um=lab.OUTER_UM)
    cpu = time.process_time() - t0
    parts = [f"{likelihood:<8} points {len(profile.r_um):>5}  CPU {cpu:7.2f} s"]
    for name, value in lab.truth(R0).items():
        rep = result.reports[name]
        lo, hi = rep.ci95
        inside = lo is not None and hi is not None and lo <= value <= hi
        z = (rep.estimate - value) / rep.stderr if rep.stderr else float("nan")
        parts.append(f"{name} z={z:+.2f} {'covers' if inside else 'MISSES'}")
    return "  ".join(parts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--draws", type=int, default=3)
    ap.add_argument("--vector-draws", type=int, default=1)
    args = ap.parse_args()
    for seed in range(args.draws):
        with tempfile.TemporaryDirectory() as tmp:
            radius, field = draw(100 + seed, Path(tmp))
            print(f"draw {seed}: {run(radius, field, 'rings')}", flush=True)
            if seed < args.vector_draws:
                print(f"draw {seed}: {run(radius, field, 'vectors')}", flush=True)


if __name__ == "__main__":
    main()
