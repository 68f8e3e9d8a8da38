"""The PIV field against the radius series at the wound edge: the edge is made of tissue, so
the tissue's radial velocity at r = R(t) is the edge speed dR/dt. A velocity unit read wrong
(px/s read as px/frame: times 1 / frame interval), or a frame interval or pair timing wrong,
breaks this by a constant factor, and the fit then turns the mismatch into a confident wrong
material (sigma 2.5 times the truth, "identified", exit 0, on the examples' tissue with
px/s read as px/frame at 4 frames/s). Checked per frame pair k, before any fit:

    a_k = mean over the vectors with R_k <= r <= R_k + EDGE_BAND_UM of v_r r / R_k
    b_k = dR/dt at t_k, the slope at t_k of the widest parabola, through the radii within
          10, 5 or 3 frame intervals of t_k (least squares), that has two radii or more on
          either side of t_k (no extrapolation) and follows them: its residuals' rms within
          twice the radii's noise s (truncate.noise_of: from the second differences, robust,
          so that the opening's few steep frames and an outline's jumps do not move it); no
          b_k where none does
    q   = sum a_k b_k / sum b_k^2 over the pairs whose b_k is over 3 of its standard errors

v_r r / R extrapolates the velocity to the edge as 1/r (incompressible flow about a hole).
The ten-frame parabola alone, the check's earlier b_k, refused correct fields: extrapolated
before a table that starts two frames after the cut (a rendered movie of R0 = 3.7 um,
T = 0.28 frame: q = 3.37), and, on an opening done within two frames with no creep after
it, q = 0.0034 (tests/python/test_edge_speed.py); there no parabola follows the radii now
and the check is not made. Measured on python/make_lab_examples.py's wounds (R0 = 4, 8,
16 um, six pairs): q = 0.871 to 0.877 noise-free (five pairs used), 0.707 +- 0.15 and
0.783 +- 0.062 with its noise (0.3 px on the radius, 0.05 um/s per component, the centre
estimated; R0 = 8 and 16 um), px/s read as px/frame at 4 frames/s 3.48 to 3.51 noise-free,
2.83 +- 0.62 and 3.13 +- 0.25 with the noise; on the OpenPIV fields of the 20 rendered
movies of python/bench/lab_coverage.py 0.45 to 1.26 (scratch re-reading of their files,
2026-12-07). Refused when q is outside [1 / EDGE_FACTOR, EDGE_FACTOR]: a velocity off by a
factor 4 or more (a frame interval of 0.25 s or less, or 4 s or more, read as the wrong one
of px/s and px/frame; any ms/s mix-up) is caught, a factor 2 is not; but not where q is
within 3 of its standard errors of a correct field's (EDGE_TYPICAL), from the errors of a_k
(the spread of v_r r / R_k over the band, over the square root of their number) and of b_k,
to first order: the examples' noisy 4 um wound reads q = -0.17 +- 0.41 from two pairs, which
was refused, and the refusal's message failed on the negative q. Unchecked when no pair has
a measurable edge speed (the sentence says how many pairs were used)."""

from __future__ import annotations

import math

import numpy as np

from .columns import InputError
from .truncate import noise_of

EDGE_BAND_UM = 8.0
EDGE_FRAMES = 10
#: The half-widths in frames of the parabolas tried for a pair's edge speed, widest first.
EDGE_WINDOWS = (EDGE_FRAMES, 5, 3)
EDGE_FACTOR = 2.5


def _slope(t, R, t0, dt, frames: int, noise: float):
    """(dR/dt at t0, its standard error, R at t0) of a parabola through the radii within
    `frames` frame intervals of t0, or None: fewer than six, fewer than two on either side
    of t0 (no extrapolation), or a parabola that does not follow them (residuals' rms over
    twice the radii's `noise`: an opening faster than the window)."""
    near = np.abs(t - t0) <= frames * dt
    if (
        near.sum() < 6
        or np.count_nonzero(near & (t < t0)) < 2
        or np.count_nonzero(near & (t > t0)) < 2
    ):
        return None
    x = t[near] - t0
    A = np.column_stack([np.ones(x.size), x, x**2])
    coef, *_ = np.linalg.lstsq(A, R[near], rcond=None)
    dof = x.size - 3
    s2 = float(np.sum((R[near] - A @ coef) ** 2)) / dof
    if s2 > (2 * noise) ** 2:
        return None
    cov = s2 * np.linalg.inv(A.T @ A)
    return float(coef[1]), math.sqrt(max(float(cov[1, 1]), 0.0)), float(coef[0])


def _speed(t, R, t0, dt, noise):
    """(dR/dt at t0, its standard error, R at t0): the slope of the widest parabola
    (EDGE_WINDOWS) that follows the radii about t0, or None where none does (module
    docstring)."""
    for frames in EDGE_WINDOWS:
        got = _slope(t, R, t0, dt, frames, noise)
        if got is not None:
            return got
    return None


