//! WoundOpening's Model Exchange states and their exact Jacobian.
//!
//! The modal coordinates `c_k` relax independently, `c_k' = (g_k(p) - c_k) / nu_k` with
//! `g_k(p) = (sigma - p) X_k` (`X_k = X[0, k]`, the mode's edge value). Under the edge
//! stress `p0` held from the cut they follow the closed form
//!
//! ```text
//! c0_k(t) = g_k(p0) (1 - exp(-t / nu_k))
//! ```
//!
//! At `lambda = 0` every mode starts at once (`nu_k` from 4.5e-6 T up): an integrator that
//! had to follow `c0` would resolve seven decades of time from the cut (fmpy's CVode at
//! rtol 1e-10 takes more than 500 steps before t = 0.45 T). So the states are the
//! departure from that closed form, and the integrator follows only what the input's
//! changes since initialization cause:
//!
//! ```text
//! y_k = c_k - c0_k(t)
//! y_k' = ((p0 - p) X_k - y_k) / nu_k          (per T; exact: c0_k' = (g_k(p0) - c0_k) / nu_k)
//! ```
//!
//! `p0` is the edge stress when initialization ends (the reference); `y = 0` at the cut
//! and stays 0 while `p = p0`. The system stays linear and uncoupled, its Jacobian
//! constant:
//!
//! ```text
//! d y_k' / d y_j        = -delta_kj / (nu_k T)
//! d y_k' / d edge_stress = -X_k / (nu_k T G)
//! d wound_radius / d y_j = R0 X_j
//! d edge_velocity / d y_j = -(R0 / T) X_j / nu_j
//! ```
//!
//! An event moves the reference. When the master changes the edge stress in Event Mode
//! (an input that jumps: fmpy and fmusim enter Event Mode at each jump of a piecewise
//! input) the reference becomes the edge stress `p1` then held from the event's time `te`
//! and the physical state `c(te)` there, the response it is the departure from
//!
//! ```text
//! c0_k(t) = c_k(te) exp(-(t - te) / nu_k) + g_k(p1) (1 - exp(-(t - te) / nu_k))
//! ```
//!
//! (the first reference is `te = 0`, `c(0) = 0`, `p1 = p0`). The states are then 0 again:
//! `fmi2NewDiscreteStates` / `fmi3UpdateDiscreteStates` say so
//! (`valuesOfContinuousStatesChanged`, and `nominalsOfContinuousStatesChanged` when the
//! nominals, which follow the reference's edge stress, move), the integrator restarts, and
//! under a piecewise-constant edge stress it has nothing to integrate: the run is exact in
//! time. An edge stress changed in Continuous-Time Mode is a continuous input (a ramp, a
//! closure model's output): the reference stays, the states follow it.
//!
//! The physical state (the solver's `c`) is `y + c0(t)`: setting the time moves it along
//! `c0` with `y` kept, as FMI's outputs are functions of time, states, inputs (and the
//! reference, a discrete state: it moves in Event Mode only). Without a reference (an
//! instance that never left initialization as Model Exchange) `c0 = 0` and the states are
//! the modal coordinates themselves.
//!
//! `edge_velocity` is then a function of them alone too: for `t > 0` the ODE's own
//! `dR/dt = R0 sum_k X_k (g_k(p) - c_k) / (nu_k T)`, the state's unresolved fast modes at
//! rest under the edge stress applied (`d edge_velocity / d edge_stress = -(R0 / T) / G
//! sum_k X_k^2 / nu_k`); at `t = 0` the cut, where the uniform tension is at rest under
//! `sigma` and an edge stress `p != sigma` meets the closed-form instantaneous response, as
//! in co-simulation ([`crate::solver::Solver::set_ode_state`]).

use super::WoundModel;
use super::variables::{MODEL_EXCHANGE_STATES, Vr};
use crate::fmi::common::model::{FmuModel, Kind, Named, Rejected};
use crate::solver::Ode;

/// What Model Exchange adds to an instance's model data (not serialized: an FMU state is
/// the physical state, and each instance reads it in its own coordinates).
#[derive(Debug, Clone, Default)]
pub(super) struct Exchange {
    /// The states beyond the mesh's modes, as the integrator last set them. They are inert
    /// (derivative 0, no effect on any output): an integrator that perturbs them for a
    /// finite-difference Jacobian sees a zero column.
    pub(super) spare: Vec<f64>,
    /// What the states depart from: set when initialization ends, moved by events.
    pub(super) reference: Option<Reference>,
}

