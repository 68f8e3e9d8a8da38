"""The README's example microscope export, made from the EXACT solution (wound_exact.py)
with noise: examples/data/ablation_export.csv.

A wound of R0 = 10 um cut at 2350 ms in a tissue of outer radius 100 um with
G = 1000 Pa, eta = 2500 Pa s, zeta = 40 Pa s/um^2 and a tension of 500 Pa, so that
lambda = 2 sqrt(eta / zeta) / R0 = 1.58, sigma = 0.5, T = zeta R0^2 / (4 G) = 1 s and
tau = eta / G = 2.5 s. The radius is recorded in pixels of 0.1625 um, one frame every
250 ms for 20 s from the first frame after the cut, with Gaussian noise of 0.3 px
(0.049 um). The file is written as a microscope's export often is: a UTF-8 byte-order
mark, `;` separators, decimal commas, the columns "Time [ms]" and "Radius [px]".

    python python/example_export.py [--out examples/data]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import wound_exact as we

R0_UM, OUTER_UM, PIXEL_UM, CUT_MS = 10.0, 100.0, 0.1625, 2350.0
MATERIAL = {"G_pa": 1000.0, "eta_pa_s": 2500.0, "zeta_pa_s_per_um2": 40.0, "tension_pa": 500.0}
NOISE_PX, FRAME_MS, FRAMES, SEED = 0.3, 250.0, 80, 2026


def parameters() -> tuple[float, float, float]:
    """(lambda, sigma, T_s) of MATERIAL and R0_UM."""
    m = MATERIAL
    return (
        2 * math.sqrt(m["eta_pa_s"] / m["zeta_pa_s_per_um2"]) / R0_UM,
        m["tension_pa"] / m["G_pa"],
        m["zeta_pa_s_per_um2"] * R0_UM**2 / (4 * m["G_pa"]),
    )


def export(path: Path) -> None:
    lam, sigma, T = parameters()
    t_ms = CUT_MS + 120.0 + FRAME_MS * np.arange(FRAMES)  # the first frame 120 ms after the cut
    radius_um = R0_UM * we.edge(lam, sigma, OUTER_UM / R0_UM, (t_ms - CUT_MS) / 1000.0 / T)[0]
    radius_px = radius_um / PIXEL_UM + NOISE_PX * np.random.default_rng(SEED).standard_normal(
        t_ms.size
    )
    rows = ["Time [ms];Radius [px]"] + [
        f"{t:.0f};{r:.3f}".replace(".", ",") for t, r in zip(t_ms, radius_px)
    ]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(rows) + "\n", encoding="utf-8-sig")


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--out", default="examples/data", help="folder (default: %(default)s)")
    export(Path(ap.parse_args().out) / "ablation_export.csv")


if __name__ == "__main__":
    main()
