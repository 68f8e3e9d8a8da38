"""The lab instrument (python/bench/lab_movies.py): a small movie rendered from the exact
solution, measured by OpenPIV-python and outlined by scikit-image as ImageJ outlines, its
files read by the package's readers (inputs/fiji.py, inputs/piv.py) and compared with the
exact solution. A test of the instrument, not of the fitter: no fit here.

Bounds, at 0.2 um per pixel and 0.5 s per frame (this seed's values measured in brackets):
- the outline's radius within 1 px (0.2 um) of the exact R(t) in every frame after the cut
  (the blur, the threshold and the pixel grid; -0.11 to +0.02 um);
- the OpenPIV vectors of the windows clear of the wound within 0.25 px per frame rms
  (0.1 um/s; radial 0.043, tangential 0.055 um/s) of the exact displacement of their
  window's material between the pair's two frames, radial and tangential about the true
  centre, their mean error within 0.1 px per frame (0.04 um/s; radial -0.015 um/s): a
  field read in the wrong axes, units or times is off by about its own speed (1 px/frame).
"""

from __future__ import annotations

import numpy as np
from bench.lab_errors import window_truth
from bench.lab_measure import SEARCH_PX, image_px
from bench.lab_movies import measure
from bench.lab_render import Movie, edge_radius_um, render

from wound_opening.inputs.fiji import read_fiji
from wound_opening.inputs.piv import Frames, read_field

MOVIE = Movie(
    R0_um=4.0, sigma=1.0, lam=1.0, T_s=1.0, size_px=160, frames=11, pre_frames=5,
    cut_offset_s=0.2, seed=7,
)  # fmt: skip
RADIUS_PX, PIV_RMS_PX, PIV_MEAN_PX = 1.0, 0.25, 0.1


def test_rendered_movie_measured_by_openpiv_and_outlined(tmp_path):
    m = MOVIE
    frames, truth = render(m)
    assert frames.shape == (m.frames, m.size_px, m.size_px) and frames.dtype == np.uint16
    record = measure(tmp_path, m, frames, truth)
    assert (tmp_path / "movie.tif").stat().st_size > frames.nbytes

    cut = record["cut_after_frame"]
    assert cut == m.pre_frames + 0.4
    series = read_fiji(
        str(tmp_path / "radius.csv"), area_col="Area", frame_col="Slice",
        frame_interval_s=m.frame_s, cut_after_frame=cut,
    )  # fmt: skip
    assert len(series.times_s) == m.frames - m.pre_frames
    exact = edge_radius_um(m, series.times_s)
    err_px = (series.radius_um - exact) / m.pixel_um
    assert np.all(np.abs(err_px) < RADIUS_PX), err_px

    field = read_field(
        str(tmp_path / "piv"), Frames(m.frame_s, cut, first_frame=m.pre_frames + 1),
        units=("um", "um/s"),
    )  # fmt: skip
    pairs = m.frames - m.pre_frames - 1
    assert len(field.files) == pairs
    cx, cy = record["centre_piv_axes_um"]
    errs = []
    for k in range(1, pairs + 1):
        sel = field.pair == k
        a = m.pre_frames + k - 1  # the pair's first frame (0-based)
        assert np.allclose(field.time_s[sel], truth["t_s"][a] + m.frame_s / 2)
        px = image_px(field.x_um[sel], field.y_um[sel], frames.shape[1:], m.pixel_um)
        true = window_truth(m, truth, a, px) / m.frame_s * [1, -1]  # y up, as the files
        d = np.column_stack([field.x_um[sel] - cx, field.y_um[sel] - cy])
        r = np.hypot(d[:, 0], d[:, 1])
        clear = r - SEARCH_PX / np.sqrt(2) * m.pixel_um > edge_radius_um(m, truth["t_s"][a + 1])
        e = np.column_stack([field.u_um_s[sel], field.v_um_s[sel]]) - true
        e_r = np.sum(e * d, 1) / r
        e_t = (e[:, 1] * d[:, 0] - e[:, 0] * d[:, 1]) / r
        errs.append(np.column_stack([e_r, e_t])[clear])
    e_px = np.concatenate(errs) * m.frame_s / m.pixel_um
    assert len(e_px) > 100
    assert np.all(np.sqrt(np.mean(e_px**2, 0)) < PIV_RMS_PX), np.sqrt(np.mean(e_px**2, 0))
    assert np.all(np.abs(e_px.mean(0)) < PIV_MEAN_PX), e_px.mean(0)
