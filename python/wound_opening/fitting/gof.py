"""Systematic residuals: a runs test on the signs of each series' residuals and the
Durbin-Watson test of their serial correlation.

A model that describes the data leaves residuals that are independent noise; a model that
cannot (a wrong fixed value, a closing wound, a wrong outer radius) leaves long stretches of
one sign. chi^2 sees the second only when the noise is given: with the noise estimated from
the residuals it absorbs the misfit into the noise (`--fix R0_um=10.5` on data with
R0 = 10: estimated noise 0.12 um against 0.025, every interval "identified" and wrong).

Runs test (Wald-Wolfowitz), per series: the radii ordered in time; the PIV vectors ordered
by distance within each time (a run never crosses two times). With n1 residuals > 0 and n2
< 0 in a sequence (zeros left out), independent noise makes every order of the signs
equally likely, and the number of runs R (maximal blocks of one sign) has the exact law

    P(R = 2k)     = 2 C(n1-1, k-1) C(n2-1, k-1) / C(n1+n2, n1)
    P(R = 2k + 1) = [C(n1-1, k-1) C(n2-1, k) + C(n1-1, k) C(n2-1, k-1)] / C(n1+n2, n1)

(mean 1 + 2 n1 n2 / n). The runs of a series of several sequences (the PIV times) are the
sum of independent such counts: its law is the convolution. Too few runs is the alarm:
p = P(R <= observed), exact, so a short series cannot produce a small p by chance (with 6
points p >= 0.1). The signs ignore the residuals' size: an outlier a robust loss
down-weights counts as one sign, and the test needs no noise level (it applies whether the
noise is given or estimated, in addition to chi^2 where it is given).

The residuals of a fit are not exactly independent (4 parameters fitted to n points);
docs/fitting.md gives the false-alarm rate measured on correct fits of exact-solution data
and the detection rate on the wrong-R0 case.

The signs lose the residuals' size; the Durbin-Watson statistic d = sum (e_i - e_{i-1})^2 /
sum e_i^2 (differences within each sequence; 2 for independent noise, 0 for a smooth
misfit) keeps it. For independent Gaussian noise d <= d0 is Q = e^T (A - d0 I) e <= 0 with A
the second-difference form of the sequences, whose eigenvalues are 2 - 2 cos(pi j / m),
j = 0 .. m - 1, for a sequence of m points: Q = sum_j mu_j Z_j^2, mu_j = those minus d0,
and P(Q <= 0) is the Lugannani-Rice saddlepoint approximation with the cumulant generating
function K(s) = -1/2 sum log(1 - 2 s mu_j) (relative error below 5 % at p = 6e-4 against
a Monte Carlo of 40 points). The residuals of a fit lose the directions of the Jacobian's
columns, which are smooth in time (low eigenvalues of A): that makes d larger, so this p is
conservative for them. Each series' p-value is the smaller of the two tests' times 2
(Bonferroni). A series with p < RUNS_FAIL_P makes the fit fail, one with p < RUNS_WARN_P gives a
warning.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize
from scipy.special import gammaln, ndtr

#: The residual runs test of a series (Bonferroni over its two tests): a p-value below
#: RUNS_FAIL_P makes the fit fail, one below RUNS_WARN_P is a warning. (The chi^2 test's
#: own thresholds: results/outcome.py, CHI2_FAIL_P.)
RUNS_FAIL_P, RUNS_WARN_P = 1e-4, 1e-3
CAUSES = (
    "the model cannot describe this series: a wrong fixed value (--fix), a wound that closes "
    "again, a wrong outer radius or a wrong time of the cut"
)


def _log_comb(n, k):
    n, k = np.asarray(n, float), np.asarray(k, float)
    ok = (k >= 0) & (k <= n)
    with np.errstate(invalid="ignore"):
        out = gammaln(n + 1) - gammaln(k + 1) - gammaln(np.maximum(n - k, 0) + 1)
    return np.where(ok, out, -np.inf)


def runs_law(n1: int, n2: int) -> np.ndarray:
    """P(R = r), r = 0 .. n1 + n2, for n1 signs of one kind and n2 of the other in random
    order (module docstring)."""
    n = n1 + n2
    p = np.zeros(n + 1)
    if n1 == 0 or n2 == 0:
        p[min(n, 1)] = 1.0
        return p
    total = _log_comb(n, n1)
    r = np.arange(2, n + 1)
    k = r // 2
    even = np.log(2.0) + _log_comb(n1 - 1, k - 1) + _log_comb(n2 - 1, k - 1)
    odd = np.logaddexp(
        _log_comb(n1 - 1, k - 1) + _log_comb(n2 - 1, k),
        _log_comb(n1 - 1, k) + _log_comb(n2 - 1, k - 1),
    )
    p[2:] = np.exp(np.where(r % 2 == 0, even, odd) - total)
    return p / p.sum()


def durbin_watson_p(d0: float, lengths) -> float:
    """P(d <= d0) for independent Gaussian noise in sequences of `lengths` points (module
    docstring: saddlepoint approximation)."""
    mu = np.concatenate([2 - 2 * np.cos(np.pi * np.arange(m) / m) for m in lengths]) - d0
    if mu.max() <= 0:
        return 1.0
    if mu.min() >= 0:
        return 0.0
    lo, hi = 1 / (2 * mu.min()), 1 / (2 * mu.max())
    s = optimize.brentq(
        lambda s: float(np.sum(mu / (1 - 2 * s * mu))),
        lo * (1 - 1e-12),
        hi * (1 - 1e-12),
        xtol=1e-15,
    )
    k = -0.5 * float(np.sum(np.log1p(-2 * s * mu)))
    k2 = float(np.sum(2 * mu**2 / (1 - 2 * s * mu) ** 2))
    if abs(s) * np.sqrt(k2) < 1e-6:  # the mean: the normal approximation
        return float(ndtr(-float(np.sum(mu)) / np.sqrt(2 * np.sum(mu**2))))
    w = np.sign(s) * np.sqrt(max(-2 * k, 0.0))
    u = s * np.sqrt(k2)
    p = ndtr(w) + np.exp(-0.5 * w * w) / np.sqrt(2 * np.pi) * (1 / w - 1 / u)
    return float(np.clip(p, 0.0, 1.0))


@dataclass(frozen=True)
class Runs:
    """The tests of one series: runs observed and expected, points, the runs test's
    P(R <= runs), the Durbin-Watson statistic and its P(d <= observed), and the series'
    p-value (the smaller times 2)."""

    series: str
    runs: int
    expected: float
    points: int
    p_runs: float
    durbin_watson: float
    p_durbin_watson: float

    @property
    def p_value(self) -> float:
        return min(1.0, 2 * min(self.p_runs, self.p_durbin_watson))

    def text(self) -> str:
        return (
            f"{self.series}: {self.runs} runs of residual signs where {self.expected:.1f} are "
            f"expected ({self.points} points, runs test p = {self.p_runs:.2g}), Durbin-Watson "
            f"{self.durbin_watson:.2f} where 2 is expected (p = {self.p_durbin_watson:.2g}): "
            "systematic residuals"
        )


def runs_test(series: str, sequences) -> Runs | None:
    """The runs test over `sequences` (residuals, each in its order); None with fewer than
    two signs of each kind in all."""
    law, runs, expected, num, den = np.ones(1), 0, 0.0, 0.0, 0.0
    pos = neg = 0
    lengths = []
    for e in sequences:
        e = np.asarray(e, float)
        lengths.append(e.size)
        s = np.sign(e[e != 0])
        if s.size == 0:
            continue
        n1, n2 = int(np.sum(s > 0)), int(np.sum(s < 0))
        runs += 1 + int(np.sum(s[1:] != s[:-1]))
        expected += 1 + 2 * n1 * n2 / s.size
        pos, neg = pos + n1, neg + n2
        law = np.convolve(law, runs_law(n1, n2))
        num += float(np.sum(np.diff(e) ** 2))
        den += float(np.sum(e**2))
    if min(pos, neg) < 2:
        return None
    p = float(min(np.sum(law[: runs + 1]), 1.0))
    d = num / den if den > 0 else 2.0
    return Runs(series, runs, expected, pos + neg, p, d, durbin_watson_p(d, lengths))


#: A series whose residuals are below this fraction of the noise given (rms), or below
#: RESOLVED of its data's range in size, is not tested: its pattern is then that of the
#: solver's own error (exact data) or of a misfit far inside the noise, not a misfit the
#: data show.
NEGLIGIBLE, RESOLVED = 0.1, 1e-8


def _resolved(obj, k: int, normalised: np.ndarray, data: np.ndarray) -> bool:
    """Whether series k (0 radius, 1 profile) of `obj` has residuals a pattern test can read:
    not below NEGLIGIBLE of a given noise, nor RESOLVED of the data's range."""
    if normalised.size == 0:
        return False
    sd = obj.split(obj.sd)[k]
    size = float(np.sqrt(np.mean((normalised * sd) ** 2)))
    span = float(np.ptp(data)) if k == 0 else float(np.max(np.abs(data)))
    if size <= RESOLVED * span:
        return False
    return obj.estimated[k] or float(np.sqrt(np.mean(normalised**2))) >= NEGLIGIBLE


