//! FMI 3.0's counterpart of `fmi2SetRealInputDerivatives` for co-simulation: Intermediate
//! Update Mode (FMI 3.0 removed input derivatives; its overview names setting inputs in
//! Intermediate Update Mode as the replacement). In an `fmi3DoStep(t, h)` of an instance
//! made with `requiredIntermediateVariables` (continuous Real inputs) and an
//! `intermediateUpdate` callback:
//!
//! ```text
//! 1. check the step; record the inputs p0 at t; state IntermediateUpdate     (instance locked)
//! 2. intermediateUpdate(t + h, set requested)   -> the importer may fmi3SetFloat64 the
//!    required inputs to its extrapolation p1 at t + h                        (lock released)
//! 3. the inputs are p0 + (p1 - p0) (s - t) / h over the step: the model's linear-in-time
//!    step (exact for a model linear in its inputs), then held again (rate 0) at p1
//!                                                                            (instance locked)
//! ```
//!
//! An importer that sets nothing holds the inputs, as without the callback.
#![forbid(unsafe_code)]

use crate::fmi::common::instance::{Instance, Rejected, Requester};
use crate::fmi::common::machine::Machine;
use crate::fmi::common::model::{Causality, Kind, Variability};

/// A step that asks the importer: its callback and the inputs at the step's start.
pub type Asking = (std::sync::Arc<dyn Requester>, Vec<f64>);

impl Instance {
    /// Use `requester` for the inputs `vrs` (each a continuous Real input) in every step.
    pub fn set_intermediate_update(
        &mut self,
        requester: std::sync::Arc<dyn Requester>,
        vrs: &[u32],
    ) -> Result<(), Rejected> {
        let d = self.description();
        for &vr in vrs {
            let v = d.typed(Kind::Real, vr)?;
            if !(v.causality == Causality::Input && v.variability == Variability::Continuous) {
                return Err(format!(
                    "{} (value reference {vr}) is not a continuous input: it cannot be an intermediate variable",
                    v.name
                ));
            }
        }
        self.intermediate = Some((requester, vrs.to_vec()));
        Ok(())
    }

    /// Phase 1: `Some((requester, inputs at t))` when this step asks the importer, after the
    /// checks of the step; the instance is then in Intermediate Update Mode.
    pub fn begin_step(&mut self, t: f64, h: f64) -> Result<Option<Asking>, Rejected> {
        self.check_step(t, h)?;
        let Some((requester, vrs)) = self.intermediate.clone() else { return Ok(None) };
        self.prepare()?;
        let now = self.clock.since_start();
        let p0 = vrs.iter().map(|&vr| self.model.get(vr, now)).collect();
        self.machine = Machine::IntermediateUpdate;
        Ok(Some((requester, p0)))
    }

    /// Phase 3: the inputs linear from `p0` to what the importer set, the step, then held.
    pub fn finish_step(&mut self, t: f64, h: f64, p0: &[f64]) -> Result<(), Rejected> {
        self.machine = Machine::StepComplete;
        let vrs = self.intermediate.as_ref().map(|(_, v)| v.clone()).unwrap_or_default();
        let now = self.clock.since_start();
        let p1: Vec<f64> = vrs.iter().map(|&vr| self.model.get(vr, now)).collect();
        for ((&vr, &a), &b) in vrs.iter().zip(p0).zip(&p1) {
            if a != b {
                let rate = (b - a) / h;
                self.model.check_input_rate(vr, rate)?;
                self.model.set(vr, a);
                self.model.set_input_rate(vr, rate);
            }
        }
        let stepped = self.do_step(t, h);
        // Held again at the values the importer set (a refused step keeps them, rate 0).
        for (&vr, &b) in vrs.iter().zip(&p1) {
            self.model.set(
                vr,
                if stepped.is_ok() { self.model.get(vr, self.clock.since_start()) } else { b },
            );
        }
        stepped
    }
}
