//! The wound-opening solver: plain safe Rust, no FMI types, no logging.
//!
//! The default ([`Scheme::Modal`]): spectral elements ([`mesh`]) in a Galerkin formulation
//! ([`galerkin`]) whose edge stresses are natural boundary terms, integrated exactly in
//! time, mode by mode ([`modal`], [`exact_time`]), for an edge stress held constant over
//! each step. The only error left is the spatial one, which falls exponentially with the
//! polynomial degree. The other schemes are there to be compared with it: the same
//! Galerkin system stepped by TR-BDF2 ([`trbdf2`]), the paper's own scheme ([`paper`]) and
//! an explicit scheme ([`explicit`]) on the paper's finite-difference grid ([`fd`]).
#![forbid(unsafe_code)]

pub mod basis;
mod bessel;
mod engine;
mod error;
pub mod exact;
mod exact_time;
mod explicit;
mod fd;
mod galerkin;
mod integrator;
mod jacobi;
mod mesh;
mod modal;
mod paper;
mod params;
mod profile_rates;
mod quadrature;
mod sensitivity;
pub mod stability;
mod tolerance;
mod trbdf2;
pub mod validity;

pub use mesh::{Mesh, MeshSpec};
pub use modal::ModalError;
pub use params::{
    EDGE_STRESS_MAX, LAMBDA_MAX, LAMBDA_MIN, ParamError, Params, R_INF_MAX, R_INF_MIN, SIGMA_MAX,
    SIGMA_MIN, check_edge_stress, check_lambda, check_r_inf, check_sigma,
};
pub use profile_rates::{VelocityRates, velocity_rates};
pub use sensitivity::{RadiusSensitivities, radius_sensitivities};
pub use tolerance::{
    DEGREE as TOLERANCE_DEGREE, FINEST_TOLERANCE, delivered_accuracy, sigma_floor,
};

pub use explicit::stability_limits as explicit_stability_limits;

pub use engine::Ode;
pub use error::SolverError;
pub use integrator::{Solver, SolverState};

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

/// Largest work of one communication step, in updates of an unknown (a few seconds of CPU).
pub const MAX_STEP_WORK: f64 = 1e9;

/// The time integrators, each with its resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scheme {
    /// Spectral elements, exact in time (the default; see [`Settings::for_tolerance`]).
    Modal(Settings),
    /// The same Galerkin system, TR-BDF2 steps of at most `max_step`.
    TrBdf2 { mesh: MeshSpec, max_step: f64 },
    /// The paper's appendix scheme on `points` uniform points, internal steps of at most `max_step`.
    Paper { points: usize, max_step: f64 },
    /// The explicit lagged-viscosity scheme on the paper's grid.
    Explicit { points: usize, max_step: f64 },
}

impl Scheme {
    /// Short name, as used in benchmarks and charts.
    pub fn name(&self) -> &'static str {
        match self {
            Scheme::Modal(_) => "modal",
            Scheme::TrBdf2 { .. } => "trbdf2",
            Scheme::Paper { .. } => "paper",
            Scheme::Explicit { .. } => "explicit",
        }
    }
}
