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
pub mod exact;
mod exact_time;
mod explicit;
mod fd;
mod galerkin;
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
    EDGE_STRESS_MAX, LAMBDA_MAX, LAMBDA_MIN, ParamError, Params, R_INF_MAX, R_INF_MIN, SIGMA_MAX, SIGMA_MIN, check_edge_stress,
    check_lambda, check_r_inf, check_sigma,
};
pub use profile_rates::{VelocityRates, velocity_rates};
pub use sensitivity::{RadiusSensitivities, radius_sensitivities};
pub use tolerance::{DEGREE as TOLERANCE_DEGREE, FINEST_TOLERANCE, delivered_accuracy, sigma_floor};

pub use explicit::stability_limits as explicit_stability_limits;

use engine::Engine;
pub use engine::Ode;
use exact_time::{ModalEngine, Operator};
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
    /// A sigma so small that the rounding of the wound radius misses the tolerance
    /// ([`tolerance::sigma_floor`]).
    Unresolved {
        sigma: f64,
        tolerance: f64,
        floor: f64,
    },
    /// A communication step that would need more internal work than allowed
    /// (its work, the limit).
    TooManySteps(f64, f64),
    /// The explicit scheme blew up in this step (state left as before the step).
    Diverged,
    /// A step of the explicit scheme beyond its von Neumann limits, refused before it is taken.
    Unstable {
        lambda: f64,
        lambda_max: f64,
        dt: f64,
        dt_max: f64,
    },
    /// An edge stress varying within a step asked of a scheme that holds it constant.
    NotLinearInTime,
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
            Self::Unresolved { sigma, tolerance, floor } => write!(
                f,
                "sigma = {sigma:e} is too small for tolerance {tolerance:e}: accepted: sigma = 0 or |sigma| >= {floor:.2e} \
                 (6 eps / tolerance; and sigma in (-6, 1e6]). The wound radius R0 (1 + u) is a double near R0, rounded to \
                 2.2e-16 R0, and the opening is about |sigma| R0 / 2: at this sigma no double meets the tolerance. \
                 A tolerance >= {:.2e} accepts this sigma",
                6.0 * f64::EPSILON / sigma.abs()
            ),
            Self::TooManySteps(work, max) => write!(
                f,
                "this step would need {work:.1e} updates of the unknowns (at most {max:.0e} are allowed in one step): take shorter communication steps or a larger internal_step"
            ),
            Self::Unstable { lambda, lambda_max, dt, dt_max } => {
                if lambda >= lambda_max {
                    write!(
                        f,
                        "the explicit scheme is unstable for lambda = {lambda} >= {lambda_max:.4e} (about dr/2 on this grid), whatever the step: use method 0"
                    )
                } else {
                    write!(
                        f,
                        "the explicit scheme's internal step {dt:.4e} breaks its stability limit dt < {dt_max:.4e} (2/kappa_max - 2 lambda^2): lower internal_step or take shorter communication steps"
                    )
                }
            }
            Self::Diverged => write!(
                f,
                "the explicit scheme blew up in this step (internal step above its stability limit, or lambda > dr/2); the state is left as before the step"
            ),
            Self::NotLinearInTime => write!(
                f,
                "an edge stress that varies within a step (an input derivative) needs method 0 (exact in time); methods 1 to 3 hold it constant over a step"
            ),
        }
    }
}

impl std::error::Error for SolverError {}

impl From<ParamError> for SolverError {
    fn from(e: ParamError) -> Self {
        Self::Param(e)
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

/// A solver state that can be saved and restored: the time and the engine's state.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverState {
    pub time: f64,
    pub coeffs: Vec<f64>,
}

/// Time integrator of one wound-opening problem.
#[derive(Debug)]
pub struct Solver {
    engine: Box<dyn Engine>,
    sigma: f64,
    time: f64,
}

impl Clone for Solver {
    fn clone(&self) -> Self {
        Self { engine: self.engine.boxed_clone(), sigma: self.sigma, time: self.time }
    }
}

fn check_resolution(points: usize, max_step: f64) -> Result<(), SolverError> {
    if !(3..=100_000).contains(&points) {
        return Err(SolverError::Mesh("grid points must be in 3 ..= 100000"));
    }
    if !(max_step.is_finite() && max_step > 0.0) {
        return Err(SolverError::Step(max_step));
    }
    Ok(())
}

impl Solver {
    /// The default scheme at `t = 0`, in the uniform-tension state `u = sigma r / 6`
    /// just after the cut.
    pub fn new(params: &Params, settings: &Settings) -> Result<Self, SolverError> {
        Self::with_scheme(params, &Scheme::Modal(*settings))
    }

