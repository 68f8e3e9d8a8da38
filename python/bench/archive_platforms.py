"""What each platform added to an archive costs fmpy, side by side in one run: fmpy's whole
co-simulation scenario (`bench.fmpy_whole.whole`: parse, extract, instantiate, initialize,
1000 steps, free) on the archive as built (five platforms) and on a copy holding only the
Linux and Windows binaries (what the archives carried before the macOS ones), and the
SciPy peer's best-accuracy run at lambda = 0.1 (`bench.scipy_peer`: DOP853, N = 25601,
rtol = 1e-10, the Targets table of docs/benchmarks.md) timed in the same process, for the
ratio docs/install.md reports (the peer's CPU time over the fmpy scenario's).
`time.process_time`, best of `--repeats` (the peer: best of 2), with BLAS on one thread as
in scripts/bench.sh: process_time counts every thread's CPU, and OpenBLAS's second thread
on two cores more than doubles the peer's (32.6 s against 15.0 s, measured 2026-12-07).

    python -m bench.archive_platforms target/fmu/WoundOpening.fmu
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
import zipfile
from pathlib import Path

# Before numpy is imported (by bench.scipy_peer): the peer's CPU time on one BLAS thread.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from bench import scipy_peer  # noqa: E402
from bench.fmpy_whole import whole  # noqa: E402

#: The binaries kept in the comparison copy (FMI 2.0 and 3.0 folder names).
BEFORE = ("linux64", "x86_64-linux", "aarch64-linux", "win64", "x86_64-windows")


def without_macos(path: str, out: Path) -> str:
    """A copy of the archive without its darwin binaries, every entry compressed as it was."""
    copy = out / Path(path).name
    with zipfile.ZipFile(path) as src, zipfile.ZipFile(copy, "w") as dst:
        for info in src.infolist():
            parts = info.filename.split("/")
            if parts[0] == "binaries" and parts[1] not in BEFORE:
                continue
            dst.writestr(info, src.read(info))
    return str(copy)


def best(run, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.process_time()
        run()
        times.append(time.process_time() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("fmu")
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    scratch = Path(tempfile.mkdtemp())
    archives = {"five platforms": args.fmu, "without macOS": without_macos(args.fmu, scratch)}
    peer = best(lambda: scipy_peer.solve(0.1, 25601, 1e-10, "DOP853"), 2)
    print("| archive | size | fmpy scenario | of it, extract | SciPy peer / scenario |")
    print("|---|---|---|---|---|")
    for name, path in archives.items():
        runs = [whole(path)[0] for _ in range(args.repeats)]
        scenario = min(sum(r.values()) for r in runs)
        extract = min(r["extract"] for r in runs)
        size = Path(path).stat().st_size / 1e6
        print(
            f"| {name} | {size:.1f} MB | {scenario * 1e3:.1f} ms | {extract * 1e3:.1f} ms "
            f"| {peer / scenario:,.0f}x |"
        )
    print(f"SciPy peer (DOP853, N=25601, rtol=1e-10, lambda=0.1): {peer:.2f} s")


if __name__ == "__main__":
    main()
