"""A wheel for each platform of the FMU archives, from the wheel built on this host
(`pip wheel .`, setup.py): the same Python modules and archives, with the host's library
replaced by the platform's own, taken from the archives (built by
`cargo run --release -- fmu`), under the file name the package loads on that platform
(`wound_opening/_native.py`), and the wheel tagged for it (WHEEL, file name; RECORD
rewritten with the new hashes).

    python python/platform_wheels.py HOST_WHEEL FMU_DIR OUT_DIR

The tags: the Linux libraries need glibc 2.17 at most (manylinux_2_17,
tests/python/test_desk_binaries.py), the Windows one is x86_64 (win_amd64), the macOS one
is darwin64's universal library (x86_64 from macOS 10.12, arm64 from 11.0:
macosx_10_12_universal2, which pip accepts on both).
"""

from __future__ import annotations

import base64
import hashlib
import sys
import zipfile
from pathlib import Path

HOST_LIBRARY = "wound_opening/libwound_opening.so"
#: platform tag -> (archive, its binary, the library's name in the package)
PLATFORMS = {
    "manylinux_2_17_x86_64": (
        "WoundOpening-fmi3.fmu",
        "binaries/x86_64-linux/WoundOpening.so",
        "libwound_opening.so",
    ),
    "manylinux_2_17_aarch64": (
        "WoundOpening-fmi3.fmu",
        "binaries/aarch64-linux/WoundOpening.so",
        "libwound_opening.so",
    ),
    "win_amd64": (
        "WoundOpening-fmi3.fmu",
        "binaries/x86_64-windows/WoundOpening.dll",
        "wound_opening.dll",
    ),
    "macosx_10_12_universal2": (
        "WoundOpening.fmu",
        "binaries/darwin64/WoundOpening.dylib",
        "libwound_opening.dylib",
    ),
}


def record_line(name: str, data: bytes) -> str:
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{name},sha256={digest},{len(data)}"


def retag(host_wheel: Path, fmu_dir: Path, out_dir: Path, tag: str) -> Path:
    archive, member, library = PLATFORMS[tag]
    with zipfile.ZipFile(fmu_dir / archive) as fmu:
        native = fmu.read(member)
    name, version = host_wheel.name.split("-")[:2]
    out = out_dir / f"{name}-{version}-py3-none-{tag}.whl"
    out_dir.mkdir(parents=True, exist_ok=True)
    with zipfile.ZipFile(host_wheel) as src, zipfile.ZipFile(out, "w") as dst:
        files = {}
        for info in src.infolist():
            if info.filename == HOST_LIBRARY or info.filename.endswith(".dist-info/RECORD"):
                continue
            data = src.read(info)
            if info.filename.endswith(".dist-info/WHEEL"):
                lines = data.decode().splitlines()
                lines = [f"Tag: py3-none-{tag}" if x.startswith("Tag:") else x for x in lines]
                data = ("\n".join(lines) + "\n").encode()
            files[info.filename] = data
        files[f"wound_opening/{library}"] = native
        dist_info = next(n for n in files if n.endswith(".dist-info/WHEEL")).rsplit("/", 1)[0]
        record = f"{dist_info}/RECORD"
        lines = [record_line(n, d) for n, d in files.items()] + [f"{record},,"]
        files[record] = ("\n".join(lines) + "\n").encode()
        for filename, data in files.items():
            # deflated, as bdist_wheel does: the archives store their libraries, so the
            # download is about half their size (pip extracts them once)
            dst.writestr(filename, data, zipfile.ZIP_DEFLATED)
    return out


def main(host_wheel: Path, fmu_dir: Path, out_dir: Path) -> list[Path]:
    return [retag(host_wheel, fmu_dir, out_dir, tag) for tag in PLATFORMS]


if __name__ == "__main__":
    for path in main(*map(Path, sys.argv[1:4])):
        print(f"{path} ({path.stat().st_size / 1e6:.1f} MB)")