    /// Any scheme at `t = 0`.
    pub fn with_scheme(params: &Params, scheme: &Scheme) -> Result<Self, SolverError> {
        params.validate()?;
        let Params { lambda, sigma, r_inf } = *params;
        let engine: Box<dyn Engine> = match *scheme {
            Scheme::Modal(settings) => {
                let op = Arc::new(Operator::new(lambda, r_inf, settings.mesh)?);
                Box::new(ModalEngine::new(op, sigma))
            }
            Scheme::TrBdf2 { mesh, max_step } => {
                check_resolution(3, max_step)?;
                Operator::check_mesh(mesh)?;
                let op = trbdf2::TrBdf2Operator::new(Mesh::new(mesh, r_inf), lambda)?;
                Box::new(trbdf2::TrBdf2Engine::new(Arc::new(op), sigma, max_step))
            }
            Scheme::Paper { points, max_step } => {
                check_resolution(points, max_step)?;
                Box::new(paper::PaperEngine::new(Arc::new(fd::Grid::new(points, r_inf)), lambda, sigma, max_step))
            }
            Scheme::Explicit { points, max_step } => {
                check_resolution(points, max_step)?;
                Box::new(explicit::ExplicitEngine::new(Arc::new(fd::Grid::new(points, r_inf)), lambda, sigma, max_step))
            }
        };
        Ok(Self { engine, sigma, time: 0.0 })
    }

    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// Number of spatial unknowns.
    pub fn unknowns(&self) -> usize {
        self.engine.unknowns()
    }

