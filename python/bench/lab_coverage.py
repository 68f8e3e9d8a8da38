"""Coverage of the lab fit on files the real tools measured: movies rendered from the EXACT
solution (lab_render.py), measured by OpenPIV and outlined as ImageJ does (lab_measure.py),
fitted with the documented command (lab_movies.fit_command) with the field and without it.

Each draw varies what a lab cannot choose: the texture and the photon noise (the seed and
the photon count), the cut's offset inside its frame interval (uniform), the wound size R0
(log-uniform 3-12 um), lambda (log-uniform 0.3-3), the tension sigma (0.5-1.5), the frame
interval (0.25, 0.5 or 1 s); zeta/G is 0.08 s/um^2 (T = zeta R0^2 / (4 G)). Per draw and
fit the 95 % profile intervals of R0 and the material values are checked against the truth:
a value reported identified must hold it. Prints one line per draw and the table of
docs/fitting.md ("Coverage on rendered movies"); writes every draw's truth.json and the
summary JSON under --out.

    cd python && python -m bench.lab_coverage --out /tmp/lab_coverage --draws 20 [--size-px 256]

With --refit the draws under --out are fitted again (their files kept): the same movies and
measurements through a changed fitter, e.g. a copy of an earlier study's folder; with
--tally they are only counted again (the table from the fits written).
"""

from __future__ import annotations

import argparse
import json
import math
import shlex
import time
from pathlib import Path

import numpy as np

from bench.lab_movies import measure, outlines_round, radius_only, run_fit
from bench.lab_render import Movie, render

KEYS = (
    "R0_um",
    "viscous_length_um",
    "zeta_over_G_s_per_um2",
    "eta_over_G_s",
    "tension_over_G",
)
ZETA_OVER_G = 0.08


def movie(seed: int, size_px: int) -> Movie:
    """The draw's movie (module docstring)."""
    rng = np.random.default_rng([seed, 37])
    R0 = float(math.exp(rng.uniform(math.log(3.0), math.log(12.0))))
    frame = float(rng.choice([0.25, 0.5, 1.0]))
    return Movie(
        R0_um=R0,
        sigma=float(rng.uniform(0.5, 1.5)),
        lam=float(math.exp(rng.uniform(math.log(0.3), math.log(3.0)))),
        T_s=ZETA_OVER_G * R0**2 / 4,
        outer_um=100.0,
        frame_s=frame,
        cut_offset_s=float(rng.uniform(0.0, frame)),
        photons=float(rng.choice([100.0, 300.0, 1000.0])),
        size_px=size_px,
        seed=seed,
    )


def draw(seed: int, out: Path, size_px: int) -> dict:
    m = movie(seed, size_px)
    t0 = time.process_time()
    frames, truth = render(m)
    record = measure(out, m, frames, truth)
    record["cpu_s"] = {"render_and_measure": round(time.process_time() - t0, 2)}
    cmd = shlex.split(record["fit_command"])
    record["fit"] = run_fit(out, record, cmd, "fit")
    record["fit_radius_only"] = run_fit(out, record, radius_only(cmd), "fit_radius")
    (out / "truth.json").write_text(json.dumps(record, indent=1) + "\n")
    return record


def refit(out: Path) -> dict:
    """A draw's files fitted again by the fitter of this checkout (--refit): the movie's
    measurement as written under `out` (or copied there), the fit commands' paths moved to
    it; truth.json rewritten with the new fits."""
    record = json.loads((out / "truth.json").read_text())
    cmd = shlex.split(record["fit_command"])
    old = str(Path(cmd[cmd.index("--json") + 1]).parent)
    cmd = [c.replace(old, str(out)) for c in cmd]
    record["fit_command"] = shlex.join(cmd)
    record["fit"] = run_fit(out, record, cmd, "fit")
    record["fit_radius_only"] = run_fit(out, record, radius_only(cmd), "fit_radius")
    (out / "truth.json").write_text(json.dumps(record, indent=1) + "\n")
    return record


