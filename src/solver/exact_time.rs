//! Spectral elements in space, exact in time: the default engine.
//!
//! The operator of one `(lambda, R_inf, mesh)` is built once ([`super::galerkin`],
//! [`super::modal`]); each step then costs one exponential-weighted update per mode.

use super::basis;
use super::engine::{Engine, Ode};
use super::exact;
use super::mesh::MeshSpec;
use super::modal::Basis;
use super::quadrature::LagrangeBasis;
use super::{SolverError, check_lambda, check_r_inf};
use nalgebra::DVector;
use std::sync::Arc;

/// The discretised operator of one `(lambda, R_inf, mesh)`: the shared lambda-independent
/// [`Basis`] with this lambda's relaxation times. Immutable, shared between a solver and
/// its saved states.
#[derive(Debug)]
pub(crate) struct Operator {
    lambda: f64,
    r_inf: f64,
    basis: Arc<Basis>,
    /// `nu_k = mu_k + lambda^2`.
    nu: DVector<f64>,
    /// Exact `d u_t(1) / d p` of the continuous model ([`exact::edge_velocity_slope`]);
    /// `-inf` at `lambda = 0`.
    slope: f64,
}

impl Operator {
    pub(crate) fn new(lambda: f64, r_inf: f64, spec: MeshSpec) -> Result<Self, SolverError> {
        check_lambda(lambda)?;
        check_r_inf(r_inf)?;
        Self::check_mesh(spec)?;
        let basis = basis::basis(spec, r_inf).map_err(SolverError::Modal)?;
        let nu = basis.relaxation_times(lambda);
        let slope = if lambda > 0.0 {
            exact::edge_velocity_slope(lambda, r_inf)
        } else {
            f64::NEG_INFINITY
        };
        Ok(Self { lambda, r_inf, basis, nu, slope })
    }

    pub(crate) fn check_mesh(spec: MeshSpec) -> Result<(), SolverError> {
        let size = spec.degree.saturating_mul(spec.elements);
        if spec.degree == 0 || spec.elements == 0 || size > 4000 {
            return Err(SolverError::Mesh(
                "need degree >= 1, elements >= 1, degree*elements <= 4000",
            ));
        }
        if !(spec.edge_scale.is_finite() && spec.edge_scale > 0.0) {
            return Err(SolverError::Mesh("edge_scale must be finite and > 0"));
        }
        Ok(())
    }

    /// Number of unknowns (nodes = modes).
    pub(crate) fn len(&self) -> usize {
        self.basis.len()
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
        (sigma - p) * &self.basis.edge_row
    }
}

/// Modal state of `v = u - sigma r / 6` on a shared [`Operator`].
///
/// The velocity is split at the edge stress `p_ref` under which the state last evolved
/// (`sigma` at the cut, where the uniform tension is at rest under `p = sigma`):
///
/// ```text
/// u_t(r; p) = u_t,mesh(r; p_ref) + (p - p_ref) w(r)
/// ```
///
/// The first term is the mesh's velocity of a state that evolved smoothly; the second is
/// the instantaneous response to a change of the edge stress, a boundary layer of width
/// lambda that no lambda-independent mesh resolves for small lambda, taken from its closed
/// form ([`exact::velocity_response`]). At `lambda = 0` that response is infinite: see
/// [`Engine::feedthrough_defined`].
#[derive(Debug, Clone)]
pub(crate) struct ModalEngine {
    op: Arc<Operator>,
    sigma: f64,
    /// Modal coordinates of `v`.
    coeffs: DVector<f64>,
    /// The edge stress of the last step (`sigma` at the cut).
    p_ref: f64,
    /// `(h, exp(-h / nu))` of the last step size, reused while `h` repeats.
    decay: Option<(f64, DVector<f64>)>,
}

impl ModalEngine {
    pub(crate) fn new(op: Arc<Operator>, sigma: f64) -> Self {
        let coeffs = DVector::zeros(op.len());
        Self { op, sigma, coeffs, p_ref: sigma, decay: None }
    }

    /// Modal rates `c_k' = (g_k - c_k) / nu_k` under the edge stress `p`.
    fn modal_rates(&self, p: f64) -> DVector<f64> {
        let target = self.op.target(self.sigma, p);
        (target - &self.coeffs).component_div(&self.op.nu)
    }

    fn profile(&self, coeffs: &DVector<f64>, radii: &[f64]) -> Vec<f64> {
        let mesh = &self.op.basis.mesh;
        let nodal = &self.op.basis.shapes * coeffs;
        let basis = LagrangeBasis::new(&mesh.reference_nodes);
        let (mut val, mut der) = (vec![0.0; basis.len()], vec![0.0; basis.len()]);
        radii
            .iter()
            .map(|&r| {
                let (e, x) = mesh.locate(r.clamp(1.0, self.op.r_inf));
                basis.eval_into(x, &mut val, &mut der);
                val.iter().enumerate().map(|(i, l)| l * nodal[mesh.global(e, i)]).sum()
            })
            .collect()
    }

