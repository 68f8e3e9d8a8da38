"""Speed of `fit` at the sizes labs have, side by side with an earlier revision in one run.
Writes OUT/fit_speed.csv and prints a markdown table (CPU seconds).

Data from the EXACT solution (wound_exact.py), made once by this process and shared by
both fitters. The tissue of examples/lab (make_lab_examples.py): viscous length 20 um,
tension/G 0.5, zeta/G 0.1 s/um^2, outer radius 100 um; 120 frames every 0.25 s after the
cut, Fiji-like noise 0.3 px of 0.2 um (0.06 um, estimated by the fit, as the command line
does for a Fiji table).

    lab_R0_4, lab_R0_8, lab_R0_16  the tissue, cuts of R0 = 4, 8, 16 um (lambda 5, 2.5, 1.25)
    lab_cut_R0_4, _8, _16          as lab_R0_*, the cut 0.3 frames after frame N fitted
    lab_friction                   lambda = 0.1, R0 = 10 um, T = 10 s
    lab_viscous                    lambda = 10, R0 = 10 um, T = 0.1 s (eta/G = 10 s)
    flat_plateau                   R0 = 8 um, 120 frames from 60 s on: only the plateau
    flat_early                     R0 = 16 um, 120 frames every 0.01 s from 0.01 s: a tiny opening
    piv_4000                       R0 = 8 um: 120 frames + 4,000 PIV vectors (6 frame pairs,
                                   0.05 um/s), `fit` with its intervals (no figure)
    tissue_3                       examples/lab's three Fiji tables by the command line
                                   (fit_wounds, figure and report)

Each single-wound case except piv_4000 does what `wound-opening fit ... --plot --report` does:
fit() with its intervals, the report (report.write_report) and the figure
(plots.fit_figure). Each case runs in a subprocess with PYTHONPATH at the current package or
at `--baseline REV`'s python/ (git archive into a temp dir), alternating, the same native
library (WOUND_OPENING_LIB). CPU time by time.process_time from the call on, the package's
modules (scipy, matplotlib, pandas: the command line reads a lab's file with it) imported
before: their import, a fixed cost of each process that a sweep or a notebook pays once, is
its own column. Native solves by counting calls of
_native.series and _native.profile_series.

    python python/bench/fit_speed.py --baseline cee82cd [--quick] [--cases lab_R0_8,piv_4000]
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import os
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.append(str(ROOT / "python"))  # wound_exact; a PYTHONPATH package goes first

VISCOUS_UM, SIGMA, ZETA_OVER_G, OUTER = 20.0, 0.5, 0.1, 100.0
NOISE_UM, NOISE_UM_S, SEED = 0.3 * 0.2, 0.05, 2026
LAB = ["Results_4um.csv", "Results_8um.csv", "Results_16um.csv"]


def tissue(R0):
    return VISCOUS_UM / R0, SIGMA, ZETA_OVER_G * R0**2 / 4


CASES = {  # name -> (R0, lambda, sigma, T, times, PIV vectors)
    **{f"lab_R0_{int(r)}": (r, *tissue(r), "frames", 0) for r in (4.0, 8.0, 16.0)},
    "lab_friction": (10.0, 0.1, SIGMA, 10.0, "frames", 0),
    "lab_viscous": (10.0, 10.0, SIGMA, 0.1, "frames", 0),
    "flat_plateau": (8.0, *tissue(8.0), "plateau", 0),
    "flat_early": (16.0, *tissue(16.0), "early", 0),
    "piv_4000": (8.0, *tissue(8.0), "frames", 4000),
    "tissue_3": None,
    **{f"lab_cut_R0_{int(r)}": (r, *tissue(r), "frames", 0) for r in (4.0, 8.0, 16.0)},
}
#: The lab_cut cases: times counted from frame N, the laser fired 0.3 frame intervals after
#: it; the fit's cut_s in [0, 0.25] s, as `--cut-after-frame N` on a Fiji table fits it.
CUT_S, FRAME_S = 0.075, 0.25
QUICK = ["lab_R0_8", "lab_friction", "flat_early", "tissue_3"]
TIMES = {
    "frames": 0.25 * np.arange(1, 121),
    "plateau": 60 + 0.25 * np.arange(120),
    "early": 0.01 * np.arange(1, 121),
}


def make_data(name: str, piv_vectors: int | None = None) -> dict:
    """Arrays of the case: times, radius; with PIV also p_times, p_r, p_v."""
    import wound_exact as we

    R0, lam, sigma, T, design, n_piv = CASES[name]
    n_piv = n_piv if piv_vectors is None or not n_piv else piv_vectors
    rng = np.random.default_rng(SEED)
    t = TIMES[design]
    r_inf = OUTER / R0
    since = t - (CUT_S if name.startswith("lab_cut") else 0.0)
    radius = R0 * we.edge(lam, sigma, r_inf, since / T)[0] + NOISE_UM * rng.standard_normal(t.size)
    out = {"times": t, "radius": radius}
    if n_piv:
        pairs = 0.25 * (np.arange(6) * 20 + 1.5)  # frame pairs 4-5, 24-25, ..: mid-pair times
        per = n_piv // pairs.size
        x = 1 + (6.0 - 1) * np.linspace(0, 1, per) ** 1.5  # reference radii out to 6 R0
        rows = []
        for tp in pairs:
            u, v = we.profile(lam, sigma, r_inf, x, np.array([tp / T]))
            rows.append((np.full(per, tp), R0 * (x + u[0]), R0 / T * v[0]))
        pt, pr, pv = (np.concatenate(c) for c in zip(*rows))
        out |= {"p_times": pt, "p_r": pr, "p_v": pv + NOISE_UM_S * rng.standard_normal(pv.size)}
    return out


def _count_solves():
    from wound_opening import _native

    counts = {"solves": 0}
    for fname in ("series", "profile_series"):
        f = getattr(_native, fname)

        def wrapped(*a, _f=f, **k):
            counts["solves"] += 1
            return _f(*a, **k)

        setattr(_native, fname, wrapped)
    return counts


def _intervals(result) -> dict:
    out = {n: [r.estimate, *r.ci95] for n, r in result.reports.items()}
    for n, p in (getattr(result, "derived_profiles", None) or {}).items():
        out[n] = [None, p.lower, p.upper]
    return out


def run_case(name: str, data_file: str, out_dir: str) -> dict:
    """One case in this process (the worker): CPU seconds, solves, estimates and intervals."""
    begin = time.process_time()
    import wound_opening as wo
    from wound_opening.results.plots import fit_figure
    from wound_opening.results.report import write_report

    wo.fit  # noqa: B018  (the fitter's modules, imported on first use)
    import pandas  # noqa: F401  (the tables and figure's; the command line reads lab files with it)

    import_s = time.process_time() - begin
    counts = _count_solves()
    out = Path(out_dir)
    if name == "tissue_3":
        from wound_opening.cli import main

        files = [str(ROOT / "examples" / "lab" / f) for f in LAB]
        argv = ["fit", *files, "--area-col", "Area", "--frame-interval-s", "0.25"]
        argv += ["--cut-after-frame", "3", "--length-unit", "px", "--pixel-size-um", "0.2"]
        argv += ["--outer-radius-um", "100", "--json", str(out / f"{name}.json")]
        argv += ["--plot", str(out / f"{name}.png"), "--report", str(out / f"{name}.html")]
        start = time.process_time()
        with open(os.devnull, "w") as sink:
            stdout, sys.stdout = sys.stdout, sink
            try:
                main(argv)
            finally:
                sys.stdout = stdout
        cpu = time.process_time() - start
        got = json.loads((out / f"{name}.json").read_text())
        est = {k: [v, None, None] for k, v in _flat_numbers(got.get("estimates", got)).items()}
        out = {"cpu_s": cpu, "fit_s": cpu, "import_s": import_s, "solves": counts["solves"]}
        return out | {"values": est}
    d = np.load(data_file)
    radius = wo.RadiusSeries(d["times"], d["radius"])
    profile = (
        wo.VelocityProfile(d["p_times"], d["p_r"], d["p_v"], noise_um_s=NOISE_UM_S)
        if "p_times" in d
        else None
    )
    params = None
    if name.startswith("lab_cut"):
        params = wo.Parameters()
        params.add("cut_s", min=0.0, max=FRAME_S)
    start = time.process_time()
    result = wo.fit(radius, profile, outer_radius_um=OUTER, params=params)
    fit_s = time.process_time() - start
    if profile is None:
        write_report(out / f"{name}.html", result, radius, profile, command="bench")
        if result.converged:
            fit_figure(result, radius, profile, out / f"{name}.png")
    cpu = time.process_time() - start
    values = _intervals(result) | {"chi2": [result.chi2, None, None]}
    return {
        "cpu_s": cpu,
        "fit_s": fit_s,
        "import_s": import_s,
        "solves": counts["solves"],
        "values": values,
    }


def _flat_numbers(d, prefix="") -> dict:
    out = {}
    for k, v in d.items() if isinstance(d, dict) else ():
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            out[prefix + k] = float(v)
        elif isinstance(v, dict):
            out |= _flat_numbers(v, prefix + k + ".")
    return out


def agreement(a: dict, b: dict) -> float:
    """Largest difference of an estimate or interval end between two runs (name -> [estimate,
    lower, upper], None where open or not given), relative to the distance from the estimate
    to the farther closed end of `a` (its width where there is no estimate, the end itself
    where only one is given); inf where an end is open in one only."""
    worst = 0.0
    for name, (e, lo, hi) in a.items():
        if name not in b or name.startswith("optimizer"):  # counts, not estimates
            continue
        ends = [x for x in (lo, hi) if x is not None]
        if e is not None:
            scale = max([abs(x - e) for x in ends] + [abs(e) * 1e-6])
        else:
            scale = max(
                (max(ends) - min(ends)) / 2 if len(ends) == 2 else 0, *map(abs, ends), 1e-300
            )
        for x, y in zip((e, lo, hi), b[name]):
            if x is None and y is None:
                continue
            if (x is None) != (y is None):
                return float("inf")
            if x != y:
                worst = max(worst, abs(x - y) / max(scale, 1e-300))
    return worst


def baseline_tree(rev: str, into: Path) -> Path:
    """python/wound_opening and python/wound_exact.py of revision `rev` under `into`."""
    tar = subprocess.run(
        ["git", "-C", str(ROOT), "archive", rev, "python/wound_opening", "python/wound_exact.py"],
        check=True,
        capture_output=True,
    ).stdout
    with tarfile.open(fileobj=io.BytesIO(tar)) as t:
        t.extractall(into, filter="data")
    return into / "python"


def _library() -> Path:
    from wound_opening import library_path

    return library_path()


def spawn(pkg: Path, name: str, data_file: str, out_dir: str) -> dict:
    """Run one case in a subprocess importing the package at `pkg`, on the native library this
    process loads (both columns of a run use the same library)."""
    env = dict(os.environ, PYTHONPATH=str(pkg), WOUND_OPENING_LIB=str(_library()))
    cmd = [sys.executable, __file__, "--worker", name, data_file, out_dir]
    got = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if got.returncode != 0:
        return {"error": got.stderr.strip().splitlines()[-1] if got.stderr.strip() else "failed"}
    return json.loads(got.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--baseline", help="a git revision to compare with (e.g. cee82cd)")
    ap.add_argument("--cases", help="comma-separated names (default: all; --quick: a few)")
    ap.add_argument("--quick", action="store_true", help=f"{', '.join(QUICK)}; 1,000 PIV vectors")
    ap.add_argument("--only", choices=("both", "baseline", "current"), default="both")
    ap.add_argument("--out", default=str(ROOT / "target" / "bench"))
    ap.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        print(json.dumps(run_case(*args.worker)))
        return 0
    names = args.cases.split(",") if args.cases else (QUICK if args.quick else list(CASES))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows, values = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        sides = [] if args.only == "baseline" else [("current", ROOT / "python")]
        if args.baseline and args.only != "current":
            sides.insert(0, ("baseline", baseline_tree(args.baseline, tmp / "base")))
        for name in names:
            data_file = str(tmp / f"{name}.npz")
            if CASES[name] is not None:
                np.savez(data_file, **make_data(name, 1000 if args.quick else None))
            got = {side: spawn(pkg, name, data_file, str(tmp)) for side, pkg in sides}
            row = {"case": name}
            for side, g in got.items():
                row[f"{side}_cpu_s"] = g.get("cpu_s")
                row[f"{side}_fit_s"] = g.get("fit_s")
                row[f"{side}_solves"] = g.get("solves")
                row[f"{side}_import_s"] = g.get("import_s")
                row[f"{side}_error"] = g.get("error", "")
            if len(got) == 2 and all("values" in g for g in got.values()):
                row["max_diff"] = agreement(got["baseline"]["values"], got["current"]["values"])
            values[name] = {side: g.get("values") for side, g in got.items()}
            rows.append(row)
            print(json.dumps(row), file=sys.stderr, flush=True)
    keys = sorted({k for r in rows for k in r}, key=lambda k: (k != "case", k))
    with open(out / "fit_speed.csv", "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    (out / "fit_speed_values.json").write_text(json.dumps(values, indent=1))
    print(table(rows))
    return 0


def _s(x, fmt="{:.2f}") -> str:
    return "-" if x is None or x == "" else fmt.format(x)


def table(rows) -> str:
    lines = [
        "| case | baseline CPU s | current CPU s | ratio | current fit s | solves (base -> now) "
        "| imports s (base -> now) | estimates and ends agree (to 1 %) |",
        "|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in rows:
        b, c = r.get("baseline_cpu_s"), r.get("current_cpu_s")
        ratio = _s(b / c, "{:.1f}x") if b and c else "-"
        d = r.get("max_diff")
        agree = "-" if d is None else ("yes" if d < 0.01 else "no") + f" (max {d:.2g})"
        err = r.get("current_error") or r.get("baseline_error")
        lines.append(
            f"| {r['case']} | {_s(b)} | {_s(c)} | {ratio} | {_s(r.get('current_fit_s'))} | "
            f"{_s(r.get('baseline_solves'), '{}')} -> {_s(r.get('current_solves'), '{}')} | "
            f"{_s(r.get('baseline_import_s'))} -> {_s(r.get('current_import_s'))} | "
            f"{agree}{' ' + err if err else ''} |"
        )
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
