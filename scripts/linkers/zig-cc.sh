#!/bin/sh
# The linker of a Linux target (.cargo/config.toml): zig's `cc` for the zig target that
# names this file (a link to this script), e.g. x86_64-linux-gnu.2.17: glibc 2.17's symbol
# versions. cargo-zigbuild adapts rustc's arguments to zig; both live in
# target/cross-tools (the PyPI packages cargo-zigbuild and ziglang: bash scripts/cross.sh).
tools="$(cd "$(dirname "$0")/../.." && pwd)/target/cross-tools"
if [ ! -x "$tools/bin/cargo-zigbuild" ]; then
    echo "error: no $tools/bin/cargo-zigbuild (the Linux linker): run bash scripts/cross.sh" >&2
    exit 1
fi
export CARGO_ZIGBUILD_ZIG_COMMAND="$tools/bin/python" CARGO_ZIGBUILD_ZIG_COMMAND_ARGS="-m ziglang"
exec "$tools/bin/cargo-zigbuild" zig cc -- -g -fno-sanitize=all -target "$(basename "$0")" "$@"
