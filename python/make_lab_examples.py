"""Writes examples/lab/: a lab's own files as Fiji and PIVlab write them, made from the EXACT
solution (wound_exact.py), for the README's "Fitting a lab's own files":

- Results_8um.csv: a Fiji Results table (" ,Label,Area,Perim.,Slice"; areas in px^2 of
  0.2 um, 3 decimals; frames 1-3 before the cut with Area 0 or NaN, two frames NaN where the
  tracking failed) of a cut of R0 = 8 um, one frame every 0.25 s;
- piv_8um/PIVlab_0001.txt ..: six PIVlab ASCII exports (calibrated, m and m/s, info lines,
  "Vector type [-]", CRLF, 10 digits, y down) of frame pairs 4-5, 24-25, .., 104-105 of the
  same movie, a 25 x 25 grid every 20 px (625 vectors each) of 32-px windows: each vector
  the exact displacement over its pair's frame interval averaged over its window, divided
  by the interval (what PIV measures), masked (NaN) where a window reaches the wound;
- Results_4um.csv, Results_8um.csv, Results_16um.csv: three wounds of one tissue.

The tissue: viscous length 20 um, tension/G 0.5, zeta/G 0.1 s/um^2 (eta/G = 10 s), outer
radius 100 um; lambda = 20 um / R0, T = zeta R0^2 / (4 G). Noise: 0.3 px on the radius,
0.05 um/s on each velocity component (seed 2026). The writers are used by the tests
(tests/python/test_lab_readers.py) on noise-free and noisy fixtures.

    python python/make_lab_examples.py [--out examples/lab]
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np
import wound_exact as we
from scipy.interpolate import CubicSpline

VISCOUS_UM, SIGMA, ZETA_OVER_G, OUTER_UM = 20.0, 0.5, 0.1, 100.0
PIXEL_UM, FRAME_S, CUT_AFTER, FRAMES = 0.2, 0.25, 3, 163
CENTRE_PX = (251.3, 262.8)
GRID_PX, IMAGE_PX, WINDOW_PX = 20, 512, 32
PIV_FIRST, PIV_STEP, PIV_PAIRS = 4, 20, 6
NOISE_PX, NOISE_UM_S, SEED = 0.3, 0.05, 2026


def parameters(R0: float) -> tuple[float, float, float]:
    """(lambda, sigma, T_s) of the tissue for a cut of radius R0 [um]."""
    return VISCOUS_UM / R0, SIGMA, ZETA_OVER_G * R0**2 / 4


def truth(R0: float) -> dict:
    lam, sigma, T = parameters(R0)
    return {"R0_um": R0, "sigma": sigma, "lambda": lam, "T_s": T}


def radius(R0: float, t) -> np.ndarray:
    """Exact wound radius [um] at times t [s since the cut]."""
    lam, sigma, T = parameters(R0)
    return R0 * we.edge(lam, sigma, OUTER_UM / R0, np.asarray(t, float) / T)[0]


def velocity(R0: float, t: float, r_um) -> np.ndarray:
    """Exact radial velocity [um/s] of the tissue at CURRENT distances r_um at time t [s]:
    the exact field on 400 material points, interpolated (cubic) at the current positions."""
    lam, sigma, T = parameters(R0)
    r_inf = OUTER_UM / R0
    X = 1 + (r_inf - 1) * np.linspace(0, 1, 400) ** 2
    u, v = we.profile(lam, sigma, r_inf, X, np.array([t / T]))
    return R0 / T * CubicSpline(X + u[0], v[0])(np.asarray(r_um, float) / R0)


def frame_times(frames) -> np.ndarray:
    return (np.asarray(frames, float) - CUT_AFTER) * FRAME_S


def write_fiji(path, R0, *, noise_px=0.0, seed=SEED, failed=(40, 97), sep=","):
    """A Fiji Results table of the wound's area [px^2] by Slice (module docstring)."""
    rng = np.random.default_rng(seed)
    frames = np.arange(1, FRAMES + 1)
    after = frames > CUT_AFTER
    r_px = np.full(frames.size, np.nan)
    r_px[after] = radius(R0, frame_times(frames[after])) / PIXEL_UM
    r_px[after] += noise_px * rng.standard_normal(after.sum())
    head = sep.join([" ", "Label", "Area", "Perim.", "Slice"])
    rows = [head]
    for k, (n, r) in enumerate(zip(frames, r_px), start=1):
        if n <= CUT_AFTER:
            area, perim = ("0", "0") if n < CUT_AFTER else ("NaN", "NaN")
        elif n in failed:
            area, perim = "NaN", "NaN"
        else:
            area, perim = f"{math.pi * r * r:.3f}", f"{2 * math.pi * r:.3f}"
        rows.append(sep.join([str(k), f"wound{R0:g}um.tif:{n:04d}", area, perim, str(n)]))
    Path(path).write_text("\n".join(rows) + "\n", encoding="utf-8")


