"""The lab instrument (python/bench/lab_movies.py): a small movie rendered from the exact
solution, measured by OpenPIV-python and outlined by scikit-image as ImageJ outlines, its
files read by the package's readers (inputs/fiji.py, inputs/piv.py) and compared with the
exact solution. A test of the instrument, not of the fitter: no fit here.

One sample per pixel (the benchmark's movies take 2 x 2) keeps it small: 3 s of CPU.
Bounds, at 0.2 um per pixel and 0.5 s per frame (this movie's values measured in brackets):
- the outline's radius within 1 px (0.2 um) of the exact R(t) in every frame after the cut
  (the blur, the threshold and the pixel grid; -0.48 to -0.36 px);
- the OpenPIV vectors of the windows clear of the wound: their error from the exact
  displacement of their window's material between the pair's two frames, radial and
  tangential about the true centre, within 0.25 px per frame rms (0.115, 0.146) and 0.1 px
  per frame on average (+0.023, +0.003); the measured radial velocity over the exact one
  (least squares) within 0.85 to 1.15 (1.113: sub-pixel displacements read about 10 % high
  here, 0.26 px per frame rms); a field read in other axes (y down), units (px) or times
  (another pair) fails these. The windows are where OpenPIV correlated them: the tutorial's
  `get_coordinates` writes them 4 px right of and below that (asserted).
"""

from __future__ import annotations

import numpy as np
from bench.lab_errors import window_truth
from bench.lab_measure import SEARCH_PX, image_px, stated_offset_px
from bench.lab_movies import measure
from bench.lab_render import Movie, edge_radius_um, render

from wound_opening.inputs.fiji import read_fiji
from wound_opening.inputs.piv import Frames, read_field

MOVIE = Movie(
    R0_um=4.0, sigma=1.0, lam=3.0, T_s=0.25, size_px=192, frames=11, pre_frames=5,
    cut_offset_s=0.2, seed=7, supersample=1,
)  # fmt: skip
RADIUS_PX, PIV_RMS_PX, PIV_MEAN_PX, SLOPE = 1.0, 0.25, 0.1, (0.85, 1.15)


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
    # OpenPIV's tutorial writes positions 4 px right of and below the windows it correlated
    offset = stated_offset_px(frames.shape[1:])
    assert offset == (4.0, 4.0)
    centre = image_px(*record["centre_piv_axes_um"], frames.shape[1:], m.pixel_um)
    assert np.allclose(centre, m.centre())
    errs, v_r = [], []
    for k in range(1, pairs + 1):
        sel = field.pair == k
        a = m.pre_frames + k - 1  # the pair's first frame (0-based)
        assert np.allclose(field.time_s[sel], truth["t_s"][a] + m.frame_s / 2)
        px = image_px(field.x_um[sel], field.y_um[sel], frames.shape[1:], m.pixel_um) - offset
        true = window_truth(m, truth, a, px) / m.frame_s  # image axes, y down
        d = px - m.centre()
        r = np.hypot(d[:, 0], d[:, 1])
        clear = r - SEARCH_PX / np.sqrt(2) > edge_radius_um(m, truth["t_s"][a + 1]) / m.pixel_um
        e = np.column_stack([field.u_um_s[sel], -field.v_um_s[sel]]) - true
        e_r = np.sum(e * d, 1) / r
        e_t = (e[:, 1] * d[:, 0] - e[:, 0] * d[:, 1]) / r
        errs.append(np.column_stack([e_r, e_t])[clear])
        v_r.append(np.sum(true * d, 1)[clear] / r[clear])
    e_px = np.concatenate(errs) * m.frame_s / m.pixel_um
    true_px = np.concatenate(v_r) * m.frame_s / m.pixel_um
    slope = 1 + np.sum(e_px[:, 0] * true_px) / np.sum(true_px**2)
    print(f"PIV: {len(e_px)} vectors, exact radial rms {np.sqrt(np.mean(true_px**2)):.3f} px/frame")
    print(f"errors rms {np.sqrt(np.mean(e_px**2, 0))}, mean {e_px.mean(0)} px/frame")
    print(f"measured radial on exact: slope {slope:.3f}; outline {err_px} px")
    assert SLOPE[0] < slope < SLOPE[1], slope
    assert len(e_px) > 100
    assert np.all(np.sqrt(np.mean(e_px**2, 0)) < PIV_RMS_PX), np.sqrt(np.mean(e_px**2, 0))
    assert np.all(np.abs(e_px.mean(0)) < PIV_MEAN_PX), e_px.mean(0)
