"""docs/benchmarks.md: the numbers behind the charts, generated (never edited by hand).

Definitions used in the tables:

* the default method is the scheme `modal`; "at 1e-9" is its cheapest run whose error is
  <= 1e-9;
* a method's "best" run is its cheapest run whose error is within 10 % of the lowest error
  it reached (so a run that buys its last digit of accuracy at twice the cost does not
  stand for the method);
* the speed-up at equal accuracy is that run's CPU time over the CPU time of the cheapest
  `modal` run whose error is <= that run's error.
"""

from __future__ import annotations

import datetime
import math
import platform
from pathlib import Path

from bench import common
from bench.work_chart import STYLE

DEFAULT, TARGET_ERROR, BEST_SLACK = "modal", 1e-9, 1.10


def _num(row: dict, key: str) -> float:
    return float(row[key])


def cheapest(rows: list[dict], max_error: float) -> dict | None:
    ok = [r for r in rows if _num(r, "error") <= max_error]
    return min(ok, key=lambda r: _num(r, "cpu_seconds")) if ok else None


def best(rows: list[dict]) -> dict | None:
    finite = [r for r in rows if math.isfinite(_num(r, "error"))]
    if not finite:
        return None
    return cheapest(finite, min(_num(r, "error") for r in finite) * BEST_SLACK)


def cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def fmt_s(seconds: float) -> str:
    """CPU time with a unit that keeps three significant digits readable."""
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6), ("ns", 1e-9)):
        if seconds >= scale:
            return f"{seconds / scale:.3g} {unit}"
    return f"{seconds:.3g} s"


def regime_table(lam: str, rows: list[dict]) -> list[str]:
    ours = [r for r in rows if r["scheme"] == DEFAULT and r["lambda"] == lam]
    out = [
        "| method | best error | its CPU time (setting) | default at that error (setting) | "
        "speed-up |",
        "|---|---|---|---|---|",
    ]
    for scheme in dict.fromkeys(r["scheme"] for r in rows):
        if scheme == DEFAULT:
            continue
        top = best([r for r in rows if r["scheme"] == scheme and r["lambda"] == lam])
        if top is None:
            ran = any(r["scheme"] == scheme and r["lambda"] == lam for r in rows)
            out.append(
                f"| {STYLE.get(scheme, (scheme,))[0]} | "
                f"{'every run blew up' if ran else 'no run'} | | | |"
            )
            continue
        match = cheapest(ours, _num(top, "error"))
        ratio = f"{_num(top, 'cpu_seconds') / _num(match, 'cpu_seconds'):,.0f}x" if match else "n/a"
        where = f"{fmt_s(_num(match, 'cpu_seconds'))} ({match['resolution']})" if match else "n/a"
        out.append(
            f"| {STYLE.get(scheme, (scheme,))[0]} | {_num(top, 'error'):.2e} | "
            f"{fmt_s(_num(top, 'cpu_seconds'))} ({top['resolution']}) | {where} | {ratio} |"
        )
    return out


def targets(rows: list[dict], step_cost: list[dict]) -> list[str]:
    out = [
        "| lambda | default tolerance (tol=1e-9): CPU, error | cheapest default run with error <= "
        "1e-9: "
        "CPU (setting, unknowns, error) | < 1 ms | SciPy peer's best accuracy: run, and how much "
        "faster "
        "the default is there (>= 1000x) |",
        "|---|---|---|---|---|",
    ]
    for lam in map(common.lam_label, common.LAMBDAS):
        ours = [r for r in rows if r["scheme"] == DEFAULT and r["lambda"] == lam]
        at_tol = next((r for r in ours if r["resolution"] == "tol=1e-9"), None)
        at_tol = (
            f"{fmt_s(_num(at_tol, 'cpu_seconds'))}, {_num(at_tol, 'error'):.1e}"
            if at_tol
            else "no run"
        )
        hit = cheapest(ours, TARGET_ERROR)
        scipy = best([r for r in rows if r["scheme"].startswith("scipy_") and r["lambda"] == lam])
        if hit is None:
            out.append(f"| {lam} | {at_tol} | not reached | NO | |")
            continue
        cpu = _num(hit, "cpu_seconds")
        vs = "no SciPy data"
        if scipy is not None:
            match = cheapest(ours, _num(scipy, "error"))
            ratio = _num(scipy, "cpu_seconds") / _num(match, "cpu_seconds")
            vs = (
                f"{scipy['scheme']} {scipy['resolution']}: error {_num(scipy, 'error'):.2e} in "
                f"{fmt_s(_num(scipy, 'cpu_seconds'))}; default "
                f"{fmt_s(_num(match, 'cpu_seconds'))}: "
                f"{ratio:,.0f}x {'yes' if ratio >= 1000 else 'NO'}"
            )
        out.append(
            f"| {lam} | {at_tol} | {fmt_s(cpu)} ({hit['resolution']}, {hit['unknowns']}, "
            f"{_num(hit, 'error'):.1e}) | {'yes' if cpu < 1e-3 else 'NO'} | {vs} |"
        )
    per_step = {r["what"]: _num(r, "seconds") for r in step_cost}
    step = per_step.get("modal_doStep_getReal_in_process")
    if step is not None:
        out += [
            "",
            f"Per step in-process (`modal_doStep_getReal_in_process`, step_cost.csv): "
            f"{fmt_s(step)}: "
            f"under 1 us: {'yes' if step < 1e-6 else 'NO'}.",
        ]
    return out


