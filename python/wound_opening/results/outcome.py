"""What every fit returns beside its estimates, one wound's (result.FitResult) or several's
(wounds.TissueFitResult): the verdict, chi^2 and its test, the thresholds of the intervals,
the warnings, G for the absolute values, the recording's settings and the figures drawn."""

from __future__ import annotations

import json
from dataclasses import dataclass, field

#: The chi^2 test of a fit with the noise given: a p-value below CHI2_FAIL_P says the model
#: does not describe the data (the fit fails: fitting/stages.py), one below CHI2_WARN_P
#: is a warning. (The residual runs' own thresholds: fitting/gof.py, RUNS_FAIL_P.)
CHI2_FAIL_P, CHI2_WARN_P = 1e-6, 1e-3


def chi2_warning(result) -> list:
    """A converged fit whose chi^2 p-value (noise given) is below CHI2_WARN_P."""
    if result.converged and result.p_value is not None and result.p_value < CHI2_WARN_P:
        return [
            f"chi^2 / dof = {result.chi2 / result.dof:.3g} (p = {result.p_value:.2g}): the model "
            f"describes the "
            "data worse than the given noise allows"
        ]
    return []


def outlier_warning(outliers: dict, loss: str) -> list:
    """The points a robust loss flagged (fitting._outliers: rows, and "where" each is)."""
    n_out = len(outliers.get("radius", [])) + len(outliers.get("profile", []))
    if not n_out:
        return []
    return [
        f"{n_out} points down-weighted by the {loss} loss (|residual| > 3 noise): "
        + "; ".join(outliers.get("where", []))
    ]


#: The verdict's fields that FitResult and TissueFitResult report first in to_dict().
VERDICT = (
    "converged",
    "reasons",
    "warnings",
    "optimizer",
    "chi2",
    "dof",
    "p_value",
    "noise_given",
    "loss",
    "residual_runs",
)


def verdict_fields(result) -> dict:
    return {name: getattr(result, name) for name in VERDICT}


@dataclass(kw_only=True)
class Outcome:
    """The fields every fit result has (module docstring); FitResult and TissueFitResult add
    their estimates, intervals and data."""

    chi2: float
    threshold: float
    dof: int = 0
    p_value: float | None = None
    noise_given: bool = False
    loss: str = "linear"
    converged: bool = True
    reasons: list = field(default_factory=list)
    optimizer: dict = field(default_factory=dict)
    evaluations: int = 0
    #: The fitted time scale against the sampling, the recording (fitting/plausibility.py).
    plausibility: list = field(default_factory=list)
    #: The runs and Durbin-Watson tests of each series' residuals (fitting/gof.py): dicts
    #: with "series", "runs", "expected", "points", "p_runs", "durbin_watson",
    #: "p_durbin_watson", "p_value" (the smaller times 2), "level" (ok, warn, fail).
    residual_runs: list = field(default_factory=list)
    #: What the readers found doubtful in the data themselves (inputs/fiji.py: outlines that
    #: are not round), also among the warnings: the status is amber (results/status.py).
    doubts: list = field(default_factory=list)
    #: G [Pa] given for the absolute material values: (value, 0) fixed or (mean, sd) a prior.
    G: tuple | None = None
    #: The recording's settings (settings.py): cut, units, pixel size, frames, files; filled
    #: by the command line (or a reader), printed by the report.
    settings: dict = field(default_factory=dict)
    #: The figures drawn (plots.drawn_once): key -> (figure, PNG bytes).
    figures: dict = field(default_factory=dict, repr=False, compare=False)

    def to_json(self, **kwargs) -> str:
        return json.dumps(self.to_dict(), **({"indent": 2} | kwargs))
