"""Weighted residuals of the model against a radius series and a velocity profile, and
their Jacobian.

Coordinates of the optimiser: z = (ln R0, sigma, lambda, ln T), lambda >= 0; the outer
radius is fixed in um, so R_inf = outer / R0 moves with R0.

Wound radius. With no edge stress the displacement is proportional to sigma, so with
h(t) = R(t; sigma = 1) - 1 (dimensionless, lambda and R_inf given)

    R_um(t) = R0 (1 + sigma h(t / T))
    d R_um / d sigma = R0 h                          (exact)
    d R_um / d ln T  = -t dR_um/dt = -(t / T) R0 sigma h'(t / T)   (exact: the edge velocity)
    d R_um / d ln R0 = R_um - R0 sigma R_inf dh/dR_inf
    d R_um / d lambda = R0 sigma dh/dlambda

dh/dR_inf and dh/dlambda come with h from one native call (`_native.series_sensitivities`,
src/solver/sensitivity.rs): the exact derivatives of the solver's h through its modal basis,
no further decomposition. They differ from the derivatives of the exact solution by about
the solver's tolerance times the opening (1e-9 in a radius-only fit; at 1e-10, 2e-8 for
the ln R_inf column at R_inf = 1.01;
tests/python/test_sensitivities.py), far below the 1e-7 of the central differences they
replace. The grid is the one the fit's tolerance picks for this R_inf (its element count is
piecewise constant in R_inf): the derivative is that of the smooth curve, not of the grid's
steps.

Velocity profile (PIV). A vector at current distance r from the centre at time t is
compared with the velocity of the tissue at r. Where r is at or inside the model's wound
edge R(t) (possible for vectors measured at the edge, for some parameter values), the
window holds the edge itself: the model value is the edge velocity dR/dt. The model is
then continuous in the parameters (no penalty branch); such vectors are counted
(`inside_edge`). The profile columns are exact on the solver's grid (`_native.profile_rates`,
src/solver/profile_rates.rs: the velocity at fixed current radius differentiated through the
modal basis, the moving mesh and the implicit reference radius, one native call per frame,
on the basis of the model's own R_inf), the edge rows' those of the edge velocity; ln R0
moves both the outer radius R_inf = outer / R0 and the current radius r / R0 of every vector.
A frame at the cut (t = 0, where the velocity is the instantaneous response) falls back to
central differences (steps STEP, relative) for all columns.
"""

from __future__ import annotations

import math

import numpy as np

from .. import _native
from . import serial
from .parameters import Coordinate, Coordinates, between, factor, span
from .problem import Problem
from .profile_model import STEP, ProfileModel

#: Largest lambda searched: a viscous length of 50 R0, beyond which the tissues of these
#: experiments (outer radius ~10 R0) move as one and R(t) depends on tau = lambda^2 T only.
LAMBDA_MAX = 50.0
#: Accuracy of the curves of a radius-only fit (relative to the opening): far below any
#: noise a lab measures (1e-9 of a 2 um opening is 2e-9 um; a noise of 1e-6 of the opening
#: would still be 1000 times larger). With every column of the Jacobian exact (differences
#: only at a frame at the cut), a finer grid buys nothing but time: the decomposition at
#: R_inf = 1000 (plateau-only data, whose fits reach R0 ~ 0.1 um) takes 11.3 ms at 1e-10
#: and 6.9 ms at 1e-9, at R_inf = 100 0.88 and 0.60 ms.
TOLERANCE_FIT = 1e-9
#: ... and of a fit with a PIV profile: the grid the tolerance picks is the wound radius's,
#: and the velocity far from the edge early on is some 40 times less accurate (at 1e-10,
#: 4e-7 of the largest velocity; tests/python/test_piv_jacobian.py holds 3e-7).
TOLERANCE_PIV = 1e-11
#: Smallest R_inf the solver accepts (the fits bound R0 by outer / R_INF_MIN).
R_INF_MIN = 1.001


def to_z(theta) -> np.ndarray:
    R0, sigma, lam, T = theta
    return np.array([math.log(R0), sigma, lam, math.log(T)])


#: The solver accepts lambda = 0 or lambda >= 1e-150 (src/solver/params.rs LAMBDA_MIN); the
#: model depends on lambda^2, so a smaller |lambda| (the fits' asinh coordinate, local.py,
#: can reach subnormal values next to the bound 0) is 0 to the last bit of every result.
LAMBDA_SOLVER_MIN = 1e-150


