//! One FMU instance in safe Rust: the FMI 2.0 co-simulation state machine, the variables,
//! FMU states and logging. It knows nothing of C: the `ffi` layer converts pointers.
//!
//! Every call goes through [`Instance::call`]: log the call (category `logCalls`), check
//! that it is allowed in the current state, run it. A call that is rejected (not allowed
//! now, or an invalid argument) is logged under `logStatusError`, returns
//! [`Status::Error`], and changes nothing: every check runs before any mutation, so the
//! master may go on with the instance as it was, restore a saved FMU state, or reset.

use super::state::{self, Machine, Saved};
use super::variables::{Causality, Kind, LOG_CATEGORIES, Variability, Vr};
use super::state::SchemeChoice;
use crate::solver::{Params, Settings, Solver, check_edge_stress, check_lambda, check_r_inf, check_sigma};
use std::collections::HashMap;

/// `fmi2Status`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    Ok = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
}

/// Where log messages go (the importer's callback, or a test's collector).
pub trait Logger {
    fn log(&self, status: Status, category: &str, message: &str);
}

/// The FMI calls, for the state-machine check and the call log.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    Get,
    Set,
    GetFmuState,
    SetFmuState,
    FreeFmuState,
    SerializeFmuState,
    DeSerializeFmuState,
    DoStep,
    CancelStep,
    GetStatus,
    GetDirectionalDerivative,
    SetRealInputDerivatives,
    GetRealOutputDerivatives,
}

impl Call {
    /// States in which FMI 2.0 (section 4.2.4) allows the call.
    fn allowed(self, m: Machine) -> bool {
        use Machine::*;
        if m == Error {
            // After an internal failure only recovery and inspection remain.
            return matches!(
                self,
                Call::Reset | Call::Get | Call::GetFmuState | Call::SetFmuState | Call::FreeFmuState
                    | Call::SerializeFmuState | Call::DeSerializeFmuState
            );
        }
        match self {
            Call::SetupExperiment | Call::EnterInitializationMode => m == Instantiated,
            Call::ExitInitializationMode => m == InitializationMode,
            Call::Terminate | Call::DoStep => m == StepComplete,
            Call::Reset
            | Call::GetFmuState
            | Call::SetFmuState
            | Call::FreeFmuState
            | Call::SerializeFmuState
            | Call::DeSerializeFmuState => true,
            Call::Get | Call::GetDirectionalDerivative => m != Instantiated,
            Call::Set | Call::SetRealInputDerivatives => m != Terminated,
            Call::GetStatus | Call::GetRealOutputDerivatives => matches!(m, StepComplete | Terminated),
            Call::CancelStep => false,
        }
    }

    pub fn fmi_name(self) -> &'static str {
        match self {
            Call::SetupExperiment => "fmi2SetupExperiment",
            Call::EnterInitializationMode => "fmi2EnterInitializationMode",
            Call::ExitInitializationMode => "fmi2ExitInitializationMode",
            Call::Terminate => "fmi2Terminate",
            Call::Reset => "fmi2Reset",
            Call::Get => "fmi2Get*",
            Call::Set => "fmi2Set*",
            Call::GetFmuState => "fmi2GetFMUstate",
            Call::SetFmuState => "fmi2SetFMUstate",
            Call::FreeFmuState => "fmi2FreeFMUstate",
            Call::SerializeFmuState => "fmi2SerializeFMUstate",
            Call::DeSerializeFmuState => "fmi2DeSerializeFMUstate",
            Call::DoStep => "fmi2DoStep",
            Call::CancelStep => "fmi2CancelStep",
            Call::GetStatus => "fmi2Get*Status",
            Call::GetDirectionalDerivative => "fmi2GetDirectionalDerivative",
            Call::SetRealInputDerivatives => "fmi2SetRealInputDerivatives",
            Call::GetRealOutputDerivatives => "fmi2GetRealOutputDerivatives",
        }
    }
}

/// A rejected call: the reason, for the logger.
pub type Rejected = String;

/// The instance's model data: what an FMU state saves (with the machine state).
#[derive(Debug, Clone)]
struct Model {
    params: Params,
    /// The `tolerance` parameter, and the tolerance of `fmi2SetupExperiment` (which wins).
    tolerance: f64,
    experiment_tolerance: Option<f64>,
    /// `method`, `grid_points` and `internal_step`.
    scheme: SchemeChoice,
    edge_stress: f64,
    start_time: f64,
    stop_time: Option<f64>,
    /// Master time of the last communication point.
    time: f64,
    /// Built when first needed after the parameters are final; dropped when they change.
    solver: Option<Solver>,
}

