"""What a PIVlab export's info lines say (+export/file_save.m: "FRAME: k, filenames: A & B,
conversion factor xy (px -> m): XY, conversion factor uv (px/frame -> m/s): UV"), checked
against the options that time the frame pairs:

- the time step PIVlab was calibrated with, XY / UV (+calibrate/calccali.m: UV = XY / step),
  against --frame-interval-s (`time_step`);
- the images of each pair, numbered in their file names (the last number of each name):
  their difference is the frames a pair spans (1: the reader's velocity is over one frame
  interval), their steps from pair to pair are --piv-pair-step, and the first image of pair
  k is frame --piv-first-frame + (k - 1) --piv-pair-step (images numbered from 1 as Fiji's
  frames) or one less (numbered from 0, as ImageJ saves image sequences) (`check_pairs`).
  A lab that forgets --piv-first-frame and --piv-pair-step would otherwise get every pair's
  time wrong with no word."""

from __future__ import annotations

import math
import os
import re

from .columns import InputError

_FACTORS = re.compile(
    r"conversion factor xy \(px -> m\):\s*(\S+?),\s*conversion factor uv "
    r"\(px/frame -> m/s\):\s*(\S+)"
)
#: num2str writes the conversion factors to 5 significant digits.
_FACTOR_RTOL = 1e-3


def time_step(path, lines, vel, dt):
    """(um/s per unit of u, notes) of a calibrated PIVlab file, its info line checked: PIVlab
    turns px/frame into m/s with the time step typed in its calibration, uv = xy / step, and
    writes both factors; the step must be the frame interval. A step of 0 ms (PIVlab's
    displacements only: uv = xy) writes m/frame under the heading "u [m/s]" (file_save.m),
    and a step of 1000 ms writes the same numbers: both read as m/frame."""
    m = next((m for _, s in lines[:2] for m in [_FACTORS.search(s)] if m), None)
    if m is None:
        return vel, ()
    try:
        xy, uv = abs(float(m.group(1))), abs(float(m.group(2)))
    except ValueError:
        return vel, ()
    if not (xy > 0 and uv > 0 and math.isfinite(xy / uv)):
        return vel, ()
    step = xy / uv  # s
    if abs(step - dt) <= _FACTOR_RTOL * dt:
        return vel, ()
    if abs(step - 1.0) <= _FACTOR_RTOL:
        return vel / dt, (
            f"{path}: PIVlab's conversion factors (line 2) are equal (px/frame -> m/s = px -> "
            "m): it was calibrated without a time step (displacements) or with 1000 ms, and "
            f"its u, v are in m/frame whatever the heading says: divided by {dt:g} s",
        )
    raise InputError(
        f"{path}: PIVlab converted px/frame to m/s with a time step of {step:.5g} s (line 2: "
        f"{m.group(0)}), but --frame-interval-s is {dt:g} s: the velocities and the times "
        f"disagree by a factor {step / dt:.4g}. Give --frame-interval-s {step:.5g} if that is "
        "the time between frames (ms typed as s?), else calibrate PIVlab with the frame "
        "interval in ms and export again"
    )


_NAMES = re.compile(r"FRAME:\s*\d+,\s*filenames:\s*(.+?)\s+&\s+(.+?),\s*conversion factor")


def image_numbers(lines) -> tuple[int, int] | None:
    """(number of the first image, of the second) of a PIVlab file's info line, or None."""
    m = next((m for _, s in lines[:2] for m in [_NAMES.search(s)] if m), None)
    if m is None:
        return None
    found = [re.findall(r"\d+", os.path.splitext(os.path.basename(n))[0]) for n in m.groups()]
    return (int(found[0][-1]), int(found[1][-1])) if all(found) else None


def check_pairs(named, frames) -> list[str]:
    """Refuse pairs whose images are not one frame apart, whose steps are not the pair step
    or whose first image is not --piv-first-frame (module docstring); [] (no notes). `named`: (path,
    pair, image numbers or None) of each PIVlab file."""
    known = sorted((pair, nums, path) for path, pair, nums in named if nums)
    for pair, (a, b), path in known:
        if b - a != 1:
            raise InputError(
                f"{path}: frame pair {pair} is images {a} and {b} (file names, line 2): "
                f"{b - a} frames apart, but a pair's velocity is read as the motion over one "
                "frame interval: export pairs of consecutive frames (PIVlab's sequencing 1-2, "
                "2-3 or 1-2, 3-4)"
            )
    for (k0, (a0, _), p0), (k1, (a1, _), p1) in zip(known, known[1:]):
        if a1 - a0 != frames.pair_step * (k1 - k0):
            raise InputError(
                f"{p1}: frame pairs {k0} and {k1} start at images {a0} and {a1} (file names, "
                f"line 2): {(a1 - a0) / (k1 - k0):g} frames per pair, but --piv-pair-step is "
                f"{frames.pair_step}: give --piv-pair-step {(a1 - a0) // (k1 - k0)}"
                if (a1 - a0) % (k1 - k0) == 0
                else f"{p1}: frame pairs {k0} and {k1} start at images {a0} and {a1} (file "
                "names, line 2): not a constant number of frames per pair"
            )
    if known:
        k, (a, _), path = known[0]
        if a - frames.pair_start(k) not in (0, -1):
            first = a - (k - 1) * frames.pair_step
            raise InputError(
                f"{path}: frame pair {k} is images {a}-{a + 1} by its file names (line 2), "
                f"frames {frames.pair_start(k)}-{frames.pair_start(k) + 1} by --piv-first-frame "
                f"{frames.first_frame}: give --piv-first-frame {first} (images numbered as the "
                f"movie's frames, from 1) or {first + 1} (from 0, as ImageJ's image sequences); "
                "images numbered from another start: rename them from 0 or 1"
            )
    return []