/// The held response the states depart from (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Reference {
    /// `p1`, the edge stress (in G) held from `time`.
    pub(super) p: f64,
    /// `te`, in T.
    pub(super) time: f64,
    /// `c(te)`, the modal coordinates then.
    pub(super) start: Vec<f64>,
}

impl WoundModel {
    fn exchange_ode(&self) -> Option<Ode> {
        self.solver.as_ref().and_then(|s| s.ode(self.p()))
    }

    /// `c0_k(t)` at `t` in T (0 without a reference).
    fn held_response(&self, ode: &Ode, t: f64) -> Vec<f64> {
        let Some(r) = &self.exchange.reference else { return vec![0.0; ode.x.len()] };
        let g = self.params.sigma - r.p;
        let modes = ode.loads.iter().zip(&ode.relaxation_times).zip(&r.start);
        modes
            .map(|((x, nu), c)| {
                let decay = -(t - r.time) / nu;
                let held = if g == 0.0 { 0.0 } else { -g * x * decay.exp_m1() };
                if *c == 0.0 { held } else { c * decay.exp() + held }
            })
            .collect()
    }

    /// `y = c - c0(t)` of the mesh's modes at the solver's time.
    fn departure(&self, ode: &Ode) -> Vec<f64> {
        let t = self.solver().time();
        ode.x.iter().zip(self.held_response(ode, t)).map(|(c, c0)| c - c0).collect()
    }

    /// Set `c = y + c0(t)` at `t` in T.
    fn set_departure(&mut self, t: f64, ode: &Ode, y: &[f64]) -> Result<(), Rejected> {
        let c: Vec<f64> = y.iter().zip(self.held_response(ode, t)).map(|(y, c0)| y + c0).collect();
        let p = self.p();
        let solver =
            self.solver.as_mut().expect("prepare() builds the solver before states are set");
        solver.set_ode_state(t, &c, p).map_err(|e| e.to_string())
    }

    /// The reference of the current edge stress and physical state.
    fn reference_now(&self) -> Option<Reference> {
        let ode = self.exchange_ode()?;
        Some(Reference { p: self.p(), time: self.solver().time(), start: ode.x })
    }

    pub(super) fn enter_exchange(&mut self) {
        self.exchange.reference = self.reference_now();
    }

    /// An event: an edge stress other than the reference's becomes the reference (module
    /// documentation). `(values changed, nominals changed)`.
    pub(super) fn exchange_event(&mut self) -> (bool, bool) {
        let Some(old) = self.exchange.reference.as_ref().filter(|r| r.p != self.p()) else {
            return (false, false);
        };
        let (states, nominals) = (self.exchange_states(), self.nominals_at(old.p));
        self.exchange.reference = self.reference_now();
        let p = self.p();
        (self.exchange_states() != states, self.nominals_at(p) != nominals)
    }

    pub(super) fn exchange_states(&self) -> Vec<f64> {
        let mut x = self.exchange_ode().map_or_else(Vec::new, |o| self.departure(&o));
        x.extend(&self.exchange.spare);
        x.resize(MODEL_EXCHANGE_STATES, 0.0);
        x
    }

    /// The modes the mesh uses, in solver units, then the inert spare states.
    pub(super) fn set_exchange_states(&mut self, time: f64, x: &[f64]) -> Result<(), Rejected> {
        let ode = self.exchange_ode();
        let used = ode.as_ref().map_or(0, |o| o.x.len());
        match ode {
            Some(ode) => self.set_departure(self.model_time(time)?, &ode, &x[..used])?,
            None => {
                let (t, p) = (self.model_time(time)?, self.p());
                self.solver
                    .as_mut()
                    .expect("prepare() builds the solver")
                    .set_ode_state(t, &[], p)
                    .map_err(|e| e.to_string())?
            }
        }
        self.exchange.spare = x[used..].to_vec();
        Ok(())
    }

    /// `time` (seconds since the cut) in T, refused with the range where it overflows.
    fn model_time(&self, time: f64) -> Result<f64, Rejected> {
        let t = time / self.scales.time;
        if t.is_finite() {
            return Ok(t);
        }
        Err(format!(
            "time = {time:e} s since the cut is beyond the range of the time scale T = {:e} s: accepted: times up to {:.3e} s (the largest double in T)",
            self.scales.time,
            f64::MAX * self.scales.time
        ))
    }

    /// The master's time moves the physical state along `c0` with the states kept.
    pub(super) fn exchange_time(&mut self, time: f64) -> Result<(), Rejected> {
        let t = self.model_time(time)?;
        let Some(ode) = self.exchange_ode() else { return Ok(()) };
        let y = self.departure(&ode);
        self.set_departure(t, &ode, &y)
    }

