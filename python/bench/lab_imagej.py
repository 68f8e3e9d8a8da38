"""The wound's outline measured by ImageJ itself (Debian's `imagej`, ImageJ 1.53, under
`xvfb-run`): the macro a lab records, run on DIR/movie.tif, its Results table saved by
ImageJ as DIR/radius_imagej.csv.

The macro: a square ROI about the laser's target duplicated as a stack, Process > Filters >
Gaussian Blur (sigma 2 px, every slice), Set Measurements (area, mean, perimeter, stack
position, 3 decimals), then per slice after the cut: Select None (else the threshold's
histogram is the last outline's), Intermodes auto-threshold (dark objects), the wand at the
target (the outline of the thresholded region holding it, holes included) and Measure;
Results saved as CSV. Needs `apt-get install imagej xvfb xauth` (a Java runtime comes with
imagej); ~4 s for 30 frames of 512 x 512 px.
"""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import numpy as np

JAR = Path("/usr/share/java/ij.jar")

MACRO = """// args: movie|results|cx|cy|half|first (lab_imagej.py)
args = split(getArgument(), "|");
movie = args[0]; out = args[1];
cx = parseInt(args[2]); cy = parseInt(args[3]); half = parseInt(args[4]);
first = parseInt(args[5]);
open(movie);
makeRectangle(cx - half, cy - half, 2 * half + 1, 2 * half + 1);
run("Duplicate...", "title=roi duplicate");
run("Gaussian Blur...", "sigma=2 stack");
run("Set Measurements...", "area mean perimeter stack redirect=None decimal=3");
run("Clear Results");
for (s = first; s <= nSlices; s++) {
    setSlice(s);
    run("Select None");
    setAutoThreshold("Intermodes");
    doWand(half, half);
    run("Measure");
}
saveAs("Results", out);
run("Quit");
"""


def available() -> str | None:
    """None when ImageJ can run here, else what is missing."""
    missing = [t for t in ("java", "xvfb-run") if shutil.which(t) is None]
    if not JAR.exists():
        missing.append(str(JAR))
    return ", ".join(missing) or None


def measure_imagej(out: Path, target_px, roi_half_px: int, first_slice: int, frames: int):
    """Runs the macro on out/movie.tif; returns the radius [um] per frame (NaN where not
    measured) from ImageJ's Results table out/radius_imagej.csv (areas in um^2: the TIFF
    carries the pixel size)."""
    macro = out / "outline_imagej.ijm"
    macro.write_text(MACRO)
    results = out / "radius_imagej.csv"
    cx, cy = (int(round(c)) for c in target_px)
    arg = "|".join(map(str, (out / "movie.tif", results, cx, cy, roi_half_px, first_slice)))
    cmd = ["xvfb-run", "-a", "java", "-Xmx1g", "-jar", str(JAR), "-macro", str(macro), arg]
    subprocess.run(cmd, check=True, capture_output=True, timeout=600)
    radius = np.full(frames, np.nan)
    lines = results.read_text().splitlines()
    head = [h.strip() for h in lines[0].split(",")]
    for line in lines[1:]:
        row = dict(zip(head, line.split(",")))
        radius[int(row["Slice"]) - 1] = math.sqrt(float(row["Area"]) / math.pi)
    return radius
