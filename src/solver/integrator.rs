//! [`Solver`]: the time integrator of one wound-opening problem, the facade every caller
//! uses over the engines ([`super::engine::Engine`]): it validates steps, edge stresses and
//! states, keeps the time, and answers the outputs.

use super::engine::{Engine, Ode};
use super::exact_time::{ModalEngine, Operator};
use super::{
    MAX_STEP_WORK, Mesh, Params, Scheme, Settings, SolverError, check_edge_stress, explicit, fd,
    paper, trbdf2, validity,
};
use std::sync::Arc;

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
                Box::new(paper::PaperEngine::new(
                    Arc::new(fd::Grid::new(points, r_inf)),
                    lambda,
                    sigma,
                    max_step,
                ))
            }
            Scheme::Explicit { points, max_step } => {
                check_resolution(points, max_step)?;
                Box::new(explicit::ExplicitEngine::new(
                    Arc::new(fd::Grid::new(points, r_inf)),
                    lambda,
                    sigma,
                    max_step,
                ))
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
    pub fn mean_velocity(
        &self,
        p: f64,
        radii: &[f64],
        window: f64,
    ) -> Result<Vec<f64>, SolverError> {
        self.mean_rate(p, window, |s| s.displacement(radii))
    }

    /// `(q(t + window) - q(t)) / window` for the quantities `q` measures, the solver
    /// advanced on a copy with `p` held.
    fn mean_rate(
        &self,
        p: f64,
        window: f64,
        q: impl Fn(&Self) -> Vec<f64>,
    ) -> Result<Vec<f64>, SolverError> {
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
