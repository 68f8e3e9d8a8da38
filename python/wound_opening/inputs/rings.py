"""A PIV field as the fit's velocity profile: the radial velocity seen from the wound centre,
averaged in rings (docs/fitting.md, "Lab files: Fiji, PIVlab, OpenPIV": why rings).

Per frame pair, vectors at or inside the wound edge (the radius series interpolated at the
pair's time) and at or beyond the outer radius are dropped; the rest fall into rings of width
`ring_width_um` starting at the edge. A ring with at least `min_vectors` vectors gives one
profile point:

    r     = the harmonic mean of its distances (exact for a velocity ~ 1/r)
    v     = the mean of its radial velocities
    sd(v) = s / sqrt(n),  s^2 the pooled variance of the vectors about their ring means
            (every ring of every pair, n - rings degrees of freedom)

so the noise comes from the scatter within the rings, as the data give it."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from . import piv_errors
from .centre import ring_sensitivity
from .columns import InputError
from .edge_speed import check_edge_speed
from .provenance import RawFile
from .series import RadiusSeries, VelocityProfile

MIN_VECTORS = 5


def _edge(radius: RadiusSeries, t):
    order = np.argsort(radius.times_s, kind="stable")
    return np.interp(t, np.asarray(radius.times_s)[order], np.asarray(radius.radius_um)[order])


#: A field with more than this fraction of its vectors inside the wound (r <= R(t)) is read in
#: the wrong lengths (um read as px shrinks it 1 / pixel size times) or about a wrong centre:
#: a PIV window inside a wound is masked or noise, and a field that is mostly wound has
#: nothing to fit. Refused.
MAX_INSIDE = 2 / 3


def keep(radius: RadiusSeries, outer_um: float, t, r):
    """(mask of vectors between the wound edge and the outer radius, inside, beyond)."""
    edge = _edge(radius, t)
    inside, beyond = r <= edge, r >= outer_um
    n = int(np.isfinite(r).sum())
    if inside.sum() > MAX_INSIDE * n:
        raise InputError(
            f"{int(inside.sum())} of {n} PIV vectors lie inside the wound (closer to the centre "
            "than the radius of the radius file at their time): a field mostly inside the "
            "wound is read in other lengths than it was written in (OpenPIV files: "
            "--piv-units, e.g. um,um/s; px: --pixel-size-um) or about a wrong centre"
        )
    return ~inside & ~beyond & np.isfinite(r), int(inside.sum()), int(beyond.sum())


@dataclass(frozen=True)
class Measurement:
    """How the field's vectors were measured: each vector's frame pair, position [um] and
    the grid step [um]; the pairs' interval [s] and the interrogation window's side [um]
    (None: not known, the vectors are then velocities at their points and times)."""

    pair: np.ndarray
    x_um: np.ndarray
    y_um: np.ndarray
    spacing_um: float
    interval_s: float | None = None
    window_um: float | None = None

    @property
    def side_um(self) -> float:
        """The window's side, or where not known the grid step (the smallest a window of
        a grid without gaps can be)."""
        return self.window_um if self.window_um is not None else self.spacing_um


def _measured(measurement, radius, t, r, ok):
    """(vectors kept, windows touching the wound, at the grid's border): a window whose
    corner comes within the wound edge at either frame of its pair, or on the grid's outer
    rows and columns, is not a measurement of the tissue's motion (piv_errors.border)."""
    if measurement is None or measurement.interval_s is None:
        return ok, 0, 0
    half_dt = 0.5 * measurement.interval_s
    reach = measurement.side_um / math.sqrt(2.0)
    edge = np.maximum(_edge(radius, t - half_dt), _edge(radius, t + half_dt))
    touch = ok & (r - reach <= edge)
    grid = piv_errors.grid_of(measurement.x_um, measurement.y_um, measurement.spacing_um)
    rim = ok & ~touch & piv_errors.border(grid)
    return ok & ~touch & ~rim, int(touch.sum()), int(rim.sum())


def ring_profile(
    t,
    r,
    vr,
    radius: RadiusSeries,
    outer_um: float,
    ring_width_um: float,
    *,
    min_vectors: int = MIN_VECTORS,
    files: tuple = (),
    source: str | None = None,
    measurement: Measurement | None = None,
    centre=None,
) -> tuple[VelocityProfile, dict]:
    """(the ring profile, counts) of radial vectors (module docstring); with their
    `measurement`, windows touching the wound or the border are left out, the points are
    the pairs' displacements over the window (fitting/piv_measure.py) and their errors
    correlated (piv_errors.py); an estimated `centre` (centre.Centre) adds its uncertainty
    to their covariance (centre.ring_sensitivity)."""
    if not (math.isfinite(ring_width_um) and ring_width_um > 0):
        raise InputError(f"--ring-width-um {ring_width_um}: must be finite and > 0")
    ok, inside, beyond = keep(radius, outer_um, t, r)
    ok, touch, rim = _measured(measurement, radius, t, r, ok)
    sel = np.flatnonzero(ok)
    t, r, vr = t[sel], r[sel], vr[sel]
    edge = _edge(radius, t)
    ring = np.floor((r - edge) / ring_width_um).astype(int)
    keys = np.stack([t, ring])
    _, group = np.unique(keys, axis=1, return_inverse=True)
    group = group.ravel()
    n = np.bincount(group)
    big = n[group] >= min_vectors
    if not big.any():
        raise InputError(
            f"no ring of width {ring_width_um:g} um holds {min_vectors} PIV vectors between the "
            "wound edge and the outer radius: widen the rings (--ring-width-um)"
        )
    few = int((~big).sum())
    t, r, vr, sel = t[big], r[big], vr[big], sel[big]
    group = np.unique(group[big], return_inverse=True)[1]
    n = np.bincount(group)
    tm = np.bincount(group, t) / n
    mean = np.bincount(group, vr) / n
    harmonic = n / np.bincount(group, 1.0 / r)
    dof = vr.size - n.size
    if dof < 2:
        raise InputError("too few PIV vectors per ring to estimate their scatter")
    s = math.sqrt(float(np.sum((vr - mean[group]) ** 2)) / dof)
    order = np.lexsort((harmonic, tm))
    counts = {
        "inside the wound edge": inside,
        "beyond the outer radius": beyond,
        "in rings of fewer than %d" % min_vectors: few,
        "used": int(vr.size),
        "rings": int(n.size),
    }
    extra, cov, corr = {}, None, None
    if measurement is not None and measurement.interval_s is not None:
        counts["windows touching the wound"] = touch
        counts["at the grid's border"] = rim
        cov, corr = _ring_covariance(measurement, sel, group, r, vr)
        if centre is not None and centre.estimated:
            m = measurement
            d = ring_sensitivity(centre, m.x_um[sel], m.y_um[sel], r, vr, group, m.pair[sel])
            cov = cov + d @ np.diag([centre.sd_x_um**2, centre.sd_y_um**2]) @ d.T
        cov = cov[np.ix_(order, order)]
        extra = {"interval_s": measurement.interval_s, "window_um": measurement.window_um}
    sd = np.sqrt(np.diag(cov)) if cov is not None else s / np.sqrt(n[order])
    profile = VelocityProfile(
        tm[order],
        harmonic[order],
        mean[order],
        sd_um_s=sd,
        source=source,
        files=tuple(files)
        + (
            RawFile(
                "(rings)", "", "ring averages", counts, (_note(counts, s, ring_width_um, corr),)
            ),
        ),
        covariance=cov,
        **extra,
    )
    return profile, counts


def _ring_covariance(measurement, sel, group, r, vr):
    """(covariance of the ring means, (rho_s at one grid step, rho_t by lag)) of the vectors
    `sel` (piv_errors.py)."""
    m = measurement
    grid = piv_errors.grid_of(m.x_um, m.y_um, m.spacing_um)
    used = piv_errors.Grid(grid.ix[sel], grid.iy[sel], grid.shape)
    reach = max(int(math.ceil(m.side_um / m.spacing_um)) - 1, 0)
    pair = m.pair[sel]
    deviation, s2 = piv_errors.deviations(r, vr, pair)
    rho, rho_t = piv_errors.correlations(deviation, pair, used, reach, s2)
    cov = piv_errors.ring_covariance(group, pair, used, rho, rho_t, s2)
    step = float(rho[reach, reach + 1]) if reach else 0.0
    return cov, (step, rho_t)


def _note(counts, s, width, corr=None) -> str:
    said = (
        ""
        if corr is None
        else f"; errors correlated {corr[0]:.2f} between neighbouring windows and "
        f"{corr[1][min(1, corr[1].size - 1)]:.2f} between consecutive frame pairs at one "
        f"grid point ({corr[1][min(10, corr[1].size - 1)]:.2f} "
        f"{min(10, corr[1].size - 1)} pairs apart); left out "
        f"{counts['windows touching the wound']} windows touching the wound, "
        f"{counts['at the grid' + chr(39) + 's border']} at the grid's border"
    )
    return (
        f"PIV: {counts['used']} vectors in {counts['rings']} rings of {width:.3g} um "
        f"(scatter within rings {s:.3g} um/s); dropped {counts['inside the wound edge']} inside "
        f"the wound edge, {counts['beyond the outer radius']} beyond the outer radius, "
        f"{counts[next(k for k in counts if k.startswith('in rings'))]} in rings too sparse" + said
    )


def vector_profile(t, r, vr, radius, outer_um, *, noise_um_s=None, files=(), source=None):
    """Every vector as a profile point (the alternative to rings; noise estimated unless
    given)."""
    ok, inside, beyond = keep(radius, outer_um, t, r)
    order = np.lexsort((r[ok], t[ok]))
    counts = {
        "inside the wound edge": inside,
        "beyond the outer radius": beyond,
        "used": int(ok.sum()),
    }
    note = (
        f"PIV: every vector ({counts['used']}); dropped {inside} inside the wound edge, "
        f"{beyond} beyond the outer radius"
    )
    profile = VelocityProfile(
        t[ok][order],
        r[ok][order],
        vr[ok][order],
        noise_um_s,
        source=source,
        files=tuple(files) + (RawFile("(vectors)", "", "every vector", counts, (note,)),),
    )
    return profile, counts


def field_profile(
    field,
    radius: RadiusSeries,
    outer_um: float,
    *,
    centre=None,
    ring_width_um: float | None = None,
    likelihood: str = "rings",
    noise_um_s: float | None = None,
    units=None,
    frame_interval_s: float | None = None,
    pixel_size_um: float | None = None,
    window_um: float | None = None,
):
    """(VelocityProfile, Centre) of a piv.Field: the centre given (centre.Centre) or
    estimated, the radial projection, then rings (default width: the PIV grid spacing) or
    every vector. `units`, `frame_interval_s`, `pixel_size_um`: as read (OpenPIV's
    --piv-units; None for files naming theirs), to name a unit mistake the edge speed
    shows (edge_speed.unit_mistake). The rings are measurements of the pairs (Measurement):
    displacements over the frame interval (`frame_interval_s`, default the field's), means
    over the interrogation window of side `window_um` (None: the window's centre, and the
    grid step as the side that decides which windows touch the wound)."""
    from .centre import radial

    measurement = Measurement(
        field.pair,
        field.x_um,
        field.y_um,
        field.spacing_um,
        frame_interval_s or getattr(field, "interval_s", None),
        window_um,
    )
    flow = flow_centre(field, radius, outer_um, measurement)
    warnings = ()
    if centre is None:
        centre = flow
    else:
        check_in_field(centre, field, flow)
        warnings = given_centre_warnings(centre, flow)
    r, vr = radial(centre, field.x_um, field.y_um, field.u_um_s, field.v_um_s)
    files = field.files + (RawFile("(centre)", "", "wound centre", {}, (centre.describe(),)),)
    keep(radius, outer_um, field.time_s, r)  # a field mostly inside the wound: refused first
    edge = check_edge_speed(
        field.time_s, r, vr, radius, units, measurement.interval_s, pixel_size_um
    )
    if edge:
        files += (RawFile("(edge)", "", "edge speed", {}, (edge,)),)
    if likelihood == "vectors":
        return vector_profile(
            field.time_s,
            r,
            vr,
            radius,
            outer_um,
            noise_um_s=noise_um_s,
            files=files,
            source=field.source,
        )[0], centre
    if likelihood != "rings":
        raise InputError(f"PIV likelihood {likelihood!r}: expected rings or vectors")
    if noise_um_s is not None:
        raise InputError(
            "--velocity-noise-um-s with PIV rings: the rings' noise is their scatter; give it "
            "with --piv-likelihood vectors"
        )
    width = ring_width_um if ring_width_um is not None else field.spacing_um
    profile, _ = ring_profile(
        field.time_s,
        r,
        vr,
        radius,
        outer_um,
        width,
        files=files,
        source=field.source,
        measurement=measurement,
        centre=centre,
    )
    return replace(profile, warnings=warnings), centre


def flow_centre(field, radius: RadiusSeries, outer_um: float, measurement: Measurement):
    """The centre the field's velocities point away from (centre.py), estimated from the
    vectors that measure the tissue: a first estimate from every vector, then again from
    those whose windows touch neither the wound nor the grid's border (as the rings keep
    them, `_measured`, but with the grid step as the windows' side). The windows on the
    wound's moving edge read 0.6-1.5 times the tissue's velocity; on a movie measured by
    OpenPIV they pulled the estimate 0.5 um off (tangential rms 0.60 um/s against 0.04
    without them). The interrogation window's own side (32 px, four grid steps in OpenPIV's
    tutorial) leaves out the vectors nearest the wound, the fastest and the ones whose
    direction says most about the centre: on the 20 rendered movies of the coverage study
    (docs/fitting.md) the centre from the vectors beyond it was 0.13-16.9 um from the true
    one (rms 5.3 um; two fields refused), from those beyond one grid step 0.16-1.83 um (rms
    0.74 um; none refused). The rings still leave out every window that touches the wound."""
    from .centre import estimate_centre, radial

    args = (field.x_um, field.y_um, field.u_um_s, field.v_um_s)
    if measurement.interval_s is None:
        return estimate_centre(*args, field.pair)
    flow = estimate_centre(*args, field.pair, check=False)  # where the wound's windows are
    r, _ = radial(flow, *args)
    ok = np.isfinite(r) & (r < outer_um)
    ok, _, _ = _measured(replace(measurement, window_um=None), radius, field.time_s, r, ok)
    if np.count_nonzero(ok) < 10:
        return flow
    return estimate_centre(*(a[ok] for a in args), field.pair[ok], start=(flow.x_um, flow.y_um))


#: A given centre this many standard errors of the flow's centre away (and over
#: CENTRE_FLOOR_UM) is not where the velocities point from: a warning, the centre used as
#: given.
CENTRE_SIGMAS, CENTRE_FLOOR_UM = 4.0, 0.5


def check_in_field(given, field, flow) -> None:
    """Refuse a given centre outside the field's extent: not a disagreement with the flow but
    other lengths or axes than the files' (pixels typed into --centre-um)."""
    x, y = np.asarray(field.x_um), np.asarray(field.y_um)
    if x.min() <= given.x_um <= x.max() and y.min() <= given.y_um <= y.max():
        return
    raise InputError(
        f"the wound centre given, ({given.x_um:.4g}, {given.y_um:.4g}) um, lies outside the PIV "
        f"field (x {x.min():.4g} to {x.max():.4g} um, y {y.min():.4g} to {y.max():.4g} um; the "
        f"velocities point away from ({flow.x_um:.4g}, {flow.y_um:.4g}) um): is it in other "
        "axes or units than the PIV files' (--centre-px is pixels in the files' axes, times "
        "--pixel-size-um; --centre-um is um in the files' axes)?"
    )


def given_centre_warnings(given, flow) -> tuple[str, ...]:
    """A warning (one string, or none) where a given centre is more than CENTRE_SIGMAS of the
    flow's centre's standard errors ((dx/sd_x)^2 + (dy/sd_y)^2, chi-square with 2 degrees of
    freedom: 3e-4 by chance) and CENTRE_FLOOR_UM away. The centre given is used: the lab
    knows where the laser was aimed; the warning names the usual causes of a disagreement
    (other axes than the files', X and Y swapped, a PIV program that states positions off
    the windows it correlated)."""
    dx, dy = given.x_um - flow.x_um, given.y_um - flow.y_um
    sx, sy = max(flow.sd_x_um, 1e-12), max(flow.sd_y_um, 1e-12)
    z = math.hypot(dx / sx, dy / sy)
    if z <= CENTRE_SIGMAS or math.hypot(dx, dy) <= CENTRE_FLOOR_UM:
        return ()
    return (
        f"the wound centre given, ({given.x_um:.4g}, {given.y_um:.4g}) um, is "
        f"{math.hypot(dx, dy):.3g} um from the centre the velocities point away from, "
        f"({flow.x_um:.4g} +- {flow.sd_x_um:.2g}, {flow.y_um:.4g} +- {flow.sd_y_um:.2g}) um "
        f"({z:.0f} standard errors); used as given. Is it in other axes than the PIV files' "
        "(--centre-px is pixels in the files' axes, times --pixel-size-um; a PIVlab "
        "calibration may flip y or add an offset), are X and Y swapped, or does the PIV "
        "program state its positions off the windows it correlated (OpenPIV's tutorial "
        "coordinates are 4 px off for windows of 32/40 px)? Without --centre-um/--centre-px "
        "the centre of the flow is used",
    )
