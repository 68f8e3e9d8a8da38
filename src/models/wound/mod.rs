//! The wound-opening model behind the FMI glue: parameters, the solver, and the physical
//! units of the master ([`crate::units`]).
//!
//! ```text
//! master            solver
//! t [s]             t / T
//! edge_stress [Pa]  p = edge_stress / G
//! wound_radius      R0 R            [um]
//! edge_velocity     (R0 / T) dR/dt  [um/s]
//! d edge_velocity / d edge_stress = (R0 / T) / G * d(dR/dt)/dp
//! ```

mod codec;
mod exchange;
mod fmu_state;
mod probes;
mod setup;
pub mod variables;

pub use codec::SchemeChoice;

use crate::fmi::common::model::{Description, FmuModel, Rejected};
use crate::solver::{
    EDGE_STRESS_MAX, Params, Solver, check_edge_stress, check_lambda, check_r_inf, check_sigma,
};
use crate::units::{Scales, check_scale};
use probes::Probes;
use std::cell::RefCell;
use variables::{DESCRIPTION, MODEL_EXCHANGE_STATES, Vr};

/// Where the edge velocity is infinite in the model (`lambda = 0`, at the cut and just
/// after a change of the edge stress), the FMU answers the mean velocity over the next
/// `MEAN_WINDOW` (in T) with the edge stress held: finite, accurate to the tolerance (the
/// radius meets it from 0.01 T on), and said so in the log.
pub const MEAN_WINDOW: f64 = 0.01;

/// The instance's model data: what an FMU state saves (with the machine state and clock).
#[derive(Debug, Clone)]
pub struct WoundModel {
    params: Params,
    scales: Scales,
    /// The `tolerance` parameter, and the tolerance of `fmi2SetupExperiment` (which wins).
    tolerance: f64,
    experiment_tolerance: Option<f64>,
    /// `method`, `grid_points` and `internal_step`.
    scheme: SchemeChoice,
    /// Edge stress in pascals (the master's unit).
    edge_stress: f64,
    /// Its time derivative in Pa/s from `fmi2SetRealInputDerivatives` (0: held).
    edge_stress_rate: f64,
    /// Built when first needed after the parameters are final; dropped when they change.
    solver: Option<Solver>,
    /// A warning for the glue to log with the current call (see [`WoundModel::warn`]).
    warning: RefCell<Option<String>>,
    /// A note for the glue to log with the current call, whose status stays OK.
    note: RefCell<Option<String>>,
    /// Model Exchange: the spare states and the reference of the states
    /// ([`exchange`]). Not serialized.
    exchange: exchange::Exchange,
    /// FMI 3.0: the probes (radii in um, master units, or the defaults following the tissue).
    probe_radii: Probes,
    /// `validity_warning`: a step leaving the validity answers fmi2Warning (else a note,
    /// status OK). Not serialized: how to report is the instance's, not the trajectory's.
    validity_warning: bool,
}

impl WoundModel {
    /// A model with the start values of the variable table.
    pub fn fresh() -> Box<dyn FmuModel> {
        let start = |vr: Vr| vr.var().start.unwrap_or(0.0);
        Box::new(Self {
            params: Params {
                lambda: start(Vr::Lambda),
                sigma: start(Vr::Sigma),
                r_inf: start(Vr::RInf),
            },
            scales: Scales {
                length: start(Vr::LengthScale),
                time: start(Vr::TimeScale),
                stress: start(Vr::StressScale),
            },
            tolerance: start(Vr::Tolerance),
            experiment_tolerance: None,
            scheme: SchemeChoice {
                method: start(Vr::Method) as i32,
                grid_points: start(Vr::GridPoints) as i32,
                internal_step: start(Vr::InternalStep),
            },
            edge_stress: start(Vr::EdgeStress),
            edge_stress_rate: 0.0,
            solver: None,
            warning: RefCell::new(None),
            note: RefCell::new(None),
            exchange: exchange::Exchange::default(),
            probe_radii: Probes::default(),
            validity_warning: start(Vr::ValidityWarning) != 0.0,
        })
    }
}

