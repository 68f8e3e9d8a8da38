//! The paper's scheme, exactly as in its appendix: a reproduction, not the default.
//!
//! ```text
//! interior:  (-I + (lambda^2 + 2 dt) D2) u^{n+1} = (-I + lambda^2 D2) u^{n-1}
//! edges:     (lambda^2 + 2 dt) D u^{n+1} = lambda^2 D u^{n-1} + 2 dt s,   s = p (wound), sigma (outer)
//! ```
//!
//! Step n+1 depends on step n-1 only: it is backward Euler with step `2 dt`, run twice
//! (even and odd levels never interact). The paper gives no start value `u^1`; this
//! reproduction takes one backward-Euler step of `dt` from `u^0` (the same rows with
//! `2 dt -> dt`), and does the same whenever the step size changes. With the first-order
//! edge rows of [`super::fd`], the method is first order in space and in time.
//!
//! Outputs: `R = 1 + u^n_0`, edge velocity `(u^n_0 - u^{n-1}_0) / dt`.

use super::SolverError;
use super::engine::{Engine, interpolate};
use super::fd::{Grid, Row, Tridiagonal};
use std::sync::Arc;

#[derive(Debug, Clone)]
pub(crate) struct PaperEngine {
    grid: Arc<Grid>,
    lambda: f64,
    sigma: f64,
    /// Largest internal step; each communication step uses `n` equal steps `dt <= max_step`.
    max_step: f64,
    /// `u^{n-1}`, `u^n` and their spacing (0 before the first step).
    prev: Vec<f64>,
    now: Vec<f64>,
    spacing: f64,
    /// Factorisations for `(dt, 2 dt)` of the current spacing.
    systems: Option<(f64, Tridiagonal, Tridiagonal)>,
}

impl PaperEngine {
    pub(crate) fn new(grid: Arc<Grid>, lambda: f64, sigma: f64, max_step: f64) -> Self {
        let u0: Vec<f64> = grid.r.iter().map(|r| sigma * r / 6.0).collect();
        Self {
            grid,
            lambda,
            sigma,
            max_step,
            prev: u0.clone(),
            now: u0,
            spacing: 0.0,
            systems: None,
        }
    }

    /// Matrix rows of `(-I + (lambda^2 + k) D2)` inside, `(lambda^2 + k) D` at the edges.
    fn rows(&self, k: f64) -> Vec<Row> {
        let c = self.lambda * self.lambda + k;
        let n = self.grid.len();
        (0..n)
            .map(|i| match i {
                0 => self.grid.d_edge.map(|x| c * x),
                _ if i == n - 1 => self.grid.d_outer.map(|x| c * x),
                _ => {
                    let d = self.grid.d2[i];
                    [c * d[0], c * d[1] - 1.0, c * d[2]]
                }
            })
            .collect()
    }

    /// Right side `(-I + lambda^2 D2) u` inside, `lambda^2 D u + k s` at the edges.
    fn rhs(&self, u: &[f64], k: f64, p: f64) -> Vec<f64> {
        let l2 = self.lambda * self.lambda;
        let n = u.len();
        (0..n)
            .map(|i| match i {
                0 => l2 * Grid::apply(&self.grid.d_edge, u, 0) + k * p,
                _ if i == n - 1 => l2 * Grid::apply(&self.grid.d_outer, u, i) + k * self.sigma,
                _ => -u[i] + l2 * Grid::apply(&self.grid.d2[i], u, i),
            })
            .collect()
    }

    fn step(&mut self, dt: f64, p: f64) {
        if self.systems.as_ref().is_none_or(|s| s.0 != dt) {
            self.systems = Some((
                dt,
                Tridiagonal::factor(&self.rows(dt)),
                Tridiagonal::factor(&self.rows(2.0 * dt)),
            ));
        }
        let (_, single, double) = self.systems.as_ref().expect("set above");
        if self.spacing != dt {
            // (Re)start: one backward-Euler step of dt from the current level.
            let mut next = self.rhs(&self.now, dt, p);
            single.solve(&mut next);
            self.prev = std::mem::replace(&mut self.now, next);
            self.spacing = dt;
            return;
        }
        let mut next = self.rhs(&self.prev, 2.0 * dt, p);
        double.solve(&mut next);
        self.prev = std::mem::replace(&mut self.now, next);
    }
}

impl Engine for PaperEngine {
    fn advance(&mut self, h: f64, p: f64) {
        super::engine::substeps(h, self.max_step, |dt| self.step(dt, p));
    }

    fn wound_radius(&self) -> f64 {
        1.0 + self.now[0]
    }

    fn edge_velocity(&self, _p: f64) -> f64 {
        if self.spacing > 0.0 { (self.now[0] - self.prev[0]) / self.spacing } else { 0.0 }
    }

    fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        interpolate(&self.grid.r, &self.now, radii)
    }

    fn velocity(&self, _p: f64, radii: &[f64]) -> Vec<f64> {
        let s = if self.spacing > 0.0 { self.spacing } else { 1.0 };
        let v: Vec<f64> = self.now.iter().zip(&self.prev).map(|(a, b)| (a - b) / s).collect();
        interpolate(&self.grid.r, &v, radii)
    }

    fn unknowns(&self) -> usize {
        self.grid.len()
    }

    /// `[spacing, u^{n-1}.., u^n..]`.
    fn state(&self) -> Vec<f64> {
        let mut s = vec![self.spacing];
        s.extend(&self.prev);
        s.extend(&self.now);
        s
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), SolverError> {
        let n = self.grid.len();
        self.spacing = state[0];
        self.prev.copy_from_slice(&state[1..=n]);
        self.now.copy_from_slice(&state[n + 1..]);
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Engine> {
        Box::new(self.clone())
    }

    fn step_work(&self, h: f64) -> f64 {
        super::engine::step_count(h, self.max_step) * self.grid.len() as f64
    }
}
