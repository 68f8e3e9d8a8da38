"""Compare the radii and edge velocities a C test program printed on two platforms
(scripts/cross_tests.sh: Linux x86_64 against Windows under Wine, aarch64 under qemu).

Each line `<who>: t = <t> R = <R> (error ..) dR/dt = <v> (error ..)` (tests/c/reference.h)
of the first output must appear, in the same order, in the second, with R within
TOLERANCE of the opening amplitude and dR/dt within TOLERANCE of max(|v|, amplitude / 100),
the scales of reference.h. TOLERANCE is 1e-12, a thousandth of the 1e-9 each run meets
against the exact solution: the platforms run the same Rust code, so they agree to
rounding (measured: printed values identical, to the 15 decimals printed).

    python3 tests/c/compare_runs.py LINUX.txt OTHER.txt
"""

import re
import sys

AMPLITUDE = 2.0 / 3.0 * 100.0 / 99.0 - 1.0 / 6.0
TOLERANCE = 1e-12
LINE = re.compile(r"^(.*): t = (\S+)\s+R = (\S+) \(error \S+\)\s+dR/dt = (\S+) \(error \S+\)")


def points(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        found = [LINE.match(line.rstrip("\r\n")) for line in f]
    return [(m[1], float(m[2]), float(m[3]), float(m[4])) for m in found if m]


def main(reference_path, other_path):
    reference, other = points(reference_path), points(other_path)
    if not reference or [p[:2] for p in reference] != [p[:2] for p in other]:
        print(f"FAILED: {other_path} does not print the points of {reference_path}")
        return 1
    worst = 0.0
    for (_, _, r0, v0), (_, _, r1, v1) in zip(reference, other):
        worst = max(worst, abs(r1 - r0) / AMPLITUDE, abs(v1 - v0) / max(abs(v0), AMPLITUDE / 100.0))
    ok = worst <= TOLERANCE
    print(f"{other_path}: {len(other)} points, largest difference from {reference_path} {worst:.1e}"
          f" ({'within' if ok else 'BEYOND'} {TOLERANCE:g})")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
