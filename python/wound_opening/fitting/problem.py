"""The protocol every objective of a fit implements, so that the local fit, the interval
walker and the starts treat one wound (objective.Objective), the user's constraints
(parameters.Constrained), a reparametrisation for a derived value (derived.Reparametrised)
and several wounds (wounds.Tissue, wound_profiles.EtaCoordinate) alike.

A problem maps coordinates z (a vector of `len(bounds()[0])` numbers) to weighted residuals
(model - data) / uncertainty, `size` of them, with their Jacobian d residuals / d z. A problem
the user constrains declares its `coordinates` by name (parameters.py).
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Protocol

import numpy as np

#: No coordinate held: the default of `Problem.fixed` (read-only, shared).
NOTHING_HELD = MappingProxyType({})


class Problem(Protocol):
    """Residuals, Jacobian, bounds, the coordinates held fixed and the number of residuals.
    Subclass it to inherit the defaults: nothing held, no bound of the user's."""

    #: Coordinates held at values (index -> value in z): the user's fixed parameters.
    fixed = NOTHING_HELD
    #: Coordinates whose bounds the user set (parameters.Constrained); a reparametrisation
    #: prefers to replace another one.
    user_bounded = frozenset()
    #: Coordinates that are lambda (>= 0): local.local_fit moves asinh of them, in which the
    #: valley along lambda^2 T = const (ln T = const - 2 ln lambda) is straight for lambda >> 1.
    stretched = ()
    #: The problem's coordinates by name (coordinates.Coordinates), where the user names them.
    coordinates = None
    #: (to z, from z, plain) where the problem's coordinates map to one wound's four
    #: parameters z = (ln R0, sigma, lambda, ln T) (valleys.py looks for other branches of
    #: the wound's model there; plain: they are z themselves), else None (several wounds).
    wound_maps = None

    @property
    def size(self) -> int:
        """The number of residuals."""
        ...

    def residuals(self, z) -> np.ndarray:
        """(model - data) / uncertainty at z, `size` of them."""
        ...

    def jacobian(self, z, columns=None) -> np.ndarray:
        """d residuals / d z; with `columns` (indices of z) only those columns are needed
        (a problem may leave the others 0: a profile fit holds one coordinate fixed)."""
        ...

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Lower and upper bounds of z (possibly infinite)."""
        ...

    def vanishing(self, z) -> list:
        """The coordinates whose Jacobian column vanishes at z (lambda, or the viscous length,
        on its bound 0: the model depends on its square): the verdict judges the others."""
        return []

    def user_bound(self, i: int, side: int) -> bool:
        """Whether the limit of coordinate i on `side` (-1 lower, +1 upper) is the user's
        (an interval ending there ends at a bound the user set, not at a rise)."""
        return False
