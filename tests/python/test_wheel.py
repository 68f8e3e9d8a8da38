"""The wheel: `pip wheel .` builds it (reusing target/), it installs into a fresh venv with
no Rust on PATH and no checkout on sys.path, and there `wound-opening fit` runs (also the
README's quick starts: its microscope export, and its three-wound fit), fmpy loads the
shipped FMUs through `wound_opening.fmu_path` and simulates them from the start values of
`wound_opening.fmu_start_values`, and the coupled worked example runs from the package
(`python -m wound_opening.coupling`).

The runtime dependencies come from the wheel's own metadata, pinned by the versions of
python/requirements.txt (pip's cache serves them). Nothing here falls back on the checkout:
a wheel without the library or an archive fails.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
import wound_exact as we
from bench.tissue_designs import TRUTH as TISSUE_TRUTH
from bench.wheel_aarch64 import pins
from test_cli import LAM, OUTER, R0, SIGMA, T, check_quick_start, readme_quick_start, write_radius

ROOT = Path(__file__).resolve().parents[2]
FMUS = (
    "WoundOpening.fmu",
    "WoundOpening-me.fmu",
    "WoundOpening-fmi3.fmu",
    "PurseString.fmu",
    "PurseString-fmi3.fmu",
)
#: The README's three-wound fit (python/example_wounds.py wrote the files).
TISSUE_COMMAND = (
    "tissue_R5um.csv",
    "tissue_R10um.csv",
    "tissue_R20um.csv",
    "--outer-radius-um",
    "80,100,120",
)
#: The material of examples/lab (python/make_lab_examples.py).
LAB_TRUTH = {"viscous_length_um": 20.0, "tension_over_G": 0.5, "zeta_over_G_s_per_um2": 0.1}
#: The FMUs' promise at the default tolerance: |R - R_exact| <= 1e-10 (R_final - R1), t >= 0.01 T.
FMU_TOL = 1e-10

# Run inside the fresh venv: where the package found its files, and two FMUs simulated from
# the start values `fmu_start_values` makes of material constants.
PROBE = """
import json, shutil, sys
import wound_opening
from fmpy import read_model_description, simulate_fmu
start = wound_opening.fmu_start_values(**%(material)r)
out = {"cargo": shutil.which("cargo"), "sys_path": sys.path, "package": wound_opening.__file__,
       "library": str(wound_opening.library_path()), "fmus": {}, "radius": {}, "start": start}
for name in %(fmus)r:
    path = wound_opening.fmu_path(name)
    out["fmus"][name] = [str(path), read_model_description(str(path)).modelName]
for name in ("WoundOpening.fmu", "WoundOpening-fmi3.fmu"):
    r = simulate_fmu(str(wound_opening.fmu_path(name)), fmi_type="CoSimulation", start_values=start,
                     stop_time=%(stop)r, output_interval=%(step)r, output=["wound_radius"])
    out["radius"][name] = [r["time"].tolist(), r["wound_radius"].tolist()]
