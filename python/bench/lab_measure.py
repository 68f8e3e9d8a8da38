"""A rendered movie (lab_render.py) measured as a lab measures one, files written as the
programs write them.

Velocity: OpenPIV-python, its tutorial's calls (openpiv/tutorials/tutorial1.py) with windows
32 / 40 px and overlap 24: `pyprocess.extended_search_area_piv` (peak2peak signal to noise),
`validation.sig2noise_val` and `validation.global_val`, `filters.replace_outliers`
(local mean), `scaling.uniform` (px per um: the files are in um and um/s), then
`tools.transform_coordinates` (y up, the grid's rows reversed) and `tools.save`: one file per
frame pair, `piv/field_NNNN.txt`.

Outline: what ImageJ's Process > Filters > Gaussian Blur, Image > Adjust > Threshold
(Intermodes, dark objects) and Analyze > Analyze Particles (include holes, the particle at
the laser's target) do, on a square region around the wound (a lab's ROI): scikit-image's
`filters.gaussian`; the threshold by ImageJ's Intermodes (Prewitt and Mendelsohn 1966, as
ImageJ's AutoThresholder does it on a 16-bit image: a 256-bin histogram between the ROI's
minimum and maximum, smoothed by a 3-point running mean until it has exactly two local
maxima j < k, threshold at bin floor((j + k) / 2)), or scikit-image's `threshold_minimum`
(the minimum between those modes) or `threshold_otsu`; `ndimage.binary_fill_holes`, the
connected dark region containing the target, its pixel count times the pixel area; written
as ImageJ saves its Results table (" ,Area,Mean,Perim.,Slice", 3 decimals, um^2 when
calibrated).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from openpiv import filters, pyprocess, scaling, tools, validation
from scipy import ndimage
from skimage import filters as skfilters
from skimage import measure

WINDOW_PX, SEARCH_PX, OVERLAP_PX = 32, 40, 24
S2N_THRESHOLD = 1.05
BLUR_PX = 2.0


def piv_pair(frame_a, frame_b, frame_s: float, pixel_um: float):
    """One frame pair as OpenPIV's tutorial measures it: (x, y, u, v, flags) after scaling
    and transform_coordinates (um, um/s, y up), and the centres of the windows correlated
    in image px (lab_render's axes; the file states them `stated_offset_px` further)."""
    a, b = frame_a.astype(np.int32), frame_b.astype(np.int32)
    u, v, s2n = pyprocess.extended_search_area_piv(
        a,
        b,
        window_size=WINDOW_PX,
        overlap=OVERLAP_PX,
        dt=frame_s,
        search_area_size=SEARCH_PX,
        sig2noise_method="peak2peak",
    )
    x, y = pyprocess.get_coordinates(
        image_size=a.shape, search_area_size=SEARCH_PX, overlap=OVERLAP_PX
    )
    x0, y0 = _grid(a.shape, False)  # the windows correlated, in lab_render's axes:
    px_img = np.column_stack([x0.ravel() - 0.5, y0.ravel() - 0.5])
    flags_s2n = validation.sig2noise_val(s2n, threshold=S2N_THRESHOLD)
    limit = SEARCH_PX / frame_s  # px/s: a displacement beyond the search area is no vector
    flags_g = validation.global_val(u, v, (-limit, limit), (-limit, limit))
    flags = flags_s2n | flags_g
    u, v = filters.replace_outliers(u, v, flags, method="localmean", max_iter=10, kernel_size=2)
    x, y, u, v = scaling.uniform(x, y, u, v, scaling_factor=1.0 / pixel_um)
    x, y, u, v = tools.transform_coordinates(x, y, u, v)
    return x, y, u, v, flags, px_img


def write_piv(folder: Path, frames, first: int, frame_s: float, pixel_um: float) -> dict:
    """OpenPIV files of pairs (first, first + 1), ..., (last - 1, last) (0-based frame
    indices); returns per pair the window centres (image px), u, v (um/s, image axes: y
    down) and flags, for the error study."""
    folder.mkdir(parents=True, exist_ok=True)
    out = {"a": [], "u": [], "v": [], "flags": []}
    for k, a in enumerate(range(first, len(frames) - 1), start=1):
        x, y, u, v, flags, px = piv_pair(frames[a], frames[a + 1], frame_s, pixel_um)
        tools.save(str(folder / f"field_{k:04d}.txt"), x, y, u, v, flags)
        out["a"].append(a)
        out["u"].append(np.asarray(u, float).ravel())
        out["v"].append(-np.asarray(v, float).ravel())  # back to image axes (y down)
        out["flags"].append(np.asarray(flags).ravel())
        out["px"] = px
    return out


def _grid(image_shape, centred: bool):
    """OpenPIV's window centres (x, y), its pixel-edge convention (pixel k spans [k, k + 1))."""
    x, y = pyprocess.get_coordinates(
        image_size=image_shape,
        search_area_size=SEARCH_PX,
        overlap=OVERLAP_PX,
        center_on_field=centred,
    )
    return x, y


def stated_offset_px(image_shape) -> tuple[float, float]:
    """How far (x, y, px) the positions the tutorial writes (get_coordinates, which centres
    the grid on the image by default) lie right of and below the windows that
    extended_search_area_piv correlated (sliding_window_array: from the image's corner):
    4 px each at 192, 256 and 512 px for windows 40 px, overlap 24."""
    (xc, yc), (x0, y0) = _grid(image_shape, True), _grid(image_shape, False)
    return float(xc.flat[0] - x0.flat[0]), float(yc.flat[0] - y0.flat[0])


def file_axes_centre_um(centre_px, image_shape, pixel_um: float) -> tuple[float, float]:
    """A point of the image (px, pixel centres at integers: lab_render's axes) in the OpenPIV
    files' axes: OpenPIV's pixel-edge convention (+ 0.5 px), x scaled, y as
    transform_coordinates leaves it (the rows reversed: y' = y_first + y_last - y), scaled."""
    _, y = _grid(image_shape, True)
    ys = np.unique(y)
    return ((centre_px[0] + 0.5) * pixel_um, (ys[0] + ys[-1] - centre_px[1] - 0.5) * pixel_um)


def image_px(x_um, y_um, image_shape, pixel_um: float) -> np.ndarray:
    """Image px (n, 2: lab_render's axes) of positions in the OpenPIV files' axes (the inverse
    of `file_axes_centre_um`)."""
    _, y = _grid(image_shape, True)
    ys = np.unique(y)
    x = np.asarray(x_um) / pixel_um - 0.5
    return np.column_stack([x, ys[0] + ys[-1] - np.asarray(y_um) / pixel_um - 0.5])


def intermodes(image) -> float:
    """ImageJ's Intermodes threshold of an image (module docstring), in grey values: the
    upper edge of bin floor((j + k) / 2)."""
    lo, hi = float(image.min()), float(image.max())
    hist, edges = np.histogram(image, bins=256, range=(lo, hi))
    h = hist.astype(float)
    for _ in range(10000):
        peaks = np.flatnonzero((h[1:-1] > h[:-2]) & (h[1:-1] > h[2:])) + 1
        if len(peaks) <= 2:
            break
        h = np.convolve(np.pad(h, 1, mode="edge"), np.ones(3) / 3, mode="valid")
    if len(peaks) != 2:
        raise RuntimeError("Intermodes: no two modes")
    return float(edges[(peaks[0] + peaks[1]) // 2 + 1])


THRESHOLDS = {
    "intermodes": intermodes,
    "minimum": skfilters.threshold_minimum,
    "otsu": skfilters.threshold_otsu,
}


def outline(frame, target_px, roi_half_px: int, method: str = "intermodes") -> dict:
    """The wound's particle in one frame (module docstring): area [px^2], mean grey value,
    perimeter [px], threshold, or area 0 where no dark region holds the target."""
    cx, cy = (int(round(c)) for c in target_px)
    r0, c0 = max(cy - roi_half_px, 0), max(cx - roi_half_px, 0)
    roi = frame[r0 : cy + roi_half_px + 1, c0 : cx + roi_half_px + 1].astype(float)
    smooth = skfilters.gaussian(roi, sigma=BLUR_PX, preserve_range=True)
    try:
        thr = THRESHOLDS[method](smooth)
    except RuntimeError:  # no two modes: what a lab then does, Otsu's
        thr = skfilters.threshold_otsu(smooth)
    dark = ndimage.binary_fill_holes(smooth <= thr)
    labels, _ = ndimage.label(dark)
    lab = labels[cy - r0, cx - c0]
    if lab == 0:
        return {"area": 0.0, "mean": math.nan, "perim": 0.0, "thr": thr}
    region = labels == lab
    return {
        "area": float(region.sum()),
        "mean": float(roi[region].mean()),
        "perim": float(measure.perimeter(region)),
        "thr": float(thr),
        "edge": bool(
            region[0].any() or region[-1].any() or region[:, 0].any() or region[:, -1].any()
        ),
    }


def write_results(
    path: Path, frames, first: int, target_px, roi_half_px, pixel_um, method="intermodes"
) -> dict:
    """The Fiji Results table of frames first.. (0-based; Slice = index + 1), areas in um^2;
    returns the measured radii [um] per frame (NaN where no particle)."""
    rows, radius = [" ,Area,Mean,Perim.,Slice"], np.full(len(frames), np.nan)
    for k in range(first, len(frames)):
        o = outline(frames[k], target_px, roi_half_px, method)
        if o["area"] == 0 or o.get("edge"):
            continue  # no particle (or one leaving the ROI): Analyze Particles lists none
        area_um2 = o["area"] * pixel_um**2
        radius[k] = math.sqrt(area_um2 / math.pi)
        rows.append(
            f"{len(rows)},{area_um2:.3f},{o['mean']:.3f},{o['perim'] * pixel_um:.3f},{k + 1}"
        )
    path.write_text("\n".join(rows) + "\n")
    return {"radius_um": radius}
