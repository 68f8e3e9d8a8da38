"""A fluorescence movie of a laser-ablated wound, rendered from the EXACT solution
(wound_exact.py), for measuring with the tools labs use (lab_measure.py).

The tissue is a membrane-labelled epithelium: a Voronoi tessellation of jittered hexagonal
seeds (cells `cell_um` across) in the reference (stress-free) plane, its edges drawn bright
with a brightness of their own per edge, the cells' cytoplasm dimmer with one level per cell.
At a point of the reference plane at distance d from the nearest cell edge, the dye is

    I = c_i + b_ij exp(-d^2 / (2 w^2)),     d = (|p - s_j|^2 - |p - s_i|^2) / (2 |s_j - s_i|)

(s_i the nearest seed, s_j the second nearest: d is the distance to their bisector, the
edge between the two cells; w the membrane's half width). After the cut the cells at the
margin seal it: a membrane of brightness `margin` along the wound edge, centred one
half-width w inside the tissue (reference radius R0 + w), adds
margin exp(-(rho - R0 - w)^2 / (2 w^2)).

Motion. Lengths in R0 and time in T (docs/model.md): a material point at reference radius
rho sits at x = rho + u(rho, t). Before the cut the tissue is under uniform tension,
u = sigma rho / 6 (a dilation); after it u is the exact profile (`wound_exact.profile`),
whose x(rho) is increasing, so a pixel at current radius r shows the material at
rho = x^-1(r) along the same direction from the centre: the texture is sampled there. After
the cut the disk r < R(t) = 1 + u(1, t) is the ablated wound, dark. The pixel integrates its
area (s x s sub-samples), the optics blur with a Gaussian point-spread function, bleaching
scales the dye by exp(-frame / bleach_frames), the camera counts photons (Poisson) and adds
Gaussian read noise and an offset (uint16 counts).

Frames n = 1, 2, ... are at (n - 1) x frame_s on the camera's clock; the cut is at
(pre_frames - 1) x frame_s + cut_offset_s: `pre_frames` frames before it, the laser fired
`cut_offset_s` (0 <= offset < frame_s) after the last of them.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
import wound_exact as we
from scipy import ndimage
from scipy.spatial import cKDTree


@dataclass(frozen=True)
class Movie:
    """What to render: the tissue, the microscope and the recording."""

    R0_um: float = 10.0
    sigma: float = 1.0
    lam: float = 1.0
    T_s: float = 2.0
    outer_um: float = 100.0
    pixel_um: float = 0.2
    frame_s: float = 0.5
    frames: int = 30
    pre_frames: int = 5
    cut_offset_s: float = 0.05
    size_px: int = 512
    #: The wound centre in image axes (x right, y down, pixel centres at integers); None: the
    #: image centre plus a sub-pixel offset drawn from the seed.
    centre_px: tuple[float, float] | None = None
    cell_um: float = 4.0
    membrane_um: float = 0.25
    psf_um: float = 0.3
    photons: float = 300.0
    read_noise: float = 3.0
    offset_counts: float = 100.0
    bleach_frames: float = 60.0
    margin: float = 1.0
    supersample: int = 2
    seed: int = 0

    def centre(self) -> tuple[float, float]:
        if self.centre_px is not None:
            return tuple(float(c) for c in self.centre_px)
        rng = np.random.default_rng([self.seed, 1])
        mid = (self.size_px - 1) / 2
        return (mid + rng.uniform(-0.5, 0.5), mid + rng.uniform(-0.5, 0.5))

    def cut_time_s(self) -> float:
        """The cut on the camera's clock (frame 1 at 0 s)."""
        return (self.pre_frames - 1) * self.frame_s + self.cut_offset_s

    def frame_times_s(self) -> np.ndarray:
        """Each frame's time since the cut [s] (negative before it)."""
        return np.arange(self.frames) * self.frame_s - self.cut_time_s()

    def check(self) -> None:
        half_diag = math.hypot(*(max(c, self.size_px - 1 - c) for c in self.centre()))
        if self.outer_um <= 1.2 * half_diag * self.pixel_um:
            raise ValueError(
                f"outer radius {self.outer_um} um: the image reaches "
                f"{half_diag * self.pixel_um:.1f} um from the centre: give 1.2 times that or more"
            )
        if not 0 <= self.cut_offset_s < self.frame_s:
            raise ValueError(f"cut offset {self.cut_offset_s} s: in [0, frame interval)")
        if self.pre_frames < 1 or self.frames < self.pre_frames + 2:
            raise ValueError("at least one frame before the cut and two after it")

    def as_dict(self) -> dict:
        d = asdict(self)
        d["centre_px"] = list(self.centre())
        return d


class Tissue:
    """The membrane-labelled epithelium in the reference plane (module docstring), in um
    about the wound centre."""

    def __init__(self, m: Movie, reach_um: float):
        rng = np.random.default_rng([m.seed, 2])
        a = m.cell_um
        n = int(reach_um / a) + 3
        i, j = np.meshgrid(np.arange(-n, n + 1), np.arange(-n, n + 1))
        x = a * (i + 0.5 * (j % 2))
        y = a * j * math.sqrt(3) / 2
        seeds = np.column_stack([x.ravel(), y.ravel()]) + rng.normal(0, 0.22 * a, (x.size, 2))
        self.seeds = seeds
        self.tree = cKDTree(seeds)
        self.cytoplasm = rng.uniform(0.25, 0.4, len(seeds))
        self.width = m.membrane_um
        self.edge_key = rng.integers(1, 2**31, 2)

    def dye(self, p: np.ndarray) -> np.ndarray:
        """Dye density at reference points p (..., 2) [um]."""
        flat = p.reshape(-1, 2)
        _, nn = self.tree.query(flat, k=2)
        si, sj = self.seeds[nn[:, 0]], self.seeds[nn[:, 1]]
        gap = np.linalg.norm(sj - si, axis=1)
        d = (np.sum((flat - sj) ** 2, 1) - np.sum((flat - si) ** 2, 1)) / (2 * gap)
        lo, hi = np.minimum(nn[:, 0], nn[:, 1]), np.maximum(nn[:, 0], nn[:, 1])
        h = (lo * self.edge_key[0] + hi * self.edge_key[1]) % 1009
        bright = 0.6 + 0.8 * h / 1009
        out = self.cytoplasm[nn[:, 0]] + bright * np.exp(-0.5 * (d / self.width) ** 2)
        return out.reshape(p.shape[:-1])