    /// `y_k' = ((p0 - p) X_k - y_k) / nu_k` per second of master time.
    pub(super) fn exchange_derivatives(&self) -> Vec<f64> {
        let mut dx = match self.exchange_ode() {
            Some(ode) => {
                let dp =
                    self.exchange.reference.as_ref().map_or(self.params.sigma, |r| r.p) - self.p();
                let y = self.departure(&ode);
                let t = self.scales.time;
                y.iter()
                    .zip(&ode.loads)
                    .zip(&ode.relaxation_times)
                    .map(|((y, x), nu)| (dp * x - y) / nu / t)
                    .collect()
            }
            None => Vec::new(),
        };
        dx.resize(MODEL_EXCHANGE_STATES, 0.0);
        dx
    }

    /// The exact Jacobian (module documentation), row-major over `unknowns` x `knowns`
    /// (outputs and derivatives over inputs and states); output-input entries are
    /// [`FmuModel::partial`]'s.
    pub(super) fn exchange_jacobian(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        time: f64,
    ) -> Result<Vec<f64>, Rejected> {
        let d = self.description();
        let ode = self.exchange_ode();
        let (s, used) = (self.scales, ode.as_ref().map_or(0, |o| o.x.len()));
        let mode = |k: usize| {
            ode.as_ref().filter(|_| k < used).map(|o| (o.loads[k], o.relaxation_times[k]))
        };
        let mut out = Vec::with_capacity(unknowns.len() * knowns.len());
        for &u in unknowns {
            let unknown = d.named(Kind::Real, u)?;
            for &k in knowns {
                let value = match (unknown, d.named(Kind::Real, k)?) {
                    (Named::Derivative(i), Named::State(j)) => match mode(i) {
                        Some((_, nu)) if i == j => -1.0 / (nu * s.time),
                        _ => 0.0,
                    },
                    (Named::Derivative(i), Named::Table(_)) if k == Vr::EdgeStress as u32 => {
                        mode(i).map_or(0.0, |(x, nu)| -x / (nu * s.time * s.stress))
                    }
                    (Named::Table(_), Named::State(j)) => self.output_slope(u, mode(j))?,
                    (Named::Table(_), Named::Table(_)) => {
                        match self.evolved_slope(u, k, ode.as_ref()) {
                            Some(slope) => slope,
                            None => self.partial(u, k, time)?,
                        }
                    }
                    _ => 0.0,
                };
                out.push(value);
            }
        }
        Ok(out)
    }

    /// The ODE's own `dR/dt` under the current edge stress, for `t > 0` in Model Exchange
    /// (module documentation); `None` at the cut and outside Model Exchange.
    pub(super) fn evolved_edge_velocity(&self) -> Option<f64> {
        self.exchange.reference.as_ref()?;
        let ode = self.exchange_ode().filter(|_| self.solver().time() > 0.0)?;
        let rate: f64 = ode.loads.iter().zip(&ode.rates).map(|(x, r)| x * r).sum();
        Some(self.scales.velocity() * rate)
    }

    /// `d edge_velocity / d edge_stress` of [`WoundModel::evolved_edge_velocity`],
    /// `-(R0 / T) / G sum_k X_k^2 / nu_k`, where it applies (other pairs: `None`).
    fn evolved_slope(&self, output: u32, input: u32, ode: Option<&Ode>) -> Option<f64> {
        let pair = (Vr::from_u32(output), Vr::from_u32(input))
            == (Some(Vr::EdgeVelocity), Some(Vr::EdgeStress));
        let ode = ode
            .filter(|_| pair && self.exchange.reference.is_some() && self.solver().time() > 0.0)?;
        let sum: f64 = ode.loads.iter().zip(&ode.relaxation_times).map(|(x, nu)| x * x / nu).sum();
        Some(-self.scales.velocity() / self.scales.stress * sum)
    }

    /// `d output / d y_j` for mode `(X_j, nu_j)` (0 for a spare state).
    fn output_slope(&self, output: u32, mode: Option<(f64, f64)>) -> Result<f64, Rejected> {
        let Some((x, nu)) = mode else { return Ok(0.0) };
        match Vr::from_u32(output) {
            Some(Vr::WoundRadius) => Ok(self.scales.length * x),
            Some(Vr::EdgeVelocity) if self.evolved_edge_velocity().is_some() || self.solver().edge_velocity_defined(self.p()) => {
                Ok(-self.scales.velocity() * x / nu)
            }
            Some(Vr::EdgeVelocity) => Err("d edge_velocity / d state is undefined here: the edge velocity is infinite in the model (lambda = 0, the edge stress differs from the one the state evolved under)".into()),
            _ => Ok(0.0),
        }
    }
}
