"""The profile likelihoods of a several-wound fit (fit_wounds, wounds.py): the shared viscous
length l, tension/G and zeta/G, each wound's R0, and eta/G = l^2 zeta/G / 4 walked in its
own coordinate (EtaCoordinate). Each is an Optimum's profile (optimum.py), as a single
wound's parameters are."""

from __future__ import annotations

import math

import numpy as np

from ..results.names import ETA, SHARED
from ..results.profiles import Profile
from .objective import LAMBDA_MAX
from .optimum import Optimum, Target
from .parameters import Coordinate, Coordinates, factor
from .problem import Problem

LN4 = math.log(4.0)


class EtaCoordinate(Problem):
    """The tissue objective with w_2 = ln eta/G = ln zeta/G + 2 ln l - ln 4 in place of
    ln zeta/G (for its profile; needs l > 0)."""

    def __init__(self, tissue: Problem):  # wounds.Tissue
        self.tissue = tissue
        # the user's fixed coordinates other than l and zeta/G are the same in w
        self.fixed = {i: v for i, v in tissue.fixed.items() if i not in (0, 2)}
        own = Coordinate(ETA, "s", log=True, lower=0.0, window=factor(1e2), step=0.1)
        self.coordinates = Coordinates(
            tuple(own if i == 2 else c for i, c in enumerate(tissue.coordinates))
        )

    @property
    def size(self) -> int:
        return self.tissue.size

    @staticmethod
    def to_y(w):
        y = np.array(w, dtype=float)
        y[2] = w[2] - 2 * math.log(max(w[0], 1e-300)) + LN4
        return y

    @staticmethod
    def to_w(y):
        w = np.array(y, dtype=float)
        w[2] = y[2] + 2 * math.log(y[0]) - LN4
        return w

    def from_w(self, w):
        """The tissue's y of w (optimum.profile maps a walk's point back with it)."""
        return self.to_y(w)

    @staticmethod
    def gradient(y) -> np.ndarray:
        """d w_2 / d y."""
        g = np.zeros(y.size)
        g[0], g[2] = 2 / y[0], 1.0
        return g

    def residuals(self, w):
        return self.tissue.residuals(self.to_y(w))

    def jacobian(self, w, columns=None):
        """dr/dw by the chain rule, every column (`columns` is not used)."""
        dy = np.eye(len(w))
        dy[2, 0] = -2 / w[0]
        return self.tissue.jacobian(self.to_y(w)) @ dy

    def bounds(self):
        lower, upper = self.tissue.bounds()
        lower[0] = 1e-9 * upper[0]
        lower[2], upper[2] = -np.inf, np.inf
        return lower, upper


def shared_profiles(optimum: Optimum) -> dict:
    """Profiles of l, sigma, zeta/G, eta/G and each R0_k (keyed ("R0_um", k)), each walked
    by `optimum.profile` within its coordinate's window (wounds.tissue_coordinates: l from 0
    to LAMBDA_MAX times the largest R0, where an interval reaching 0 is closed but does not
    identify l, as lambda's; sigma within 10 |sigma| + 1, zeta/G within a factor 100, R0
    within a factor 3). A coordinate the user holds fixed is its value; eta/G with l or
    zeta/G fixed is the other one's profile carried over."""
    tissue = optimum.problem
    out = {}
    for i in range(3 + wound_count(tissue)):  # the nuisances after them: not profiled
        out[SHARED[i] if i < 3 else ("R0_um", i - 3)] = optimum.profile(Target(i))
    out[ETA] = _eta_profile(optimum, out)
    return out


def _eta_profile(optimum: Optimum, walked: dict) -> Profile:
    """eta/G = l^2 zeta/G / 4: walked in its own coordinate (EtaCoordinate), or, with l or
    zeta/G held fixed, the other one's profile carried over (eta/G is monotonic in it)."""
    tissue, y_hat = optimum.problem, optimum.z
    fixed = tissue.fixed
    zg, l_hat = math.exp(y_hat[2]), y_hat[0]
    if 0 in fixed and 2 in fixed:
        v = l_hat**2 * zg / 4
        return Profile(v, v, False, [(v, 0.0)])
    if 0 in fixed:  # eta/G = (l^2 / 4) zeta/G
        return _scaled(walked[SHARED[2]], lambda v: l_hat**2 / 4 * v)
    if 2 in fixed:  # eta/G = (zeta/G / 4) l^2, l >= 0
        return _scaled(walked[SHARED[0]], lambda v: zg * v * v / 4)
    l_max = LAMBDA_MAX * math.exp(max(y_hat[3 : 3 + wound_count(tissue)]))
    if any(c[0] <= 1e-8 * l_max for c, _ in optimum.centres(optimum.threshold)):
        return Profile(0.0, None, True)  # eta/G = 0 is allowed: not identified
    rep = EtaCoordinate(tissue)
    return optimum.profile(Target(2, rep))


def wound_count(tissue) -> int:
    """The wounds of a tissue problem: its R0_um[NAME] coordinates (after the shared three)."""
    return sum(1 for c in tissue.coordinates if c.name.startswith("R0_um["))


def _scaled(p: Profile, f) -> Profile:
    """The profile of f(value), f increasing in the value (>= 0)."""
    return Profile(
        None if p.lower is None else f(p.lower),
        None if p.upper is None else f(p.upper),
        p.at_bound,
        sorted((f(v), d) for v, d in p.points),
        p.bounded,
    )
