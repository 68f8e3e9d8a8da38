"""Python side of the benchmarks: exact references, two peers written the way a
researcher would (SciPy method of lines, the paper's scheme in NumPy), fmpy timing, and
every chart and docs/benchmarks.md. `bash scripts/bench.sh` runs it all."""
