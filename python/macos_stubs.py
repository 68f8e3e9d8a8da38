"""Writes the macOS system-library stubs that rust-lld links the darwin libraries against
(.cargo/config.toml): zig's `libSystem.tbd` (the `ziglang` package of this interpreter, a
text list of the symbols each library of /usr/lib/system exports), with its architecture
names made those of ld64.lld (`arm64e-macos` -> `arm64-macos`; Mac Catalyst and arm64e.x1
left out), as usr/lib/libSystem.tbd and, for Rust's `-lc -lm`, usr/lib/libc.tbd and
usr/lib/libm.tbd (on macOS both are libSystem itself): OUT_DIR is then a minimal SDK root
(SDKROOT, which rustc hands to the linker as -syslibroot).

    python python/macos_stubs.py OUT_DIR
"""

import re
import sys
from pathlib import Path

import ziglang

KEEP = {"x86_64-macos": "x86_64-macos", "arm64-macos": "arm64-macos", "arm64e-macos": "arm64-macos"}


def targets(match: re.Match) -> str:
    names = [n.strip() for n in match.group(1).replace("\n", " ").split(",")]
    kept = dict.fromkeys(KEEP[n] for n in names if n in KEEP)
    return f"targets: [ {', '.join(kept)} ]"


def main(out: Path) -> None:
    source = Path(ziglang.__file__).parent / "lib" / "libc" / "darwin" / "libSystem.tbd"
    text = re.sub(r"targets:\s*\[([^\]]*)\]", targets, source.read_text())
    lib = out / "usr" / "lib"
    lib.mkdir(parents=True, exist_ok=True)
    for name in ("libSystem.tbd", "libc.tbd", "libm.tbd"):
        (lib / name).write_text(text)


if __name__ == "__main__":
    main(Path(sys.argv[1]))