def material_maps(m: Movie, t_s: np.ndarray, n_rho: int = 500):
    """Per frame (x_of_rho, rho) tables in units of R0: current radius of the material at
    reference radius rho (tissue beyond the wound), for frames after the cut; None before."""
    r_inf = m.outer_um / m.R0_um
    rho = 1 + (r_inf - 1) * np.linspace(0, 1, n_rho) ** 2
    after = t_s > 0
    maps = [None] * len(t_s)
    if after.any():
        u, _ = we.profile(m.lam, m.sigma, r_inf, rho, t_s[after] / m.T_s)
        for k, uk in zip(np.flatnonzero(after), u):
            x = rho + uk
            if np.any(np.diff(x) <= 0):
                raise ValueError("x(rho) not increasing: the exact map cannot be inverted")
            maps[k] = x
    return rho, maps


def reference_radius_um(m: Movie, rho_map, x_map, r_um: np.ndarray) -> np.ndarray:
    """Reference radius [um] of the material at current radii r_um; NaN inside the wound.
    Before the cut (x_map None) the dilation x = rho (1 + sigma / 6)."""
    r = r_um / m.R0_um
    if x_map is None:
        return r_um / (1 + m.sigma / 6)
    rho = np.interp(r, x_map, rho_map, right=np.nan)
    far = r > x_map[-1]
    rho[far] = r[far] - (x_map[-1] - rho_map[-1])  # beyond the outer radius: m.check refuses
    rho[r < x_map[0]] = np.nan
    return rho * m.R0_um


def render(m: Movie) -> tuple[np.ndarray, dict]:
    """The movie (frames, size, size) uint16 and the exact truth per frame: time since the
    cut [s], wound radius [um] (NaN before the cut)."""
    m.check()
    cx, cy = m.centre()
    s = m.supersample
    sub = (np.arange(s) + 0.5) / s - 0.5
    ax = (np.arange(m.size_px)[:, None] + sub[None, :]).ravel()
    X, Y = np.meshgrid(ax - cx, ax - cy)  # image axes, y down; (row, col) = (Y, X)
    r_px = np.hypot(X, Y)
    r_um = r_px * m.pixel_um
    cos, sin = X / np.maximum(r_px, 1e-12), Y / np.maximum(r_px, 1e-12)
    tissue = Tissue(m, r_um.max() + 2 * m.cell_um)
    t_s = m.frame_times_s()
    rho_map, maps = material_maps(m, t_s)
    rng = np.random.default_rng([m.seed, 3])
    frames = np.empty((m.frames, m.size_px, m.size_px), np.uint16)
    radius = np.full(m.frames, np.nan)
    for k, x_map in enumerate(maps):
        rho_um = reference_radius_um(m, rho_map, x_map, r_um)
        wound = np.isnan(rho_um)
        ref = np.stack([np.nan_to_num(rho_um) * cos, np.nan_to_num(rho_um) * sin], -1)
        dye = tissue.dye(ref)
        if x_map is not None:
            w = m.membrane_um
            dye += m.margin * np.exp(-0.5 * ((rho_um - m.R0_um - w) / w) ** 2)
        dye = np.where(wound, 0.03, dye)
        dye = dye.reshape(m.size_px, s, m.size_px, s).mean(axis=(1, 3))
        dye = ndimage.gaussian_filter(dye, m.psf_um / m.pixel_um, mode="nearest")
        mean = m.photons * math.exp(-k / m.bleach_frames) * dye
        counts = rng.poisson(mean) + rng.normal(m.offset_counts, m.read_noise, mean.shape)
        frames[k] = np.clip(np.rint(counts), 0, 65535).astype(np.uint16)
        if x_map is not None:
            radius[k] = x_map[0] * m.R0_um
    return frames, {"t_s": t_s, "radius_um": radius, "rho": rho_map, "maps": maps}


def lagrangian_displacement_um(m: Movie, truth: dict, a: int, pts_px: np.ndarray) -> np.ndarray:
    """Exact displacement [um] (x, y in image axes) from frame a to frame a + 1 of the material
    at points pts_px (n, 2: x, y in px) of frame a; NaN where frame a shows the wound."""
    cx, cy = m.centre()
    d = pts_px - np.array([cx, cy])
    r = np.hypot(d[:, 0], d[:, 1]) * m.pixel_um
    rho_um = reference_radius_um(m, truth["rho"], truth["maps"][a], r)
    xb = truth["maps"][a + 1]
    rb = (
        rho_um * (1 + m.sigma / 6)
        if xb is None
        else np.interp(rho_um / m.R0_um, truth["rho"], xb) * m.R0_um
    )
    scale = (rb - r) / np.maximum(r, 1e-12)
    return d * m.pixel_um * scale[:, None]


def edge_radius_um(m: Movie, t_s) -> np.ndarray:
    """Exact wound radius [um] at times t_s since the cut (> 0)."""
    t = np.atleast_1d(np.asarray(t_s, float))
    return m.R0_um * we.edge(m.lam, m.sigma, m.outer_um / m.R0_um, t / m.T_s)[0]
