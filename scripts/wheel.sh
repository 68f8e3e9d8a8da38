#!/usr/bin/env bash
# The wheels, one per platform of the archives, into dist/: manylinux_2_17 x86_64 and
# aarch64, win_amd64 and macosx_10_12_universal2, each with the Python package, the five
# FMU archives (every platform inside) and its own platform's library (docs/install.md).
# Needs Rust and the cross toolchains (scripts/cross.sh, run here), not the development
# environment: pip builds this host's wheel in its isolated build environment (setuptools,
# setuptools-rust; setup.py builds the archives), python/platform_wheels.py makes each
# platform's wheel from it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/cross.sh
rm -rf dist
python3 -m pip wheel . --no-deps --quiet --disable-pip-version-check -w dist/host
python3 python/platform_wheels.py dist/host/wound_opening-*.whl target/fmu dist
rm -rf dist/host
