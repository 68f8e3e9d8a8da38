"""Calibration of the wound-centre estimate (inputs/centre.py): on noisy PIVlab fields of the
exact solution (make_lab_examples.py: R0 = 8 um, six frame pairs, 0.05 um/s per component),
the error of the estimate in units of its stated standard error, per coordinate.

    PYTHONPATH=python python python/bench/piv_centre.py [--draws 12]
"""

from __future__ import annotations

import argparse
import tempfile
import time

import make_lab_examples as lab
import numpy as np

from wound_opening.inputs.centre import estimate_centre
from wound_opening.inputs.piv import Frames, read_field


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--draws", type=int, default=12)
    draws = ap.parse_args().draws
    true = np.array(lab.CENTRE_PX) * lab.PIXEL_UM
    frames = Frames(lab.FRAME_S, lab.CUT_AFTER, lab.PIV_FIRST, lab.PIV_STEP)
    z, sd, cpu = [], [], []
    for seed in range(draws):
        with tempfile.TemporaryDirectory() as tmp:
            lab.write_pivlab(tmp, 8.0, noise=lab.NOISE_UM_S, seed=seed)
            f = read_field(tmp, frames)
        t0 = time.process_time()
        c = estimate_centre(f.x_um, f.y_um, f.u_um_s, f.v_um_s, f.pair)
        cpu.append(time.process_time() - t0)
        z += [(c.x_um - true[0]) / c.sd_x_um, (c.y_um - true[1]) / c.sd_y_um]
        sd += [c.sd_x_um, c.sd_y_um]
    z = np.array(z)
    print(
        f"{draws} draws, {z.size} coordinates: rms z = {np.sqrt(np.mean(z**2)):.2f}, "
        f"max |z| = {np.abs(z).max():.2f}, |z| > 2: {int(np.sum(np.abs(z) > 2))}; "
        f"mean sd {np.mean(sd):.2f} um; CPU {np.mean(cpu):.2f} s per estimate"
    )


if __name__ == "__main__":
    main()
