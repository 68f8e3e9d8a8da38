"""One parameter's (or derived value's) profile likelihood, as the interval walker
(fitting/intervals.py) leaves it."""

from __future__ import annotations

from dataclasses import dataclass, field, replace


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
    #: The delta chi^2 threshold of its 95 % interval where it is not the fit's (a bound
    #: nearby: fitting/bounds.py); None: the fit's `threshold`.
    threshold: float | None = None
    #: Why its interval is not vouched for ("" when it is): a warning of the readers on the
    #: data themselves (DOUBT), which biases the value by more than the interval shows.
    doubt: str = ""

    @property
    def identifies(self) -> bool:
        """Both interval ends set by the data (a rise of the profile by the threshold): an
        interval reaching lambda's bound 0 does not identify it (it only bounds it above),
        nor does an end on a bound the user set, nor an interval the data's own warning
        doubts (`doubt`)."""
        return (
            self.lower is not None
            and self.upper is not None
            and not self.at_bound
            and not any(self.bounded)
            and not self.doubt
        )


#: Profile.doubt of a fit whose radius series carries a reader's warning (inputs/fiji.py:
#: outlines that are not round). On the rendered movies of docs/fitting.md ("Coverage on
#: rendered movies") such outlines sat 0.2-1 um outside the edge, by an amount that follows
#: the cells the threshold took in, and with the field those four fits reported four values
#: identified that missed the truth (of five such misses in twenty draws): their intervals
#: are kept, none is said to identify.
DOUBT = (
    "not vouched for: the outlines are not round (their warning), so the radius is not the "
    "edge's and the value is biased by more than its interval shows"
)


def doubted(profiles: dict, doubts) -> dict:
    """`profiles` (name -> Profile or None), each with DOUBT where the readers doubted the
    data (`doubts`: their warnings), else as they are; a value held fixed (an interval of
    one point) stays as the caller gave it."""
    if not doubts:
        return profiles
    return {
        k: p
        if p is None or (p.lower is not None and p.lower == p.upper)
        else replace(p, doubt=DOUBT)
        for k, p in profiles.items()
    }


def own_thresholds(profiles: dict) -> dict:
    """name -> the threshold of a profile that has its own (lambda's bound nearby)."""
    return {
        name: p.threshold
        for name, p in profiles.items()
        if p is not None and getattr(p, "threshold", None) is not None
    }


def threshold_line(threshold: float, profiles: dict) -> str | None:
    """The summary's line on the thresholds of delta chi^2 where some differ from the fit's."""
    own = own_thresholds(profiles)
    if not own:
        return None
    return (
        f"95 % thresholds of delta chi^2: {threshold:.3g}, except "
        + ", ".join(f"{k} {v:.3g}" for k, v in own.items())
        + " (lambda's bound 0 within reach: fitting/bounds.py, docs/fitting.md)"
    )
