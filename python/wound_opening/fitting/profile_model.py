"""The PIV rows of a one-wound fit: the model's values at the profile points and their
Jacobian columns, and the whitening of correlated profile errors (a mixin of
objective.Objective, which holds the data: `groups`, `outer`, `tolerance`, `interval`,
`half_window`, `n_radius`, `inside_edge`; the mathematics is in objective.py's module
docstring and piv_measure.py)."""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_triangular

from .. import _native
from . import piv_measure, serial

#: Relative step of the central differences.
STEP = 1e-4


class ProfileModel:
    """Model values, Jacobian columns and whitening of the profile rows."""

    def _whitening(self, profile):
        """The inverse of the lower Cholesky factor L of the profile points' correlation
        matrix (group order), or None: the profile's residuals are then L^-1 (model - data) / sd,
        independent and of unit variance when the covariance holds."""
        cov = getattr(profile, "covariance", None) if profile is not None else None
        if cov is None:
            return None
        rows = np.concatenate([g[3] for g in self.groups])
        c = np.asarray(cov, float)[np.ix_(rows, rows)]
        sd = np.sqrt(np.diag(c))
        lower = np.linalg.cholesky(c / np.outer(sd, sd))
        return solve_triangular(lower, np.eye(sd.size), lower=True)  # L^-1, once

    def _whitened(self, a: np.ndarray) -> np.ndarray:
        """`a` (residuals or Jacobian rows over sd) with its radius rows' serial correlation
        (serial.py) and its profile rows' correlation whitened."""
        out = a
        if self.radius_rho:
            out = out.copy()
            out[: self.n_radius] = serial.whiten(a[: self.n_radius], self.radius_rho, self.gaps)
        if self.whiten is not None:
            out = out.copy() if out is a else out
            out[self.n_radius :] = self.whiten @ a[self.n_radius :]
        return out

    def _rows(self, R0: float, edge_r: np.ndarray) -> list:
        """Per group the rows' radii in R0 with the mask of those beyond the model's wound
        edge (`edge_r`, in R0, per group): the tissue."""
        rows = []
        for k, (_, r, _, _) in enumerate(self.groups):
            x = r / R0
            rows.append((x, x > edge_r[k] * (1 + 1e-12)))
        return rows

    def _profile(self, theta, r_inf: float, times) -> np.ndarray:
        """Model values [um/s] of the profile rows (group order) at the groups' `times` after
        the cut: the PIV measurement (piv_measure.py) when the profile has a frame interval,
        else the velocity (_velocity); sets `inside_edge`."""
        if self.interval is None or not self.groups:
            return self._velocity(theta, r_inf, times)
        key = _key(theta, r_inf, times)
        last = getattr(self, "_last_measure", None)
        if last is not None and last[0] == key:  # the Jacobian at the point just evaluated
            self.inside_edge = last[2]
            return last[1].copy()
        out = self._measure(theta, r_inf, times)
        self._last_measure = (key, out.copy(), self.inside_edge)
        return out

    def _measure(self, theta, r_inf: float, times) -> np.ndarray:
        """The PIV measurement's model values of the profile rows (piv_measure.py)."""
        R0, sigma, lam, T = theta
        half_dt = 0.5 * self.interval
        ends = np.concatenate([times - half_dt, times + half_dt]) / T
        order = np.argsort(ends, kind="stable")
        h = np.empty_like(ends)
        h[order] = self._h(lam, r_inf, ends[order])[0]
        edge = 1.0 + sigma * h
        m = times.size
        r, group = self._flat_rows()
        x = r / R0
        v = piv_measure.flat_window_velocities(
            abs(lam),
            sigma,
            r_inf,
            ends[:m],
            ends[m:],
            x,
            group,
            self.half_window / R0,
            edge[:m],
            edge[m:],
            tolerance=self.tolerance,
        )
        self.inside_edge = int(np.count_nonzero(~(x > edge[:m][group] * (1 + 1e-12))))
        return R0 / T * v

    def _flat_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """The profile rows' radii [um] in group order and each row's group, made once."""
        known = getattr(self, "_flat", None)
        if known is None or known[0] is not self.groups:
            r = [np.asarray(g[1], float) for g in self.groups]
            group = np.repeat(np.arange(len(r)), [x.size for x in r])
            known = self._flat = (self.groups, np.concatenate(r), group)
        return known[1], known[2]

    def _velocity(self, theta, r_inf: float, times) -> np.ndarray:
        """Model velocities [um/s] of the profile rows (group order) at the groups' `times`
        after the cut, the edge velocity for rows at or inside the model's wound edge; sets
        `inside_edge`."""
        R0, sigma, lam, T = theta
        if not self.groups:
            return np.empty(0)
        tau = times / T
        h, dh = self._h(lam, r_inf, tau)
        out, inside = [], 0
        for k, (x, tissue) in enumerate(self._rows(R0, 1.0 + sigma * h)):
            v = np.full(x.size, sigma * dh[k])
            if np.any(tissue):
                _, vt = _native.profile_series(
                    abs(lam), sigma, r_inf, [tau[k]], x[tissue], tolerance=self.tolerance
                )
                v[tissue] = vt[0]
            inside += int(np.sum(~tissue))
            out.append(R0 / T * v)
        self.inside_edge = inside
        return np.concatenate(out)

    def _profile_columns(self, theta, r_inf: float, times) -> np.ndarray:
        """d (model velocity) / d (ln R0, sigma, lambda, ln T) of the profile rows,
        (n_profile, 4).

        With the dimensionless velocity V at fixed current radius x = r / R0, tau = t / T and
        R_inf = outer / R0, the data's R0 / T V has d/d sigma = R0/T dV/dsigma,
        d/d lambda = R0/T dV/dlambda, d/d ln T = -(R0/T) (V + tau dV/dtau) and
        d/d ln R0 = R0/T (V - x dV/dx - R_inf dV/dR_inf) (x and R_inf both scale as 1 / R0),
        exact on the solver's grid; edge rows take the edge's (its material point held:
        dV/dx = 0). A row switches from tissue to edge where the edge radius e(z) crosses its
        x: the model is continuous there, its slope is not. With g = e - x and its rate
        g' (h, sigma dh/dlambda, -tau sigma h' in sigma, lambda, ln T; x - R_inf sigma
        dh/dR_inf in ln R0, where x moves too), where the crossing is within the step s of a
        coordinate (|g / g'| < s), the column is the central difference over z -+ s of the two
        one-sided slopes (the edge's own, J_in, and the tissue's limit at the edge, J_out):
        with the crossing at d = -g / g' and J_+ the slope beyond it (J_in when g' > 0),
        (J_- (s + d) + J_+ (s - d)) / (2 s). This is the central difference the fit used
        before, without its evaluations; a one-sided slope there leaves the trust region
        stepping across the kink (fits stop at a chi^2 higher by ~1e-5 and move the
        estimates in their 4th digit)."""
        R0, sigma, lam, T = theta
        tau = times / T
        h, dh, dh_dl, dh_dr = self._h_rates(lam, r_inf, tau)
        edge_r = 1.0 + sigma * h
        step = np.array([STEP, STEP * max(1.0, abs(sigma)), STEP * max(lam, 0.01), STEP])
        rows = self._rows(R0, edge_r)
        k = np.repeat(np.arange(tau.size), [x.size for x, _ in rows])  # each row's group
        x = np.concatenate([x for x, _ in rows])
        tissue = np.concatenate([m for _, m in rows])
        order = np.argsort(tau, kind="stable")
        edge = np.empty((tau.size, 2, 6))
        edge[order] = _native.profile_rates(
            abs(lam), sigma, r_inf, tau[order], [], tolerance=self.tolerance
        )[1]
        d_in = edge[k, 0]  # (V, dV/dsigma, dV/dlambda, dV/dtau, dV/dR_inf, dV/dx)
        d_out = edge[k, 1].copy()
        if np.any(tissue):
            d_out[tissue] = _native.point_rates(
                abs(lam), sigma, r_inf, tau[k][tissue], x[tissue], tolerance=self.tolerance
            )
        tau_k = tau[k]

        def columns(d):  # d V / d z
            return np.column_stack(
                [
                    d[:, 0] - x * d[:, 5] - r_inf * d[:, 4],
                    d[:, 1],
                    d[:, 2],
                    -(d[:, 0] + tau_k * d[:, 3]),
                ]
            )

        j_in, j_out = columns(d_in), columns(d_out)
        j = np.where(tissue[:, None], j_out, j_in)
        slope = np.column_stack(  # g' per row and coordinate
            [x - r_inf * sigma * dh_dr[k], h[k], sigma * dh_dl[k], -tau_k * sigma * dh[k]]
        )
        j_plus = np.where(slope > 0, j_in, j_out)
        j_minus = np.where(slope > 0, j_out, j_in)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # g' = 0: never near
            cross = -(edge_r[k] - x)[:, None] / slope
            blend = (j_minus * (step + cross) + j_plus * (step - cross)) / (2 * step)
        near = np.abs(cross) < step
        velocity = np.where(tissue, d_out[:, 0], d_in[:, 0])
        self._rates_velocity = (_key(theta, r_inf, times), R0 / T * velocity)
        return R0 / T * np.where(near, blend, j)

    def _measure_ratio(self, theta, r_inf, times) -> np.ndarray:
        """Per profile row, the PIV measurement over the velocity at the pair's middle and
        the window's centre: the measurement's Jacobian rows are the velocity's (exact) times
        this ratio. The ratio's own derivatives are left out: they move the gradient by a
        fraction of the residuals (1e-2 of them for pairs as long as T), so the optimum and the
        profile likelihoods move by a negligible part of a unit of chi^2, while the residuals
        and chi^2 themselves are exact. A velocity within 1e-9 of the largest is given
        ratio 1. Returns (ratio, measurement)."""
        inside = self.inside_edge
        m = self._profile(theta, r_inf, times)
        known = getattr(self, "_rates_velocity", None)  # from _profile_columns, at this point
        if known is not None and known[0] == _key(theta, r_inf, times):
            e = known[1]
        else:
            e = self._velocity(theta, r_inf, times)
        self.inside_edge = inside
        small = np.abs(e) <= 1e-9 * max(float(np.max(np.abs(e), initial=0.0)), 1e-300)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(small, 1.0, m / e), m


def _key(theta, r_inf, times) -> tuple:
    """What the model's profile rows depend on, as a cache key."""
    return (tuple(theta), r_inf, np.asarray(times, float).tobytes())