print(json.dumps(out))
"""


def _without_rust(path: str) -> str:
    """PATH less every folder that holds cargo or rustc."""
    keep = [
        d
        for d in path.split(os.pathsep)
        if not any((Path(d) / exe).exists() for exe in ("cargo", "rustc"))
    ]
    return os.pathsep.join(keep)


def _constraints(tmp_path: Path) -> Path:
    """python/requirements.txt as a constraints file (pins only: constraints take no extras)."""
    path = tmp_path / "constraints.txt"
    path.write_text("".join(f"{pin}\n" for pin in pins()))
    return path


def build_wheel(dist: Path) -> Path:
    built = subprocess.run(
        [
            sys.executable,
            "-m",
            "pip",
            "wheel",
            str(ROOT),
            "--no-deps",
            "--quiet",
            "--disable-pip-version-check",
            "-w",
            str(dist),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert built.returncode == 0, built.stderr
    (path,) = dist.glob("wound_opening-*.whl")
    return path


#: platform tag -> the library a wheel of that tag holds, and how its first bytes begin:
#: ELF of e_machine x86_64 (62) or aarch64 (183), PE of machine x86_64, universal Mach-O
#: (the headers of each platform's library are checked in test_desk_binaries.py).
WHEEL_LIBRARIES = {
    "manylinux_2_17_x86_64": ("libwound_opening.so", lambda b: b[:4] == b"\x7fELF" and b[18] == 62),
    "manylinux_2_17_aarch64": (
        "libwound_opening.so",
        lambda b: b[:4] == b"\x7fELF" and b[18] == 183,
    ),
    "win_amd64": (
        "wound_opening.dll",
        lambda b: b[:2] == b"MZ" and b[int.from_bytes(b[60:64], "little") + 4 :][:2] == b"\x64\x86",
    ),
    "macosx_10_12_universal2": ("libwound_opening.dylib", lambda b: b[:4] == b"\xca\xfe\xba\xbe"),
}


def check_platform_wheels(host_wheel: Path, out: Path) -> dict[str, Path]:
    """python/platform_wheels.py on the host's wheel: one wheel per platform, each with the
    host wheel's files but the library, its own platform's library under the name
    `wound_opening._native` loads there, its tag in WHEEL and file name, a RECORD whose
    hashes match every file; the same library as the archives carry."""
    import platform_wheels

    host = zipfile.ZipFile(host_wheel)
    common = set(host.namelist()) - {"wound_opening/libwound_opening.so"}
    common = {n for n in common if not n.endswith("dist-info/RECORD")}
    wheels = {
        p.name.rsplit("-", 1)[1].removesuffix(".whl"): p
        for p in platform_wheels.main(host_wheel, ROOT / "target" / "fmu", out)
    }
    assert sorted(wheels) == sorted(WHEEL_LIBRARIES)
    for tag, path in wheels.items():
        library, is_native = WHEEL_LIBRARIES[tag]
        with zipfile.ZipFile(path) as z:
            names = set(z.namelist())
            record = next(n for n in names if n.endswith(".dist-info/RECORD"))
            assert names - {record} == common | {f"wound_opening/{library}"}, tag
            native = z.read(f"wound_opening/{library}")
            assert is_native(native), tag
            archive, member, _ = platform_wheels.PLATFORMS[tag]
            assert native == zipfile.ZipFile(host.open(f"wound_opening/fmu/{archive}")).read(member)
            wheel_file = next(n for n in names if n.endswith(".dist-info/WHEEL"))
            assert f"Tag: py3-none-{tag}" in z.read(wheel_file).decode().splitlines(), tag
            rows = [r.split(",") for r in z.read(record).decode().splitlines()]
            assert {r[0] for r in rows} == names, tag
            for name, digest, size in rows:
                if name != record:
                    assert (
                        platform_wheels.record_line(name, z.read(name)) == f"{name},{digest},{size}"
                    )
            for name in common - {n for n in names if n.endswith("dist-info/WHEEL")}:
                assert z.read(name) == host.read(name), (tag, name)
    return wheels


def test_wheel_installs_and_runs_without_rust_or_checkout(tmp_path):
    """One test, one build: builds share the checkout's build/ folder, so two in parallel
    (pytest-xdist) would race on it."""
    wheel = build_wheel(tmp_path / "dist")
    names = set(zipfile.ZipFile(wheel).namelist())
    assert "wound_opening/libwound_opening.so" in names
    assert {f"wound_opening/fmu/{name}" for name in FMUS} <= names
    assert {
        f"wound_opening/coupling/{m}.py"
        for m in ("__init__", "__main__", "start", "loop", "example")
    } <= names
    # ctypes, no CPython ABI: any Python 3, one platform.
    assert wheel.name.endswith("-py3-none-linux_x86_64.whl"), wheel.name
    # scripts/wheel.sh's wheels, made from it; the manylinux x86_64 one is installed below.
    wheels = check_platform_wheels(wheel, tmp_path / "platforms")
    wheel = wheels["manylinux_2_17_x86_64"]

    venv, work = tmp_path / "venv", tmp_path / "work"
    work.mkdir()
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("PYTHONPATH", "VIRTUAL_ENV", "WOUND_OPENING_LIB")
    }
    env["PATH"] = _without_rust(os.environ["PATH"])
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=120)
    python = venv / "bin" / "python"
    installed = subprocess.run(
        [
            str(python),
            "-m",
            "pip",
            "install",
            "--quiet",
            "--no-compile",
            "--disable-pip-version-check",
            "-c",
            str(_constraints(tmp_path)),
            str(wheel),
            "fmpy",
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=work,
        timeout=600,
    )
    assert installed.returncode == 0, installed.stderr

    # The command line: a fit of exact data with noise, as in test_cli.
    write_radius(work / "radius.csv")
    fit = subprocess.run(
        [
            str(venv / "bin" / "wound-opening"),
            "fit",
            "radius.csv",
            "--outer-radius-um",
            str(OUTER),
            "--json",
            "fit.json",
        ],
        capture_output=True,
        text=True,
        env=env,
        cwd=work,
        timeout=600,
    )
    assert fit.returncode == 0, fit.stderr
    parameters = json.loads((work / "fit.json").read_text())["parameters"]
    for name, truth in {"R0_um": R0, "sigma": SIGMA, "lambda": LAM, "T_s": T}.items():
        assert abs(parameters[name]["estimate"] - truth) < 7 * parameters[name]["stderr"], (
            name,
            parameters[name],
        )

    # The README's quick start: a microscope export, R0 fixed, a prior on G.
    (work / "examples" / "data").mkdir(parents=True)
    (work / "examples" / "data" / "ablation_export.csv").write_bytes(
        (ROOT / "examples" / "data" / "ablation_export.csv").read_bytes()
    )
    quick = subprocess.run(
        [str(venv / "bin" / "wound-opening"), *readme_quick_start()],
        capture_output=True,
        text=True,
        env=env,
        cwd=work,
        timeout=600,
    )
    assert quick.returncode == 0, quick.stderr
    check_quick_start(work)
    # The README's three-wound fit (examples/data, copied: the checkout stays off the paths).
    for name in TISSUE_COMMAND[:3]:
        shutil.copy(ROOT / "examples" / "data" / name, work)
    tissue = subprocess.run(
        [str(venv / "bin" / "wound-opening"), "fit", *TISSUE_COMMAND, "--json", "tissue.json"],
        capture_output=True,
        text=True,
        env=env,
        cwd=work,
        timeout=600,
    )
    assert tissue.returncode == 0, tissue.stderr
    shared = json.loads((work / "tissue.json").read_text())["shared"]
    for name, truth in TISSUE_TRUTH.items():
        assert (
            shared[name]["identifiable"]
            and shared[name]["ci95"][0] < truth < shared[name]["ci95"][1]
        ), (name, shared)

    # The README's lab quick starts as written: a Fiji table and a PIVlab folder, one wound
    # and three, with their figures and reports (examples/lab copied beside them).
    shutil.copytree(ROOT / "examples" / "lab", work / "examples" / "lab")
    for k, command in enumerate(readme_lab_commands()):
        argv = shlex.split(command)[1:] + ["--json", f"lab{k}.json"]
        lab = subprocess.run(
            [str(venv / "bin" / "wound-opening"), *argv],
            capture_output=True,
            text=True,
            env=env,
            cwd=work,
            timeout=600,
        )
        assert lab.returncode == 0, (command, lab.stderr)
        for option in ("--plot", "--report"):
            out = work / argv[argv.index(option) + 1]
            assert out.stat().st_size > 10_000, out
        result = json.loads((work / f"lab{k}.json").read_text())
        raw = result["settings"]["raw_files"]
        assert all(len(f["sha256"]) == 64 for f in raw if f["path"].endswith((".csv", ".txt")))
        values = result["shared"] if "shared" in result else result["material"]
        for name, truth in LAB_TRUTH.items():
            lo, hi = values[name]["ci95"]
            assert lo < truth < hi, (command, name, values[name])

    # The package's files, and fmpy on the shipped archives.
    stop, step = 20.0, 1.0
    G = 100.0
    material = dict(
        G_pa=G,
        eta_pa_s=LAM**2 * T * G,
        zeta_pa_s_per_um2=4 * T * G / R0**2,
        tension_pa=SIGMA * G,
        R0_um=R0,
        outer_radius_um=OUTER,
    )
    script = PROBE % dict(material=material, fmus=FMUS, stop=stop, step=step)
    probe = subprocess.run(
        [str(python), "-c", script], capture_output=True, text=True, env=env, cwd=work, timeout=300
    )
    assert probe.returncode == 0, probe.stderr
    out = json.loads(probe.stdout)
    assert out["cargo"] is None
    assert not any(
        Path(p).resolve() == ROOT or ROOT in Path(p).resolve().parents for p in out["sys_path"] if p
    )
    package = Path(out["package"]).parent
    assert package.is_relative_to(venv), package
    assert Path(out["library"]) == package / "libwound_opening.so"
    for name, (path, model) in out["fmus"].items():
        assert Path(path) == package / "fmu" / name
        assert model in ("WoundOpening", "PurseString")
    assert out["start"] == pytest.approx(
        {"lambda": LAM, "sigma": SIGMA, "R_inf": OUTER / R0, "R0": R0, "T": T, "G": G}, rel=1e-14
    )
    opening = R0 * (we.final_radius(SIGMA, OUTER / R0) - we.initial_radius(SIGMA))
    for name, (t, radius) in out["radius"].items():
        t, radius = np.array(t), np.array(radius)
        assert t[-1] == pytest.approx(stop)
        keep = t >= 0.01 * T
        exact = R0 * we.edge(LAM, SIGMA, OUTER / R0, t[keep] / T)[0]
        assert np.abs(radius[keep] - exact).max() <= FMU_TOL * opening, name

    # The coupled worked example from the installed package, with its shipped archives.
    coupled = subprocess.run(
        [str(python), "-m", "wound_opening.coupling", "--out", "coupled"],
        capture_output=True,
        text=True,
        env=env,
        cwd=work,
        timeout=300,
    )
    assert coupled.returncode == 0, coupled.stderr
    closure = np.genfromtxt(work / "coupled" / "coupled_closure.csv", delimiter=",", names=True)
    w = {"R0": 10.0, "sigma": 1.0, "lambda": 1.0, "T": 10.0, "R_inf": 10.0}  # docs/model.md
    opening = w["R0"] * (we.final_radius(w["sigma"], w["R_inf"]) - we.initial_radius(w["sigma"]))
    t = closure["time_s"][1:]
    exact = w["R0"] * we.edge(w["lambda"], w["sigma"], w["R_inf"], t / w["T"])[0]
    assert np.abs(closure["free_wound_radius_um"][1:] - exact).max() <= FMU_TOL * opening
    # the purse-string closes the wound: below the free opening by the end
    assert closure["wound_radius_um"][-1] < closure["free_wound_radius_um"][-1] - 5.0


def test_the_source_distribution_carries_what_builds_the_wheel(tmp_path):
    """`python -m build --sdist` on the tracked files (copied, so that no build folder is
    shared with the wheel test): the sdist holds the crate (manifest, lock file, every
    source file and the models' pages) and the C header, and no build output. Building the
    wheel from it compiles the crate from scratch (minutes): see docs/install.md."""
    tracked = subprocess.run(
        ["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, text=True, check=True
    )
    tree = tmp_path / "tree"
    for name in filter(None, tracked.stdout.split("\0")):
        dest = tree / name
        dest.parent.mkdir(parents=True, exist_ok=True)
        dest.write_bytes((ROOT / name).read_bytes())
    built = subprocess.run(
        [sys.executable, "-m", "build", "--sdist", "-o", str(tmp_path / "dist"), str(tree)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert built.returncode == 0, built.stdout[-2000:] + built.stderr[-2000:]
    (sdist,) = (tmp_path / "dist").glob("wound_opening-*.tar.gz")
    import tarfile

    with tarfile.open(sdist) as tar:
        names = {n.split("/", 1)[1] for n in tar.getnames() if "/" in n}
    crate = {n for n in tracked.stdout.split("\0") if n.startswith("src/")} | {
        "Cargo.toml",
        "Cargo.lock",
        "include/wound_opening.h",
    }
    assert crate <= names, sorted(crate - names)
    assert {"setup.py", "pyproject.toml", "python/wound_opening/cli/options.py"} <= names
    assert not any(n.startswith(("target/", ".venv/", "dist/", "build/")) for n in names), sorted(
        names
    )


def readme_lab_commands() -> list[str]:
    """The commands of the README's "Fitting a lab's own files", as written."""
    text = (ROOT / "README.md").read_text()
    section = text[text.index("## Fitting a lab's own files") :]
    blocks = re.findall(r"```(?:bash|sh)?\n(.*?)```", section.split("\n## ")[0], re.S)
    commands = [
        c.strip()
        for b in blocks
        for c in b.replace("\\\n", " ").splitlines()
        if c.strip().startswith("wound-opening fit")
    ]
    assert len(commands) == 2, commands
    return commands