    /// `(p - p_ref) * response`, exactly 0 when `p = p_ref` (also at `lambda = 0`).
    fn jump(&self, p: f64, response: f64) -> f64 {
        if p == self.p_ref { 0.0 } else { (p - self.p_ref) * response }
    }
}

impl Engine for ModalEngine {
    /// Exact for any `h`: `c_k <- g_k + exp(-h / nu_k) (c_k - g_k)`.
    fn advance(&mut self, h: f64, p: f64) {
        let nu = &self.op.nu;
        let decay = match &self.decay {
            Some((h0, d)) if *h0 == h => d,
            _ => &self.decay.insert((h, nu.map(|v| (-h / v).exp()))).1,
        };
        let target = self.op.target(self.sigma, p);
        for k in 0..self.coeffs.len() {
            self.coeffs[k] = target[k] + decay[k] * (self.coeffs[k] - target[k]);
        }
        self.p_ref = p;
    }

    /// `R = 1 + sigma / 6 + v(1, t)`.
    fn wound_radius(&self) -> f64 {
        1.0 + self.sigma / 6.0 + self.op.basis.edge_row.dot(&self.coeffs)
    }

    /// `sum_k X[0, k] (g_k(p_ref) - c_k) / nu_k + (p - p_ref) w(1)`.
    fn edge_velocity(&self, p: f64) -> f64 {
        if !self.op.slope.is_finite() {
            // lambda = 0: with p != p_ref the exact value is infinite (the caller checks
            // feedthrough_defined() and says so); this is then the mesh's own answer.
            return self.modal_rates(p).dot(&self.op.basis.edge_row);
        }
        self.modal_rates(self.p_ref).dot(&self.op.basis.edge_row) + self.jump(p, self.op.slope)
    }

    /// The exact `w(1)` (`-inf` at `lambda = 0`).
    fn edge_velocity_slope(&self) -> f64 {
        self.op.slope
    }

    fn feedthrough_defined(&self, p: f64) -> bool {
        self.op.slope.is_finite() || p == self.p_ref
    }

    fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        let v = self.profile(&self.coeffs, radii);
        radii
            .iter()
            .zip(v)
            .map(|(r, v)| self.sigma * r.clamp(1.0, self.op.r_inf) / 6.0 + v)
            .collect()
    }

    /// The same values as [`Engine::displacement`] (the same sums, in the same order), and
    /// the slope of the interpolant: `sigma / 6 + (2 / (b - a)) sum_i l_i'(x) v_i` in the
    /// element `[a, b]` holding `r`.
    fn displacement_slope(&self, radii: &[f64]) -> Option<Vec<(f64, f64)>> {
        let mesh = &self.op.basis.mesh;
        let nodal = &self.op.basis.shapes * &self.coeffs;
        let basis = LagrangeBasis::new(&mesh.reference_nodes);
        let (mut val, mut der) = (vec![0.0; basis.len()], vec![0.0; basis.len()]);
        let mut at = |r: f64| {
            let (e, x) = mesh.locate(r.clamp(1.0, self.op.r_inf));
            basis.eval_into(x, &mut val, &mut der);
            let v: f64 = val.iter().enumerate().map(|(i, l)| l * nodal[mesh.global(e, i)]).sum();
            let d: f64 = der.iter().enumerate().map(|(i, l)| l * nodal[mesh.global(e, i)]).sum();
            let scale = 2.0 / (mesh.breaks[e + 1] - mesh.breaks[e]);
            (self.sigma * r.clamp(1.0, self.op.r_inf) / 6.0 + v, self.sigma / 6.0 + scale * d)
        };
        Some(radii.iter().map(|&r| at(r)).collect())
    }

    /// `u = sigma r / 6 + v`, each term a dot product with a row the basis keeps (the
    /// validity check, O(modes) per step).
    fn edges(&self, _r_inf: f64) -> [f64; 3] {
        let (s, b) = (self.sigma / 6.0, &self.op.basis);
        let v = |row: &DVector<f64>| row.dot(&self.coeffs);
        [s + v(&b.edge_row), s + v(&b.edge_slope_row), s * self.op.r_inf + v(&b.outer_row)]
    }

    fn velocity(&self, p: f64, radii: &[f64]) -> Vec<f64> {
        let (lambda, r_inf) = (self.op.lambda, self.op.r_inf);
        if lambda == 0.0 || p == self.p_ref {
            return self.profile(&self.modal_rates(p), radii);
        }
        let mesh = self.profile(&self.modal_rates(self.p_ref), radii);
        let response = |r: f64| exact::velocity_response(lambda, r_inf, r.clamp(1.0, r_inf));
        radii.iter().zip(mesh).map(|(&r, v)| v + self.jump(p, response(r))).collect()
    }

    fn unknowns(&self) -> usize {
        self.op.len()
    }

    /// The modal coordinates, then `p_ref`.
    fn state(&self) -> Vec<f64> {
        self.coeffs.iter().copied().chain([self.p_ref]).collect()
    }

    fn restore(&mut self, state: &[f64]) -> Result<(), SolverError> {
        let n = self.coeffs.len();
        self.coeffs.copy_from_slice(&state[..n]);
        self.p_ref = state[n];
        Ok(())
    }

    fn boxed_clone(&self) -> Box<dyn Engine> {
        Box::new(self.clone())
    }

    /// Exact for an edge stress linear in time over the step. With
    ///
    /// ```text
    /// p(t) = p0 + p1 (t - t0),   g(t) = (sigma - p(t)) X[0, :],   g1 = dg/dt = -p1 X[0, :]
    ///
    /// c_k' = (g_k(t) - c_k) / nu_k  has the particular solution  g_k(t) - nu_k g1_k
    /// (its derivative g1_k equals (g_k - (g_k - nu_k g1_k)) / nu_k), so
    ///
    /// c_k(t0 + h) = g_k(t0 + h) - nu_k g1_k + (c_k(t0) - g_k(t0) + nu_k g1_k) exp(-h / nu_k)
    /// ```
    ///
    /// (`p1 = 0` is the held step of [`Engine::advance`]). After the step the state has
    /// evolved under the edge stress `p0 + p1 h`, the reference of the velocity split.
    fn advance_linear(&mut self, h: f64, p0: f64, p1: f64) -> bool {
        let nu = &self.op.nu;
        let decay = match &self.decay {
            Some((h0, d)) if *h0 == h => d,
            _ => &self.decay.insert((h, nu.map(|v| (-h / v).exp()))).1,
        };
        let p_end = p0 + p1 * h;
        let (start, end) = (self.op.target(self.sigma, p0), self.op.target(self.sigma, p_end));
        let g1 = -p1 * &self.op.basis.edge_row;
        for k in 0..self.coeffs.len() {
            let shift = nu[k] * g1[k];
            self.coeffs[k] = end[k] - shift + (self.coeffs[k] - start[k] + shift) * decay[k];
        }
        self.p_ref = p_end;
        true
    }

    /// The modal coordinates with `c_k' = (g_k(p) - c_k) / nu_k`: uncoupled, linear,
    /// with the relaxation times `nu_k` (the fastest sets the stiffness).
    fn ode(&self, p: f64) -> Option<Ode> {
        Some(Ode {
            x: self.coeffs.iter().copied().collect(),
            rates: self.modal_rates(p).iter().copied().collect(),
            relaxation_times: self.op.nu.iter().copied().collect(),
            loads: self.op.basis.edge_row.iter().copied().collect(),
        })
    }

    /// The coordinates, with `p_ref` the reference of the velocity split ([`super::Solver::set_ode_state`]).
    fn set_ode_state(&mut self, x: &[f64], p_ref: f64) -> bool {
        self.coeffs.copy_from_slice(x);
        self.p_ref = p_ref;
        true
    }

    /// One nominal for every coordinate: the edge-stress scale `s = max(|sigma|, |p|)`
    /// (in G; 1 when both are 0, where nothing moves). Each coordinate relaxes towards
    /// `g_k = (sigma - p) X[0, k]` and the radius is `R - R1 = sum_k X[0, k] c_k`, of size
    /// `s sum_k X[0, k]^2` (the static opening; about `s / 2` at `R_inf = 10`), so an
    /// integrator's absolute tolerance `rtol s` on each coordinate bounds the radius error
    /// per step by `rtol s sum_k |X[0, k]|`: relative to the opening it does not depend on
    /// sigma. A nominal per mode (`s |X[0, k]|`) would hold the fast modes, which barely
    /// reach the edge, to a tolerance the radius does not need, and costs an integrator
    /// twice the steps at `lambda = 0`, where every mode starts at once.
    fn ode_nominals(&self, p: f64) -> Option<Vec<f64>> {
        let s = match self.sigma.abs().max(p.abs()) {
            s if s > 0.0 => s,
            _ => 1.0,
        };
        Some(vec![s; self.coeffs.len()])
    }
}
