"""Lab data from rendered movies, measured by the real tools: a fluorescence movie of a wound
opening rendered from the EXACT solution (lab_render.py), its velocity measured by
OpenPIV-python and its outline by scikit-image as ImageJ outlines one (lab_measure.py), the
files written as those programs write them, and their errors against the truth
(lab_errors.py). Independent of the fitter: nothing of wound_opening is used to make the files.

    cd python && python -m bench.lab_movies --out DIR --R0-um 10 --sigma 1 --lambda 1 --T-s 2 \
        [--pixel-um 0.2 --frame-s 0.5 --frames 30 --size-px 512 --cut-offset-s 0.05 --seed 0] \
        [--imagej] [--fit]

writes

- DIR/movie.tif: the frames (uint16, ImageJ hyperstack metadata: pixel size, frame interval);
- DIR/piv/field_0001.txt ...: one OpenPIV file per frame pair after the cut (um, um/s, y up;
  positions as the tutorial writes them: 4 px right of and below the windows correlated);
- DIR/radius.csv: the Fiji Results table of the wound's area (um^2) per Slice;
- DIR/truth.json: the true parameters and material ratios, the true centre in the PIV files'
  axes (um), the cut on the camera's clock, the exact radius per frame, the files' errors
  against the truth, and `fit_command`, the documented `wound-opening fit` of these files;
- with --imagej, the outline measured by ImageJ itself too (lab_imagej.py):
  DIR/radius_imagej.csv, its errors and its fit command in truth.json (with --fit run too:
  DIR/fit_imagej.*, "fit_imagej");
- with --fit, that command run (DIR/fit.json, DIR/fit_report.html, DIR/fit.png), its output
  in DIR/fit.txt and its estimates against the truth in truth.json's "fit"; and the same
  without the PIV options (DIR/fit_radius.*, "fit_radius_only").
"""

from __future__ import annotations

import argparse
import json
import math
import shlex
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import tifffile

from bench.lab_errors import outline_errors, piv_errors
from bench.lab_imagej import available, measure_imagej
from bench.lab_measure import file_axes_centre_um, stated_offset_px, write_piv, write_results
from bench.lab_render import Movie, render


def material(m: Movie) -> dict:
    """The tissue's ratios as the fit reports them (docs/model.md: T = zeta R0^2 / (4 G),
    lambda = 2 sqrt(eta / zeta) / R0)."""
    zeta_g = 4 * m.T_s / m.R0_um**2
    return {
        "viscous_length_um": m.lam * m.R0_um,
        "zeta_over_G_s_per_um2": zeta_g,
        "eta_over_G_s": m.lam**2 * m.T_s,
        "tension_over_G": m.sigma,
    }


def fit_command(out: Path, m: Movie, radius: Path, piv: Path, stem: str = "fit") -> list[str]:
    """The documented `wound-opening fit` of the files (docs/fitting.md, "Lab files: Fiji,
    PIVlab, OpenPIV"): frames 1..pre_frames before the cut (the cut itself fitted between
    frames N and N + 1), the PIV pairs from frame N + 1, one frame apart, in um and um/s."""
    n = m.pre_frames
    return [
        "wound-opening", "fit", str(radius),
        "--area-col", "Area", "--frame-col", "Slice",
        "--frame-interval-s", repr(m.frame_s), "--cut-after-frame", str(n),
        "--outer-radius-um", repr(m.outer_um),
        "--piv", str(piv), "--piv-first-frame", str(n + 1), "--piv-pair-step", "1",
        "--piv-units", "um,um/s",
        "--json", str(out / f"{stem}.json"), "--report", str(out / f"{stem}_report.html"),
        "--plot", str(out / f"{stem}.png"),
    ]  # fmt: skip


