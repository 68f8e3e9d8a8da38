//! An explicit scheme on the paper's grid: the baseline that fails as lambda grows.
//!
//! The viscous term `lambda^2 D2 u_t` is taken from the previous step, so that no system
//! is solved inside the domain:
//!
//! ```text
//! v^n_i     = D2 u^n_i + lambda^2 D2 v^{n-1}_i          (interior)
//! u^{n+1}_i = u^n_i + dt v^n_i
//! edges:      D (u^{n+1} + lambda^2 (u^{n+1} - u^n) / dt) = s    (one unknown per edge)
//! ```
//!
//! Stability (von Neumann, interior): a mode with `D2 -> -kappa` obeys
//! `z^2 + (a - 1 + dt kappa) z - a = 0`, `a = lambda^2 kappa`. Both roots lie in the
//! unit disc iff `a < 1` and `dt kappa < 2 (1 - a)`, so with `kappa_max ~ 4 / dr^2`:
//!
//! ```text
//! lambda < 1 / sqrt(kappa_max) ~ dr / 2     (whatever dt: the lagged viscous term alone)
//! dt     < 2 / kappa_max - 2 lambda^2       (~ dr^2 / 2 - 2 lambda^2)
//! ```
//!
//! This is the explicit variant whose instability grows with lambda, as the paper states.
//! [`stability_limits`] evaluates both limits with the grid's exact `kappa_max`.

use super::SolverError;
use super::engine::{Engine, interpolate};
use super::fd::{Grid, Row};
use std::sync::Arc;

#[derive(Debug, Clone)]
pub(crate) struct ExplicitEngine {
    grid: Arc<Grid>,
    lambda: f64,
    sigma: f64,
    max_step: f64,
    u: Vec<f64>,
    /// `v^{n-1}`, the velocity of the last step.
    v: Vec<f64>,
    /// `kappa_max` of this grid (see [`stability_limits`]).
    kappa: f64,
}

impl ExplicitEngine {
    pub(crate) fn new(grid: Arc<Grid>, lambda: f64, sigma: f64, max_step: f64) -> Self {
        let u = grid.r.iter().map(|r| sigma * r / 6.0).collect();
        let v = vec![0.0; grid.len()];
        let kappa = kappa_max(&grid);
        Self { grid, lambda, sigma, max_step, u, v, kappa }
    }

    /// Solve the edge row `D (u' + c (u' - u)) = s` for the edge value, given the neighbour's
    /// new value; `row` holds the edge and neighbour coefficients `(d_edge, d_neighbour)`.
    fn edge_value(row: (f64, f64), c: f64, s: f64, old: (f64, f64), neighbour_new: f64) -> f64 {
        let (de, dn) = row;
        (s + de * c * old.0 - dn * ((1.0 + c) * neighbour_new - c * old.1)) / (de * (1.0 + c))
    }

    fn step(&mut self, dt: f64, p: f64) {
        let n = self.grid.len();
        let l2 = self.lambda * self.lambda;
        let d2u = self.grid.d2_of(&self.u);
        let d2v = self.grid.d2_of(&self.v);
        let mut v: Vec<f64> = (0..n).map(|i| d2u[i] + l2 * d2v[i]).collect();
        let mut u: Vec<f64> = (0..n).map(|i| self.u[i] + dt * v[i]).collect();
        let c = l2 / dt;
        let (e, o): (Row, Row) = (self.grid.d_edge, self.grid.d_outer);
        u[0] = Self::edge_value((e[1], e[2]), c, p, (self.u[0], self.u[1]), u[1]);
        u[n - 1] =
            Self::edge_value((o[1], o[0]), c, self.sigma, (self.u[n - 1], self.u[n - 2]), u[n - 2]);
        v[0] = (u[0] - self.u[0]) / dt;
        v[n - 1] = (u[n - 1] - self.u[n - 1]) / dt;
        self.u = u;
        self.v = v;
    }
}

/// `(lambda_max, dt_max(lambda))` of the explicit scheme on an `N`-point grid, from the
/// largest `kappa` of `-D2` (interior rows, Dirichlet-closed), by the analysis above.
pub fn stability_limits(points: usize, r_inf: f64, lambda: f64) -> (f64, f64) {
    limits(kappa_max(&Grid::new(points, r_inf)), lambda)
}

