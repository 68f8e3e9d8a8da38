"""The problem of several wounds of one tissue (wounds.py's `fit_wounds`): its coordinates
and the wounds' Objectives as one objective.

Coordinates y: the shared l, sigma and ln zeta/G, each wound's ln R0_k (wounds.py's module
docstring), then the nuisances the fit names (objective.NUISANCES; each wound's Objective
holds its own, in z_k after its four parameters):

    outline_offset_um     one radial offset of every wound's outline: the wounds of one movie
                          set are outlined by one segmentation (one threshold, one blur)
    cut_s[NAME]           each wound's cut on its own movie's clock (each was cut apart)
    piv_gain[NAME]        each PIV field's gain (a PIV program's bias depends on the texture)

z_k takes the nuisances of wound k from y as they are (d z_k / d y is 1 there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..results.names import ETA, SHARED
from .objective import CUT, LAMBDA_MAX, OUTLINE_OFFSET, PIV_GAIN, Objective, from_z, r0_coordinate
from .parameters import G_NAME, Coordinate, Coordinates, factor, span
from .problem import Problem
from .wound_profiles import LN4

#: One wound's names, refused with a hint in a fit of several.
SINGLE_ONLY = ("sigma", "lambda", "T_s", "R0_um")


@dataclass(frozen=True)
class TissueNuisances:
    """Which nuisances a fit of several wounds has: one outline offset (`offset`), the cut of
    the wounds named in `cut` and the PIV gain of those named in `gain`."""

    offset: bool = False
    cut: tuple = ()
    gain: tuple = ()

    @classmethod
    def every(cls, names, with_profile) -> TissueNuisances:
        """Every nuisance the wounds `names` can have (a gain where a field is given)."""
        return cls(True, tuple(names), tuple(n for n, p in zip(names, with_profile) if p))

    def of(self, name: str) -> tuple[str, ...]:
        """Wound `name`'s nuisances in its Objective's order (objective.NUISANCES)."""
        mine = [(OUTLINE_OFFSET.name, self.offset), (CUT.name, name in self.cut)]
        return tuple(n for n, on in mine + [(PIV_GAIN.name, name in self.gain)] if on)


def nuisance_coordinates(names, nuisances: TissueNuisances) -> tuple:
    """The nuisances' coordinates after the shared ones and the R0s (module docstring)."""
    out = (OUTLINE_OFFSET,) if nuisances.offset else ()
    out += tuple(_named(CUT, n) for n in names if n in nuisances.cut)
    return out + tuple(_named(PIV_GAIN, n) for n in names if n in nuisances.gain)


def _named(c: Coordinate, wound: str) -> Coordinate:
    return replace(c, name=f"{c.name}[{wound}]")


def tissue_coordinates(names, outers, nuisances: TissueNuisances | None = None) -> Coordinates:
    """The coordinates y of wounds `names` in tissues of outer radii `outers` (module
    docstring), by name: the shared l, tension/G and zeta/G, then R0_um[NAME] of each wound
    (also R0_um[K], K from 1), then the `nuisances`' (also cut_s[K], piv_gain[K]). Profiles
    search l from 0 to LAMBDA_MAX times the largest R0, sigma within 10 |sigma| + 1, zeta/G
    a factor 100 and each R0 a factor 3 either way."""
    nuisances = nuisances or TissueNuisances()

    def l_window(centre, y_hat, i):
        return 0.0, LAMBDA_MAX * math.exp(max(y_hat[3 : 3 + len(names)]))

    shared = (
        Coordinate(
            SHARED[0],
            "um",
            lower=0.0,
            closed=True,
            window=l_window,
            step=lambda y_hat: 0.1 * math.exp(float(np.median(y_hat[3 : 3 + len(names)]))),
        ),
        Coordinate(
            SHARED[1],
            "1 (tension / G)",
            window=span(),
            step=lambda y_hat: 0.05 * abs(y_hat[1]) + 0.01,
        ),
        Coordinate(SHARED[2], "s/um^2", log=True, lower=0.0, window=factor(1e2)),
    )
    radii = tuple(r0_coordinate(f"R0_um[{n}]", outer) for n, outer in zip(names, outers))
    extra = nuisance_coordinates(names, nuisances)
    everything = shared + radii + extra

    def unknown(name: str) -> str:
        if name == ETA:
            return (
                f"{ETA} is not a coordinate of the fit of several wounds (eta/G = l^2 zeta/G / 4): "
                f"constrain {SHARED[0]} or {SHARED[2]} instead"
            )
        hint = (
            f" ({name} is one wound's parameter: with several wounds use "
            f"{', '.join(SHARED)} or R0_um[NAME])"
            if name in SINGLE_ONLY
            else ""
        )
        if name in (CUT.name, PIV_GAIN.name):
            hint = f" (each wound has its own: {name}[NAME])"
        more = "".join(f", {c.name}" for c in extra)
        return (
            f"parameter {name!r} is unknown for several wounds{hint}: expected one of "
            f"{', '.join(SHARED + (G_NAME,))}, R0_um[NAME] or R0_um[K]{more} with NAME one of "
            f"{', '.join(names)} (K from 1 to {len(names)})"
        )

    aliases = {f"R0_um[{k + 1}]": 3 + k for k in range(len(names))}
    index = {c.name: i for i, c in enumerate(everything)}
    for k, n in enumerate(names):
        for base in (CUT.name, PIV_GAIN.name):
            if f"{base}[{n}]" in index:
                aliases[f"{base}[{k + 1}]"] = index[f"{base}[{n}]"]
    return Coordinates(everything, aliases, unknown)


