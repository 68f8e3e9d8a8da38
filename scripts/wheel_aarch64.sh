#!/usr/bin/env bash
# The aarch64 wheel installed and run in an aarch64 Python under qemu-user
# (python/bench/wheel_aarch64.py; docs/install.md): too slow for scripts/test.sh (about
# 75 s of pip under emulation), so run on its own. Installs debootstrap and qemu-user
# (apt-get) when missing, builds the wheels (scripts/wheel.sh) when dist/ has no aarch64
# one, keeps the arm64 Debian root in target/arm64-root for the next run.
set -euo pipefail
cd "$(dirname "$0")/.."
missing=()
command -v debootstrap >/dev/null || missing+=(debootstrap)
command -v qemu-aarch64 >/dev/null || missing+=(qemu-user)
if [ ${#missing[@]} -gt 0 ]; then
    echo "== apt-get install ${missing[*]}"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" </dev/null
fi
compgen -G "dist/*-manylinux_2_17_aarch64.whl" >/dev/null || bash scripts/wheel.sh
source scripts/venv.sh
export PYTHONPATH="$PWD/python${PYTHONPATH:+:$PYTHONPATH}"
python -m bench.wheel_aarch64 "$@"