def measure(out: Path, m: Movie, frames, truth: dict, imagej: bool = False) -> dict:
    """Every file of the module docstring but the fit's; returns truth.json's content."""
    out.mkdir(parents=True, exist_ok=True)
    tifffile.imwrite(
        out / "movie.tif",
        frames,
        imagej=True,
        resolution=(1 / m.pixel_um, 1 / m.pixel_um),
        metadata={"axes": "TYX", "unit": "um", "finterval": m.frame_s},
    )
    first = m.pre_frames  # 0-based index of the first frame after the cut
    piv = write_piv(out / "piv", frames, first, m.frame_s, m.pixel_um)
    r_final = m.R0_um * (1 + 2 * m.sigma / 3 * (m.outer_um / m.R0_um) ** 2 /
                         ((m.outer_um / m.R0_um) ** 2 - 1))  # fmt: skip
    roi_half = int(min(2 * r_final / m.pixel_um, m.size_px / 2 - 2))
    rad = write_results(out / "radius.csv", frames, first, m.centre(), roi_half, m.pixel_um)
    cmd = fit_command(out, m, out / "radius.csv", out / "piv")
    record = {
        "parameters": {"R0_um": m.R0_um, "sigma": m.sigma, "lambda": m.lam, "T_s": m.T_s},
        "material": material(m),
        "movie": m.as_dict(),
        "centre_piv_axes_um": list(file_axes_centre_um(m.centre(), frames.shape[1:], m.pixel_um)),
        "centre_image_px": list(m.centre()),
        "cut_time_s": m.cut_time_s(),
        "cut_offset_s": m.cut_offset_s,
        "cut_after_frame": m.pre_frames + m.cut_offset_s / m.frame_s,
        "frame_interval_s": m.frame_s,
        "pixel_size_um": m.pixel_um,
        "frame_times_since_cut_s": [float(t) for t in truth["t_s"]],
        "radius_exact_um": [None if math.isnan(r) else float(r) for r in truth["radius_um"]],
        "radius_measured_um": [None if math.isnan(r) else float(r) for r in rad["radius_um"]],
        "outline_roi_half_px": roi_half,
        "piv_pairs": len(piv["a"]),
        "piv_vectors_per_pair": int(len(piv["px"])),
        "piv_stated_offset_px": list(stated_offset_px(frames.shape[1:])),
        "outline_errors": outline_errors(m, truth, rad["radius_um"]),
        "piv_errors": piv_errors(m, truth, piv),
        "fit_command": shlex.join(cmd),
    }
    if imagej:
        missing = available()
        if missing:
            raise SystemExit(f"--imagej: {missing} missing (apt-get install imagej xvfb xauth)")
        r_ij = measure_imagej(out, m.centre(), roi_half, first + 1, m.frames)
        record["radius_imagej_um"] = [None if math.isnan(r) else float(r) for r in r_ij]
        record["outline_errors_imagej"] = outline_errors(m, truth, r_ij)
        record["fit_command_imagej"] = shlex.join(
            fit_command(out, m, out / "radius_imagej.csv", out / "piv", "fit_imagej")
        )
    return record


def radius_only(cmd: list[str]) -> list[str]:
    """The fit command without its PIV options, its outputs renamed fit_radius.*."""
    out, skip = [], 0
    for arg in cmd:
        if skip:
            skip -= 1
            continue
        if arg.startswith("--piv"):
            skip = 1
            continue
        path = Path(arg)
        if path.suffix in (".json", ".html", ".png"):
            arg = str(path.with_name(path.name.replace("fit", "fit_radius", 1)))
        out.append(arg)
    return out


def outlines_round(fit: dict) -> bool:
    """Whether a fit's JSON carries no reader's warning that the outlines are not round
    (inputs/fiji.outline_warnings): such a fit reports nothing identified."""
    return not any("outlines are not round" in w for w in fit.get("warnings") or [])


