"""Which measurement makes a coverage draw's field fit miss: the draw's fit with field
(lab_coverage.py) re-run with the radius table, the OpenPIV field or both replaced by the
exact truth in the same files' formats, plus white noise, and with the two as measured.

The exact radius is R(t) of each frame the table lists (the same rows, Area = pi R^2, Perim.
= 2 pi R) plus Gaussian noise of --radius-noise-um; the exact field is, at every vector of
every file, the window-averaged Lagrangian displacement over the pair (lab_errors.
window_truth, the truth the PIV error study uses) per frame interval, plus Gaussian noise of
--velocity-noise-um-s per component (the files' flags and positions kept). A miss that goes
with the measured radius and not with the exact one is the outline's; one that stays with
the exact radius is the field's (or the fit's).

    cd python && python -m bench.lab_swap --draw /tmp/lab_coverage/draw_009 --out /tmp/swap9
"""

from __future__ import annotations

import argparse
import json
import math
import shlex
from pathlib import Path

import numpy as np

from bench.lab_coverage import KEYS
from bench.lab_errors import window_truth
from bench.lab_measure import write_piv
from bench.lab_movies import run_fit
from bench.lab_render import Movie, render


def outline_table(draw: Path, rec: dict):
    """The draw's Fiji table: (its header line, column names, each row's cells, the exact
    radius at each row's frame [um])."""
    lines = (draw / "radius.csv").read_text().splitlines()
    head = lines[0].split(",")
    cells = [line.split(",") for line in lines[1:]]
    frame = head.index("Slice")
    exact = np.array([rec["radius_exact_um"][int(c[frame]) - 1] for c in cells])
    return lines[0], head, cells, exact


def exact_radius(table, out: Path, noise_um: float, seed: int) -> Path:
    """The draw's Fiji table (outline_table) with each row's area and perimeter those of the
    exact radius plus noise."""
    rng = np.random.default_rng([seed, 1])
    header, head, cells, exact = table
    area, perim = head.index("Area"), head.index("Perim.")
    rows = [header]
    for row, r_exact in zip(cells, exact):
        cells_out = list(row)
        r = r_exact + rng.normal(0.0, noise_um)
        cells_out[area], cells_out[perim] = f"{math.pi * r * r:.3f}", f"{2 * math.pi * r:.3f}"
        rows.append(",".join(cells_out))
    path = out / "radius_exact.csv"
    path.write_text("\n".join(rows) + "\n")
    return path


def exact_field(draw: Path, out: Path, rec: dict, noise_um_s: float, seed: int) -> Path:
    """The draw's OpenPIV files with each vector the exact window displacement per frame
    interval plus noise (the movie rendered again from its record: the same seed, the same
    frames)."""
    m = Movie(**rec["movie"])
    frames, truth = render(m)
    piv = write_piv(out / "piv_remeasured", frames, m.pre_frames, m.frame_s, m.pixel_um)
    rng = np.random.default_rng([seed, 2])
    folder = out / "piv_exact"
    folder.mkdir(parents=True, exist_ok=True)
    for k, a in enumerate(piv["a"], start=1):
        src = draw / "piv" / f"field_{k:04d}.txt"
        header = src.read_text().splitlines()[0].lstrip("# ")
        rows = np.loadtxt(src)
        true = window_truth(m, truth, a, piv["px"]) / m.frame_s  # um/s, image axes (y down)
        ok = np.isfinite(true).all(axis=1)
        rows[ok, 2] = true[ok, 0] + rng.normal(0.0, noise_um_s, ok.sum())
        rows[ok, 3] = -true[ok, 1] + rng.normal(0.0, noise_um_s, ok.sum())  # files: y up
        np.savetxt(folder / src.name, rows, fmt="%.6e", delimiter="\t", header=header)
    return folder


def leak_regression(table) -> dict:
    """The outline's error against its excess perimeter x = Perim. / 2 pi - r / sqrt(the
    largest circularity) (r = sqrt(Area / pi): zero for the roundest outline) over the
    draw's table (outline_table): the slope, the correlation, and the error's spread before
    and after the regression [um]."""
    _, head, cells, exact = table
    area = np.array([float(c[head.index("Area")]) for c in cells])
    perim = np.array([float(c[head.index("Perim.")]) for c in cells])
    r = np.sqrt(area / math.pi)
    circ = 4 * math.pi * area / perim**2
    x = perim / (2 * math.pi) - r / math.sqrt(circ.max())
    err = r - exact
    X = np.column_stack([np.ones_like(x), x])
    coef = np.linalg.lstsq(X, err, rcond=None)[0]
    corr = float(np.corrcoef(x, err)[0, 1]) if x.std() > 0 else 0.0
    return {
        "slope": float(coef[1]),
        "correlation": corr,
        "error_sd_um": float(err.std()),
        "after_sd_um": float((err - X @ coef).std()),
        "circularity": (float(circ.min()), float(circ.max())),
    }


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--draw", type=Path, required=True, help="a lab_coverage draw's folder")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--radius-noise-um", type=float, default=0.02)
    ap.add_argument("--velocity-noise-um-s", type=float, default=0.05)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    rec = json.loads((a.draw / "truth.json").read_text())
    table = outline_table(a.draw, rec)
    radius = {
        "measured": a.draw / "radius.csv",
        "exact": exact_radius(table, a.out, a.radius_noise_um, a.seed),
    }
    field = {
        "measured": a.draw / "piv",
        "exact": exact_field(a.draw, a.out, rec, a.velocity_noise_um_s, a.seed),
    }
    leak = leak_regression(table)
    print(
        f"outline error on its excess perimeter: slope {leak['slope']:.3f}, correlation "
        f"{leak['correlation']:.2f}, sd {leak['error_sd_um']:.3f} -> {leak['after_sd_um']:.3f}"
        f" um (circularity {leak['circularity'][0]:.2f}-{leak['circularity'][1]:.2f})",
        flush=True,
    )
    cmd = shlex.split(rec["fit"]["command"])
    for r_kind, p_kind in (("measured", "measured"), ("exact", "measured"), ("measured", "exact")):
        name = f"radius_{r_kind}_field_{p_kind}"
        sub = {
            str(a.draw / "radius.csv"): str(radius[r_kind]),
            str(a.draw / "piv"): str(field[p_kind]),
        }
        own = [sub.get(x, x.replace(str(a.draw / "fit"), str(a.out / name))) for x in cmd]
        res = run_fit(a.out, rec, own, name)
        est = res.get("estimates", {})
        misses = [
            k
            for k in KEYS
            if (row := est.get(k)) and row.get("identified") and not row.get("covers")
        ]
        print(
            f"radius {r_kind}, field {p_kind}: exit {res['exit']}, "
            f"{(res.get('status') or {}).get('level')}, identified misses {misses or 'none'}",
            flush=True,
        )


if __name__ == "__main__":
    main()
