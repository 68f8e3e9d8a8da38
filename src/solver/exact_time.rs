//! Spectral elements in space, exact in time: the default engine.
//!
//! The operator of one `(lambda, R_inf, mesh)` is built once ([`super::galerkin`],
//! [`super::modal`]); each step then costs one exponential-weighted update per mode.

use super::engine::Engine;
use super::galerkin;
use super::mesh::{Mesh, MeshSpec};
use super::modal::Modes;
use super::quadrature::LagrangeBasis;
use super::{SolverError, check_lambda, check_r_inf};
use nalgebra::DVector;
use std::sync::Arc;

/// The discretised operator of one `(lambda, R_inf, mesh)`: immutable, shared between
/// a solver and its saved states.
#[derive(Debug)]
pub(crate) struct Operator {
    r_inf: f64,
    mesh: Mesh,
    modes: Modes,
    /// Row of the mode shapes at the wound edge, `X[0, :]`.
    edge_row: DVector<f64>,
}

impl Operator {
    pub(crate) fn new(lambda: f64, r_inf: f64, spec: MeshSpec) -> Result<Self, SolverError> {
        check_lambda(lambda)?;
        check_r_inf(r_inf)?;
        Self::check_mesh(spec)?;
        let mesh = Mesh::new(spec, r_inf);
        let m = galerkin::assemble(&mesh);
        let mass = 4.0 * &m.mass + lambda * lambda * &m.stiffness;
        let modes = Modes::new(&m.stiffness, &mass).map_err(SolverError::Modal)?;
        let edge_row = modes.shapes.row(0).transpose();
        Ok(Self { r_inf, mesh, modes, edge_row })
    }

    pub(crate) fn check_mesh(spec: MeshSpec) -> Result<(), SolverError> {
        let size = spec.degree.checked_mul(spec.elements).unwrap_or(usize::MAX);
        if spec.degree == 0 || spec.elements == 0 || size > 4000 {
            return Err(SolverError::Mesh("need degree >= 1, elements >= 1, degree*elements <= 4000"));
        }
        if !(spec.edge_scale.is_finite() && spec.edge_scale > 0.0) {
            return Err(SolverError::Mesh("edge_scale must be finite and > 0"));
        }
        Ok(())
    }

    /// Number of unknowns (nodes = modes).
    pub(crate) fn len(&self) -> usize {
        self.modes.len()
    }

    /// Modal target of the departure `v = u - sigma r / 6` from the uniform tension:
    ///
    /// ```text
    /// A (sigma r / 6) = F(p = sigma) exactly (the uniform tension balances both edge
    /// tractions, galerkin.rs), so  B v_t = -A v + F(p) - F(sigma) = -A v + (sigma - p) e_first
    /// and in modes  g = X^T (sigma - p) e_first = (sigma - p) X[0, :].
    /// ```
    ///
    /// Working with `v` (zero at the cut) keeps `R(0) = 1 + sigma / 6` exact and makes
    /// `p = sigma` a state of rest to the last bit.
    fn target(&self, sigma: f64, p: f64) -> DVector<f64> {
        (sigma - p) * &self.edge_row
    }
}

/// Modal state of `v = u - sigma r / 6` on a shared [`Operator`].
#[derive(Debug, Clone)]
pub(crate) struct ModalEngine {
    op: Arc<Operator>,
    sigma: f64,
    /// Modal coordinates of `v`.
    coeffs: DVector<f64>,
    /// `(h, exp(-h / nu))` of the last step size, reused while `h` repeats.
    decay: Option<(f64, DVector<f64>)>,
}

impl ModalEngine {
    pub(crate) fn new(op: Arc<Operator>, sigma: f64) -> Self {
        let coeffs = DVector::zeros(op.len());
        Self { op, sigma, coeffs, decay: None }
    }

    /// Modal rates `c_k' = (g_k - c_k) / nu_k`.
    fn modal_rates(&self, p: f64) -> DVector<f64> {
        let target = self.op.target(self.sigma, p);
        (target - &self.coeffs).component_div(&self.op.modes.nu)
    }

    fn profile(&self, coeffs: &DVector<f64>, radii: &[f64]) -> Vec<f64> {
        let mesh = &self.op.mesh;
        let nodal = &self.op.modes.shapes * coeffs;
        let basis = LagrangeBasis::new(&mesh.reference_nodes);
        radii
            .iter()
            .map(|&r| {
                let (e, x) = mesh.locate(r.clamp(1.0, self.op.r_inf));
                let (val, _) = basis.eval(x);
                val.iter().enumerate().map(|(i, l)| l * nodal[mesh.global(e, i)]).sum()
            })
            .collect()
    }
}

impl Engine for ModalEngine {
    /// Exact for any `h`: `c_k <- g_k + exp(-h / nu_k) (c_k - g_k)`.
    fn advance(&mut self, h: f64, p: f64) {
        let nu = &self.op.modes.nu;
        let decay = match &self.decay {
            Some((h0, d)) if *h0 == h => d,
            _ => &self.decay.insert((h, nu.map(|v| (-h / v).exp()))).1,
        };
        let target = self.op.target(self.sigma, p);
        for k in 0..self.coeffs.len() {
            self.coeffs[k] = target[k] + decay[k] * (self.coeffs[k] - target[k]);
        }
    }

    /// `R = 1 + sigma / 6 + v(1, t)`.
    fn wound_radius(&self) -> f64 {
        1.0 + self.sigma / 6.0 + self.op.edge_row.dot(&self.coeffs)
    }

    /// `sum_k X[0, k] (g_k - c_k) / nu_k`.
    fn edge_velocity(&self, p: f64) -> f64 {
        self.modal_rates(p).dot(&self.op.edge_row)
    }

    /// ```text
    /// d/dp sum_k X[0, k] ((sigma - p) X[0, k] - c_k) / nu_k = -sum_k X[0, k]^2 / nu_k
    /// ```
    /// (independent of the state: a negative constant of the operator).
    fn edge_velocity_slope(&self) -> f64 {
        -self.op.edge_row.iter().zip(self.op.modes.nu.iter()).map(|(x, nu)| x * x / nu).sum::<f64>()
    }

    fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        let v = self.profile(&self.coeffs, radii);
        radii.iter().zip(v).map(|(r, v)| self.sigma * r.clamp(1.0, self.op.r_inf) / 6.0 + v).collect()
    }

    fn velocity(&self, p: f64, radii: &[f64]) -> Vec<f64> {
        self.profile(&self.modal_rates(p), radii)
    }

    fn unknowns(&self) -> usize {
        self.op.len()
    }

    fn state(&self) -> Vec<f64> {
        self.coeffs.iter().copied().collect()
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), SolverError> {
        self.coeffs.copy_from_slice(state);
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Engine> {
        Box::new(self.clone())
    }
}