def run_fit(out: Path, record: dict, cmd: list[str], name: str) -> dict:
    """A fit command run in this interpreter's environment (its output in DIR/NAME.txt); its
    estimates, intervals and verdicts against the truth."""
    cmd = list(cmd)
    exe = Path(sys.executable).with_name("wound-opening")
    cmd[0] = str(exe) if exe.exists() else cmd[0]
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    (out / f"{name}.txt").write_text(proc.stdout + proc.stderr)
    res = {"command": shlex.join(cmd), "exit": proc.returncode, "wall_s": round(wall, 2)}
    try:
        fit = json.loads((out / f"{name}.json").read_text())
    except (OSError, ValueError):
        return res
    res["converged"] = fit.get("converged")
    res["reasons"] = fit.get("reasons")
    res["status"] = fit.get("status")
    res["outlines_round"] = outlines_round(fit)
    truth = {**record["parameters"], **record["material"], "cut_s": record["cut_offset_s"]}
    rows = {}
    for key, value in (fit.get("estimate_at_stop") or {}).items():
        rows[key] = {"estimate": value, "truth": truth.get(key), "at_stop": True}
    for group in ("parameters", "material"):
        for key, entry in (fit.get(group) or {}).items():
            if not (isinstance(entry, dict) and "estimate" in entry):
                continue
            ci = entry.get("ci95") or [None, None]
            row = {"estimate": entry["estimate"], "ci95": ci, "truth": truth.get(key)}
            row["identified"] = entry.get("identifiable")
            if row["truth"] is not None:
                lo = -math.inf if ci[0] is None else ci[0]
                hi = math.inf if ci[1] is None else ci[1]
                row["covers"] = bool(lo <= row["truth"] <= hi)
            rows[key] = row
    res["estimates"] = rows
    return res


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--R0-um", type=float, default=10.0)
    ap.add_argument("--sigma", type=float, default=1.0)
    ap.add_argument("--lambda", dest="lam", type=float, default=1.0)
    ap.add_argument("--T-s", type=float, default=2.0)
    ap.add_argument("--outer-radius-um", type=float, default=100.0)
    ap.add_argument("--pixel-um", type=float, default=0.2)
    ap.add_argument("--frame-s", type=float, default=0.5)
    ap.add_argument("--frames", type=int, default=30, help="5 before the cut, 24 pairs after")
    ap.add_argument("--pre-frames", type=int, default=5)
    ap.add_argument("--size-px", type=int, default=512)
    ap.add_argument(
        "--cut-offset-s",
        type=float,
        default=0.05,
        help="the laser after the last frame before the cut [s]; -1: random in [0, frame)",
    )
    ap.add_argument("--cell-um", type=float, default=4.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--fit", action="store_true", help="run the fit command on the files")
    ap.add_argument(
        "--imagej", action="store_true", help="outline by ImageJ too (radius_imagej.csv)"
    )
    a = ap.parse_args(argv)
    offset = a.cut_offset_s
    if offset < 0:
        offset = float(np.random.default_rng([a.seed, 4]).uniform(0, a.frame_s))
    m = Movie(
        R0_um=a.R0_um, sigma=a.sigma, lam=a.lam, T_s=a.T_s, outer_um=a.outer_radius_um,
        pixel_um=a.pixel_um, frame_s=a.frame_s, frames=a.frames, pre_frames=a.pre_frames,
        cut_offset_s=offset, size_px=a.size_px, cell_um=a.cell_um, seed=a.seed,
    )  # fmt: skip
    t0 = time.process_time()
    frames, truth = render(m)
    t1 = time.process_time()
    record = measure(a.out, m, frames, truth, imagej=a.imagej)
    record["cpu_s"] = {"render": round(t1 - t0, 2), "measure": round(time.process_time() - t1, 2)}
    if a.fit:
        cmd = shlex.split(record["fit_command"])
        record["fit"] = run_fit(a.out, record, cmd, "fit")
        record["fit_radius_only"] = run_fit(a.out, record, radius_only(cmd), "fit_radius")
        if a.imagej:
            cmd = shlex.split(record["fit_command_imagej"])
            record["fit_imagej"] = run_fit(a.out, record, cmd, "fit_imagej")
    (a.out / "truth.json").write_text(json.dumps(record, indent=1) + "\n")
    p = record["piv_errors"]
    print(f"{a.out}: {record['piv_pairs']} pairs x {record['piv_vectors_per_pair']} vectors; "
          f"cpu {record['cpu_s']}")  # fmt: skip
    for name in ("outline_errors", "outline_errors_imagej"):
        if name in record:
            o = record[name]
            print(
                f"{name}: offset {o['offset_mean_um']:+.3f} um (sd {o['offset_sd_um']:.3f}, "
                f"{o['offset_min_um']:+.3f}..{o['offset_max_um']:+.3f}), lag-1 "
                f"{o['lag1_correlation']:.2f}, {o['lag1_correlation_detrended']:.2f} less the drift"
            )
    for comp in ("radial", "tangential"):
        c = p[comp]
        print(f"PIV {comp}: rms {c['rms_um_s']:.4f} um/s, mean {c['mean_um_s']:+.4f}; "
              f"pairs lag {c['pairs_lag']}; neighbours {c['neighbours_steps']}")  # fmt: skip
    print(f"PIV ring at the wound: measured / exact radial {p['wound_ring_ratio_range']}")
    print(
        "PIV tissue windows: measured radial on exact, slope "
        f"{p['radial_slope_on_window_truth']:.3f} (window), "
        f"{p['radial_slope_on_centre_point']:.3f} (centre point)"
    )
    print(f"fit: {record['fit_command']}")
    for name in ("fit", "fit_radius_only", "fit_imagej") if a.fit else ():
        if name not in record:
            continue
        f = record[name]
        print(f"{name}: exit {f['exit']}, {f['wall_s']} s wall; {f.get('reasons') or ''}")
        for key, row in f.get("estimates", {}).items():
            print(f"  {key}: {row}")


if __name__ == "__main__":
    main()
