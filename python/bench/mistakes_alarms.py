"""False alarms and caught unit mistakes of the recording checks (fitting/recording.py,
inputs/truncate.py) on random valid recordings of the exact solution (python/wound_exact.py).

Valid: frames 0.05-30 s apart (log-uniform), 20-200 frames over 2 s to 1 h from the cut,
lambda 0-3, T 0.3-300 s (log-uniform), noise 0.2-5 % of the opening, given for half of them
(estimated from the second differences for the others). Each recording is checked as it is
(an alarm is any refusal or warning), then with its times x 1000 (ms read as s) and / 1000
(s read as ms): refused, warned about, or passed silently.

    PYTHONPATH=python python -m bench.mistakes_alarms 1000
"""

from __future__ import annotations

import sys
from collections import Counter

import numpy as np
import wound_exact as we

from wound_opening.fitting.recording import check_recording
from wound_opening.inputs.series import RadiusSeries

R0, SIGMA, OUTER = 10.0, 0.5, 100.0


def recordings(n: int, seed: int = 7):
    rng = np.random.default_rng(seed)
    made = 0
    while made < n:
        dt = float(np.exp(rng.uniform(np.log(0.05), np.log(30.0))))
        frames = int(rng.integers(20, 201))
        if not 2.0 <= frames * dt <= 3600.0:
            continue
        made += 1
        t = dt * np.arange(1, frames + 1)
        lam, T = rng.uniform(0, 3), float(np.exp(rng.uniform(np.log(0.3), np.log(300.0))))
        sd = rng.uniform(0.002, 0.05) * R0 * 2 * SIGMA / 3
        r = R0 * we.edge(lam, SIGMA, OUTER / R0, t / T)[0] + sd * rng.standard_normal(t.size)
        yield t, r, (sd if made % 2 else None)


def outcome(t, r, noise) -> str:
    try:
        return "warned" if check_recording(RadiusSeries(t, r, noise)) else "silent"
    except ValueError:
        return "refused"


def main(n: int) -> None:
    counts = {"as recorded": Counter(), "ms read as s": Counter(), "s read as ms": Counter()}
    for t, r, noise in recordings(n):
        counts["as recorded"][outcome(t, r, noise)] += 1
        counts["ms read as s"][outcome(t * 1e3, r, noise)] += 1
        counts["s read as ms"][outcome(t * 1e-3, r, noise)] += 1
    print(f"{n} random valid recordings")
    print("| times | refused | warned | silent |")
    print("|---|---|---|---|")
    for name, c in counts.items():
        print(f"| {name} | {c['refused']} | {c['warned']} | {c['silent']} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 1000)