def series_tests(obj, residuals, prefix: str = "") -> list[Runs]:
    """Runs tests of an Objective's series at its `residuals` (objective.py order): the radius
    in time, the PIV profile by distance within each time; a series whose residuals are not
    resolved (`_resolved`) is left out."""
    radius, profile = obj.split(np.asarray(residuals, float))
    velocities = obj.split(obj.data())[1]
    out = [runs_test(f"{prefix}radius", [radius])] if _resolved(obj, 0, radius, obj.radius) else []
    if obj.groups and _resolved(obj, 1, profile, velocities):
        pieces, start = [], 0
        for _, r, _, _ in obj.groups:
            part = profile[start : start + r.size]
            pieces.append(part[np.argsort(r, kind="stable")])
            start += r.size
        out.append(runs_test(f"{prefix}PIV profile", pieces))
    return [t for t in out if t is not None]


def level(t: Runs) -> str:
    return "fail" if t.p_value < RUNS_FAIL_P else ("warn" if t.p_value < RUNS_WARN_P else "ok")


def as_dicts(tests) -> list[dict]:
    """The tests as the result reports them (FitResult.residual_runs)."""
    return [
        {
            "series": t.series,
            "runs": t.runs,
            "expected": t.expected,
            "points": t.points,
            "p_runs": t.p_runs,
            "durbin_watson": t.durbin_watson,
            "p_durbin_watson": t.p_durbin_watson,
            "p_value": t.p_value,
            "level": level(t),
        }
        for t in tests
    ]


def judge_series(tests) -> tuple[list[str], list[str]]:
    """(reasons the fit fails, warnings) from runs tests."""
    said = {k: [f"{t.text()}; {CAUSES}" for t in tests if level(t) == k] for k in ("fail", "warn")}
    return said["fail"], said["warn"]
