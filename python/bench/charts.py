"""Every chart and docs/benchmarks.md from the benchmark CSVs.

Reads from IN (target/bench): work_precision.csv, stability.csv, explicit_limits.csv,
step_cost.csv, profiles.csv (the Rust examples), scipy_peer.csv, paper_peer.csv,
fmpy_timing.csv (the Python side). Writes to OUT (docs):

    work_precision_lambda_{0.1,1,10}.png, work_precision.csv   error against CPU time
    stability_{scheme}.png                                     lambda against dt, per grid
    explicit_limits.png                                        explicit limits, measured and theory
    paper_panels_lambda_{0.1,1,10}.png                         the paper's four panels
    benchmarks.md                                              the numbers, generated

A missing input only skips what needs it (and says so).

    python -m bench.charts --data target/bench --out docs      (with python/ on PYTHONPATH)
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from bench import common, panels_chart, stability_chart, summary, work_chart  # noqa: E402

CHART_NOTES = {
    "work_precision": "error against CPU time for the whole scenario, one line per method "
    "(data: `work_precision.csv`)",
    "stability": "status over lambda (rows, 0 at the bottom) and dt (columns), one panel per grid",
    "explicit_limits": "the explicit scheme's step limit against lambda and its lambda limit "
    "against "
    "grid size, measured (circles) and theory (lines)",
    "paper_panels": "the paper's four panels: u(r), v(r) at several t; normalised u(t), v(t) at "
    "several r",
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", type=Path, default=Path("target/bench"))
    parser.add_argument("--out", type=Path, default=Path("docs"))
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    read = lambda name: common.read_rows(args.data / f"{name}.csv")  # noqa: E731
    rust, fmpy = read("work_precision"), read("fmpy_timing")
    peers = read("scipy_peer") + read("paper_peer")
    stability, limits, profiles = read("stability"), read("explicit_limits"), read("profiles")
    made = []

    def note(path: Path, kind: str) -> None:
        made.append(f"- [`{path.name}`]({path.name}): {CHART_NOTES[kind]}")
        print(path)

    for lam in map(common.lam_label, common.LAMBDAS):
        path = args.out / f"work_precision_lambda_{lam}.png"
        work_chart.plot_regime(lam, rust, peers, fmpy, path)
        note(path, "work_precision")
    common.write_rows(
        args.out / "work_precision.csv", common.WORK_COLUMNS, work_chart.all_rows(rust, peers, fmpy)
    )

    for scheme in dict.fromkeys(r["scheme"] for r in stability):
        path = args.out / f"stability_{scheme}.png"
        stability_chart.plot_scheme(
            scheme,
            [r for r in stability if r["scheme"] == scheme],
            limits if scheme == "explicit" else [],
            path,
        )
        note(path, "stability")
    if limits:
        stability_chart.plot_explicit_limits(limits, args.out / "explicit_limits.png")
        note(args.out / "explicit_limits.png", "explicit_limits")

    for lam in map(common.lam_label, common.LAMBDAS):
        mine = [r for r in profiles if common.lam_label(float(r["lambda"])) == lam]
        if mine:
            path = args.out / f"paper_panels_lambda_{lam}.png"
            panels_chart.plot_lambda(lam, mine, path)
            note(path, "paper_panels")

    for name, rows in (
        ("work_precision", rust),
        ("stability", stability),
        ("profiles", profiles),
        ("scipy_peer/paper_peer", peers),
        ("fmpy_timing", fmpy),
    ):
        if not rows:
            print(f"charts: no {name} data in {args.data}: skipped what needs it")
    summary.write(
        args.out / "benchmarks.md",
        rust + peers,
        read("step_cost"),
        fmpy,
        stability,
        limits,
        made,
        read("fresh_cost"),
        read("fmpy_whole"),
    )
    print(args.out / "benchmarks.md")


if __name__ == "__main__":
    main()
