"""The wound centre estimated from OpenPIV fields of rendered movies, against the truth: the
laser's target (lab_render.py) moved by the 4 px by which OpenPIV's tutorial states its
positions off the windows it correlated. Reads the draws that lab_coverage.py wrote (their
files and truth.json; no fit) and prints, per draw and over all, (estimate - truth) / sd
for both coordinates: calibrated standard errors give an rms of 1 and about one coordinate
in 20 beyond 2. The numbers of docs/fitting.md, "Lab files: Fiji, PIVlab, OpenPIV" (the
wound centre):

    cd python && python -m bench.lab_centre --out /tmp/lab_cov
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from wound_opening.cli.lab import window_of
from wound_opening.inputs.fiji import read_fiji
from wound_opening.inputs.piv import Frames, read_field
from wound_opening.inputs.rings import Measurement, flow_centre


def centre_z(where: Path) -> tuple[float, float, float]:
    """One draw's (z_x, z_y) and the CPU seconds of reading its files and the centre."""
    rec = json.loads((where / "truth.json").read_text())
    m, n = rec["movie"], int(rec["cut_after_frame"])
    t0 = time.process_time()
    radius = read_fiji(
        str(where / "radius.csv"), area_col="Area", frame_col="Slice",
        frame_interval_s=m["frame_s"], cut_after_frame=n,
    )  # fmt: skip
    frames = Frames(m["frame_s"], n, first_frame=n + 1)
    field = read_field(str(where / "piv"), frames, units=("um", "um/s"))
    window = window_of("32px", None, field)  # the fit command's default for these files
    measurement = Measurement(
        field.pair, field.x_um, field.y_um, field.spacing_um, m["frame_s"], window
    )
    c = flow_centre(field, radius, m["outer_um"], measurement)
    cpu = time.process_time() - t0
    (x0, y0), (ox, oy) = rec["centre_piv_axes_um"], rec["piv_stated_offset_px"]
    dx = c.x_um - (x0 + ox * m["pixel_um"])
    dy = c.y_um - (y0 - oy * m["pixel_um"])
    print(
        f"{where.name}: R0 {m['R0_um']:.2f} um, off ({dx:+.3f}, {dy:+.3f}) um, "
        f"sd ({c.sd_x_um:.3f}, {c.sd_y_um:.3f}) um, z ({dx / c.sd_x_um:+.2f}, "
        f"{dy / c.sd_y_um:+.2f})",
        flush=True,
    )
    return dx / c.sd_x_um, dy / c.sd_y_um, cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--out", type=Path, required=True, help="lab_coverage.py's --out")
    a = ap.parse_args()
    got = [centre_z(d) for d in sorted(a.out.glob("draw_*")) if (d / "truth.json").exists()]
    z = np.array([g[:2] for g in got]).ravel()
    print(
        f"{len(got)} draws, {z.size} coordinates: rms z {np.sqrt(np.mean(z**2)):.2f}, "
        f"beyond 2: {int(np.sum(np.abs(z) > 2))}, mean z {z.mean():+.2f}; "
        f"CPU {np.mean([g[2] for g in got]):.2f} s per draw (files read and the centre)"
    )


if __name__ == "__main__":
    main()
