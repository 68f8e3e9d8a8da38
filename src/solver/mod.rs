//! The wound-opening solver: plain safe Rust, no FMI types, no logging.
//!
//! Space: spectral elements ([`mesh`]) in a Galerkin formulation ([`galerkin`]) whose edge
//! stresses are natural boundary terms. Time: exact, mode by mode ([`modal`]), for an edge
//! stress held constant over each step. The only error left is the spatial one, which
//! falls exponentially with the polynomial degree.

pub mod exact;
mod galerkin;
mod mesh;
mod modal;
mod params;
mod quadrature;
mod tolerance;

pub use mesh::{Mesh, MeshSpec};
pub use modal::ModalError;
pub use tolerance::{DEGREE as TOLERANCE_DEGREE, FINEST_TOLERANCE};
pub use params::{
    ParamError, Params, check_edge_stress, check_lambda, check_r_inf, check_sigma,
};

use modal::Modes;
use nalgebra::DVector;
use quadrature::LagrangeBasis;
use std::sync::Arc;

/// Discretisation settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    pub mesh: MeshSpec,
}

impl Default for Settings {
    /// The shipped default: degree 8 on 10 elements graded from `ell = 0.05` (81
    /// unknowns). Against the exact solution it is within ~1e-11 of the opening
    /// amplitude for lambda in [0, 100] and R_inf in [2, 100] (tests/python).
    fn default() -> Self {
        Self { mesh: MeshSpec { degree: 8, elements: 10, edge_scale: 0.05 } }
    }
}

/// Why a solver could not be built or advanced.
#[derive(Debug, Clone, PartialEq)]
pub enum SolverError {
    Param(ParamError),
    Modal(ModalError),
    /// A step size that is not finite and positive.
    Step(f64),
    /// A state of the wrong length (expected, actual).
    StateLength(usize, usize),
    /// A state with a non-finite time or coefficient.
    StateNotFinite,
    /// Mesh settings out of range, with the reason.
    Mesh(&'static str),
    /// A tolerance that is not finite and positive.
    Tolerance(f64),
}

impl std::fmt::Display for SolverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Param(e) => e.fmt(f),
            Self::Modal(e) => write!(f, "modal decomposition failed: {e}"),
            Self::Step(h) => write!(f, "step size {h} is invalid: it must be finite and > 0"),
            Self::StateLength(want, got) => {
                write!(f, "state has {got} modal coefficients but the solver has {want}")
            }
            Self::StateNotFinite => write!(f, "state holds a non-finite value"),
            Self::Mesh(why) => write!(f, "mesh settings invalid: {why}"),
            Self::Tolerance(t) => write!(f, "tolerance = {t} is invalid: it must be finite and > 0"),
        }
    }
}

impl std::error::Error for SolverError {}

impl From<ParamError> for SolverError {
    fn from(e: ParamError) -> Self {
        Self::Param(e)
    }
}

/// The discretised operator of one `(lambda, R_inf, mesh)`: immutable, shared between
/// a solver and its saved states.
#[derive(Debug)]
pub struct Operator {
    lambda: f64,
    r_inf: f64,
    mesh: Mesh,
    modes: Modes,
    /// Row of the mode shapes at the wound edge, `X[0, :]`.
    edge_row: DVector<f64>,
}

impl Operator {
    pub fn new(lambda: f64, r_inf: f64, spec: MeshSpec) -> Result<Self, SolverError> {
        check_lambda(lambda)?;
        check_r_inf(r_inf)?;
        if spec.degree == 0 || spec.elements == 0 || spec.degree * spec.elements > 4000 {
            return Err(SolverError::Mesh("need degree >= 1, elements >= 1, degree*elements <= 4000"));
        }
        if !(spec.edge_scale.is_finite() && spec.edge_scale > 0.0) {
            return Err(SolverError::Mesh("edge_scale must be finite and > 0"));
        }
        let mesh = Mesh::new(spec, r_inf);
        let m = galerkin::assemble(&mesh);
        let mass = 4.0 * &m.mass + lambda * lambda * &m.stiffness;
        let modes = Modes::new(&m.stiffness, &mass).map_err(SolverError::Modal)?;
        let edge_row = modes.shapes.row(0).transpose();
        Ok(Self { lambda, r_inf, mesh, modes, edge_row })
    }

    pub fn lambda(&self) -> f64 {
        self.lambda
    }