    /// Time since the cut, in T.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Advance by `h > 0` with the edge stress `p` held constant.
    ///
    /// The stepping schemes refuse a step whose work (internal steps times the cost of one)
    /// exceeds [`MAX_STEP_WORK`] (so that no call runs for minutes), and the explicit scheme
    /// refuses a step in which it blew up, restoring the state from before it.
    pub fn advance(&mut self, h: f64, p: f64) -> Result<(), SolverError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(SolverError::Step(h));
        }
        check_edge_stress(p)?;
        self.engine.check_step(h)?;
        let work = self.engine.step_work(h);
        if work > MAX_STEP_WORK {
            return Err(SolverError::TooManySteps(work, MAX_STEP_WORK));
        }
        let before = self.engine.may_diverge().then(|| self.engine.state());
        self.engine.advance(h, p);
        if let Some(before) = before {
            let finite = self.engine.state().iter().all(|x| x.is_finite());
            if !finite || !self.engine.wound_radius().is_finite() {
                self.engine.restore(&before)?;
                return Err(SolverError::Diverged);
            }
        }
        self.time += h;
        Ok(())
    }

    /// Advance by `h > 0` under the edge stress `p0 + p1 (t - t0)`, linear in time over the
    /// step: exact for the modal scheme (see its `advance_linear`); refused for the stepping
    /// schemes, which hold the edge stress over a step. `p1 = 0` is [`Solver::advance`].
    /// Both `p0` and the final `p0 + p1 h` must be accepted edge stresses.
    pub fn advance_linear(&mut self, h: f64, p0: f64, p1: f64) -> Result<(), SolverError> {
        if p1 == 0.0 {
            return self.advance(h, p0);
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(SolverError::Step(h));
        }
        check_edge_stress(p0)?;
        check_edge_stress(p0 + p1 * h)?;
        if !self.engine.advance_linear(h, p0, p1) {
            return Err(SolverError::NotLinearInTime);
        }
        self.time += h;
        Ok(())
    }

    /// Wound radius `R = 1 + u(1, t)`, in R0.
    pub fn wound_radius(&self) -> f64 {
        self.engine.wound_radius()
    }

    /// Edge velocity `dR/dt = u_t(1, t)` with edge stress `p` applied now, in R0 / T.
    pub fn edge_velocity(&self, p: f64) -> f64 {
        self.engine.edge_velocity(p)
    }

    /// `d edge_velocity(p) / d p`, the direct response of the edge velocity to the edge
    /// stress applied now: the exact closed form for the modal scheme (`-inf` at
    /// `lambda = 0`), the mesh's for TR-BDF2, zero for the paper's and the explicit scheme,
    /// whose velocity is a difference of stored states.
    pub fn edge_velocity_slope(&self) -> f64 {
        self.engine.edge_velocity_slope()
    }

    /// Whether [`Solver::edge_velocity`] with `p` applied now is finite in the model: false
    /// at `lambda = 0` when `p` differs from the edge stress of the last step (`sigma` at the
    /// cut), where the exact edge velocity is infinite and the value returned is the mesh's.
    pub fn edge_velocity_defined(&self, p: f64) -> bool {
        self.engine.feedthrough_defined(p)
    }

    /// `u(1)`, `du/dr(1)` and `u(R_inf)` for the validity check ([`validity`]): O(modes) for
    /// the default scheme.
    pub fn edges(&self, r_inf: f64) -> validity::Edges {
        let [edge, edge_slope, outer] = self.engine.edges(r_inf);
        validity::Edges { edge, edge_slope, outer }
    }

    /// Why the current state is outside the model's validity ([`validity::violation`]).
    pub fn validity_violation(&self, r_inf: f64) -> Option<String> {
        validity::violation(self.edges(r_inf), r_inf)
    }

    /// Mean edge velocity over the next `window` (in T) with `p` held,
    /// `(R(t + window) - R(t)) / window`: finite where [`Solver::edge_velocity`] is not.
    pub fn mean_edge_velocity(&self, p: f64, window: f64) -> Result<f64, SolverError> {
        Ok(self.mean_rate(p, window, |s| vec![s.wound_radius()])?[0])
    }

    /// Mean velocity at each radius over the next `window` (in T) with `p` held,
    /// `(u(r, t + window) - u(r, t)) / window`.
    pub fn mean_velocity(&self, p: f64, radii: &[f64], window: f64) -> Result<Vec<f64>, SolverError> {
        self.mean_rate(p, window, |s| s.displacement(radii))
    }

    /// `(q(t + window) - q(t)) / window` for the quantities `q` measures, the solver
    /// advanced on a copy with `p` held.
    fn mean_rate(&self, p: f64, window: f64, q: impl Fn(&Self) -> Vec<f64>) -> Result<Vec<f64>, SolverError> {
        let mut ahead = self.clone();
        ahead.advance(window, p)?;
        Ok(q(&ahead).iter().zip(q(self)).map(|(b, a)| (b - a) / window).collect())
    }

    /// Displacement `u(r)` at each requested radius (clamped into `[1, R_inf]`).
    pub fn displacement(&self, radii: &[f64]) -> Vec<f64> {
        self.engine.displacement(radii)
    }

    /// Displacement and its radial slope `(u(r), du/dr(r))` at radii inside `[1, R_inf]`,
    /// for the schemes that interpolate with a slope (the modal one); `None` for the others.
    pub fn displacement_slope(&self, radii: &[f64]) -> Option<Vec<(f64, f64)>> {
        self.engine.displacement_slope(radii)
    }

    /// Velocity `u_t(r)` with edge stress `p`, at each requested radius.
    pub fn velocity(&self, p: f64, radii: &[f64]) -> Vec<f64> {
        self.engine.velocity(p, radii)
    }

    /// The semi-discrete system as an ODE for an outside integrator (Model Exchange),
    /// under the edge stress `p`: its coordinates, their rates (per unit of T) and the
    /// relaxation times (in T); `None` for the schemes that are not such an ODE (all but
    /// the modal one).
    pub fn ode(&self, p: f64) -> Option<Ode> {
        self.engine.ode(p)
    }

    /// Nominal magnitudes of the coordinates of [`Solver::ode`] under the edge stress `p`
    /// (see the modal engine); `None` for the schemes without an ODE.
    pub fn ode_nominals(&self, p: f64) -> Option<Vec<f64>> {
        self.engine.ode_nominals(p)
    }

    /// Set the coordinates of [`Solver::ode`] at time `time`, the state having evolved
    /// under `p`. Refused for a length other than the ODE's, for values that are not
    /// finite, and for schemes without an ODE.
    ///
    /// The velocity split's reference follows from the time alone: at `time = 0` nothing
    /// has evolved (the cut: the uniform tension at rest under `sigma`, so an edge stress
    /// `p != sigma` meets the closed-form instantaneous response); at any later time the
    /// state has evolved under `p` and its unresolved fast modes are at rest under it.
    pub fn set_ode_state(&mut self, time: f64, x: &[f64], p: f64) -> Result<(), SolverError> {
        let want = self.engine.ode(p).map_or(0, |o| o.x.len());
        if x.len() != want {
            return Err(SolverError::StateLength(want, x.len()));
        }
        if !time.is_finite() || x.iter().any(|c| !c.is_finite()) {
            return Err(SolverError::StateNotFinite);
        }
        check_edge_stress(p)?;
        let reference = if time == 0.0 { self.sigma } else { p };
        if !self.engine.set_ode_state(x, reference) {
            return Err(SolverError::StateLength(0, x.len()));
        }
        self.time = time;
        Ok(())
    }

    pub fn state(&self) -> SolverState {
        SolverState { time: self.time, coeffs: self.engine.state() }
    }

    pub fn restore(&mut self, state: &SolverState) -> Result<(), SolverError> {
        let want = self.engine.state().len();
        if state.coeffs.len() != want {
            return Err(SolverError::StateLength(want, state.coeffs.len()));
        }
        if !state.time.is_finite() || state.coeffs.iter().any(|c| !c.is_finite()) {
            return Err(SolverError::StateNotFinite);
        }
        self.engine.restore(&state.coeffs)?;
        self.time = state.time;
        Ok(())
    }
}
