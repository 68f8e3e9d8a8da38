//! The interface every time integrator implements, behind the [`super::Solver`] facade.
//!
//! Engines work with the departure `v = u - sigma r / 6` from the uniform tension where
//! they can (zero at the cut, so `R(0) = R1` exactly); the facade validates arguments and
//! keeps the time, so an engine sees only valid steps and edge stresses.

use super::SolverError;

pub(crate) trait Engine: std::fmt::Debug + Send + Sync {
    /// Advance by `h > 0` with the edge stress `p` held constant.
    fn advance(&mut self, h: f64, p: f64);
    /// Wound radius `1 + u(1, t)`.
    fn wound_radius(&self) -> f64;
    /// Edge velocity `u_t(1, t)` with edge stress `p` applied now.
    fn edge_velocity(&self, p: f64) -> f64;
    /// `d u_t(1, t) / d p`: the edge velocity is affine in the edge stress applied now,
    /// so its difference over a unit change of `p` is the slope (engines with a closed
    /// form override this).
    fn edge_velocity_slope(&self) -> f64 {
        self.edge_velocity(1.0) - self.edge_velocity(0.0)
    }
    /// Whether the edge velocity with `p` applied now is finite in the continuous model
    /// (false only where a jump of the edge stress meets an infinite response: the modal
    /// engine at `lambda = 0`).
    fn feedthrough_defined(&self, _p: f64) -> bool {
        true
    }
    /// `u(r)` at each radius (inside `[1, R_inf]`).
    fn displacement(&self, radii: &[f64]) -> Vec<f64>;
    /// `(u(r), du/dr(r))` at each radius inside `[1, R_inf]`, where the scheme has the slope
    /// of its own interpolant (the modal engine); `None` otherwise.
    fn displacement_slope(&self, _radii: &[f64]) -> Option<Vec<(f64, f64)>> {
        None
    }
    /// `[u(1), du/dr(1), u(R_inf)]`. By default from [`Engine::displacement`], the slope a
    /// one-sided difference over 1e-6 of the ring (the comparison schemes' own accuracy).
    fn edges(&self, r_inf: f64) -> [f64; 3] {
        let h = 1e-6 * (r_inf - 1.0);
        let u = self.displacement(&[1.0, 1.0 + h, r_inf]);
        [u[0], (u[1] - u[0]) / h, u[2]]
    }
    /// `u_t(r)` at each radius, with edge stress `p`.
    fn velocity(&self, p: f64, radii: &[f64]) -> Vec<f64>;
    /// Number of spatial unknowns.
    fn unknowns(&self) -> usize;
    /// The evolving state, flattened.
    fn state(&self) -> Vec<f64>;
    /// Restore a state of length `state().len()` (checked by the facade).
    fn restore(&mut self, state: &[f64]) -> Result<(), SolverError>;
    fn boxed_clone(&self) -> Box<dyn Engine>;
    /// Work of `advance(h)` in floating-point updates, roughly: internal steps times the
    /// cost of one (the unknowns for exact integration, which takes one step).
    fn step_work(&self, _h: f64) -> f64 {
        self.unknowns() as f64
    }
    /// Refuse a step that the scheme cannot take stably (only the explicit scheme).
    fn check_step(&self, _h: f64) -> Result<(), SolverError> {
        Ok(())
    }
    /// Whether a step can blow up (only the explicit scheme, beyond its limits).
    fn may_diverge(&self) -> bool {
        false
    }
    /// Advance by `h > 0` under the edge stress `p(t) = p0 + p1 (t - t0)`, linear in time
    /// over the step, exactly; `false` (nothing done) for engines that cannot.
    fn advance_linear(&mut self, _h: f64, _p0: f64, _p1: f64) -> bool {
        false
    }
    /// The semi-discrete system as an ODE in its own coordinates, for an outside
    /// integrator (Model Exchange): `(x, dx/dt under p, relaxation times)`, `None` for
    /// engines whose state is not such a system (all but the modal one).
    fn ode(&self, _p: f64) -> Option<Ode> {
        None
    }
    /// Set the ODE coordinates of [`Engine::ode`], `p_ref` the reference of the velocity
    /// split (the edge stress its unresolved modes are at rest under); `false` where there
    /// is no ODE.
    fn set_ode_state(&mut self, _x: &[f64], _p_ref: f64) -> bool {
        false
    }
    /// Typical magnitudes of the coordinates of [`Engine::ode`] under the edge stresses
    /// `sigma` and `p` (each `> 0`), for an integrator's absolute tolerance; `None` where
    /// there is no ODE.
    fn ode_nominals(&self, _p: f64) -> Option<Vec<f64>> {
        None
    }
}

/// See [`Engine::ode`].
#[derive(Debug, Clone, PartialEq)]
pub struct Ode {
    pub x: Vec<f64>,
    pub rates: Vec<f64>,
    pub relaxation_times: Vec<f64>,
    /// How each coordinate's target depends on the edge stress: `x_k` relaxes towards
    /// `(sigma - p) loads_k` (the mode's edge value `X[0, k]`, also `d R / d x_k`).
    pub loads: Vec<f64>,
}

/// Number of equal internal steps of at most `max_step` covering `h`.
pub(crate) fn step_count(h: f64, max_step: f64) -> f64 {
    (h / max_step).ceil().max(1.0)
}

/// Cover `h` by [`step_count`] equal internal steps, calling `step(dt)` for each.
pub(crate) fn substeps(h: f64, max_step: f64, mut step: impl FnMut(f64)) {
    let n = step_count(h, max_step);
    for _ in 0..n as usize {
        step(h / n);
    }
}

/// Linear interpolation of nodal values on ascending `nodes`, for profile output of the
/// finite-difference engines.
pub(crate) fn interpolate(nodes: &[f64], values: &[f64], radii: &[f64]) -> Vec<f64> {
    radii
        .iter()
        .map(|&r| {
            let k = nodes[1..].partition_point(|&x| x < r).min(nodes.len() - 2);
            let s = ((r - nodes[k]) / (nodes[k + 1] - nodes[k])).clamp(0.0, 1.0);
            values[k] + s * (values[k + 1] - values[k])
        })
        .collect()
}
