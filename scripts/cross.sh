#!/usr/bin/env bash
# The toolchains of the archives' Windows (x86_64-windows) and aarch64 Linux binaries, and
# the emulators that test them (scripts/cross_tests.sh): the Rust targets (rustup), the
# cross linkers .cargo/config.toml names (MinGW-w64, GCC for aarch64 with its C library),
# Wine and qemu-user, with apt-get when missing. Does nothing when all are there. With them,
# `cargo run --release -- fmu` puts win64 / x86_64-windows and aarch64-linux binaries into
# every archive beside the host's (src/package/platforms.rs).
#
#   bash scripts/cross.sh [PACKAGE ...]   also installs each PACKAGE whose command of the
#                                         same name is missing (scripts/test.sh: valgrind,
#                                         chromium), in the same apt-get
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(x86_64-pc-windows-gnu aarch64-unknown-linux-gnu)
installed=$(rustup target list --installed)
for target in "${targets[@]}"; do
    grep -qx "$target" <<<"$installed" || rustup target add "$target"
done
missing=()
command -v x86_64-w64-mingw32-gcc >/dev/null || missing+=(gcc-mingw-w64-x86-64)
command -v aarch64-linux-gnu-gcc >/dev/null || missing+=(gcc-aarch64-linux-gnu)
command -v wine >/dev/null && [ -x /usr/lib/wine/wine64 ] || missing+=(wine wine64)
command -v qemu-aarch64 >/dev/null || missing+=(qemu-user)
for package in "$@"; do
    command -v "$package" >/dev/null || missing+=("$package")
done
if ((${#missing[@]})); then
    echo "== installing ${missing[*]} (Debian packages: cross linkers, emulators, test tools)"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" </dev/null
fi
