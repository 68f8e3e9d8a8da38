"""The benchmark scenario, shared by the peers, the fmpy timing and the charts.

    R_inf = 10, sigma = 1, edge stress 0, lambda in {0.1, 1, 10}
    t in [0, 100], 1000 communication steps of 0.1 (points t = 0.1, 0.2, ..., 100)
    error = max over the communication points of |R - R_exact| / (R_final - R1)
    R1 = 1 + sigma/6,   R_final = 1 + (2 sigma/3) R_inf^2 / (R_inf^2 - 1)

R_exact is `wound_exact.edge` (Laplace-domain solution, ~1e-14). CPU time is
`time.process_time`, best of a few repeats, for the whole scenario including set-up.
"""

from __future__ import annotations

import csv
import sys
import time
from pathlib import Path
from typing import Callable, Iterable, Sequence

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import wound_exact  # noqa: E402

LAMBDAS = (0.1, 1.0, 10.0)
SIGMA, R_INF, T_END = 1.0, 10.0, 100.0
STEP, STEPS = 0.1, 1000
R1 = wound_exact.initial_radius(SIGMA)
AMPLITUDE = wound_exact.final_radius(SIGMA, R_INF) - R1

#: Columns of every work-precision CSV (the Rust one and the peers').
WORK_COLUMNS = ("scheme", "lambda", "resolution", "unknowns", "error", "cpu_seconds")


def lam_label(lam: float) -> str:
    """0.1 -> '0.1', 1.0 -> '1', 10.0 -> '10' (file names and the CSVs' lambda column)."""
    return f"{lam:g}"


def times() -> np.ndarray:
    """The 1000 communication points 0.1, 0.2, ..., 100 (t = 0 excluded: R(0) = R1 exactly)."""
    return np.arange(1, STEPS + 1) * STEP


_REFERENCE: dict[float, np.ndarray] = {}


def reference(lam: float) -> np.ndarray:
    """Exact R at `times()` (cached: computing it is not part of any timed run)."""
    if lam not in _REFERENCE:
        _REFERENCE[lam] = wound_exact.edge(lam, SIGMA, R_INF, times())[0]
    return _REFERENCE[lam]


def error(lam: float, radius: np.ndarray) -> float:
    """max_t |R - R_exact| / (R_final - R1); nan/inf (a blown-up run) count as inf."""
    err = np.abs(np.asarray(radius, dtype=float) - reference(lam)) / AMPLITUDE
    return float(err.max()) if np.all(np.isfinite(err)) else float("inf")


def best_cpu(
    run: Callable[[], np.ndarray], repeats: int, budget: float = 5.0
) -> tuple[float, np.ndarray]:
    """Best CPU time of `repeats` calls of `run` (fewer once `budget` CPU seconds are spent).

    Returns (seconds, the last result). One call always happens.
    """
    best, spent, result = float("inf"), 0.0, None
    for _ in range(max(repeats, 1)):
        start = time.process_time()
        result = run()
        elapsed = time.process_time() - start
        best, spent = min(best, elapsed), spent + elapsed
        if spent > budget:
            break
    return best, result


def sweep_sizes(
    scheme: str,
    lam: float,
    sizes: Sequence[int],
    setting: str,
    run: Callable[[int], np.ndarray],
    repeats: int,
    slow_run: float,
    log=print,
) -> list[tuple]:
    """Work-precision rows of `run(n)` (-> R at `times()`) for the grid sizes in ascending
    order, stopping after the first run slower than `slow_run` CPU seconds."""
    rows = []
    for n in sizes:
        cpu, radius = best_cpu(lambda: run(n), repeats)
        err = error(lam, radius)
        rows.append((scheme, lam_label(lam), f"N={n} {setting}", n, err, cpu))
        log(
            f"{scheme:13s} lambda={lam:<4g} N={n:<6d} {setting:<11s} error={err:.2e} "
            f"cpu={cpu:.3g} s"
        )
        if cpu > slow_run:
            break
    return rows


def observed_orders(rows: Sequence[tuple]) -> list[tuple[str, str, str, int, int, float]]:
    """(scheme, lambda, setting, N1, N2, order) for consecutive grid sizes of `sweep_sizes`
    rows that share scheme, lambda and setting, against the spacing dr ~ 1 / (N - 1):

        order = log(e1 / e2) / log((N2 - 1) / (N1 - 1))
    """
    out = []
    for a, b in zip(rows, rows[1:]):
        setting_a, setting_b = a[2].split(" ", 1)[1], b[2].split(" ", 1)[1]
        if a[:2] == b[:2] and setting_a == setting_b and 0 < b[4] < float("inf"):
            order = np.log(a[4] / b[4]) / np.log((b[3] - 1) / (a[3] - 1))
            out.append((a[0], a[1], setting_a, a[3], b[3], float(order)))
    return out


def write_reference(out: Path) -> list[Path]:
    """out/reference_{lam}.csv: rows `t,R` (no header) at the 1000 communication points."""
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for lam in LAMBDAS:
        path = out / f"reference_{lam_label(lam)}.csv"
        np.savetxt(path, np.column_stack([times(), reference(lam)]), delimiter=",", fmt="%.17g")
        paths.append(path)
    return paths


def write_rows(path: Path, columns: Sequence[str], rows: Iterable[Sequence]) -> None:
    """A CSV with a header; floats with 6 significant digits unless they are exact labels."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as f:
        out = csv.writer(f)
        out.writerow(columns)
        for row in rows:
            out.writerow([f"{x:.6g}" if isinstance(x, float) else x for x in row])


def read_rows(path: Path) -> list[dict[str, str]]:
    """A headed CSV as a list of dicts (empty if the file does not exist)."""
    if not path.exists():
        return []
    with path.open(newline="") as f:
        return list(csv.DictReader(f))
