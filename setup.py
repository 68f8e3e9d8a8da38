"""Wheel build with setuptools-rust: the native library and the FMU archives go inside the
package `wound_opening`, so that an installed wheel needs neither Rust nor the repository.

* The cdylib (`RustExtension`, `Binding.NoBinding`: a plain C ABI, loaded with ctypes) is
  copied to `wound_opening/libwound_opening.so`.
* Before it, `cargo run --release -- fmu` builds the same library and packs it into the five
  archives, copied to `wound_opening/fmu/` (the archives embed `target/release`'s library,
  so both come from one build).
* The tag is `py3-none-<platform>`: nothing is compiled against CPython.
* An editable install (`pip install -e .`, scripts/venv.sh) builds nothing: the package then
  loads the checkout's `target/release` library and `target/fmu` archives.
"""

import os
import runpy
import shutil
import subprocess
from pathlib import Path

from setuptools import setup
from setuptools.command.bdist_wheel import bdist_wheel
from setuptools_rust import Binding, RustExtension, build_rust

ROOT = Path(__file__).resolve().parent
PACKAGE = "wound_opening"
LIBRARY = "libwound_opening.so"
# The archives `wound_opening.fmu_path` serves (the module has no imports to satisfy here).
FMUS = runpy.run_path(str(ROOT / "python" / PACKAGE / "shipped.py"))["FMUS"]


class BuildNative(build_rust):
    """build_rust that also builds and packs the FMU archives, and skips editable installs."""

    def run(self):
        build_ext = self.get_finalized_command("build_ext")
        if self.inplace or getattr(build_ext, "editable_mode", False):
            return
        # build/lib persists between builds: drop what an earlier one left, so that the
        # wheel holds this build's files or none.
        package = Path(build_ext.build_lib) / PACKAGE
        shutil.rmtree(package / "fmu", ignore_errors=True)
        for stale in package.glob("*.so"):
            stale.unlink()
        subprocess.run(["cargo", "run", "--release", "--quiet", "--", "fmu"], cwd=ROOT, check=True)
        super().run()
        target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
        dest = package / "fmu"
        dest.mkdir(parents=True)
        for name in FMUS:
            shutil.copyfile(target / "fmu" / name, dest / name)

    def get_dylib_ext_path(self, ext, target_fname):
        # build_ext names an extension module `<name>.cpython-3XX-<arch>.so`; a ctypes
        # library keeps its own, version-independent name.
        return str(Path(super().get_dylib_ext_path(ext, target_fname)).with_name(LIBRARY))


class PlatformWheel(bdist_wheel):
    """Tag `py3-none-<platform>`: any Python 3 interpreter, native code for one platform."""

    def get_tag(self):
        return "py3", "none", super().get_tag()[2]


setup(
    # The crate types of Cargo.toml (setuptools-rust would ask for cdylib alone): cargo then
    # finds the library of `cargo build --release` fresh instead of rebuilding it.
    rust_extensions=[
        RustExtension(
            f"{PACKAGE}.{LIBRARY.removesuffix('.so')}",
            path="Cargo.toml",
            binding=Binding.NoBinding,
            args=["--crate-type", "cdylib", "--crate-type", "rlib"],
        )
    ],
    cmdclass={"build_rust": BuildNative, "bdist_wheel": PlatformWheel},
    zip_safe=False,
)