def edge_ratio(time_s, r, vr, radius) -> tuple[float, int, float] | None:
    """(q, pairs used, standard error of q) of the module docstring, or None when no pair is
    measurable."""
    order = np.argsort(radius.times_s, kind="stable")
    t = np.asarray(radius.times_s, dtype=float)[order]
    R = np.asarray(radius.radius_um, dtype=float)[order]
    dt = float(np.median(np.diff(np.unique(t)))) if np.unique(t).size > 1 else None
    if dt is None:
        return None
    noise = noise_of(radius)
    rows = []  # (a_k, its standard error, b_k, its standard error)
    for tk in np.unique(time_s):
        got = _speed(t, R, tk, dt, noise)
        if got is None or abs(got[0]) <= 3 * got[1]:
            continue
        Rk = got[2]
        sel = (time_s == tk) & (r >= Rk) & (r <= Rk + EDGE_BAND_UM)
        if sel.sum() < 3:
            continue
        va = vr[sel] * r[sel] / Rk
        rows.append((float(np.mean(va)), float(np.std(va, ddof=1)) / math.sqrt(va.size), *got[:2]))
    if not rows:
        return None
    a, sa, b, sb = np.array(rows).T
    den = float(np.sum(b * b))
    q = float(np.sum(a * b)) / den
    # first order in the errors of a_k and b_k (d q / d b_k = (a_k - 2 q b_k) / sum b^2)
    se = math.sqrt(float(np.sum((b * sa) ** 2 + ((a - 2 * q * b) * sb) ** 2))) / den
    return q, len(rows), se


def check_edge_speed(
    time_s, r, vr, radius, units=None, frame_interval_s=None, pixel_size_um=None
) -> str | None:
    """Refuse a field whose edge velocity is not the edge speed (module docstring), naming
    the option at fault where q is a unit mistake's factor (unit_mistake: `units` the
    --piv-units read, None for files that name theirs); the sentence for the report
    otherwise (None when unchecked)."""
    got = edge_ratio(np.asarray(time_s), np.asarray(r), np.asarray(vr), radius)
    if got is None:
        return None
    q, n, se = got
    said = (
        f"PIV velocity at the wound edge / edge speed dR/dt of the radius file = {q:.3g} +- "
        f"{se:.2g} ({n} frame pairs; 1 expected, 0.71 to 0.88 on the examples' noisy and "
        "exact fields, 0.45 to 1.26 on OpenPIV fields of rendered movies)"
    )
    if not 1 / EDGE_FACTOR <= q <= EDGE_FACTOR and abs(q - EDGE_TYPICAL) > 3 * se:
        named = unit_mistake(q, units, frame_interval_s, pixel_size_um)
        raise InputError(
            f"{said}: the tissue at the edge must move with the edge. "
            + (
                named
                or "The velocities are likely in another unit than read (OpenPIV files: "
                "--piv-units, px,px/s against px,px/frame differs by the frame interval), or "
                "the pairs' times are wrong (--frame-interval-s, --piv-first-frame, "
                "--piv-pair-step)"
            )
        )
    return said


#: The ratio q of a correct field (the module docstring's 0.45 to 1.26), and how far from a
#: unit mistake's factor times it a measured q may be to be named as that mistake.
EDGE_TYPICAL, EDGE_NAMED = 0.8, 1.6


def unit_mistake(q, units=None, frame_interval_s=None, pixel_size_um=None) -> str | None:
    """The sentence naming the option at fault when q is a unit mistake's factor times a
    correct field's (within EDGE_NAMED), else None. `units`: the --piv-units read (LENGTH,
    VELOCITY); None for files that name their units (PIVlab). A velocity per frame read per
    s scales q by the frame interval, per s read per frame by its inverse; lengths in um
    read as px scale positions and velocities by the pixel size, q (v r / R at the edge,
    the flow ~ 1 / r) by its square."""
    if units is None or not q > 0:
        return None
    length, velocity = units
    per = velocity.split("/", 1)[-1]
    other = "s" if per == "frame" else "frame"
    fixes = []
    if frame_interval_s:
        factor = frame_interval_s if per == "s" else 1 / frame_interval_s
        fixes.append(
            (
                factor,
                f"velocities in {length}/{other} read as {velocity}: give "
                f"--piv-units {length},{length}/{other}",
            )
        )
    if pixel_size_um and length == "px":
        fixes.append(
            (
                pixel_size_um**2,
                f"files in um read as px (the pixel size {pixel_size_um:g} "
                "on positions and velocities): give --piv-units um,um/s (or um,um/frame)",
            )
        )
    if length == "um" and pixel_size_um:
        fixes.append(
            (
                1 / pixel_size_um**2,
                "files in px read as um: give --piv-units px,px/s "
                "(or px,px/frame) with --pixel-size-um",
            )
        )
    for factor, text in fixes:
        if abs(math.log(q / (EDGE_TYPICAL * factor))) <= math.log(EDGE_NAMED):
            return f"A factor {factor:.3g} from a correct field's: {text}."
    return None