impl Model {
    /// The tolerance in force: the experiment's if defined, else the parameter.
    fn effective_tolerance(&self) -> f64 {
        self.experiment_tolerance.unwrap_or(self.tolerance)
    }

    /// The mesh the parameters and the tolerance in force give.
    fn settings(&self) -> Result<Settings, Rejected> {
        Settings::for_tolerance(&self.params, self.effective_tolerance()).map_err(|e| e.to_string())
    }

    /// A solver at the cut for these parameters, tolerance and scheme choice.
    fn build_solver(&self) -> Result<Solver, Rejected> {
        let scheme = self.scheme.scheme(self.settings()?);
        Solver::with_scheme(&self.params, &scheme).map_err(|e| e.to_string())
    }

    fn new() -> Self {
        let start = |vr: Vr| vr.var().start.unwrap_or(0.0);
        Self {
            params: Params { lambda: start(Vr::Lambda), sigma: start(Vr::Sigma), r_inf: start(Vr::RInf) },
            tolerance: start(Vr::Tolerance),
            experiment_tolerance: None,
            scheme: SchemeChoice {
                method: start(Vr::Method) as i32,
                grid_points: start(Vr::GridPoints) as i32,
                internal_step: start(Vr::InternalStep),
            },
            edge_stress: start(Vr::EdgeStress),
            start_time: 0.0,
            stop_time: None,
            time: 0.0,
            solver: None,
        }
    }
}

/// A saved FMU state, as held in the instance's table of states.
#[derive(Debug, Clone)]
struct Snapshot {
    machine: Machine,
    model: Model,
}

/// An FMU instance.
pub struct Instance {
    name: String,
    logger: Box<dyn Logger>,
    /// Debug categories switched on (index into `LOG_CATEGORIES`); errors always log.
    categories: [bool; LOG_CATEGORIES.len()],
    machine: Machine,
    model: Model,
    /// FMU states handed to the master, by handle (never 0).
    states: HashMap<u64, Snapshot>,
    next_handle: u64,
}

const LOG_CALLS: usize = 2;

