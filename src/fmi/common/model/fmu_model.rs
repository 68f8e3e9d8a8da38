//! The [`FmuModel`] trait: what a model provides to the FMI glue (values, steps,
//! derivatives, FMU states, Model Exchange and arrays), with defaults for models that have
//! no continuous states or arrays. Re-exported as `crate::fmi::common::model::FmuModel`.

use super::{Description, Rejected};

/// A model behind the FMI glue. Value references arrive checked against the
/// description (existing, of the right type; outputs never set; fixed parameters only
/// before initialization ends). Times are since the master's `startTime` (the cut), in
/// the master's unit: every model of the FMU counts from the same instant.
pub trait FmuModel: Send {
    fn description(&self) -> &'static Description;
    fn boxed_clone(&self) -> Box<dyn FmuModel>;
    /// Validate `x` for variable `vr` (a parameter or input); return the value to store.
    fn check(&self, vr: u32, x: f64) -> Result<f64, Rejected>;
    /// Store a checked value.
    fn set(&mut self, vr: u32, x: f64);
    /// The tolerance of `fmi2SetupExperiment`, if defined.
    fn set_experiment_tolerance(&mut self, tolerance: Option<f64>);
    /// Build what outputs and steps need, if not yet built; `Some(text)` to log when
    /// something was built.
    fn prepare(&mut self) -> Result<Option<String>, Rejected>;
    /// Value of `vr` at time `time` since the cut (after [`FmuModel::prepare`] for outputs).
    fn get(&self, vr: u32, time: f64) -> f64;
    /// Advance from `time` by `h > 0` (after `prepare`).
    fn step(&mut self, time: f64, h: f64) -> Result<(), Rejected>;
    /// `d output / d input` at time `time` since the cut (after `prepare`); `Err` with the
    /// reason where the exact derivative is infinite or undefined.
    fn partial(&self, output: u32, input: u32, time: f64) -> Result<f64, Rejected>;
    /// The Jacobian `d unknown_i / d known_j`, row-major (`unknowns.len()` rows), at time
    /// `time` since the cut (after `prepare`). Unknowns are outputs or (Model Exchange)
    /// derivatives, knowns inputs or (Model Exchange) states, checked by the glue. The
    /// default is [`FmuModel::partial`] per entry (models without states).
    fn jacobian(&self, unknowns: &[u32], knowns: &[u32], time: f64) -> Result<Vec<f64>, Rejected> {
        let mut out = Vec::with_capacity(unknowns.len() * knowns.len());
        for &u in unknowns {
            for &k in knowns {
                out.push(self.partial(u, k, time)?);
            }
        }
        Ok(out)
    }
    /// The model's part of a serialized FMU state.
    fn encode(&self) -> Result<Vec<u8>, Rejected>;
    /// A model from `encode`d bytes, which must fit this instance's parameters.
    fn decode(&self, bytes: &[u8]) -> Result<Box<dyn FmuModel>, Rejected>;
    /// A warning about the call that just succeeded, if the model has one (taken: asked
    /// once per call). The glue logs it under `logStatusWarning` and the call returns
    /// `fmi2Warning`: the result is usable, but the master should know (FMI 2.0.2,
    /// section 2.1.3). The default has none.
    fn take_warning(&mut self) -> Option<String> {
        None
    }
    /// A note about the current call: logged under `logStatusWarning` with status OK (the
    /// call's status stays OK), for what the master should know about a result that is
    /// the best answer the model has (a tolerance below the floor, an infinite value in
    /// the model answered by a stated finite one). The default has none.
    fn take_note(&mut self) -> Option<String> {
        None
    }

    /// `fmi2SetRealInputDerivatives`: validate `rate`, the first time derivative of the
    /// input `vr` per second of master time, which makes the input linear in time over the
    /// next steps (`canInterpolateInputs`). The default refuses.
    fn check_input_rate(&self, vr: u32, _rate: f64) -> Result<(), Rejected> {
        Err(format!("value reference {vr}: this model does not interpolate its inputs"))
    }
    /// Store a checked input rate (reset to 0 by the next `set` of that input).
    fn set_input_rate(&mut self, _vr: u32, _rate: f64) {}

    /// Model Exchange: whether this parameter set can run as an ODE for an outside
    /// integrator (`Err` with the reason; after [`FmuModel::prepare`]). Models without
    /// states can.
    fn check_model_exchange(&self) -> Result<(), Rejected> {
        Ok(())
    }
    /// Model Exchange starts (initialization ends, after [`FmuModel::check_model_exchange`]):
    /// the inputs set now are the start of the run.
    fn enter_model_exchange(&mut self) {}
    /// The master's time, `time` since the cut, set in Model Exchange (the states and
    /// inputs kept).
    fn set_time(&mut self, _time: f64) -> Result<(), Rejected> {
        Ok(())
    }
    /// The continuous states, `description().state_count()` of them (after `prepare`).
    fn continuous_states(&self) -> Vec<f64> {
        Vec::new()
    }
    /// Set the continuous states at time `time` since the cut (validated: finite, the
    /// declared count).
    fn set_continuous_states(&mut self, _time: f64, x: &[f64]) -> Result<(), Rejected> {
        if x.is_empty() {
            Ok(())
        } else {
            Err(format!("this model has no continuous states, {} given", x.len()))
        }
    }
    /// `dx/dt` per unit of the master's time at `time` since the cut, under the inputs set.
    fn derivatives(&self, _time: f64) -> Vec<f64> {
        Vec::new()
    }
    /// Model Exchange, Event Mode (`fmi2NewDiscreteStates`): update the discrete states
    /// after the inputs set; `(values of the continuous states changed, their nominals
    /// changed)`. The default has none.
    fn update_discrete_states(&mut self) -> (bool, bool) {
        (false, false)
    }
    /// Nominal values of the states (> 0).
    fn nominals(&self) -> Vec<f64> {
        vec![1.0; self.description().state_count()]
    }

    /// FMI 3.0 arrays ([`Arrays`]): the current length.
    fn array_length(&self) -> u64 {
        0
    }
    /// Set the length (checked by the glue against `1 ..= length_max`); the parameter
    /// arrays take their start values, or as many as fit.
    fn set_array_length(&mut self, _n: u64) {}
    /// Validate the values of parameter array `j` (length checked by the glue).
    fn check_array(&self, j: usize, _values: &[f64]) -> Result<(), Rejected> {
        Err(format!("array {j} cannot be set"))
    }
    fn set_array(&mut self, _j: usize, _values: &[f64]) {}
    /// Array `j` at time `time` since the cut (after `prepare` for outputs).
    fn get_array(&self, j: usize, _time: f64) -> Result<Vec<f64>, Rejected> {
        Err(format!("this model has no array {j}"))
    }
}