impl FmuModel for WoundModel {
    fn description(&self) -> &'static Description {
        &DESCRIPTION
    }

    fn boxed_clone(&self) -> Box<dyn FmuModel> {
        Box::new(self.clone())
    }

    fn check(&self, vr: u32, x: f64) -> Result<f64, Rejected> {
        let Some(vr) = Vr::from_u32(vr) else {
            return Err(format!("no variable has value reference {vr}"));
        };
        let positive = |name: &str| {
            if x.is_finite() && x > 0.0 {
                Ok(x)
            } else {
                Err(format!("{name} = {x} is invalid: it must be finite and > 0"))
            }
        };
        let in_range = || {
            let (lo, hi) = vr.var().range.expect("Integer variables declare a range");
            if (lo as f64..=hi as f64).contains(&x) {
                Ok(x)
            } else {
                Err(format!("{} = {x} is invalid: it must be in {lo} ..= {hi}", vr.var().name))
            }
        };
        let scale = |name| check_scale(name, x).map_err(|e| e.to_string());
        match vr {
            Vr::Lambda => check_lambda(x).map_err(|e| e.to_string()),
            Vr::Sigma => check_sigma(x).map_err(|e| e.to_string()),
            Vr::RInf => check_r_inf(x).map_err(|e| e.to_string()),
            Vr::Tolerance => positive("tolerance"),
            Vr::InternalStep => positive("internal_step"),
            Vr::Method | Vr::GridPoints | Vr::ValidityWarning => in_range(),
            Vr::LengthScale => scale("R0"),
            Vr::TimeScale => scale("T"),
            Vr::StressScale => scale("G"),
            Vr::EdgeStress => check_edge_stress(x / self.scales.stress).map(|_| x).map_err(|_| {
                let g = self.scales.stress;
                let bound = EDGE_STRESS_MAX * g;
                format!("edge_stress = {x} Pa is outside the accepted range [-{bound:e}, {bound:e}] Pa ({EDGE_STRESS_MAX:e} G, G = {g} Pa)")
            }),
            Vr::WoundRadius | Vr::EdgeVelocity => Err(format!("{} is an output", vr.var().name)),
        }
    }

    fn set(&mut self, vr: u32, x: f64) {
        let Some(vr) = Vr::from_u32(vr) else { return };
        match vr {
            Vr::Lambda => self.params.lambda = x,
            Vr::Sigma => self.params.sigma = x,
            Vr::RInf => self.params.r_inf = x,
            Vr::Tolerance => self.tolerance = x,
            Vr::Method => self.scheme.method = x as i32,
            Vr::GridPoints => self.scheme.grid_points = x as i32,
            Vr::InternalStep => self.scheme.internal_step = x,
            Vr::LengthScale => self.scales.length = x,
            Vr::TimeScale => self.scales.time = x,
            Vr::StressScale => self.scales.stress = x,
            Vr::EdgeStress => (self.edge_stress, self.edge_stress_rate) = (x, 0.0),
            Vr::ValidityWarning => self.validity_warning = x != 0.0,
            Vr::WoundRadius | Vr::EdgeVelocity => {}
        }
        // Everything but the input and the reporting changes the solver (scales: the internal step).
        if !matches!(vr, Vr::EdgeStress | Vr::ValidityWarning) {
            self.solver = None;
        }
    }

    fn set_experiment_tolerance(&mut self, tolerance: Option<f64>) {
        self.experiment_tolerance = tolerance;
        self.solver = None;
    }

    fn prepare(&mut self) -> Result<Option<String>, Rejected> {
        if self.solver.is_some() {
            return Ok(None);
        }

        let solver = self.build_solver()?;
        let text = format!(
            "solver: lambda = {}, sigma = {}, R_inf = {}, {} unknowns (tolerance {:e}, {:?}, {:?})",
            self.params.lambda,
            self.params.sigma,
            self.params.r_inf,
            solver.unknowns(),
            self.effective_tolerance(),
            self.scheme,
            self.scales
        );
        self.solver = Some(solver);
        if let Some(w) = self.setup_warning() {
            self.warn(w);
        }
        if let Some(n) = self.setup_note() {
            self.note(n);
        }
        Ok(Some(text))
    }

    fn get(&self, vr: u32, _time: f64) -> f64 {
        let Some(vr) = Vr::from_u32(vr) else { return f64::NAN };
        match vr {
            Vr::Lambda => self.params.lambda,
            Vr::Sigma => self.params.sigma,
            Vr::RInf => self.params.r_inf,
            Vr::EdgeStress => self.edge_stress,
            Vr::Tolerance => self.tolerance,
            Vr::Method => self.scheme.method as f64,
            Vr::GridPoints => self.scheme.grid_points as f64,
            Vr::InternalStep => self.scheme.internal_step,
            Vr::LengthScale => self.scales.length,
            Vr::TimeScale => self.scales.time,
            Vr::StressScale => self.scales.stress,
            Vr::ValidityWarning => f64::from(u8::from(self.validity_warning)),
            Vr::WoundRadius => self.scales.length * self.solver().wound_radius(),
            Vr::EdgeVelocity => {
                if let Some(v) = self.evolved_edge_velocity() {
                    return v;
                }
                let (solver, p) = (self.solver(), self.p());
                if !solver.edge_velocity_defined(p) {
                    let Ok(mean) = solver
                        .mean_edge_velocity(p, MEAN_WINDOW)
                        .map(|v| self.scales.velocity() * v)
                    else {
                        self.warn("edge_velocity is infinite in the model here and its mean over the next 0.01 T could not be computed: the value returned is the mesh's".into());
                        return self.scales.velocity() * solver.edge_velocity(p);
                    };
                    self.note(format!(
                        "edge_velocity is infinite in the model at lambda = 0 at the cut and just after a change of edge_stress (it decays like t^(-1/2)); the value returned, {mean:e} um/s, is the mean edge velocity over the next {:e} s ({MEAN_WINDOW} T) with edge_stress held",
                        MEAN_WINDOW * self.scales.time
                    ));
                    return mean;
                }
                self.scales.velocity() * solver.edge_velocity(p)
            }
        }
    }

    /// Held (`advance`) or, after `fmi2SetRealInputDerivatives`, linear in time over the
    /// step (`advance_linear`, exact); the input then ends the step at its value there.
    ///
    /// A step that takes the state out of the model's validity (wound radius <= 0, a folded
    /// ring, strains beyond what the linear model claims: [`crate::solver::validity`]) is
    /// answered with a warning naming the reason and the time, and how to run on
    /// (`validity_warning = 0`), or with that text logged and status OK when
    /// `validity_warning = 0`; O(modes) per step.
    fn step(&mut self, time: f64, h: f64) -> Result<(), Rejected> {
        let r_inf = self.params.r_inf;
        let was_valid =
            self.solver().time() == 0.0 || self.solver().validity_violation(r_inf).is_none();
        let (dt, p, rate) = (h / self.scales.time, self.p(), self.edge_stress_rate);
        if !dt.is_finite() {
            let t = self.scales.time;
            return Err(format!(
                "a step of {h:e} s is beyond the range of the time scale T = {t:e} s: accepted: steps up to {:.3e} s",
                f64::MAX * t
            ));
        }
        let p1 = rate * self.scales.time / self.scales.stress;
        let solver = self.solver.as_mut().expect("prepare() builds the solver before a step");
        solver.advance_linear(dt, p, p1).map_err(|e| e.to_string())?;
        self.edge_stress += rate * h;
        if let Some(why) = self.solver().validity_violation(r_inf).filter(|_| was_valid) {
            let text = format!("at t = {} s the run leaves the model's validity: {why}", time + h);
            if self.validity_warning {
                self.warn(format!("{text} (a master that stops on a warning status runs on, with this message logged and status OK, when the parameter validity_warning is set to 0)"));
            } else {
                self.note(format!("{text} (reported with status OK: validity_warning = 0)"));
            }
        }
        Ok(())
    }

    /// The edge stress's rate (Pa/s); only method 0 integrates a varying input exactly.
    fn check_input_rate(&self, vr: u32, _rate: f64) -> Result<(), Rejected> {
        if Vr::from_u32(vr) != Some(Vr::EdgeStress) {
            return Err(format!("value reference {vr} is not edge_stress"));
        }
        if self.scheme.method != 0 {
            return Err(crate::solver::SolverError::NotLinearInTime.to_string());
        }
        Ok(())
    }

    fn set_input_rate(&mut self, _vr: u32, rate: f64) {
        self.edge_stress_rate = rate;
    }

    /// `d edge_velocity / d edge_stress = (R0 / T) / G * w(1)`, the exact closed form of the
    /// instantaneous response ([`crate::solver::exact::velocity_response`]); infinite at
    /// `lambda = 0`, and refused there with the reason.
    fn partial(&self, output: u32, input: u32, _time: f64) -> Result<f64, Rejected> {
        match (Vr::from_u32(output), Vr::from_u32(input)) {
            (Some(Vr::EdgeVelocity), Some(Vr::EdgeStress)) => {
                let slope = self.solver().edge_velocity_slope();
                if slope.is_infinite() {
                    return Err("d edge_velocity / d edge_stress is infinite at lambda = 0 (the edge of a frictional tissue without viscosity responds to a change of edge stress with an unbounded velocity; it is -1/(4 lambda) R0/(T G) for small lambda > 0)".into());
                }
                Ok(self.scales.velocity() / self.scales.stress * slope)
            }
            _ => Ok(0.0),
        }
    }

    fn encode(&self) -> Result<Vec<u8>, Rejected> {
        self.saved()
    }

    fn take_warning(&mut self) -> Option<String> {
        self.warning.get_mut().take()
    }

    fn take_note(&mut self) -> Option<String> {
        self.note.get_mut().take()
    }

    /// Only the modal scheme is an ODE in its coordinates (methods 1 to 3 are stepping
    /// schemes kept for comparison).
    fn check_model_exchange(&self) -> Result<(), Rejected> {
        match self.solver().ode(self.p()) {
            Some(ode) if ode.x.len() <= MODEL_EXCHANGE_STATES => Ok(()),
            Some(ode) => Err(format!(
                "the mesh has {} modes, more than the {MODEL_EXCHANGE_STATES} states declared",
                ode.x.len()
            )),
            None => Err(format!(
                "Model Exchange needs method = 0 (the modal scheme, an ODE in its modal coordinates); method = {} is a stepping scheme",
                self.scheme.method
            )),
        }
    }

    fn enter_model_exchange(&mut self) {
        self.enter_exchange();
    }

    fn continuous_states(&self) -> Vec<f64> {
        self.exchange_states()
    }

    fn set_continuous_states(&mut self, time: f64, x: &[f64]) -> Result<(), Rejected> {
        self.set_exchange_states(time, x)
    }

    fn set_time(&mut self, time: f64) -> Result<(), Rejected> {
        self.exchange_time(time)
    }

    fn jacobian(&self, unknowns: &[u32], knowns: &[u32], time: f64) -> Result<Vec<f64>, Rejected> {
        self.exchange_jacobian(unknowns, knowns, time)
    }

    fn array_length(&self) -> u64 {
        self.probe_radii.len() as u64
    }

    /// The default radii (following R0 and R_inf) as far as they go, then the outer edge.
    fn set_array_length(&mut self, n: u64) {
        self.probe_radii = Probes::Default(n as usize);
        self.solver = None;
    }

    fn check_array(&self, j: usize, values: &[f64]) -> Result<(), Rejected> {
        if j != 0 {
            return Err(format!("{} is an output", variables::PROBE_ARRAYS[j.min(2)].name));
        }
        match values.iter().find(|r| !(r.is_finite() && **r > 0.0)) {
            Some(r) => Err(format!(
                "probe radius {r} um is invalid: it must be finite and > 0 (and in [R0, R0 R_inf])"
            )),
            None => Ok(()),
        }
    }

    fn set_array(&mut self, _j: usize, values: &[f64]) {
        self.probe_radii = Probes::Set(values.to_vec());
        self.solver = None;
    }

    /// The radii, or u and u_t there (the solver's, at reference radii in R0, scaled to um
    /// and um/s).
    /// A radius outside the tissue is refused when the field is read (the probes need not
    /// fit a tissue until then: R_inf may be set after them, and FMI 2.0 has no probes).
    fn get_array(&self, j: usize, _time: f64) -> Result<Vec<f64>, Rejected> {
        let (r0, p) = (self.scales.length, self.p());
        let probes = self.probe_radii.radii(r0, self.params.r_inf);
        if j == 0 {
            return Ok(probes);
        }
        let (lo, hi) = (r0, r0 * self.params.r_inf);
        if let Some(r) = probes.iter().find(|&&r| !(lo..=hi).contains(&r)) {
            return Err(format!(
                "probe radius {r} um is outside the tissue [R0, R0 R_inf] = [{lo}, {hi}] um"
            ));
        }
        let radii: Vec<f64> = probes.iter().map(|r| r / r0).collect();
        Ok(match j {
            1 => self.solver().displacement(&radii).iter().map(|u| u * r0).collect(),
            _ => {
                let solver = self.solver();
                if !solver.edge_velocity_defined(p) {
                    self.note(format!("velocity is infinite in the model at the edge at lambda = 0 at the cut and just after a change of edge_stress; the values returned are the mean velocities over the next {MEAN_WINDOW} T with edge_stress held"));
                    let mean =
                        solver.mean_velocity(p, &radii, MEAN_WINDOW).map_err(|e| e.to_string())?;
                    return Ok(mean.iter().map(|v| v * self.scales.velocity()).collect());
                }
                solver.velocity(p, &radii).iter().map(|v| v * self.scales.velocity()).collect()
            }
        })
    }

    /// Nominals of the modal coordinates ([`Solver::ode_nominals`]: the edge-stress scale
    /// times each mode's edge value), read by integrators for their absolute tolerance;
    /// the inert spare states take the largest.
    /// Those of the reference's edge stress (they move at events only).
    fn nominals(&self) -> Vec<f64> {
        self.nominals_at(self.exchange.reference.as_ref().map_or(self.p(), |r| r.p))
    }

    fn update_discrete_states(&mut self) -> (bool, bool) {
        self.exchange_event()
    }

    fn derivatives(&self, _time: f64) -> Vec<f64> {
        self.exchange_derivatives()
    }

    /// The bytes must come from an instance with the same parameters, scales, tolerance
    /// and scheme ([`WoundModel::restored`]).
    fn decode(&self, bytes: &[u8]) -> Result<Box<dyn FmuModel>, Rejected> {
        Ok(Box::new(self.restored(bytes)?))
    }
}
