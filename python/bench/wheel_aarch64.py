"""The manylinux_2_17 aarch64 wheel installed and run in an aarch64 Python, under qemu-user.

Too slow for the test command (pip alone takes about 75 s under emulation), so a
benchmark-style check, run by `bash scripts/wheel_aarch64.sh` (docs/install.md):

1. an arm64 Debian root (bookworm, Python 3.11) made by `debootstrap --foreign`, its
   packages unpacked with `dpkg-deb -x` (no chroot, no binfmt_misc: every aarch64 program
   is started as `qemu-aarch64 -L ROOT program`, so nothing of the host is changed);
2. a venv of that Python, and the wheel installed into it by pip (run from Debian's pip
   wheel), with its dependencies from PyPI's aarch64 wheels and fmpy, all at the pins of
   python/requirements.txt;
3. inside it, under qemu: the package's library (its own, aarch64), `simulate` at six
   times against the exact solution at the solver's tolerance, the command line's fit of a
   noisy radius series (its intervals must hold the truth), and fmpy on the FMI 3.0 archive
   (its `binaries/aarch64-linux`), also against the exact solution.

The exact values come from python/wound_exact.py on the host; nothing is compared with
the code's own output.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import wound_exact as we

ROOT = Path(__file__).resolve().parents[2]
SUITE, MIRROR = "bookworm", "http://deb.debian.org/debian"
LAM, SIGMA, R0, T, OUTER = 0.5, 0.5, 10.0, 10.0, 100.0
TIMES = [30.0, 0.1, 5.0, 60.0, 0.5, 12.5]
#: The solver's tolerance, 1e-10 of the opening, with the margin of tests/python/test_package.py.
TOL = 1e-9

PROBE = """
import json, platform, sys
import numpy as np
import wound_opening as wo
from fmpy import simulate_fmu
t = np.array(%(times)r)
sim = wo.simulate(t, lam=%(lam)r, sigma=%(sigma)r, R0_um=%(r0)r, T_s=%(T)r,
                  outer_radius_um=%(outer)r)
start = wo.fmu_start_values(G_pa=100.0, eta_pa_s=%(lam)r**2 * %(T)r * 100.0,
                            zeta_pa_s_per_um2=4 * %(T)r * 100.0 / %(r0)r**2,
                            tension_pa=%(sigma)r * 100.0, R0_um=%(r0)r,
                            outer_radius_um=%(outer)r)
r = simulate_fmu(str(wo.fmu_path("WoundOpening-fmi3.fmu")), fmi_type="CoSimulation",
                 start_values=start, stop_time=20.0, output_interval=1.0,
                 output=["wound_radius"])
print(json.dumps({"machine": platform.machine(), "python": sys.version.split()[0],
                  "package": wo.__file__, "library": str(wo.library_path()),
                  "radius": sim.radius_um.tolist(),
                  "fmu_time": r["time"].tolist(), "fmu_radius": r["wound_radius"].tolist()}))
