"""The archives' macOS and Linux libraries, checked without running them (no Mac here; the
Linux ones also run under the other tests): every archive holds x86_64-darwin and
aarch64-darwin (FMI 3.0) or a universal darwin64 (FMI 2.0), and each macOS slice is a
dylib for its architecture, linked against libSystem alone, with its stated minimum macOS,
no build path, no symbol table beyond what dyld exports, exactly the C functions the Linux
library of the same archive exports, and (arm64) an ad-hoc signature whose page hashes
match its code. The Linux libraries need no glibc symbol version newer than 2.17.
"""

from __future__ import annotations

import re
import subprocess
import zipfile
from pathlib import Path

import macho
import pytest
from test_pinned_interface import exported_symbols

ROOT = Path(__file__).resolve().parents[2]
FMI2 = ("WoundOpening.fmu", "WoundOpening-me.fmu", "PurseString.fmu")
FMI3 = ("WoundOpening-fmi3.fmu", "PurseString-fmi3.fmu")
# folder -> architectures of its library; the Linux x86_64 folder of the same archive
DARWIN = {
    "fmi2": {"darwin64": ["arm64", "x86_64"]},
    "fmi3": {"x86_64-darwin": ["x86_64"], "aarch64-darwin": ["arm64"]},
}
LINUX = {"fmi2": ("linux64", "aarch64-linux"), "fmi3": ("x86_64-linux", "aarch64-linux")}
MINIMUM_MACOS = {"x86_64": (10, 12), "arm64": (11, 0)}
MH_DYLIB = 6
GLIBC_FLOOR = (2, 17)
CASES = [(a, v) for v, archives in (("fmi2", FMI2), ("fmi3", FMI3)) for a in archives]


def extract(fmu: Path, folder: str, tmp_path: Path) -> Path:
    with zipfile.ZipFile(fmu) as z:
        names = [n for n in z.namelist() if n.startswith(f"binaries/{folder}/")]
        assert len(names) == 1, (fmu.name, folder, names)
        path = tmp_path / folder / Path(names[0]).name
        path.parent.mkdir(parents=True)
        path.write_bytes(z.read(names[0]))
    return path


@pytest.mark.parametrize("archive, version", CASES)
def test_macos_libraries_headers(archive, version, tmp_path, fmu_path):
    fmu = Path(fmu_path).parent / archive
    linux = [f"_{name}" for name in exported_symbols(fmu, LINUX[version][0])]
    assert len(linux) > 100 and all(re.match(r"_(fmi2|fmi3|wo_)", n) for n in linux), linux
    for folder, archs in DARWIN[version].items():
        slices = macho.read(extract(fmu, folder, tmp_path))
        assert sorted(s.arch for s in slices) == archs, (folder, slices)
        for s in slices:
            where = (archive, folder, s.arch)
            assert s.filetype == MH_DYLIB, where
            assert s.dylibs == ["/usr/lib/libSystem.B.dylib"], where
            assert s.install_name == "@rpath/libwound_opening.dylib", where
            assert s.minimum_os == MINIMUM_MACOS[s.arch], where
            assert s.exports == linux, where
            assert s.local_symbols == 0, where
            if s.arch == "arm64":
                sig = s.signature
                assert sig and sig["adhoc"] and sig["covers_code"] and sig["hashes_ok"], sig


@pytest.mark.parametrize("archive, version", CASES)
def test_linux_libraries_need_glibc_2_17_at_most(archive, version, tmp_path, fmu_path):
    fmu = Path(fmu_path).parent / archive
    for folder in LINUX[version]:
        library = extract(fmu, folder, tmp_path)
        out = subprocess.run(
            ["readelf", "--version-info", "-W", str(library)],
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        needed = {tuple(map(int, v)) for v in re.findall(r"Name: GLIBC_(\d+)\.(\d+)", out)}
        assert needed and max(needed) <= GLIBC_FLOOR, (archive, folder, sorted(needed))