def pair_time(k: int) -> float:
    return (PIV_FIRST + (k - 1) * PIV_STEP + 0.5 - CUT_AFTER) * FRAME_S


def grid_px():
    c = np.arange(GRID_PX // 2 + 6, IMAGE_PX, GRID_PX, dtype=float)[:25]
    x, y = np.meshgrid(c, c)
    return x.T.ravel(), y.T.ravel()  # MATLAB's reshape order (column-major): y runs fastest


def displacement(R0: float, t_a: float, t_b: float):
    """The exact radial displacement [um] from t_a to t_b [s] of the material point at
    CURRENT distance r_um at t_a: u(X, t_b) - u(X, t_a) at the X with X + u(X, t_a) = r, on
    400 material points, interpolated (cubic) at the current positions."""
    lam, sigma, T = parameters(R0)
    r_inf = OUTER_UM / R0
    X = 1 + (r_inf - 1) * np.linspace(0, 1, 400) ** 2
    u, _ = we.profile(lam, sigma, r_inf, X, np.array([t_a, t_b]) / T)
    spline = CubicSpline(X + u[0], u[1] - u[0])
    return lambda r_um: R0 * spline(np.asarray(r_um, float) / R0)


def measured(R0: float, t: float, dx_um, dy_um):
    """(u, v) [um/s] that PIV measures for the pair about time t (frames t -+ FRAME_S / 2)
    in windows of WINDOW_PX centred at dx, dy [um] from the wound centre: the mean of the
    exact displacement over the axis-aligned square window (6 x 6 Gauss-Legendre points)
    divided by the frame interval."""
    move = displacement(R0, t - FRAME_S / 2, t + FRAME_S / 2)
    g, w = np.polynomial.legendre.leggauss(6)
    half = WINDOW_PX * PIXEL_UM / 2
    dx, dy = np.asarray(dx_um, float), np.asarray(dy_um, float)
    u, v = np.zeros(dx.size), np.zeros(dx.size)
    for a, wa in zip(g, w):
        for b, wb in zip(g, w):
            px, py = dx + a * half, dy + b * half
            r = np.hypot(px, py)
            d = move(r) * wa * wb / 4
            u, v = u + d * px / r, v + d * py / r
    return u / FRAME_S, v / FRAME_S


def measured_radial(R0: float, t: float, dx_um, dy_um) -> np.ndarray:
    """The radial component [um/s] of `measured` at offsets dx, dy [um] from the centre."""
    u, v = measured(R0, t, dx_um, dy_um)
    return (u * np.asarray(dx_um) + v * np.asarray(dy_um)) / np.hypot(dx_um, dy_um)


def field(R0, t, *, noise=0.0, rng=None):
    """(x, y [px], u, v [um/s], vector type) of the field PIV measures (`measured`) for the
    pair about time t, y down: type 0 (NaN) for windows reaching into the wound at either
    frame (a corner within R(t + FRAME_S / 2))."""
    x, y = grid_px()
    dx, dy = (x - CENTRE_PX[0]) * PIXEL_UM, (y - CENTRE_PX[1]) * PIXEL_UM
    r = np.hypot(dx, dy)
    edge = radius(R0, [t + FRAME_S / 2])[0]
    kind = np.where(r - WINDOW_PX / 2 * PIXEL_UM * math.sqrt(2) <= edge, 0, 1)
    u, v = np.zeros(r.size), np.zeros(r.size)
    ok = kind == 1
    u[ok], v[ok] = measured(R0, t, dx[ok], dy[ok])
    if noise:
        u, v = u + noise * rng.standard_normal(r.size), v + noise * rng.standard_normal(r.size)
        interp = (rng.random(r.size) < 0.03) & (kind == 1)
        kind[interp] = 2
    u[kind == 0], v[kind == 0] = np.nan, np.nan
    return x, y, u, v, kind


def write_pivlab(folder, R0, *, calibrated=True, noise=0.0, seed=SEED, sep=","):
    """PIVlab ASCII exports PIVlab_0001.txt .. of the frame pairs (module docstring)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    cal_xy, cal_uv = PIXEL_UM * 1e-6, PIXEL_UM * 1e-6 / FRAME_S
    for k in range(1, PIV_PAIRS + 1):
        x, y, u, v, kind = field(R0, pair_time(k), noise=noise, rng=rng)
        a = PIV_FIRST + (k - 1) * PIV_STEP
        info = [
            "PIVlab, ASCII chart output - 02-Dec-2026",
            f"FRAME: {k}, filenames: wound{R0:g}um_{a:04d}.tif & wound{R0:g}um_{a + 1:04d}.tif, "
            f"conversion factor xy (px -> m): {cal_xy:g}, conversion factor uv (px/frame -> m/s):"
            f" {cal_uv:g}",
        ]
        if calibrated:
            head = ["x [m]", "y [m]", "u [m/s]", "v [m/s]", "Vector type [-]"]
            cols = [x * cal_xy, y * cal_xy, u * 1e-6, v * 1e-6, kind]
        else:
            head = ["x [px]", "y [px]", "u [px/frame]", "v [px/frame]", "Vector type [-]"]
            f = FRAME_S / PIXEL_UM
            cols = [x, y, u * f, v * f, kind]
        rows = info + [sep.join(head)] + [sep.join(_g10(c[i]) for c in cols) for i in range(x.size)]
        (folder / f"PIVlab_{k:04d}.txt").write_bytes(("\r\n".join(rows) + "\r\n").encode())


def _g10(value) -> str:
    """MATLAB dlmwrite 'precision', 10: %.10g, NaN as NaN."""
    return "NaN" if not np.isfinite(value) else f"{value:.10g}"


def write_openpiv(folder, R0, *, noise=0.0, seed=SEED):
    """OpenPIV files (openpiv.tools.save: '# x\\ty\\tu\\tv\\tflags\\tmask', %.4e, tabs) in px
    and px/s; masked vectors written 0 with mask 1, interpolated ones flag 2."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    rng = np.random.default_rng(seed)
    for k in range(1, PIV_PAIRS + 1):
        x, y, u, v, kind = field(R0, pair_time(k), noise=noise, rng=rng)
        mask = (kind == 0).astype(float)
        flags = np.where(kind == 2, 2.0, 0.0)
        u, v = np.nan_to_num(u) / PIXEL_UM, np.nan_to_num(v) / PIXEL_UM
        out = np.column_stack([x, y, u, v, flags, mask])
        np.savetxt(
            folder / f"exp_{k:03d}.txt",
            out,
            fmt="%.4e",
            delimiter="\t",
            header="\t".join(["x", "y", "u", "v", "flags", "mask"]),
        )


def main() -> None:
    ap = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    ap.add_argument("--out", default=str(Path(__file__).resolve().parents[1] / "examples" / "lab"))
    out = Path(ap.parse_args().out)
    out.mkdir(parents=True, exist_ok=True)
    for k, R0 in enumerate((4.0, 8.0, 16.0)):
        write_fiji(out / f"Results_{R0:g}um.csv", R0, noise_px=NOISE_PX, seed=SEED + k)
    write_pivlab(out / "piv_8um", 8.0, noise=NOISE_UM_S, seed=SEED)
    print(f"Fiji tables of 3 wounds and {PIV_PAIRS} PIVlab frame pairs -> {out}")


if __name__ == "__main__":
    main()