impl Instance {
    pub fn new(name: &str, logger: Box<dyn Logger>, logging_on: bool) -> Self {
        Self {
            name: name.to_owned(),
            logger,
            categories: [true, true, logging_on],
            machine: Machine::Instantiated,
            model: Model::new(),
            states: HashMap::new(),
            next_handle: 1,
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn machine(&self) -> Machine {
        self.machine
    }

    /// After an internal failure (a caught panic): the model data may be half-updated,
    /// so only reset, restoring a saved FMU state, or inspection remain allowed.
    pub fn fail(&mut self, message: &str) {
        self.machine = Machine::Error;
        self.log_error(message);
    }

    /// Log under an error category (always on).
    pub fn log_error(&self, message: &str) {
        self.logger.log(Status::Error, "logStatusError", message);
    }

    fn log_calls_on(&self) -> bool {
        self.categories[LOG_CALLS]
    }

    fn log_debug(&self, message: &str) {
        if self.log_calls_on() {
            self.logger.log(Status::Ok, "logCalls", message);
        }
    }

    /// Frame one FMI call: log it, check the state machine, run `body`, log a rejection.
    pub fn call<T>(
        &mut self,
        call: Call,
        describe: impl FnOnce() -> String,
        body: impl FnOnce(&mut Self) -> Result<T, Rejected>,
    ) -> Result<T, Status> {
        if self.log_calls_on() {
            let text = describe();
            self.log_debug(&text);
        }
        if !call.allowed(self.machine) {
            self.log_error(&format!("{} is not allowed in state {:?}", call.fmi_name(), self.machine));
            return Err(Status::Error);
        }
        body(self).map_err(|why| {
            self.log_error(&format!("{}: {why}", call.fmi_name()));
            Status::Error
        })
    }

    /// `fmi2SetDebugLogging`: switch the listed categories (all when empty).
    pub fn set_debug_logging(&mut self, on: bool, names: &[String]) -> Result<(), Rejected> {
        let mut idx = Vec::with_capacity(names.len());
        for n in names {
            let i = LOG_CATEGORIES.iter().position(|(c, _)| c == n);
            idx.push(i.ok_or_else(|| format!("unknown log category \"{n}\"; declared: {}", category_list()))?);
        }
        if idx.is_empty() {
            idx = (0..LOG_CATEGORIES.len()).collect();
        }
        idx.into_iter().for_each(|i| self.categories[i] = on);
        self.categories[0] = true;
        Ok(())
    }

    pub fn setup_experiment(&mut self, tolerance: Option<f64>, start: f64, stop: Option<f64>) -> Result<(), Rejected> {
        if !start.is_finite() {
            return Err(format!("startTime = {start} is invalid: it must be finite"));
        }
        if let Some(s) = stop.filter(|&s| !(s.is_finite() && s >= start)) {
            return Err(format!("stopTime = {s} is invalid: it must be finite and >= startTime = {start}"));
        }
        if let Some(tol) = tolerance.filter(|&t| !(t.is_finite() && t > 0.0)) {
            return Err(format!("tolerance = {tol} is invalid: it must be finite and > 0"));
        }
        self.model.start_time = start;
        self.model.time = start;
        self.model.stop_time = stop;
        self.model.experiment_tolerance = tolerance;
        self.model.solver = None;
        Ok(())
    }

    pub fn enter_initialization_mode(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::InitializationMode;
        Ok(())
    }

    pub fn exit_initialization_mode(&mut self) -> Result<(), Rejected> {
        self.ensure_solver()?;
        self.machine = Machine::StepComplete;
        Ok(())
    }

    pub fn terminate(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::Terminated;
        Ok(())
    }

    /// `fmi2Reset`: back to the state after instantiation (saved FMU states are kept).
    pub fn reset(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::Instantiated;
        self.model = Model::new();
        Ok(())
    }

    fn ensure_solver(&mut self) -> Result<&Solver, Rejected> {
        if self.model.solver.is_none() {
            let m = &self.model;
            let solver = m.build_solver()?;
            self.log_debug(&format!(
                "solver: lambda = {}, sigma = {}, R_inf = {}, {} unknowns (tolerance {:e}, {:?})",
                m.params.lambda,
                m.params.sigma,
                m.params.r_inf,
                solver.unknowns(),
                m.effective_tolerance(),
                m.scheme
            ));
            self.model.solver = Some(solver);
        }
        Ok(self.model.solver.as_ref().expect("built above"))
    }

    /// Values of the listed variables, all of type `kind` (Integers are exact in f64).
    fn get_values(&mut self, kind: Kind, vrs: &[u32]) -> Result<Vec<f64>, Rejected> {
        let vrs: Vec<Vr> = vrs.iter().map(|&v| typed_vr(kind, v)).collect::<Result<_, _>>()?;
        let p = self.model.edge_stress;
        let needs_solver = vrs.iter().any(|v| matches!(v, Vr::WoundRadius | Vr::EdgeVelocity));
        if needs_solver {
            self.ensure_solver()?;
        }
        let m = &self.model;
        Ok(vrs
            .into_iter()
            .map(|vr| match vr {
                Vr::Lambda => m.params.lambda,
                Vr::Sigma => m.params.sigma,
                Vr::RInf => m.params.r_inf,
                Vr::EdgeStress => p,
                Vr::Tolerance => m.tolerance,
                Vr::Method => m.scheme.method as f64,
                Vr::GridPoints => m.scheme.grid_points as f64,
                Vr::InternalStep => m.scheme.internal_step,
                Vr::WoundRadius => m.solver.as_ref().expect("built").wound_radius(),
                Vr::EdgeVelocity => m.solver.as_ref().expect("built").edge_velocity(p),
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

    /// Set the listed variables of type `kind`: all values are checked first; any
    /// rejection sets none of them.
    fn set_values(&mut self, kind: Kind, vrs: &[u32], values: &[f64]) -> Result<(), Rejected> {
        let mut checked = Vec::with_capacity(vrs.len());
        for (&v, &x) in vrs.iter().zip(values) {
            let vr = typed_vr(kind, v)?;
            let var = vr.var();
            let fixed_now = var.variability == Variability::Fixed
                && !matches!(self.machine, Machine::Instantiated | Machine::InitializationMode);
            if var.causality == Causality::Output {
                return Err(format!("{} (value reference {v}) is an output and cannot be set", var.name));
            }
            if fixed_now {
                return Err(format!(
                    "{} is a fixed parameter: it can only be set before fmi2ExitInitializationMode (state is {:?})",
                    var.name, self.machine
                ));
            }
            checked.push((vr, check_value(vr, x)?));
        }
        for (vr, x) in checked {
            let m = &mut self.model;
            match vr {
                Vr::Lambda => m.params.lambda = x,
                Vr::Sigma => m.params.sigma = x,
                Vr::RInf => m.params.r_inf = x,
                Vr::Tolerance => m.tolerance = x,
                Vr::Method => m.scheme.method = x as i32,
                Vr::GridPoints => m.scheme.grid_points = x as i32,
                Vr::InternalStep => m.scheme.internal_step = x,
                _ => m.edge_stress = x,
            }
            if vr != Vr::EdgeStress {
                m.solver = None;
            }
        }
        Ok(())
    }

    /// `fmi2SetReal`.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), Rejected> {
        self.set_values(Kind::Real, vrs, values)
    }

    /// `fmi2SetInteger`.
    pub fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), Rejected> {
        let values: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        self.set_values(Kind::Integer, vrs, &values)
    }

    /// `fmi2DoStep`: the edge stress set before the call is held over `[t, t + h]`.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<(), Rejected> {
        let now = self.model.time;
        if !t.is_finite() || (t - now).abs() > 1e-12 * now.abs().max(1.0) {
            return Err(format!("Expected currentCommunicationPoint = {now} but was {t}"));
        }
        if !(h.is_finite() && h > 0.0) {
            return Err(format!("communicationStepSize = {h} is invalid: it must be finite and > 0"));
        }
        if let Some(stop) = self.model.stop_time.filter(|&s| now + h > s + 1e-12 * s.abs().max(1.0)) {
            return Err(format!("a step of {h} from {now} would pass stopTime = {stop}"));
        }
        let p = self.model.edge_stress;
        self.ensure_solver()?;
        let solver = self.model.solver.as_mut().expect("built above");
        solver.advance(h, p).map_err(|e| e.to_string())?;
        self.model.time = now + h;
        Ok(())
    }

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    pub fn last_successful_time(&self) -> f64 {
        self.model.time
    }

    /// `fmi2GetBooleanStatus(fmi2Terminated)`: true once the stop time is reached.
    pub fn wants_to_terminate(&self) -> bool {
        self.model.stop_time.is_some_and(|s| self.model.time >= s - 1e-12 * s.abs().max(1.0))
    }

    /// `fmi2GetFMUstate`: save into `handle` if given (it must be ours), else a new one.
    pub fn get_fmu_state(&mut self, handle: Option<u64>) -> Result<u64, Rejected> {
        let snap = Snapshot { machine: self.machine, model: self.model.clone() };
        let h = match handle {
            Some(h) if self.states.contains_key(&h) => h,
            Some(h) => return Err(format!("FMU state {h:#x} was not allocated by this instance")),
            None => self.new_handle(),
        };
        self.states.insert(h, snap);
        Ok(h)
    }

    fn new_handle(&mut self) -> u64 {
        let h = self.next_handle;
        self.next_handle += 1;
        h
    }

    fn snapshot(&self, handle: u64) -> Result<&Snapshot, Rejected> {
        self.states
            .get(&handle)
            .ok_or_else(|| format!("FMU state {handle:#x} is unknown (never allocated here, or already freed)"))
    }

    pub fn set_fmu_state(&mut self, handle: u64) -> Result<(), Rejected> {
        let snap = self.snapshot(handle)?.clone();
        self.machine = snap.machine;
        self.model = snap.model;
        Ok(())
    }

    pub fn free_fmu_state(&mut self, handle: u64) -> Result<(), Rejected> {
        self.snapshot(handle)?;
        self.states.remove(&handle);
        Ok(())
    }

    pub fn serialize_fmu_state(&self, handle: u64) -> Result<Vec<u8>, Rejected> {
        let snap = self.snapshot(handle)?;
        let m = &snap.model;
        Ok(state::encode(&Saved {
            machine: snap.machine,
            params: m.params,
            settings: m.settings()?,
            tolerance: m.tolerance,
            experiment_tolerance: m.experiment_tolerance,
            scheme: m.scheme,
            edge_stress: m.edge_stress,
            start_time: m.start_time,
            time: m.time,
            stop_time: m.stop_time,
            solver: m.solver.as_ref().map(Solver::state),
        }))
    }

    /// `fmi2DeSerializeFMUstate`: the bytes must come from an instance with the same
    /// parameters (a state is a point of one trajectory, not a parameter set).
    /// Into `target` if given (it must be ours), else into a new state.
    pub fn deserialize_fmu_state(&mut self, bytes: &[u8], target: Option<u64>) -> Result<u64, Rejected> {
        let saved = state::decode(bytes)?;
        let (mine, theirs) = (self.model.params, saved.params);
        for (name, a, b) in [
            ("lambda", mine.lambda, theirs.lambda),
            ("sigma", mine.sigma, theirs.sigma),
            ("R_inf", mine.r_inf, theirs.r_inf),
        ] {
            if a.to_bits() != b.to_bits() {
                return Err(format!("serialized FMU state has {name} = {b} but this instance has {name} = {a}"));
            }
        }
        let mine = self.model.effective_tolerance();
        let theirs = saved.experiment_tolerance.unwrap_or(saved.tolerance);
        if mine.to_bits() != theirs.to_bits() {
            return Err(format!("serialized FMU state has tolerance = {theirs} but this instance has tolerance = {mine}"));
        }
        if saved.scheme != self.model.scheme {
            return Err(format!("serialized FMU state has {:?} but this instance has {:?}", saved.scheme, self.model.scheme));
        }
        // The mesh follows from parameters and tolerance (checked equal to ours above):
        // bytes that claim another are forged.
        let expected = self.model.settings()?;
        if saved.settings != expected {
            return Err(format!(
                "serialized FMU state has mesh {:?} but its parameters and tolerance give {:?}",
                saved.settings.mesh, expected.mesh
            ));
        }
        let mut model = Model {
            params: saved.params,
            tolerance: saved.tolerance,
            experiment_tolerance: saved.experiment_tolerance,
            scheme: saved.scheme,
            edge_stress: saved.edge_stress,
            start_time: saved.start_time,
            stop_time: saved.stop_time,
            time: saved.time,
            solver: None,
        };
        if let Some(st) = &saved.solver {
            // Same parameters, tolerance and scheme: a clone of our own solver shares its operator.
            let mut s = match &self.model.solver {
                Some(own) => own.clone(),
                None => model.build_solver()?,
            };
            s.restore(st).map_err(|e| format!("serialized FMU state: {e}"))?;
            model.solver = Some(s);
        }
        let handle = match target {
            Some(h) => self.snapshot(h).map(|_| h)?,
            None => self.new_handle(),
        };
        self.states.insert(handle, Snapshot { machine: saved.machine, model });
        Ok(handle)
    }
}

/// Validate a value for a settable variable; the message names the variable and value.
fn check_value(vr: Vr, x: f64) -> Result<f64, Rejected> {
    let positive = |name: &str| {
        if x.is_finite() && x > 0.0 { Ok(x) } else { Err(format!("{name} = {x} is invalid: it must be finite and > 0")) }
    };
    let in_range = || {
        let (lo, hi) = vr.var().range.expect("Integer variables declare a range");
        if (lo as f64..=hi as f64).contains(&x) {
            Ok(x)
        } else {
            Err(format!("{} = {x} is invalid: it must be in {lo} ..= {hi}", vr.var().name))
        }
    };
    match vr {
        Vr::Lambda => check_lambda(x).map_err(|e| e.to_string()),
        Vr::Sigma => check_sigma(x).map_err(|e| e.to_string()),
        Vr::RInf => check_r_inf(x).map_err(|e| e.to_string()),
        Vr::Tolerance => positive("tolerance"),
        Vr::InternalStep => positive("internal_step"),
        Vr::Method | Vr::GridPoints => in_range(),
        _ => check_edge_stress(x).map_err(|e| e.to_string()),
    }
}

/// The variable of a value reference, which must be of type `kind`.
fn typed_vr(kind: Kind, v: u32) -> Result<Vr, Rejected> {
    match Vr::from_u32(v) {
        Some(vr) if vr.var().kind == kind => Ok(vr),
        Some(vr) => Err(format!("{} (value reference {v}) is {}, not {}", vr.var().name, vr.var().kind.as_str(), kind.as_str())),
        None => Err(format!("no {} variable has value reference {v}", kind.as_str())),
    }
}

fn category_list() -> String {
    LOG_CATEGORIES.iter().map(|(c, _)| *c).collect::<Vec<_>>().join(", ")
}