def step_table(step_cost: list[dict], fmpy: list[dict]) -> list[str]:
    out = ["| what | lambda | CPU time |", "|---|---|---|"]
    out += [
        f"| {r['what']} (Rust, in-process) | | {fmt_s(_num(r, 'seconds'))} |" for r in step_cost
    ]
    out += [
        f"| {r['what']} (Python, fmpy FMU2Slave) | {r['lambda']} | {fmt_s(_num(r, 'seconds'))} |"
        for r in fmpy
    ]
    return out


def fresh_table(fresh: list[dict]) -> list[str]:
    """What a fresh parameter set costs against one step (examples/fresh_cost.rs)."""
    meaning = {
        "step": "`fmi2DoStep` + `fmi2GetReal` of both outputs",
        "step_without_guard": "the same through the safe `Instance` API (the difference is the C "
        "boundary's guard)",
        "fresh_instance": "`fmi2Instantiate`, a new lambda, initialization, `fmi2GetReal`, "
        "`fmi2FreeInstance`",
        "reset_new_lambda": "`fmi2Reset`, a new lambda, initialization, `fmi2GetReal`",
        "fresh_outer_radius": "a new instance at a new R_inf (cache miss: assembly and "
        "decomposition, 49 unknowns)",
    }
    out = ["| what | CPU time | in steps |", "|---|---|---|"]
    out += [
        f"| {meaning.get(r['what'], r['what'])} | {fmt_s(_num(r, 'seconds'))} | "
        f"{_num(r, 'steps'):,.1f} |"
        for r in fresh
    ]
    return out


