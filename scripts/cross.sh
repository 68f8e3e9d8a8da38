#!/usr/bin/env bash
# The toolchains of the archives' binaries (src/package/platforms.rs, linkers in
# .cargo/config.toml), each installed only when missing:
#   - the Rust targets of Windows x86_64, Linux aarch64 and macOS x86_64 and arm64 (rustup);
#   - target/cross-tools, a venv with the PyPI packages ziglang and cargo-zigbuild: zig
#     links both Linux libraries (this host's too) against glibc 2.17;
#   - target/macos-stubs: libSystem's symbol lists for rust-lld (python/macos_stubs.py);
#   - MinGW-w64, the Windows linker (apt-get).
# With them, `cargo run --release -- fmu` puts all five platforms into every archive.
#
#   bash scripts/cross.sh                  the above (scripts/main.sh, scripts/wheel.sh)
#   bash scripts/cross.sh --zig            the zig venv alone (the linker of every host build)
#   bash scripts/cross.sh --tests [PKG...] also what only the tests run (scripts/test.sh):
#                                          GCC for aarch64 with its C library (the C test
#                                          programs), Wine and qemu-user, and each PKG whose
#                                          command of the same name is missing (valgrind,
#                                          chromium), in the same apt-get
set -euo pipefail
cd "$(dirname "$0")/.."
tools=target/cross-tools
if [ ! -x "$tools/bin/cargo-zigbuild" ]; then
    echo "== $tools: ziglang and cargo-zigbuild (the Linux linker)"
    python3 -m venv "$tools"
    "$tools/bin/python" -m pip install --quiet --disable-pip-version-check ziglang==0.17.1 cargo-zigbuild==0.24.1
fi
[ "${1:-}" = --zig ] && exit 0
if [ ! -f target/macos-stubs/usr/lib/libSystem.tbd ]; then
    "$tools/bin/python" python/macos_stubs.py target/macos-stubs
fi
targets=(x86_64-pc-windows-gnu aarch64-unknown-linux-gnu x86_64-apple-darwin aarch64-apple-darwin)
installed=$(rustup target list --installed)
for target in "${targets[@]}"; do
    grep -qx "$target" <<<"$installed" || rustup target add "$target"
done
missing=()
command -v x86_64-w64-mingw32-gcc >/dev/null || missing+=(gcc-mingw-w64-x86-64)
if [ "${1:-}" = --tests ]; then
    shift
    command -v aarch64-linux-gnu-gcc >/dev/null || missing+=(gcc-aarch64-linux-gnu)
    command -v wine >/dev/null && [ -x /usr/lib/wine/wine64 ] || missing+=(wine wine64)
    command -v qemu-aarch64 >/dev/null || missing+=(qemu-user)
    for package in "$@"; do
        command -v "$package" >/dev/null || missing+=("$package")
    done
fi
if ((${#missing[@]})); then
    echo "== installing ${missing[*]} (Debian packages)"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" </dev/null
fi
