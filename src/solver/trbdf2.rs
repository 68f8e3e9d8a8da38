//! The Galerkin system of [`super::galerkin`] stepped in time by TR-BDF2: the "careful
//! second-order" alternative to exact time integration, with a time-step error to measure.
//!
//! For `B v' = -A v + f`, `f = (sigma - p) e_first`, `v = u - sigma r / 6`, a step `dt` is
//! (Bank et al. 1985; L-stable, second order, `gamma = 2 - sqrt 2`):
//!
//! ```text
//! (B + gamma dt/2 A) v_g   = (B - gamma dt/2 A) v_n + gamma dt f                 (trapezoid)
//! (B + w dt A)       v_n+1 = B (v_g - (1 - gamma)^2 v_n) / (gamma (2 - gamma)) + w dt f,
//!                                                          w = (1 - gamma) / (2 - gamma)   (BDF2)
//! ```
//!
//! Both matrices are symmetric positive definite (Cholesky, cached per `dt`).

use super::SolverError;
use super::engine::Engine;
use super::galerkin;
use super::mesh::Mesh;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use std::sync::Arc;

const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;

/// A Cholesky factor of one step's system.
type Factor = Cholesky<f64, Dyn>;

#[derive(Debug)]
pub(crate) struct TrBdf2Operator {
    mesh: Mesh,
    stiffness: DMatrix<f64>,
    mass: DMatrix<f64>,
    mass_chol: Cholesky<f64, Dyn>,
}

impl TrBdf2Operator {
    pub(crate) fn new(mesh: Mesh, lambda: f64) -> Result<Self, SolverError> {
        let m = galerkin::assemble(&mesh, galerkin::Functions::Nodal);
        let mass = 4.0 * &m.mass + lambda * lambda * &m.stiffness;
        let mass_chol = mass
            .clone()
            .cholesky()
            .ok_or(SolverError::Mesh("mass matrix is not positive definite"))?;
        Ok(Self { mesh, stiffness: m.stiffness, mass, mass_chol })
    }
}

#[derive(Debug, Clone)]
pub(crate) struct TrBdf2Engine {
    op: Arc<TrBdf2Operator>,
    sigma: f64,
    max_step: f64,
    v: DVector<f64>,
    /// `(dt, chol(B + gamma dt/2 A), chol(B + w dt A))`.
    systems: Option<(f64, Factor, Factor)>,
}

impl TrBdf2Engine {
    pub(crate) fn new(op: Arc<TrBdf2Operator>, sigma: f64, max_step: f64) -> Self {
        let v = DVector::zeros(op.mesh.len());
        Self { op, sigma, max_step, v, systems: None }
    }

    fn load(&self, p: f64) -> DVector<f64> {
        let mut f = DVector::zeros(self.v.len());
        f[0] = self.sigma - p;
        f
    }

    fn step(&mut self, dt: f64, p: f64) {
        let (a, b) = (&self.op.stiffness, &self.op.mass);
        let w = (1.0 - GAMMA) / (2.0 - GAMMA);
        if self.systems.as_ref().is_none_or(|s| s.0 != dt) {
            let tr = (b + (GAMMA * dt / 2.0) * a).cholesky().expect("SPD: B + c A with c > 0");
            let bdf = (b + (w * dt) * a).cholesky().expect("SPD: B + c A with c > 0");
            self.systems = Some((dt, tr, bdf));
        }
        let f = self.load(p);
        let (_, tr, bdf) = self.systems.as_ref().expect("set above");
        let vg = tr.solve(&(b * &self.v - (GAMMA * dt / 2.0) * (a * &self.v) + (GAMMA * dt) * &f));
        let mix = (vg - (1.0 - GAMMA).powi(2) * &self.v) / (GAMMA * (2.0 - GAMMA));
        self.v = bdf.solve(&(b * mix + (w * dt) * f));
    }

    /// `v' = B^-1 (f - A v)`.
    fn rate(&self, p: f64) -> DVector<f64> {
        self.op.mass_chol.solve(&(self.load(p) - &self.op.stiffness * &self.v))
    }
}

impl Engine for TrBdf2Engine {
    fn advance(&mut self, h: f64, p: f64) {
        super::engine::substeps(h, self.max_step, |dt| self.step(dt, p));
    }

    fn wound_radius(&self) -> f64 {
        1.0 + self.sigma / 6.0 + self.v[0]
    }

    fn edge_velocity(&self, p: f64) -> f64 {
        self.rate(p)[0]
    }

    fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        let nodes = self.op.mesh.nodes();
        let u: Vec<f64> =
            nodes.iter().zip(self.v.iter()).map(|(r, v)| self.sigma * r / 6.0 + v).collect();
        super::engine::interpolate(nodes, &u, radii)
    }

    fn velocity(&self, p: f64, radii: &[f64]) -> Vec<f64> {
        super::engine::interpolate(self.op.mesh.nodes(), self.rate(p).as_slice(), radii)
    }

    fn unknowns(&self) -> usize {
        self.v.len()
    }

    fn state(&self) -> Vec<f64> {
        self.v.iter().copied().collect()
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), SolverError> {
        self.v.copy_from_slice(state);
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Engine> {
        Box::new(self.clone())
    }

    fn step_work(&self, h: f64) -> f64 {
        super::engine::step_count(h, self.max_step) * (self.v.len() * self.v.len()) as f64
    }
}