def from_z(z) -> tuple[float, float, float, float]:
    lam = abs(float(z[2]))
    return math.exp(z[0]), float(z[1]), lam if lam >= LAMBDA_SOLVER_MIN else 0.0, math.exp(z[3])


def r0_coordinate(name: str, outer_radius_um: float) -> Coordinate:
    """A wound's R0 [um], below the outer radius / R_INF_MIN, searched a factor 3 either way."""
    return Coordinate(
        name,
        "um",
        log=True,
        lower=0.0,
        upper=outer_radius_um / R_INF_MIN,
        window=factor(3.0),
        step=0.05,
        note=" (R0 below the outer radius / 1.001)",
    )


#: The radial offset of the measured outline from the tissue's edge [um]: every measured
#: radius is R(t) + offset (a threshold that puts the edge a few tenths of a micrometre out),
#: so d residual / d offset = 1 / sd on the radius rows and 0 on the PIV rows.
OUTLINE_OFFSET = Coordinate("outline_offset_um", "um", window=span(), step=0.05)
#: The time of the cut on the data's clock [s], when the times given are counted from an
#: earlier instant (frame N, the last before the laser fired): every time t is t - cut after
#: the cut, the cut lies before the first data time (Objective.bounds), and a bound of the
#: user's says between which frames (params.add("cut_s", max=frame_interval)). The model
#: depends on t only through (t - cut) / T, so d/d cut = -(1/T) d/d tau: on a radius row
#: J_lnT / (t - cut), on a PIV row (J_lnT + v) / (t - cut), v the model velocity.
CUT = Coordinate("cut_s", "s", lower=0.0, closed=True, window=between(0.0, math.inf), step=0.01)
#: The nuisances a one-wound fit can add after its four parameters, by name: each is one
#: declaration here and its term in Objective.model and Objective.jacobian. A fit adds the
#: ones the user names in its Parameters (fixed: a known value; free, bounded or with a
#: prior: fitted).
#: The PIV field's gain: every modelled PIV value is gain x the model's (a PIV program's
#: calibration: sub-pixel bias, peak locking and the window's smoothing make OpenPIV read 4 to
#: 11 % high or 9 % low on movies rendered from the exact solution), so d/d gain = the
#: model's value and every other PIV column is multiplied by the gain. With a prior (the
#: command line's default 1 +- 0.1) the field keeps its shape (the viscous length) and its
#: timing and weighs its magnitude as the program's calibration allows.
PIV_GAIN = Coordinate("piv_gain", "1", lower=0.0, window=factor(2.0), step=0.01, start=1.0)
NUISANCES = {c.name: c for c in (OUTLINE_OFFSET, CUT, PIV_GAIN)}


def wound_coordinates(outer_radius_um: float, nuisances=()) -> Coordinates:
    """One wound's coordinates z = (ln R0, sigma, lambda, ln T) by name, with the values a fit
    of a wound in a tissue of that outer radius accepts (R0 below outer / R_INF_MIN), their
    profile windows (R0 a factor 3, sigma 10 |sigma| + 1, lambda its whole range, T a factor
    100 either way) and first steps; the user's fit moves asinh of sigma and lambda. Then
    the `nuisances` named (NUISANCES)."""
    return Coordinates(
        (
            r0_coordinate("R0_um", outer_radius_um),
            Coordinate(
                "sigma",
                "1 (tension / G)",
                window=span(),
                step=lambda z_hat: 0.05 * abs(z_hat[1]) + 0.01,
                stretched=True,
            ),
            Coordinate(
                "lambda",
                "1 (viscous length / R0)",
                lower=0.0,
                upper=LAMBDA_MAX,
                closed=True,
                window=between(0.0, LAMBDA_MAX),
                stretched=True,
            ),
            Coordinate("T_s", "s", log=True, lower=0.0, window=factor(1e2)),
        )
        + tuple(NUISANCES[name] for name in nuisances)
    )


def _as_z(w) -> np.ndarray:
    return np.asarray(w, dtype=float)


