//! One FMU instance in safe Rust: the FMI 2.0 state machine (co-simulation here, Model
//! Exchange in [`crate::fmi::common::exchange`]), the variables, FMU states and logging. It knows
//! nothing of C: the `ffi` layer converts pointers.
//!
//! Every call goes through [`Instance::call`]: log the call (category `logCalls`), check
//! that it is allowed in the current state, run it. A call that is rejected (not allowed
//! now, or an invalid argument) is logged under `logStatusError`, returns
//! [`Status::Error`], and changes nothing: every check runs before any mutation, so the
//! master may go on with the instance as it was, restore a saved FMU state, or reset.

pub use crate::fmi::common::call::{Call, Dialect};
use crate::fmi::common::log::Log;
pub use crate::fmi::common::log::{Logger, Status};
pub use crate::fmi::common::machine::{Clock, Interface, Machine, time_slack};
pub use crate::fmi::common::model::Rejected;
use crate::fmi::common::model::{Causality, Description, FmuModel, Kind, Named, Variability};
use std::collections::HashMap;
use std::sync::Arc;

/// The Jacobian, directional and adjoint derivatives of an instance.
mod derivatives;
mod fmu_states;
use fmu_states::Snapshot;

/// The importer's `intermediateUpdate` callback (FMI 3.0): asked for the inputs at `time`
/// inside a step ([`crate::fmi::fmi3::intermediate`]).
pub trait Requester: Send + Sync {
    fn request_inputs(&self, time: f64);
}

/// An FMU instance.
pub struct Instance {
    name: String,
    log: Log,
    pub(in crate::fmi) interface: Interface,
    /// The FMI version it was made through: its rules and its function names in messages.
    dialect: Dialect,
    pub(in crate::fmi) machine: Machine,
    pub(in crate::fmi) clock: Clock,
    pub(in crate::fmi) model: Box<dyn FmuModel>,
    /// A fresh model, for `fmi2Reset`.
    fresh: fn() -> Box<dyn FmuModel>,
    /// FMU states handed to the master, by handle. Handles come from the process-wide
    /// counter ([`fresh_handle`]), never reused, so a handle of another instance (of either
    /// model), of a freed instance, or a made-up one is never in this table.
    states: HashMap<u64, Snapshot>,
    /// FMI 3.0 co-simulation: the importer's `intermediateUpdate` callback and the inputs
    /// it may set in Intermediate Update Mode (see [`crate::fmi::fmi3::intermediate`]).
    pub(in crate::fmi) intermediate: Option<(Arc<dyn Requester>, Vec<u32>)>,
}

const FRESH_CLOCK: Clock = Clock { start: 0.0, stop: None, time: 0.0 };

