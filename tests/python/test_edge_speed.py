"""The field's edge velocity against the radius file's edge speed (inputs/edge_speed.py) on an
opening faster than a frame and on a table that starts after the opening's first frames:
a correct field reads q near 1, a unit mistake is still refused."""

from __future__ import annotations

import numpy as np
import pytest

from wound_opening.inputs.columns import InputError
from wound_opening.inputs.edge_speed import check_edge_speed, edge_ratio, unit_mistake
from wound_opening.inputs.series import RadiusSeries

R0, OPENING, FRAME_S, FIRST_S = 3.7, 3.1, 1.0, 0.19


def radius(t, T):
    return R0 + OPENING * (1 - np.exp(-t / T))


def field(T, scale=1.0, pairs=24):
    """Vectors beside the edge as a PIV program measures them: the displacement of the
    tissue at r_a (frame a) over the pair, per frame interval; incompressible tissue keeps
    the area between itself and the edge, r_b^2 - r_a^2 = R_b^2 - R_a^2. Pair k spans
    frames k and k + 1, its time their middle."""
    t, r, v = [], [], []
    for k in range(pairs):
        ta = FIRST_S + k * FRAME_S
        Ra, Rb = radius(ta, T), radius(ta + FRAME_S, T)
        ra = Ra + np.linspace(0.5, 7.5, 15)
        rb = np.sqrt(ra**2 + Rb**2 - Ra**2)
        t += [ta + 0.5 * FRAME_S] * ra.size
        r += list(ra)
        v += list(scale * (rb - ra) / FRAME_S)
    return np.array(t), np.array(r), np.array(v)


def series(T, first_frame: int) -> RadiusSeries:
    """The radii of frames first_frame..24 after the cut (frame 0 at FIRST_S), noise
    0.01 um."""
    t = FIRST_S + FRAME_S * np.arange(first_frame, 25)
    noise = np.random.default_rng(3).normal(0, 0.01, t.size)
    return RadiusSeries(t, radius(t, T) + noise)


@pytest.mark.parametrize("first_frame", [0, 2])
def test_a_correct_field_reads_near_one(first_frame):
    """An opening with T = 5 frames, the table from the cut's first frame or from two frames
    later: q within 0.8-1.05 of a correct field's 1, to its standard error."""
    got = edge_ratio(*field(5.0), series(5.0, first_frame))
    assert got is not None
    q, used, se = got
    assert 0.8 <= q <= 1.05 and se < 0.05, got
    check_edge_speed(*field(5.0), series(5.0, first_frame), frame_interval_s=FRAME_S)


@pytest.mark.parametrize("first_frame", [0, 2])
def test_an_opening_within_two_frames_leaves_the_field_unchecked(first_frame):
    """T = 0.28 frame: no parabola follows the radii about the opening's pairs, and after
    them the wound has stopped, so no pair has a measurable edge speed and the check is not
    made. The ten-frame parabola alone read q = 0.0034 from the cut's first frame, and,
    extrapolated before a table from two frames later, 3.4e3: both refused as unit
    mistakes of a correct field."""
    assert edge_ratio(*field(0.28), series(0.28, first_frame)) is None
    assert (
        check_edge_speed(*field(0.28), series(0.28, first_frame), frame_interval_s=FRAME_S) is None
    )


def test_a_field_too_noisy_to_judge_is_not_refused():
    """Edge velocities buried in noise give a q far from 1 with a standard error to match
    (the examples' noisy 4 um wound read -0.17 +- 0.41): not refused, and a negative q no
    longer breaks the refusal's message (it raised "math domain error")."""
    t, r, v = field(5.0)
    v = v + np.random.default_rng(5).normal(0, 3.0, v.size)
    q, used, se = edge_ratio(t, r, v, series(5.0, 0))
    assert not 1 / 2.5 <= q <= 2.5, (q, se)  # outside the range: the error is what spares it
    assert abs(q - 0.8) <= 3 * se, (q, se)
    assert "edge speed" in check_edge_speed(t, r, v, series(5.0, 0), ("px", "px/s"), FRAME_S, 0.2)
    assert unit_mistake(-0.2, ("px", "px/s"), FRAME_S, 0.2) is None


@pytest.mark.parametrize("first_frame", [0, 2])
def test_a_velocity_four_times_too_large_is_refused(first_frame):
    """The same fields read 4 times too fast (px/frame read as px/s at 4 frames a second) are
    refused."""
    with pytest.raises(InputError, match="edge speed"):
        check_edge_speed(*field(5.0, scale=4.0), series(5.0, first_frame), frame_interval_s=FRAME_S)