def stability_lines(stability: list[dict], limits: list[dict]) -> list[str]:
    out = ["| scheme | grid | bounded | oscillating | unbounded |", "|---|---|---|---|---|"]
    for key in dict.fromkeys((r["scheme"], r["points"]) for r in stability):
        mine = [r["status"] for r in stability if (r["scheme"], r["points"]) == key]
        grid = "default mesh" if key[1] == "0" else f"{key[1]} points"
        out.append(
            f"| {key[0]} | {grid} | "
            + " | ".join(str(mine.count(s)) for s in ("bounded", "oscillating", "unbounded"))
            + " |"
        )
    if limits:
        out += [
            "",
            "Explicit scheme, measured against theory (relative difference):",
            "",
            "| N | lambda | dt_max theory | dt_max measured | diff | lambda_max theory | measured "
            "| diff |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for r in limits:
            dt_t, dt_m = _num(r, "dt_max_theory"), _num(r, "dt_max_measured")
            l_t, l_m = _num(r, "lambda_max_theory"), _num(r, "lambda_max_measured")
            out.append(
                f"| {r['points']} | {_num(r, 'lambda'):.4g} | {dt_t:.4g} | {dt_m:.4g} | "
                f"{(dt_m - dt_t) / dt_t:+.1%} | {l_t:.4g} | {l_m:.4g} | {(l_m - l_t) / l_t:+.1%} |"
            )
    return out


def peer_orders(rows: list[dict]) -> list[str]:
    """Observed orders of each peer along its grid sizes, at the setting of its best run."""
    peers = [r for r in rows if r["scheme"].startswith("scipy_") or r["scheme"] == "paper_peer"]
    as_tuples = [
        (
            r["scheme"],
            r["lambda"],
            r["resolution"],
            int(r["unknowns"]),
            _num(r, "error"),
            _num(r, "cpu_seconds"),
        )
        for r in peers
    ]
    orders = common.observed_orders(as_tuples)
    out = [
        "| peer | lambda | setting | N | observed orders between successive N |",
        "|---|---|---|---|---|",
    ]
    for scheme, lam in dict.fromkeys((r["scheme"], r["lambda"]) for r in peers):
        finite = [
            r
            for r in peers
            if (r["scheme"], r["lambda"]) == (scheme, lam) and math.isfinite(_num(r, "error"))
        ]
        if not finite:
            continue
        setting = min(finite, key=lambda r: _num(r, "error"))["resolution"].split(" ", 1)[1]
        mine = [o for o in orders if o[:3] == (scheme, lam, setting)]
        sizes = ", ".join(str(n) for n in [o[3] for o in mine[:1]] + [o[4] for o in mine])
        out.append(
            f"| {STYLE.get(scheme, (scheme,))[0]} | {lam} | {setting} | {sizes} | "
            + ", ".join(f"{o[5]:.2f}" for o in mine)
            + " |"
        )
    return out


def loading_lines(whole: list[dict]) -> list[str]:
    """The section on loading the FMU through fmpy (`bench.fmpy_whole`), if measured: the
    whole scenario and each of its phases, best of the repeats."""
    if not whole:
        return []
    from bench.fmpy_whole import PHASES

    lines = [
        "## Loading the FMU",
        "",
        "fmpy's whole co-simulation scenario per archive: parse the model description, extract the "
        "archive, load the library and instantiate, initialize, 1000 steps of 0.1 at lambda = 1 "
        "with "
        "wound_radius read after each through fmpy's ctypes calls, terminate, free the instance "
        "and the "
        "library and remove the extracted folder (`python -m bench.fmpy_whole "
        "target/fmu/WoundOpening.fmu "
        "--both target/fmu/WoundOpening-me.fmu`). `-both` is one archive declaring both FMI 2.0 "
        "interfaces (the Model Exchange states and their derivatives included, library deflated); "
        "the "
        "product ships co-simulation and Model Exchange as separate archives so that the "
        "co-simulation "
        "one stays small (Model Exchange: [fmi.md](fmi.md)). Best of the repeats, for the whole "
        "and for "
        "each phase on its own.",
        "",
        "| archive | variables | whole scenario | " + " | ".join(PHASES) + " |",
        "|---" * (3 + len(PHASES)) + "|",
    ]
    for r in whole:
        phases = " | ".join(fmt_s(float(r[f"{p}_seconds"])) for p in PHASES)
        lines.append(
            f"| {r['archive']} | {r['variables']} | {fmt_s(float(r['seconds']))} | {phases} |"
        )
    return lines + [""]


def write(
    path: Path,
    rows: list[dict],
    step_cost: list[dict],
    fmpy: list[dict],
    stability: list[dict],
    limits: list[dict],
    charts: list[str],
    fresh: list[dict],
    whole: list[dict] = (),
) -> None:
    today = datetime.date.today().isoformat()
    lines = [
        "# Benchmarks: accuracy and speed, methods side by side",
        "",
        f"Generated by `bash scripts/bench.sh` on {today} ({cpu_model()}, {platform.system()}); "
        "do not edit by hand: run the command again.",
        "",
        "Scenario: R_inf = 10, sigma = 1, edge stress 0, t in [0, 100] in 1000 communication "
        "steps of 0.1, lambda = 0.1 (friction), 1, 10 (viscous). Error: max over the 1000 "
        "communication "
        "points of |R - R_exact| / (R_final - R1), R_exact from `python/wound_exact.py` (~1e-14). "
        "CPU "
        "time: the whole scenario including set-up (the basis cache emptied before each repeat), "
        "best of several repeats; Rust in-process "
        "(`examples/work_precision.rs`), the peers with `time.process_time` "
        "(single-threaded BLAS).",
        "",
        "The Python package's speed (a whole R(t) curve, a fit, a sweep, Dask) is measured side "
        "by side "
        "with the fmpy path in [benchmarks_fitting.md](benchmarks_fitting.md) "
        "(`python python/bench/fitting_bench.py --out docs`).",
        "",
        "Peers, written the way a researcher would: `python/bench/scipy_peer.py` (second-order "
        "finite "
        "differences on a uniform grid, `solve_ivp` with BDF, LSODA or DOP853, swept over grid "
        "size and "
        "rtol) and `python/bench/paper_peer.py` (the paper's appendix scheme in NumPy/SciPy, "
        "swept over "
        "grid size and dt).",
        "",
        "## Targets",
        "",
        *targets(rows, step_cost),
        "",
        "## Per regime: each method's best run against the default method at the same accuracy",
        "",
        "Best run: the cheapest run within 10 % of the lowest error the method reached. Default "
        "at that "
        "error: the cheapest `modal` run with an error no larger. Speed-up: the ratio of the two "
        "CPU times.",
        "",
    ]
    for lam in map(common.lam_label, common.LAMBDAS):
        lines += [f"### lambda = {lam}", "", *regime_table(lam, rows), ""]
    lines += [
        "## The peers converge to the exact solution",
        "",
        "Order of the error against the grid spacing, at the setting (rtol or dt) of each "
        "peer's most accurate run: 2 expected for the SciPy peer (second-order differences), "
        "1 for the paper's scheme (first-order edge rows); it falls where the time error or "
        "round-off takes over.",
        "",
        *peer_orders(rows),
        "",
        "## Cost per step",
        "",
        *step_table(step_cost, fmpy),
        "",
        "## A fresh parameter set against one step",
        "",
        "Through the exported FMI functions, side by side in one run (`examples/fresh_cost.rs`, "
        "R_inf = 10, "
        "tolerance 1e-10). The modal basis does not depend on lambda and is cached per mesh and "
        "outer "
        "radius (`src/solver/basis.rs`), so only a new outer radius pays a decomposition.",
        "",
        *fresh_table(fresh),
        "",
        *loading_lines(list(whole)),
        "## Stability map (cells per status)",
        "",
        *stability_lines(stability, limits),
        "",
        "## Charts",
        "",
        *charts,
        "",
    ]
    path.write_text("\n".join(lines))
