"""Compare `cargo run --release --example accuracy_scan -- TOL` output with the exact solution.

    cargo run --release --example accuracy_scan -- 1e-10 > scan.csv
    python python/bench/accuracy_scan.py scan.csv

Prints, per (lambda, R_inf), the number of unknowns, the basis build time, and the largest
error of the wound radius relative to the opening amplitude over t in [0.01, 1e16], against
`wound_exact.edge` (the double-precision Talbot inversion of the Laplace-domain solution);
the last line is the worst over the scan. This is how the tolerance rule of
src/solver/tolerance.rs was verified over the accepted domain.
"""

import argparse
import collections
import csv
import pathlib
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
import wound_exact as we  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="output of the accuracy_scan example")
    args = parser.parse_args()
    cases = collections.OrderedDict()
    for row in csv.DictReader(open(args.csv)):
        cases.setdefault((float(row["lambda"]), float(row["R_inf"])), []).append(row)
    worst = 0.0
    for (lam, r_inf), rows in cases.items():
        t = np.array([float(x["t"]) for x in rows])
        radius = np.array([float(x["R"]) for x in rows])
        exact, _ = we.edge(lam, 1.0, r_inf, t)
        amplitude = we.final_radius(1, r_inf) - we.initial_radius(1)
        err = np.abs(radius - exact) / amplitude
        worst = max(worst, err.max())
        print(
            f"lambda {lam:<7g} R_inf {r_inf:<7g} unknowns {rows[0]['unknowns']:>3} "
            f"build {float(rows[0]['build_s']):.4f} s  max error {err.max():.2e} at t = "
            f"{t[err.argmax()]:.3g}"
        )
    print(f"worst {worst:.2e}")


if __name__ == "__main__":
    main()