class Objective(ProfileModel, Problem):
    """Residuals (model - data) / uncertainty, radius points first, then profile points.
    `sd` holds the per-point uncertainties: the data's own where given, else a first guess
    (`estimated` says which data sets: radius, profile) that `estimate_noise` scales to the
    residuals."""

    wound_maps = (_as_z, _as_z, True)  # its coordinates are the wound's z

    def __init__(self, radius, profile, outer_radius_um: float, nuisances=()):
        self.outer = float(outer_radius_um)
        self.inputs = (radius, profile)  # the series read (rows, file lines)
        t = np.asarray(radius.times_s, dtype=float)
        self.order = np.argsort(t, kind="stable")
        self.t_sorted = t[self.order]
        self.radius = np.asarray(radius.radius_um, dtype=float)[self.order]
        self.groups = []  # (time, r_um, velocity_um_s, indices in the profile's rows)
        if profile is not None:
            pt = np.asarray(profile.times_s, dtype=float)
            for time in np.unique(pt):
                idx = np.flatnonzero(pt == time)
                self.groups.append(
                    (
                        float(time),
                        np.asarray(profile.r_um, float)[idx],
                        np.asarray(profile.velocity_um_s, float)[idx],
                        idx,
                    )
                )
        self.n_radius = self.radius.size
        self.n_profile = sum(g[1].size for g in self.groups)
        self.group_times = np.array([g[0] for g in self.groups])
        self.sd, self.estimated = self._uncertainties(radius, profile)  # [um or um/s]
        self.tolerance = TOLERANCE_PIV if self.groups else TOLERANCE_FIT
        #: a PIV profile's frame interval [s] and window half-side [um] (piv_measure.py): its
        #: points are displacements over [t - dt/2, t + dt/2] / dt, window means; None: the
        #: velocity at t and r
        self.interval = getattr(profile, "interval_s", None) if profile is not None else None
        self.whiten = self._whitening(profile)
        #: the radius errors' lag-1 correlation (serial.py), estimated with their noise for
        #: a series flagged `serial` (outlines), else 0; each point's gap in frames
        self.serial = bool(getattr(radius, "serial", False)) and self.estimated[0]
        self.radius_rho = 0.0
        self.gaps = serial.gaps(self.t_sorted)
        #: the least radius noise an estimate takes [um] (RadiusSeries.noise_floor_um)
        self.radius_floor = getattr(radius, "noise_floor_um", None) if self.estimated[0] else None
        self.radius_floor_said = getattr(radius, "noise_floor_said", "")
        self.half_window = 0.5 * (getattr(profile, "window_um", None) or 0.0)
        self.evaluations = 0
        self.inside_edge = 0
        self.coordinates = wound_coordinates(self.outer, nuisances)
        names = self.coordinates.names
        #: the outline offset's and the cut time's index in z, or None
        self.offset = names.index(OUTLINE_OFFSET.name) if OUTLINE_OFFSET.name in names else None
        self.cut = names.index(CUT.name) if CUT.name in names else None
        self.gain = names.index(PIV_GAIN.name) if PIV_GAIN.name in names else None

    def _uncertainties(self, radius, profile) -> tuple[np.ndarray, list]:
        """Initial per-point uncertainties and which data sets have theirs estimated: 1 % of
        the mean radius, a tenth of the velocities' spread."""
        r_sd = (
            radius.sd_um
            if radius.sd_um is not None
            else np.full(self.n_radius, radius.noise_um or 1.0)
        )
        sd = [np.asarray(r_sd, float)[self.order]]
        estimated = [radius.noise_um is None and radius.sd_um is None, False]
        if profile is not None:
            p_sd = (
                profile.sd_um_s
                if profile.sd_um_s is not None
                else np.full(self.n_profile, profile.noise_um_s or 1.0)
            )
            sd.append(np.concatenate([np.asarray(p_sd, float)[g[3]] for g in self.groups]))
            estimated[1] = profile.noise_um_s is None and profile.sd_um_s is None
            if estimated[1]:
                sd[1][:] = (
                    max(float(np.std(np.concatenate([g[2] for g in self.groups]))), 1e-12) * 0.1
                )
        if estimated[0]:
            sd[0][:] = 0.01 * float(np.mean(self.radius))
        return np.concatenate(sd), estimated

    def estimate_noise(self, z, robust: bool, share: float | None = None) -> None:
        """Scale the estimated data sets' uncertainties to their residuals at z; `share`: the
        fraction of each set's points taken by the parameters (default 4 / the points). The
        radius's no lower than its floor (`radius_floor`: RadiusSeries.noise_floor_um, the
        readers' half pixel)."""
        parts = list(self.split(self.residuals(z)))
        if self.serial:  # the radius's marginal scale, and its correlation, from the raw
            raw = ((self.model(z) - self.data()) / self.sd)[: self.n_radius]
            self.radius_rho = serial.lag1(raw, self.gaps)
            parts[0] = raw
        scale = []
        for k, part in enumerate(parts):
            if not (self.estimated[k] and part.size):
                scale.append(np.ones(part.size))
                continue
            if robust:
                factor = 1.4826 * float(np.median(np.abs(part)))
            else:
                dof = max(part.size * (1 - (4 / self.size if share is None else share)), 1.0)
                factor = math.sqrt(float(np.sum(part**2)) / dof)
            scale.append(np.full(part.size, max(factor, 1e-300)))
        self.sd = self.sd * np.concatenate(scale)
        if self.radius_floor:  # an outline's error: the series' floor at least (fiji.py)
            np.maximum(self.sd[: self.n_radius], self.radius_floor, out=self.sd[: self.n_radius])

    def floor_reached(self) -> bool:
        """Whether the radius noise is the floor's (the residuals' scale is below it)."""
        floor = self.radius_floor
        return bool(floor) and bool(np.all(self.sd[: self.n_radius] <= floor * (1 + 1e-12)))

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        """Bounds in z: R0 between 1 % of the smallest radius and the outer radius / 1.001
        (R_inf >= 1.001), sigma free, 0 <= lambda <= LAMBDA_MAX, T within 1e-6 .. 1e6 of the
        last time."""
        t_max = float(self.t_sorted[-1]) if self.t_sorted[-1] > 0 else 1.0
        lower = np.array(
            [math.log(0.01 * float(np.min(self.radius))), -np.inf, 0.0, math.log(1e-6 * t_max)]
        )
        upper = np.array([math.log(self.outer / 1.001), np.inf, LAMBDA_MAX, math.log(1e6 * t_max)])
        extra = self.coordinates[4:]  # nuisances: their accepted ranges
        lower = np.append(lower, [c.bound_z(c.lower) for c in extra])
        upper = np.append(upper, [c.bound_z(c.upper) for c in extra])
        if self.cut is not None:  # the cut before every time (a frame at the cut excluded)
            starts = self.group_times - 0.5 * (self.interval or 0.0)  # a pair's first frame
            first = min(float(self.t_sorted[0]), float(np.min(starts, initial=np.inf)))
            upper[self.cut] = min(upper[self.cut], first * (1 - 1e-9))
        return lower, upper

    def vanishing(self, z) -> list:
        """lambda on its bound 0, where its column is 0 (R depends on lambda^2), or on its
        search limit LAMBDA_MAX, where the model has reached its viscous limit: R(t) and the
        flow depend on tau = lambda^2 T alone there (to ~1 / LAMBDA_MAX^2), so lambda's
        column is T's times (2 T / lambda) and the Jacobian is singular although the data
        determine R0, sigma and lambda^2 T; lambda's interval is then open above."""
        return [2] if z[2] <= 1e-8 or z[2] >= LAMBDA_MAX * (1 - 1e-6) else []

    def since_cut(self, z) -> tuple[np.ndarray, np.ndarray]:
        """The radius and the PIV groups' times after the cut at z [s]."""
        cut = 0.0 if self.cut is None else z[self.cut]
        return self.t_sorted - cut, self.group_times - cut

    @property
    def size(self) -> int:
        return self.n_radius + self.n_profile

    def data(self) -> np.ndarray:
        return np.concatenate([self.radius] + [g[2] for g in self.groups])

    def _h(self, lam: float, r_inf: float, times):
        """h = R(sigma = 1) - 1 and h' at ascending dimensionless times."""
        r, v = _native.series(abs(lam), 1.0, r_inf, times, tolerance=self.tolerance)
        return r - 1.0, v

    def _h_rates(self, lam: float, r_inf: float, times):
        """h, h', dh/dlambda and dh/dR_inf at ascending dimensionless times (exact on the grid)."""
        r, v, d_lam, d_r_inf = _native.series_sensitivities(
            abs(lam), 1.0, r_inf, times, tolerance=self.tolerance
        )
        return r - 1.0, v, d_lam, d_r_inf

    def model(self, z) -> np.ndarray:
        """Model values at the data points (radius [um], then velocities [um/s])."""
        R0, sigma, lam, T = theta = from_z(z)
        r_inf = self.outer / R0
        self.evaluations += 1
        t, times = self.since_cut(z)
        h, _ = self._h(lam, r_inf, t / T)
        radius = R0 * (1 + sigma * h) + (0.0 if self.offset is None else z[self.offset])
        gain = 1.0 if self.gain is None else z[self.gain]
        return np.concatenate([radius, gain * self._profile(theta, r_inf, times)])

    def residuals(self, z) -> np.ndarray:
        return self._whitened((self.model(z) - self.data()) / self.sd)

    def jacobian(self, z, columns=None) -> np.ndarray:
        """d residuals / d z, (size, n): see the module docstring (a nuisance's column: its
        declaration). Only `columns` are computed (the others are 0; None: all): a profile fit
        holds one coordinate fixed.

        Every column needs the modal basis of R_inf alone (and its rates), except at a frame
        at the cut, whose profile columns are central differences (in ln R0 between the outer
        radii rc -+ dr, two more bases)."""
        n = len(self.coordinates)
        columns = range(n) if columns is None else columns
        R0, sigma, lam, T = theta = from_z(z)
        r_inf = self.outer / R0
        t, times = self.since_cut(z)
        measured = None  # the PIV measurement's model values, when computed below
        h, dh, dh_dl, dh_dr = self._h_rates(lam, r_inf, t / T)
        with np.errstate(invalid="ignore"):
            dlnT = np.where(t > 0, -(t / T) * R0 * sigma * dh, 0.0)
        jr = np.column_stack(
            [R0 * (1 + sigma * h) - R0 * sigma * r_inf * dh_dr, R0 * h, R0 * sigma * dh_dl, dlnT]
        )
        if self.groups:
            inside = self.inside_edge  # as the last model evaluation left it
            if np.all(times > 0):
                sign = np.array([1, 1, math.copysign(1, z[2]), 1])
                profile = self._profile_columns(theta, r_inf, times) * sign
                if self.interval is not None:
                    ratio, measured = self._measure_ratio(theta, r_inf, times)
                    profile *= ratio[:, None]
            else:  # a frame at the cut: central differences
                steps = np.array([STEP, STEP * max(1.0, abs(sigma)), STEP * max(lam, 0.01), STEP])
                profile = np.zeros((self.n_profile, 4))
                for i in columns:
                    if i >= 4:  # a nuisance: its column is its declaration's
                        continue
                    if i == 0:  # R0 = outer / R_inf at R_inf = rc -+ dr, inside the solver's range
                        dr = STEP * r_inf
                        rc = max(r_inf, R_INF_MIN + dr)
                        up = self._profile((self.outer / (rc - dr), sigma, lam, T), rc - dr, times)
                        down = self._profile(
                            (self.outer / (rc + dr), sigma, lam, T), rc + dr, times
                        )
                        profile[:, 0] = (up - down) / math.log((rc + dr) / (rc - dr))
                        continue
                    e = np.zeros(len(z))
                    e[i] = steps[i]
                    profile[:, i] = (
                        self._profile(from_z(z + e), r_inf, times)
                        - self._profile(from_z(z - e), r_inf, times)
                    ) / (2 * steps[i])
            self.inside_edge = inside  # not the differences' shifted points
            jr = np.vstack([jr, profile])
        gain = 1.0 if self.gain is None else z[self.gain]
        if n > 4:
            jr = np.hstack([jr, np.zeros((self.size, n - 4))])
            if self.offset is not None:
                jr[: self.n_radius, self.offset] = 1.0
            if self.cut is not None and self.cut in columns:
                jr[:, self.cut] = self._cut_column(theta, r_inf, t, times, jr[:, 3], measured)
            if self.gain is not None and self.groups:
                if measured is None:
                    inside = self.inside_edge
                    measured = self._profile(theta, r_inf, times)
                    self.inside_edge = inside
                jr[self.n_radius :, self.gain] = measured  # the model's value
        if gain != 1.0:  # every other column of the PIV rows scales with the gain
            others = [i for i in range(n) if i != self.gain]
            jr[self.n_radius :, others] *= gain
        jr[:, [i for i in range(n) if i not in columns]] = 0.0
        return self._whitened(jr / self.sd[:, None])

    def _cut_column(self, theta, r_inf, t, times, d_ln_t, v=None) -> np.ndarray:
        """d model / d cut (CUT's declaration): (d model / d ln T + the model velocity `v` on
        the PIV rows, computed when None) / (t - cut)."""
        if v is None:
            inside = self.inside_edge
            v = self._profile(theta, r_inf, times)
            self.inside_edge = inside
        after = np.concatenate([t] + [np.full(g[1].size, s) for g, s in zip(self.groups, times)])
        return (d_ln_t + np.concatenate([np.zeros(self.n_radius), v])) / after

    def split(self, res: np.ndarray):
        """(radius part, profile part) of a vector over the data points."""
        return res[: self.n_radius], res[self.n_radius :]
