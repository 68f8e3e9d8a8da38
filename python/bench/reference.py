"""Write OUT/reference_{lam}.csv (rows `t,R`, no header, t = 0.1 .. 100) for the Rust examples.

R is the exact wound radius of the benchmark scenario (`bench.common`), from the
Laplace-domain solution in python/wound_exact.py; `examples/work_precision.rs` measures
every scheme's error against these files.

    python -m bench.reference --out target/bench      (with python/ on PYTHONPATH)
"""

from __future__ import annotations

import argparse
from pathlib import Path

from bench import common


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("target/bench"))
    for path in common.write_reference(parser.parse_args().out):
        print(path)


if __name__ == "__main__":
    main()
