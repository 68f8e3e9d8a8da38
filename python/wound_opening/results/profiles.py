"""One parameter's (or derived value's) profile likelihood, as the interval walker
(fitting/intervals.py) leaves it."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Profile:
    """One parameter's profile: the interval ends (in the parameter's own units; None where
    the search limit was reached), whether lambda's lower end is its bound, and the points."""

    lower: float | None
    upper: float | None
    at_bound: bool
    points: list = field(default_factory=list)  # (value, delta chi^2), value in its own units
    #: (lower, upper): the end is a bound the user set, not a rise of the profile.
    bounded: tuple = (False, False)