impl Instance {
    /// An instance of `interface` of the model that `fresh` makes, in the words and rules
    /// of `dialect` (`Instance::new` in [`crate::fmi::fmi2::names`] for FMI 2.0
    /// co-simulation).
    pub fn of_interface(
        interface: Interface,
        dialect: Dialect,
        fresh: fn() -> Box<dyn FmuModel>,
        name: &str,
        logger: Arc<dyn Logger>,
        logging_on: bool,
    ) -> Self {
        Self {
            name: name.to_owned(),
            log: Log::new(logger, logging_on),
            interface,
            dialect,
            machine: Machine::Instantiated,
            clock: FRESH_CLOCK,
            model: fresh(),
            fresh,
            states: HashMap::new(),
            intermediate: None,
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// The logger, to log for this instance while it is busy (see `fmi::frame`).
    pub fn logger(&self) -> Arc<dyn Logger> {
        self.log.logger()
    }

    pub fn machine(&self) -> Machine {
        self.machine
    }

    pub fn interface(&self) -> Interface {
        self.interface
    }

    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// Whether the FMU has no computed values yet: only start values can be read.
    pub(in crate::fmi) fn before_initialization(&self) -> bool {
        matches!(self.machine, Machine::Instantiated | Machine::ConfigurationMode)
    }

    /// The name of `call` in this instance's FMI version.
    pub fn name_of(&self, call: Call) -> String {
        (self.dialect.name)(call)
    }

    pub fn description(&self) -> &'static Description {
        self.model.description()
    }

    /// After an internal failure (a caught panic): the model data may be half-updated,
    /// so only reset, restoring a saved FMU state, or inspection remain allowed.
    pub fn fail(&mut self, message: &str) {
        self.machine = Machine::Error;
        self.log_error(message);
    }

    /// Log under an error category (always on).
    pub fn log_error(&self, message: &str) {
        self.log.error(message);
    }

    /// A call this FMU cannot answer but that leaves it usable: log why (category
    /// `logStatusDiscard`) and return [`Status::Discard`] for the call to return.
    pub fn discard(&self, message: &str) -> Status {
        self.log.discard(message);
        Status::Discard
    }

    /// Frame one FMI call: log it, check the state machine, run `body`, log a rejection.
    /// After a success, the model's warning about the call, if any, is logged and makes
    /// the status [`Status::Warning`] (returned with the body's value; the caller keeps
    /// the worse of it and its own).
    pub fn call<T>(
        &mut self,
        call: Call,
        describe: impl FnOnce() -> String,
        body: impl FnOnce(&mut Self) -> Result<T, Rejected>,
    ) -> Result<(T, Status), Status> {
        if self.log.calls_on() {
            self.log.call(&describe());
        }
        let name = self.name_of(call);
        if let Some(only) = call.interface().filter(|&i| i != self.interface) {
            self.log_error(&format!(
                "{name} is a {only:?} function but this instance is {:?}",
                self.interface
            ));
            return Err(Status::Error);
        }
        if !call.allowed_in(self.machine, &self.dialect) {
            self.log_error(&format!("{name} is not allowed in state {:?}", self.machine));
            return Err(Status::Error);
        }
        let value = body(self).map_err(|why| {
            self.log_error(&format!("{name}: {why}"));
            Status::Error
        })?;
        if let Some(note) = self.model.take_note() {
            self.log.note(&format!("{name}: {note}"));
        }
        match self.model.take_warning() {
            Some(warning) => {
                self.log.warning(&format!("{name}: {warning}"));
                Ok((value, Status::Warning))
            }
            None => Ok((value, Status::Ok)),
        }
    }

    /// `fmi2SetDebugLogging`: switch the listed categories (all when empty).
    pub fn set_debug_logging(&mut self, on: bool, names: &[String]) -> Result<(), Rejected> {
        self.log.switch(on, names)
    }

    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start: f64,
        stop: Option<f64>,
    ) -> Result<(), Rejected> {
        if !start.is_finite() {
            return Err(format!("startTime = {start} is invalid: it must be finite"));
        }
        if let Some(s) = stop.filter(|&s| !(s.is_finite() && s >= start)) {
            return Err(format!(
                "stopTime = {s} is invalid: it must be finite and >= startTime = {start}"
            ));
        }
        if let Some(tol) = tolerance.filter(|&t| !(t.is_finite() && t >= 0.0)) {
            return Err(format!(
                "tolerance = {tol} is invalid: it must be finite and > 0 (or 0: none given)"
            ));
        }
        // 0 is "none given": OMSimulator passes it when an SSP sets no tolerance.
        if tolerance == Some(0.0) {
            self.log.note(
                "tolerance = 0 with toleranceDefined is taken as no tolerance given: the model's own (its tolerance parameter) is in force",
            );
        }
        let tolerance = tolerance.filter(|&t| t != 0.0);
        self.clock = Clock { start, stop, time: start };
        self.model.set_experiment_tolerance(tolerance);
        Ok(())
    }

    pub fn enter_initialization_mode(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::InitializationMode;
        Ok(())
    }

    /// Into `StepComplete` (co-simulation) or `EventMode` (Model Exchange, once the model
    /// says its parameters make an ODE).
    pub fn exit_initialization_mode(&mut self) -> Result<(), Rejected> {
        self.prepare()?;
        self.machine = match self.interface {
            Interface::CoSimulation => Machine::StepComplete,
            Interface::ModelExchange => {
                self.model.check_model_exchange()?;
                self.model.enter_model_exchange();
                Machine::EventMode
            }
        };
        Ok(())
    }

    pub fn terminate(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::Terminated;
        Ok(())
    }

    /// `fmi2Reset`: back to the state after instantiation (saved FMU states are kept).
    pub fn reset(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::Instantiated;
        self.clock = FRESH_CLOCK;
        self.model = (self.fresh)();
        Ok(())
    }