/// Wound radius after each of `steps` explicit steps of `dt` from the cut, with no
/// stability check: for measuring where the scheme really fails (examples/stability_map.rs,
/// tests/stability.rs), which the [`super::Solver`] no longer lets it reach.
pub fn unchecked_trajectory(
    points: usize,
    r_inf: f64,
    lambda: f64,
    sigma: f64,
    dt: f64,
    steps: usize,
) -> Vec<f64> {
    let mut engine = ExplicitEngine::new(Arc::new(Grid::new(points, r_inf)), lambda, sigma, dt);
    (0..steps)
        .map(|_| {
            engine.step(dt, 0.0);
            engine.wound_radius()
        })
        .collect()
}

fn limits(kappa: f64, lambda: f64) -> (f64, f64) {
    (1.0 / kappa.sqrt(), 2.0 / kappa - 2.0 * lambda * lambda)
}

fn kappa_max(grid: &Grid) -> f64 {
    let n = grid.len();
    let rows: Vec<Row> = grid.d2[1..n - 1].to_vec();
    spectral_radius(&rows)
}

/// Largest |eigenvalue| of a tridiagonal matrix whose off-diagonal products are positive
/// (similar to a symmetric one), by bisection on its Sturm sequence.
fn spectral_radius(rows: &[Row]) -> f64 {
    let m = rows.len();
    let diag: Vec<f64> = rows.iter().map(|r| r[1]).collect();
    let prod: Vec<f64> = (1..m).map(|i| rows[i][0] * rows[i - 1][2]).collect();
    let bound = rows.iter().map(|r| r[0].abs() + r[1].abs() + r[2].abs()).fold(0.0, f64::max);
    // Count eigenvalues below x (Sturm sequence of the symmetrised matrix).
    let below = |x: f64| {
        let (mut count, mut q) = (0, diag[0] - x);
        if q < 0.0 {
            count += 1;
        }
        for i in 1..m {
            let qq = if q == 0.0 { 1e-300 } else { q };
            q = diag[i] - x - prod[i - 1] / qq;
            if q < 0.0 {
                count += 1;
            }
        }
        count
    };
    let (mut lo, mut hi) = (-bound, bound);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if below(mid) >= 1 { hi = mid } else { lo = mid }
    }
    // D2 is negative definite: the most negative eigenvalue is the spectral radius.
    (0.5 * (lo + hi)).abs()
}

impl Engine for ExplicitEngine {
    fn advance(&mut self, h: f64, p: f64) {
        super::engine::substeps(h, self.max_step, |dt| self.step(dt, p));
    }

    fn wound_radius(&self) -> f64 {
        1.0 + self.u[0]
    }

    fn edge_velocity(&self, _p: f64) -> f64 {
        self.v[0]
    }

    fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        interpolate(&self.grid.r, &self.u, radii)
    }

    fn velocity(&self, _p: f64, radii: &[f64]) -> Vec<f64> {
        interpolate(&self.grid.r, &self.v, radii)
    }

    fn unknowns(&self) -> usize {
        self.grid.len()
    }

    /// `[u.., v..]`.
    fn state(&self) -> Vec<f64> {
        [self.u.as_slice(), self.v.as_slice()].concat()
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), SolverError> {
        let n = self.grid.len();
        self.u.copy_from_slice(&state[..n]);
        self.v.copy_from_slice(&state[n..]);
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Engine> {
        Box::new(self.clone())
    }

    fn step_work(&self, h: f64) -> f64 {
        super::engine::step_count(h, self.max_step) * self.grid.len() as f64
    }

    fn may_diverge(&self) -> bool {
        true
    }

    /// Refuse, before taking it, a step whose internal step `h / ceil(h / max_step)` or
    /// whose lambda breaks the von Neumann limits above (measured limits lie 0.2 % to 3 %
    /// beyond them, so nothing stable is refused by more than that).
    fn check_step(&self, h: f64) -> Result<(), SolverError> {
        let (lambda_max, dt_max) = limits(self.kappa, self.lambda);
        let dt = h / super::engine::step_count(h, self.max_step);
        if self.lambda >= lambda_max || dt >= dt_max {
            return Err(SolverError::Unstable { lambda: self.lambda, lambda_max, dt, dt_max });
        }
        Ok(())
    }
}