"""


def run(argv, log, **kw):
    """One command, its output appended to the log; raises on failure."""
    started = time.perf_counter()
    with open(log, "a") as out:
        out.write(f"$ {' '.join(map(str, argv))}\n")
        out.flush()
        subprocess.run(argv, check=True, stdout=out, stderr=subprocess.STDOUT, **kw)
    return time.perf_counter() - started


def debian_root(root: Path, log: Path) -> float:
    """An arm64 Debian root with python3-venv, made once (kept for the next run)."""
    if (root / "usr" / "bin" / "python3.11").is_file():
        return 0.0
    shutil.rmtree(root, ignore_errors=True)
    spent = run(
        ["debootstrap", "--foreign", "--arch=arm64", "--variant=minbase",
         "--include=python3-venv", SUITE, str(root), MIRROR],
        log,
    )  # fmt: skip
    # --foreign unpacks the base only; the rest waits in the cache for a second stage that
    # would need a chroot: unpack those too (no maintainer script is needed by Python).
    for deb in sorted((root / "var" / "cache" / "apt" / "archives").glob("*.deb")):
        spent += run(["dpkg-deb", "-x", str(deb), str(root)], log)
    return spent


def pins() -> list[str]:
    """The pins of python/requirements.txt as pip constraints ("name==version", without
    extras: constraints take none); tests/python/test_wheel.py uses them too."""
    text = (ROOT / "python" / "requirements.txt").read_text()
    return [n + v for n, v in re.findall(r"^([A-Za-z0-9_.-]+)(?:\[[^\]]*\])?(==\S+)", text, re.M)]


def exact_radius(times) -> np.ndarray:
    return R0 * we.edge(LAM, SIGMA, OUTER / R0, np.asarray(times) / T)[0]


def noisy_series(path: Path, noise=0.05, seed=3) -> None:
    t = np.linspace(0.5, 60, 30)
    r = exact_radius(t) + noise * np.random.default_rng(seed).standard_normal(t.size)
    rows = "".join(f"{a!r},{b!r}\n" for a, b in zip(t.tolist(), r.tolist()))
    path.write_text("time_s,radius_um\n" + rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--wheel", type=Path, help="default: dist/*manylinux_2_17_aarch64.whl")
    ap.add_argument("--root", type=Path, default=ROOT / "target" / "arm64-root")
    ap.add_argument("--work", type=Path, default=ROOT / "target" / "arm64-check")
    args = ap.parse_args(argv)
    wheel = args.wheel or next((ROOT / "dist").glob("*-py3-none-manylinux_2_17_aarch64.whl"))
    shutil.rmtree(args.work, ignore_errors=True)
    args.work.mkdir(parents=True)
    log = args.work / "log.txt"
    q = ["qemu-aarch64", "-L", str(args.root)]
    spent = {"debian root": debian_root(args.root, log)}

    venv, python = args.work / "venv", args.work / "venv" / "bin" / "python"
    spent["venv"] = run([*q, str(args.root / "usr/bin/python3.11"), "-m", "venv",
                         "--without-pip", str(venv)], log)  # fmt: skip
    (args.work / "constraints.txt").write_text("\n".join(pins()) + "\n")
    (pip_wheel,) = (args.root / "usr" / "share" / "python-wheels").glob("pip-*.whl")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    spent["pip install"] = run(
        [*q, str(python), f"{pip_wheel}/pip", "install", "--quiet", "--no-compile",
         "--disable-pip-version-check", "-c", str(args.work / "constraints.txt"),
         str(wheel), "fmpy"],
        log, env=env, cwd=args.work,
    )  # fmt: skip

    failures = []
    started = time.perf_counter()
    probe = subprocess.run(
        [*q, str(python), "-c", PROBE % dict(times=TIMES, lam=LAM, sigma=SIGMA, r0=R0, T=T,
                                               outer=OUTER)],
        capture_output=True, text=True, env=env, cwd=args.work, check=False,
    )  # fmt: skip
    spent["simulate and fmpy"] = time.perf_counter() - started
    if probe.returncode:
        print(probe.stdout[-2000:], probe.stderr[-4000:], file=sys.stderr)
        return 1
    # fmpy prints to stdout when it lacks its logging helper for this platform.
    out = json.loads(probe.stdout.strip().splitlines()[-1])
    opening = R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))
    package = Path(out["package"]).parent
    print(f"aarch64 Python {out['python']} ({out['machine']}), package in {package}")
    if out["machine"] != "aarch64" or Path(out["library"]) != package / "libwound_opening.so":
        failures.append(f"not the wheel's aarch64 library: {out}")
    err = np.abs(np.array(out["radius"]) - exact_radius(TIMES)).max() / opening
    print(f"simulate at {len(TIMES)} times: max error {err:.2e} of the opening (allowed {TOL})")
    if not err <= TOL:
        failures.append(f"simulate: error {err:.3e}")
    t, radius = np.array(out["fmu_time"]), np.array(out["fmu_radius"])
    keep = t >= 0.01 * T
    err = np.abs(radius[keep] - exact_radius(t[keep])).max() / opening
    print(f"fmpy, FMI 3.0 archive (aarch64-linux): max error {err:.2e} of the opening")
    if not (err <= TOL and t[-1] == 20.0):
        failures.append(f"fmpy: error {err:.3e}, last time {t[-1]}")

    noisy_series(args.work / "radius.csv")
    started = time.perf_counter()
    fit = subprocess.run(
        [*q, str(python), "-m", "wound_opening.cli", "fit", "radius.csv",
         "--outer-radius-um", str(OUTER), "--json", "fit.json"],
        capture_output=True, text=True, env=env, cwd=args.work, check=False,
    )  # fmt: skip
    spent["fit"] = time.perf_counter() - started
    if fit.returncode:
        failures.append(f"fit exit {fit.returncode}: {fit.stderr[-2000:]}")
    else:
        result = json.loads((args.work / "fit.json").read_text())["parameters"]
        for name, truth in {"R0_um": R0, "sigma": SIGMA, "lambda": LAM, "T_s": T}.items():
            lo, hi = (
                b if b is not None else s for b, s in zip(result[name]["ci95"], (-np.inf, np.inf))
            )
            value = result[name]["estimate"]
            print(f"fit: {name} = {value:.4g} [{lo:.4g}, {hi:.4g}], truth {truth}")
            if not lo < truth < hi:
                failures.append(f"fit: {name} interval [{lo}, {hi}] misses {truth}")

    print("wall time: " + ", ".join(f"{k} {v:.0f} s" for k, v in spent.items()))
    for f in failures:
        print("FAILED:", f, file=sys.stderr)
    print("log:", log)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