    pub(in crate::fmi) fn prepare(&mut self) -> Result<(), Rejected> {
        if let Some(text) = self.model.prepare()? {
            self.log.call(&text);
        }
        Ok(())
    }

    /// Values of the listed variables, all of type `kind` (Integers are exact in f64).
    fn get_values(&mut self, kind: Kind, vrs: &[u32]) -> Result<Vec<f64>, Rejected> {
        let d = self.description();
        let mut named = Vec::new();
        for &v in vrs {
            named.push(d.named(kind, v)?);
        }
        let computed =
            |n: &Named| !matches!(n, Named::Table(v) if v.causality != Causality::Output);
        if !named.iter().any(computed) {
            let t = self.clock.since_start();
            return Ok(vrs.iter().map(|&v| self.model.get(v, t)).collect());
        }
        self.prepare()?;
        let t = self.clock.since_start();
        let states = named
            .iter()
            .any(|n| matches!(n, Named::State(_)))
            .then(|| self.model.continuous_states());
        let rates = named
            .iter()
            .any(|n| matches!(n, Named::Derivative(_)))
            .then(|| self.model.derivatives(t));
        Ok(vrs
            .iter()
            .zip(&named)
            .map(|(&v, n)| match n {
                Named::Table(_) => self.model.get(v, t),
                Named::State(k) => states.as_ref().map_or(f64::NAN, |x| x[*k]),
                Named::Derivative(k) => rates.as_ref().map_or(f64::NAN, |x| x[*k]),
            })
            .collect())
    }

    pub fn get_real(&mut self, vrs: &[u32], values: &mut [f64]) -> Result<(), Rejected> {
        let got = self.get_values(Kind::Real, vrs)?;
        values.iter_mut().zip(got).for_each(|(o, v)| *o = v);
        Ok(())
    }

    pub fn get_integer(&mut self, vrs: &[u32], values: &mut [i32]) -> Result<(), Rejected> {
        let got = self.get_values(Kind::Integer, vrs)?;
        values.iter_mut().zip(got).for_each(|(o, v)| *o = v as i32);
        Ok(())
    }

    /// Whether `vr` may be set now: anything outside Intermediate Update Mode, only the
    /// required intermediate inputs inside it.
    fn settable_now(&self, vr: u32) -> Result<(), Rejected> {
        match (&self.intermediate, self.machine) {
            (Some((_, vrs)), Machine::IntermediateUpdate) if !vrs.contains(&vr) => Err(format!(
                "value reference {vr} is not a required intermediate variable: it cannot be set in Intermediate Update Mode"
            )),
            _ => Ok(()),
        }
    }

    /// Set the listed variables of type `kind`: all values are checked first; any
    /// rejection sets none of them.
    fn set_values(&mut self, kind: Kind, vrs: &[u32], values: &[f64]) -> Result<(), Rejected> {
        let d = self.description();
        let mut checked = Vec::new();
        let mut states = Vec::new();
        for (&v, &x) in vrs.iter().zip(values) {
            self.settable_now(v)?;
            let var = match d.named(kind, v)? {
                Named::Table(var) => var,
                Named::State(k) if self.machine == Machine::ContinuousTimeMode => {
                    states.push((k, x));
                    continue;
                }
                state => {
                    let name = d.state_name(state);
                    return Err(format!(
                        "{name} (value reference {v}) is a continuous state or derivative: states are set with {}",
                        self.name_of(Call::SetContinuousStates)
                    ));
                }
            };
            let fixed_now = var.variability == Variability::Fixed
                && !matches!(self.machine, Machine::Instantiated | Machine::InitializationMode);
            if var.causality == Causality::Output {
                return Err(format!(
                    "{} (value reference {v}) is an output and cannot be set",
                    var.name
                ));
            }
            if fixed_now {
                return Err(format!(
                    "{} is a fixed parameter: it can only be set before {} (state is {:?})",
                    var.name,
                    self.name_of(Call::ExitInitializationMode),
                    self.machine
                ));
            }
            checked.push((v, self.model.check(v, x)?));
        }
        if states.is_empty() {
            checked.into_iter().for_each(|(v, x)| self.model.set(v, x));
            return Ok(());
        }
        // States with other variables: the states are the model's to check (after the
        // inputs they are read under), so the whole call is undone if it refuses them.
        if let Some((k, x)) = states.iter().find(|(_, x)| !x.is_finite()) {
            let name = d.state_name(Named::State(*k));
            return Err(format!("{name} = {x} is invalid: states must be finite"));
        }
        let before = self.model.boxed_clone();
        checked.into_iter().for_each(|(v, x)| self.model.set(v, x));
        self.set_some_states(&states).inspect_err(|_| self.model = before)
    }