class Tissue(Problem):
    """The wounds' Objectives as one objective in y (see the module docstring)."""

    def __init__(self, parts: list[Objective], names, nuisances: TissueNuisances | None = None):
        self.parts = parts
        self.nuisances = nuisances or TissueNuisances()
        self.coordinates = tissue_coordinates(names, [p.outer for p in parts], self.nuisances)
        self.n = len(self.coordinates)
        index = {c.name: i for i, c in enumerate(self.coordinates)}
        #: per wound, the y index of each of its nuisances (its Objective's z[4:])
        self.maps = [
            [index[c if c == OUTLINE_OFFSET.name else f"{c}[{name}]"] for c in own]
            for name, own in ((n, p.coordinates.names[4:]) for n, p in zip(names, parts))
        ]

    @property
    def size(self) -> int:
        return sum(p.size for p in self.parts)

    @property
    def evaluations(self) -> int:
        return sum(p.evaluations for p in self.parts)

    def z(self, y, k: int) -> np.ndarray:
        """Wound k's coordinates z_k = (ln R0_k, sigma, lambda_k, ln T_k, its nuisances)."""
        ln_r0 = y[3 + k]
        base = [ln_r0, y[1], y[0] / math.exp(ln_r0), y[2] + 2 * ln_r0 - LN4]
        return np.array(base + [y[i] for i in self.maps[k]])

    def theta(self, y, k: int) -> tuple[float, float, float, float]:
        return from_z(self.z(y, k)[:4])

    def residuals(self, y) -> np.ndarray:
        return np.concatenate([p.residuals(self.z(y, k)) for k, p in enumerate(self.parts)])

    def jacobian(self, y, columns=None) -> np.ndarray:
        """dr/dy by the chain rule, every column (`columns` is not used)."""
        blocks = []
        for k, p in enumerate(self.parts):
            z = self.z(y, k)
            a = np.zeros((z.size, self.n))  # d z_k / d y
            a[0, 3 + k] = 1.0
            a[1, 1] = 1.0
            a[2, 0], a[2, 3 + k] = math.exp(-z[0]), -z[2]
            a[3, 2], a[3, 3 + k] = 1.0, 2.0
            for j, i in enumerate(self.maps[k]):
                a[4 + j, i] = 1.0
            blocks.append(p.jacobian(z) @ a)
        return np.vstack(blocks)

    def vanishing(self, y) -> list:
        """l on its bound 0 (relative to the largest R0), where its column is 0 (R depends on
        lambda^2), or on its search limit LAMBDA_MAX outer radii, where every wound has
        reached the viscous limit (Objective.vanishing): R(t) depends on l^2 zeta/G alone
        there and l's column is zeta/G's times a constant."""
        top = LAMBDA_MAX * max(p.outer for p in self.parts) * (1 - 1e-6)
        small = y[0] <= 1e-8 * math.exp(max(y[3 : 3 + len(self.parts)]))
        return [0] if small or y[0] >= top else []

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Each wound's bounds (Objective.bounds) on its R0 and T, carried to y: l from 0 to a
        viscous length of LAMBDA_MAX outer radii, zeta/G over the union of the wounds' T
        ranges; each nuisance within every wound's bounds on it."""
        each = [p.bounds() for p in self.parts]
        z_lo = min(lo[3] + LN4 - 2 * hi[0] for lo, hi in each)
        z_hi = max(hi[3] + LN4 - 2 * lo[0] for lo, hi in each)
        lower = np.array([0.0, -np.inf, z_lo] + [lo[0] for lo, _ in each])
        upper = np.array(
            [LAMBDA_MAX * max(p.outer for p in self.parts), np.inf, z_hi]
            + [hi[0] for _, hi in each]
        )
        lower = np.append(lower, np.full(self.n - lower.size, -np.inf))
        upper = np.append(upper, np.full(self.n - upper.size, np.inf))
        for (lo, hi), mine in zip(each, self.maps):
            for j, i in enumerate(mine):
                lower[i], upper[i] = max(lower[i], lo[4 + j]), min(upper[i], hi[4 + j])
        return lower, upper

    def nuisance_start(self) -> np.ndarray:
        """The nuisances' starting values in y (their coordinates' neutral `start`; a cut in
        the middle of its bounds)."""
        lower, upper = self.bounds()
        out = []
        for i in range(3 + len(self.parts), self.n):
            c = self.coordinates[i]
            v = c.start  # none of them is a log coordinate
            if c.name.startswith(CUT.name):
                v = 0.5 * (lower[i] + upper[i]) if math.isfinite(upper[i]) else lower[i]
            out.append(float(np.clip(v, lower[i], upper[i])))
        return np.array(out)