def recount(out: Path) -> dict:
    """A draw's record as written (--tally), each fit's outlines_round read from its JSON."""
    record = json.loads((out / "truth.json").read_text())
    for fit, name in (("fit", "fit"), ("fit_radius_only", "fit_radius")):
        try:
            said = json.loads((out / f"{name}.json").read_text())
        except (OSError, ValueError):
            continue
        record[fit]["outlines_round"] = outlines_round(said)
    return record


def tally(records: list, fit: str) -> dict:
    """Per key: fits with numbers, reported identified, identified and holding the truth,
    intervals (identified or not) holding it; and the fits whose outlines the reader did not
    warn about (lab_movies.outlines_round) and their intervals holding it."""
    out = {}
    for key in KEYS:
        rows = [(r[fit].get("estimates", {}).get(key), r[fit]) for r in records]
        rows = [(row, f) for row, f in rows if row and row.get("truth") is not None]
        ident = [row for row, _ in rows if row.get("identified")]
        round_ = [row for row, f in rows if f.get("outlines_round", True)]
        out[key] = {
            "fits": len(rows),
            "identified": len(ident),
            "identified_covering": sum(bool(row.get("covers")) for row in ident),
            "covering": sum(bool(row.get("covers")) for row, _ in rows),
            "round_fits": len(round_),
            "round_covering": sum(bool(row.get("covers")) for row in round_),
        }
    return out


def table(summary: dict, draws: int) -> str:
    lines = [
        "| value | fit | numbers | identified | identified and holding the truth | "
        "95 % interval holding the truth | the same, outlines round |",
        "|---|---|---|---|---|---|---|",
    ]
    for key in KEYS:
        for fit, label in (("fit", "radius + PIV"), ("fit_radius_only", "radius alone")):
            c = summary[fit][key]
            lines.append(
                f"| {key} | {label} | {c['fits']} of {draws} | {c['identified']} | "
                f"{c['identified_covering']} | {c['covering']} of {c['fits']} | "
                f"{c['round_covering']} of {c['round_fits']} |"
            )
    return "\n".join(lines)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--draws", type=int, default=20)
    ap.add_argument("--first", type=int, default=0, help="the first draw's seed")
    ap.add_argument("--size-px", type=int, default=256)
    ap.add_argument(
        "--refit",
        action="store_true",
        help="fit the draws already under --out again (a copy of an earlier study's folder): "
        "no rendering or measuring, the same files",
    )
    ap.add_argument(
        "--tally",
        action="store_true",
        help="count the draws already fitted under --out again (their truth.json and fit "
        "JSON): no fit",
    )
    a = ap.parse_args(argv)
    records = []
    for seed in range(a.first, a.first + a.draws):
        where = a.out / f"draw_{seed:03d}"
        if a.tally:
            rec = recount(where)
        else:
            rec = refit(where) if a.refit else draw(seed, where, a.size_px)
        records.append(rec)
        m = rec["movie"]
        said = []
        for fit in ("fit", "fit_radius_only"):
            f = rec[fit]
            misses = [
                k
                for k in KEYS
                if (row := f.get("estimates", {}).get(k)) and row.get("identified")
                and not row.get("covers")
            ]  # fmt: skip
            said.append(
                f"{fit}: exit {f['exit']} {f['wall_s']} s, identified misses {misses or 'none'}"
            )
        print(
            f"draw {seed}: R0 {m['R0_um']:.2f} um, lambda {m['lam']:.2f}, sigma "
            f"{m['sigma']:.2f}, frame {m['frame_s']} s, cut +{m['cut_offset_s']:.3f} s, "
            f"photons {m['photons']:g}; " + "; ".join(said),
            flush=True,
        )
    summary = {fit: tally(records, fit) for fit in ("fit", "fit_radius_only")}
    (a.out / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    print(table(summary, len(records)))


if __name__ == "__main__":
    main()