    /// `fmi2SetReal`.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), Rejected> {
        self.set_values(Kind::Real, vrs, values)
    }

    /// `fmi2SetRealInputDerivatives`: first derivatives of Real inputs (order 1 only,
    /// `maxInputDerivativeOrder` being 1), all checked before any is stored. The input is
    /// then `value + rate (t - t_now)` over the next steps, until `fmi2SetReal` sets it
    /// again (which resets its rate to 0).
    pub fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        rates: &[f64],
    ) -> Result<(), Rejected> {
        let d = self.description();
        for ((&v, &order), &rate) in vrs.iter().zip(orders).zip(rates) {
            let var = d.typed(Kind::Real, v)?;
            if var.causality != Causality::Input {
                return Err(format!("{} (value reference {v}) is not an input", var.name));
            }
            if order != 1 {
                return Err(format!(
                    "order = {order} for {} is invalid: this FMU interpolates linearly (order 1 only)",
                    var.name
                ));
            }
            if !rate.is_finite() {
                return Err(format!(
                    "the derivative of {} = {rate} is invalid: it must be finite",
                    var.name
                ));
            }
            self.model.check_input_rate(v, rate)?;
        }
        vrs.iter().zip(rates).for_each(|(&v, &rate)| self.model.set_input_rate(v, rate));
        Ok(())
    }

    /// `fmi2SetInteger`.
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), Rejected> {
        let values: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        self.set_values(Kind::Integer, vrs, &values)
    }

    /// `fmi2DoStep`: the inputs set before the call are held over `[t, t + h]`.
    ///
    /// The master's clock is the truth (as in the Reference-FMUs): its
    /// `currentCommunicationPoint` t is accepted when it is the instance's time within
    /// [`time_slack`], and the time after the step is `t + h`, whatever the instance had.
    /// A master computing its points as `t_n = n h` thus never drifts away from the
    /// instance, as it did from a clock that summed the step sizes. The step may end past
    /// `stopTime` by the same slack and no more.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<(), Rejected> {
        let end = self.check_step(t, h)?;
        self.prepare()?;
        self.model.step(t - self.clock.start, h)?;
        self.clock.time = end;
        Ok(())
    }

    /// The checks of [`Instance::do_step`], before anything moves: the end of the step.
    pub(in crate::fmi) fn check_step(&self, t: f64, h: f64) -> Result<f64, Rejected> {
        if !(h.is_finite() && h > 0.0) {
            return Err(format!(
                "communicationStepSize = {h} is invalid: it must be finite and > 0"
            ));
        }
        let now = self.clock.time;
        let slack = time_slack(h, now);
        if !(t.is_finite() && (t - now).abs() <= slack) {
            return Err(format!(
                "Expected currentCommunicationPoint = {now} but was {t} (accepted within {slack:e}: \
                 1e-6 communicationStepSize + 4 eps |time|)"
            ));
        }
        let end = t + h;
        if !end.is_finite() {
            return Err(format!(
                "a step of {h} from {t} ends at {end}: communicationStepSize is too large"
            ));
        }
        if let Some(stop) = self.clock.stop.filter(|&s| end > s + time_slack(h, s)) {
            return Err(format!(
                "a step of {h} from {t} would end at {end}, past stopTime = {stop}"
            ));
        }
        Ok(end)
    }

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    pub fn last_successful_time(&self) -> f64 {
        self.clock.time
    }

    /// `fmi2GetBooleanStatus(fmi2Terminated)`: true once the stop time is reached (to the
    /// rounding of a time near it, [`time_slack`] of a zero step).
    pub fn wants_to_terminate(&self) -> bool {
        self.clock.stop.is_some_and(|s| self.clock.time >= s - time_slack(0.0, s))
    }
}
