#!/bin/sh
# The linker of a Linux target (.cargo/config.toml): zig's `cc` for the zig target that
# names this file (a link to this script), e.g. x86_64-linux-gnu.2.17: glibc 2.17's symbol
# versions. cargo-zigbuild adapts rustc's arguments to zig; both live in
# target/cross-tools (the PyPI packages cargo-zigbuild and ziglang: bash scripts/cross.sh).
tools="$(cd "$(dirname "$0")/../.." && pwd)/target/cross-tools"
if [ ! -x "$tools/bin/cargo-zigbuild" ]; then
    # Without zig (a plain `cargo build` before any script ran), the host's own library links
    # with its C compiler: it runs here, without the glibc 2.17 floor the scripts' builds have
    # (the archives and wheels: the test command checks the floor).
    case "$(basename "$0")" in
    "$(uname -m)"-linux-gnu.*) exec cc "$@" ;;
    esac
    echo "error: no $tools/bin/cargo-zigbuild (the Linux linker): run bash scripts/cross.sh" >&2
    exit 1
fi
export CARGO_ZIGBUILD_ZIG_COMMAND="$tools/bin/python" CARGO_ZIGBUILD_ZIG_COMMAND_ARGS="-m ziglang"
exec "$tools/bin/cargo-zigbuild" zig cc -- -g -fno-sanitize=all -target "$(basename "$0")" "$@"
