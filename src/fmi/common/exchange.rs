//! Model Exchange (FMI 2.0, chapter 3) on the shared [`Instance`]: the master integrates
//! the model's continuous states ([`crate::fmi::common::model::ContinuousStates`]) with its own solver.
//! The glue supports models without state or time events: no event indicators, no time
//! events, and `fmi2CompletedIntegratorStep` never asks for event mode. A model may keep
//! discrete states that move when the master enters Event Mode (an input that jumps):
//! `fmi2NewDiscreteStates` updates them and says whether the continuous states' values or
//! nominals changed.
//!
//! ```text
//! fmi2ExitInitializationMode      -> EventMode (after the model accepts the parameters)
//! fmi2NewDiscreteStates           the model's discrete states, after the inputs set
//! fmi2EnterContinuousTimeMode     -> ContinuousTimeMode
//! fmi2SetTime t                   finite, not before startTime
//! fmi2SetContinuousStates x       exactly nx finite values, checked by the model
//! fmi2GetDerivatives              dx/dt per second of master time
//! ```

use crate::fmi::common::instance::{Instance, Rejected};
use crate::fmi::common::machine::Machine;

/// The flags `fmi2NewDiscreteStates` returns in `fmi2EventInfo`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EventInfo {
    pub new_discrete_states_needed: bool,
    pub terminate_simulation: bool,
    pub nominals_changed: bool,
    pub values_changed: bool,
    pub next_event_time: Option<f64>,
}

impl Instance {
    fn check_count(&self, n: usize, what: &str) -> Result<(), Rejected> {
        let want = self.description().state_count();
        if n == want {
            Ok(())
        } else {
            Err(format!("{what} = {n} but this model has {want} continuous states"))
        }
    }

    pub fn enter_event_mode(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::EventMode;
        Ok(())
    }

    /// The model's discrete states updated (after the inputs set in Event Mode); no time
    /// events, nothing more to iterate.
    pub fn new_discrete_states(&mut self) -> Result<EventInfo, Rejected> {
        self.prepare()?;
        let (values_changed, nominals_changed) = self.model.update_discrete_states();
        Ok(EventInfo { values_changed, nominals_changed, ..EventInfo::default() })
    }

    pub fn enter_continuous_time_mode(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::ContinuousTimeMode;
        Ok(())
    }

    /// `(enterEventMode, terminateSimulation)`: never: the glue supports models without events only.
    pub fn completed_integrator_step(&mut self) -> Result<(bool, bool), Rejected> {
        Ok((false, false))
    }

    /// `fmi2SetTime`: the master's time, not before `startTime` (the cut).
    pub fn set_time(&mut self, t: f64) -> Result<(), Rejected> {
        if !(t.is_finite() && t >= self.clock.start) {
            return Err(format!(
                "time = {t} is invalid: it must be finite and >= startTime = {}",
                self.clock.start
            ));
        }
        self.model.set_time(t - self.clock.start)?;
        self.clock.time = t;
        Ok(())
    }

    /// Model Exchange: continuous states set one by one with `fmi2SetReal` /
    /// `fmi3SetFloat64` in Continuous-Time Mode, where `fmi2SetContinuousStates` is allowed
    /// (FMI 3.0 allows it there for continuous-time states, FMI 2.0's mathematical
    /// description too; integrators use it for finite-difference Jacobians): the others
    /// keep their values, and the model checks the new vector as with
    /// `fmi2SetContinuousStates`.
    pub(super) fn set_some_states(&mut self, states: &[(usize, f64)]) -> Result<(), Rejected> {
        if states.is_empty() {
            return Ok(());
        }
        let mut x = self.get_continuous_states(self.description().state_count())?;
        for &(k, v) in states {
            x[k] = v;
        }
        self.set_continuous_states(&x)
    }

    pub fn set_continuous_states(&mut self, x: &[f64]) -> Result<(), Rejected> {
        self.check_count(x.len(), "nx")?;
        if let Some(i) = x.iter().position(|v| !v.is_finite()) {
            return Err(format!("x[{i}] = {} is invalid: states must be finite", x[i]));
        }
        let t = self.clock.since_start();
        self.model.set_continuous_states(t, x)
    }

    pub fn get_continuous_states(&mut self, n: usize) -> Result<Vec<f64>, Rejected> {
        self.check_count(n, "nx")?;
        self.prepare()?;
        Ok(self.model.continuous_states())
    }

    pub fn get_derivatives(&mut self, n: usize) -> Result<Vec<f64>, Rejected> {
        self.check_count(n, "nx")?;
        self.prepare()?;
        let rates = self.model.derivatives(self.clock.since_start());
        match rates.iter().position(|x| !x.is_finite()) {
            Some(i) => Err(format!(
                "derivative {i} is {}: the states set are outside what the model accepts",
                rates[i]
            )),
            None => Ok(rates),
        }
    }

    /// The model's nominals (after `prepare`: they follow the parameters and the inputs).
    pub fn get_nominals(&mut self, n: usize) -> Result<Vec<f64>, Rejected> {
        self.check_count(n, "nx")?;
        self.prepare()?;
        Ok(self.model.nominals())
    }

    /// No event indicators: only `ni = 0` is valid.
    pub fn get_event_indicators(&mut self, n: usize) -> Result<(), Rejected> {
        if n == 0 {
            Ok(())
        } else {
            Err(format!("ni = {n} but this model has no event indicators"))
        }
    }
}
