"""The wound centre from the flow of a rendered movie measured by OpenPIV, against the true
centre (python/bench/lab_render.py's, moved by the 4 px by which OpenPIV's tutorial states
its positions off the windows it correlated: the flow's centre in the files' axes).

Draw 4 of the coverage study (bench/lab_coverage.py: R0 11.8 um, 1 s frames, 256 px at
0.2 um): with the vectors beyond the interrogation window's reach of the wound (32 px, the
fit's own selection for its rings) the centre came out 16.9 um from the truth with standard
errors of 2.4 and 2.7 um; from the vectors beyond one grid step, 0.19 um (0.16, 0.27). The
bound: within 1 um, and within 3 of its own standard errors (chi-square, 2 degrees of
freedom, 1 %: 3.03). About 8 s of CPU (render and measure).
"""

from __future__ import annotations

import math

from bench.lab_coverage import movie
from bench.lab_movies import measure
from bench.lab_render import render

from wound_opening.cli.lab import window_of
from wound_opening.inputs.fiji import read_fiji
from wound_opening.inputs.piv import Frames, read_field
from wound_opening.inputs.rings import Measurement, flow_centre

DRAW, WITHIN_UM, WITHIN_SD = 4, 1.0, 3.03


def test_centre_of_a_large_wound_from_openpiv_files_holds_the_truth(tmp_path):
    m = movie(DRAW, 256)
    frames, truth = render(m)
    record = measure(tmp_path, m, frames, truth)
    n = int(record["cut_after_frame"])
    radius = read_fiji(
        str(tmp_path / "radius.csv"), area_col="Area", frame_col="Slice",
        frame_interval_s=m.frame_s, cut_after_frame=n,
    )  # fmt: skip
    field = read_field(
        str(tmp_path / "piv"), Frames(m.frame_s, n, first_frame=n + 1), units=("um", "um/s")
    )
    window = window_of("32px", None, field)  # the fit command's default for these files
    measurement = Measurement(
        field.pair, field.x_um, field.y_um, field.spacing_um, m.frame_s, window
    )
    centre = flow_centre(field, radius, m.outer_um, measurement)
    off = [o * m.pixel_um for o in record["piv_stated_offset_px"]]
    x0, y0 = record["centre_piv_axes_um"]
    dx, dy = centre.x_um - (x0 + off[0]), centre.y_um - (y0 - off[1])
    print(f"centre off by ({dx:.3f}, {dy:.3f}) um, sd ({centre.sd_x_um:.3f}, {centre.sd_y_um:.3f})")
    assert math.hypot(dx, dy) < WITHIN_UM
    assert math.hypot(dx / centre.sd_x_um, dy / centre.sd_y_um) < WITHIN_SD