    pub fn r_inf(&self) -> f64 {
        self.r_inf
    }

    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Number of unknowns (nodes = modes).
    pub fn len(&self) -> usize {
        self.modes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.modes.len() == 0
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

/// A solver state that can be saved and restored: the time and the modal coefficients
/// of `v = u - sigma r / 6`.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverState {
    pub time: f64,
    pub coeffs: Vec<f64>,
}

/// Time integrator of one wound-opening problem.
#[derive(Debug, Clone)]
pub struct Solver {
    op: Arc<Operator>,
    sigma: f64,
    time: f64,
    /// Modal coordinates of `v = u - sigma r / 6`.
    coeffs: DVector<f64>,
    /// `(h, exp(-h / nu))` of the last step size, reused while `h` repeats.
    decay: Option<(f64, DVector<f64>)>,
}

impl Solver {
    /// A solver at `t = 0`, in the uniform-tension state `u = sigma r / 6` just after the cut.
    pub fn new(params: &Params, settings: &Settings) -> Result<Self, SolverError> {
        params.validate()?;
        let op = Arc::new(Operator::new(params.lambda, params.r_inf, settings.mesh)?);
        Ok(Self::with_operator(op, params.sigma)?)
    }

    /// A solver on an existing operator (shared, not rebuilt).
    pub fn with_operator(op: Arc<Operator>, sigma: f64) -> Result<Self, SolverError> {
        check_sigma(sigma)?;
        let coeffs = DVector::zeros(op.len());
        Ok(Self { op, sigma, time: 0.0, coeffs, decay: None })
    }

    pub fn operator(&self) -> &Arc<Operator> {
        &self.op
    }

    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// Time since the cut, in T.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Advance by `h > 0` with the edge stress `p` held constant: exact in time.
    pub fn advance(&mut self, h: f64, p: f64) -> Result<(), SolverError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(SolverError::Step(h));
        }
        check_edge_stress(p)?;
        let nu = &self.op.modes.nu;
        let decay = match &self.decay {
            Some((h0, d)) if *h0 == h => d,
            _ => &self.decay.insert((h, nu.map(|v| (-h / v).exp()))).1,
        };
        let target = self.op.target(self.sigma, p);
        for k in 0..self.coeffs.len() {
            self.coeffs[k] = target[k] + decay[k] * (self.coeffs[k] - target[k]);
        }
        self.time += h;
        Ok(())
    }

    /// Wound radius `R = 1 + u(1, t) = 1 + sigma / 6 + v(1, t)`, in R0.
    pub fn wound_radius(&self) -> f64 {
        1.0 + self.sigma / 6.0 + self.op.edge_row.dot(&self.coeffs)
    }

    /// Edge velocity `dR/dt = u_t(1, t)` with edge stress `p` applied now, in R0 / T:
    /// `sum_k X[0, k] (g_k - c_k) / nu_k`.
    pub fn edge_velocity(&self, p: f64) -> f64 {
        self.modal_rates(p).dot(&self.op.edge_row)
    }

    /// Modal rates `c_k' = (g_k - c_k) / nu_k`.
    fn modal_rates(&self, p: f64) -> DVector<f64> {
        let target = self.op.target(self.sigma, p);
        (target - &self.coeffs).component_div(&self.op.modes.nu)
    }

    /// Displacement `u(r)` at each requested radius (clamped into `[1, R_inf]`).
    pub fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        let v = self.profile(&self.coeffs, radii);
        radii.iter().zip(v).map(|(r, v)| self.sigma * r.clamp(1.0, self.op.r_inf) / 6.0 + v).collect()
    }

    /// Velocity `u_t(r)` with edge stress `p`, at each requested radius.
    pub fn velocity(&self, p: f64, radii: &[f64]) -> Vec<f64> {
        self.profile(&self.modal_rates(p), radii)
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

    pub fn state(&self) -> SolverState {
        SolverState { time: self.time, coeffs: self.coeffs.iter().copied().collect() }
    }

    pub fn restore(&mut self, state: &SolverState) -> Result<(), SolverError> {
        if state.coeffs.len() != self.coeffs.len() {
            return Err(SolverError::StateLength(self.coeffs.len(), state.coeffs.len()));
        }
        if !state.time.is_finite() || state.coeffs.iter().any(|c| !c.is_finite()) {
            return Err(SolverError::StateNotFinite);
        }
        self.time = state.time;
        self.coeffs.copy_from_slice(&state.coeffs);
        Ok(())
    }
}
