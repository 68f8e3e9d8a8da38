//! The glue's warning channel ([`FmuModel::take_warning`]), with a test-only model that
//! warns after every second step (and after every call from the fifth step on): the call
//! returns `fmi2Warning` and the warning is logged under `logStatusWarning`; a worse status
//! of the call wins; a call without a warning is OK.

mod common;

use common::fmi::*;
use std::sync::{Arc, Mutex};
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::frame;
use wound_opening::fmi::common::instance::{Call, Instance, Logger, Status};
use wound_opening::fmi::common::model::{Description, Experiment, FmuModel, Rejected, Variable};

static VARIABLES: [Variable; 1] = [Variable::output("steps", 0, "1", "Steps taken")];
static DESCRIPTION: Description = Description {
    model_identifier: "Warner",
    guid: "{test-only}",
    summary: "",
    about: "",
    variables: &VARIABLES,
    outputs: &[(0, &[])],
    initial_unknowns: &[],
    units: &[("1", &[])],
    default_experiment: Experiment { start: 0.0, stop: 1.0, step: 0.1, tolerance: 1e-10 },
    states: None,
    arrays: None,
};

/// Counts its steps; after every second step it has a warning, and from the fifth step on
/// after every call.
#[derive(Clone, Default)]
struct Warner {
    steps: u32,
    warning: Option<String>,
}

impl Warner {
    fn fresh() -> Box<dyn FmuModel> {
        Box::new(Self::default())
    }
}

impl FmuModel for Warner {
    fn description(&self) -> &'static Description {
        &DESCRIPTION
    }
    fn boxed_clone(&self) -> Box<dyn FmuModel> {
        Box::new(self.clone())
    }
    fn check(&self, vr: u32, _x: f64) -> Result<f64, Rejected> {
        Err(format!("{vr} cannot be set"))
    }
    fn set(&mut self, _vr: u32, _x: f64) {}
    fn set_experiment_tolerance(&mut self, _tolerance: Option<f64>) {}
    fn prepare(&mut self) -> Result<Option<String>, Rejected> {
        Ok(None)
    }
    fn get(&self, _vr: u32, _time: f64) -> f64 {
        self.steps as f64
    }
    fn step(&mut self, _time: f64, _h: f64) -> Result<(), Rejected> {
        self.steps += 1;
        if self.steps % 2 == 0 {
            self.warning = Some(format!("step {} is even", self.steps));
        }
        Ok(())
    }
    fn partial(&self, _output: u32, _input: u32, _time: f64) -> Result<f64, Rejected> {
        Ok(0.0)
    }
    fn encode(&self) -> Result<Vec<u8>, Rejected> {
        Ok(Vec::new())
    }
    fn decode(&self, _bytes: &[u8]) -> Result<Box<dyn FmuModel>, Rejected> {
        Ok(self.boxed_clone())
    }
    fn take_warning(&mut self) -> Option<String> {
        if self.steps >= 5 { Some("five steps or more".into()) } else { self.warning.take() }
    }
}

#[derive(Default)]
struct Collect(Mutex<Vec<(Status, String, String)>>);

impl Logger for Collect {
    fn log(&self, status: Status, category: &str, message: &str) {
        self.0.lock().unwrap().push((status, category.into(), message.into()));
    }
}

fn warner(log: &Arc<Collect>) -> Instance {
    let mut i = Instance::new(Warner::fresh, "warner", log.clone(), false);
    i.call(Call::EnterInitializationMode, String::new, |i| i.enter_initialization_mode()).unwrap();
    i.call(Call::ExitInitializationMode, String::new, |i| i.exit_initialization_mode()).unwrap();
    i
}

/// Guards against a model's warning being lost: the call that caused it returns
/// `Status::Warning` (with its value) and logs it under `logStatusWarning`, once.
#[test]
fn a_model_warning_makes_the_call_a_logged_warning() {
    let log = Arc::new(Collect::default());
    let mut i = warner(&log);
    let step = |i: &mut Instance, t: f64| i.call(Call::DoStep, String::new, |i| i.do_step(t, 1.0));
    assert_eq!(step(&mut i, 0.0), Ok(((), Status::Ok)));
    assert_eq!(step(&mut i, 1.0), Ok(((), Status::Warning)));
    assert_eq!(
        log.0.lock().unwrap().last().cloned(),
        Some((Status::Warning, "logStatusWarning".into(), "fmi2DoStep: step 2 is even".into()))
    );
    let mut steps = [0.0];
    assert_eq!(i.call(Call::Get, String::new, |i| i.get_real(&[0], &mut steps)), Ok(((), Status::Ok)), "taken once");
    assert_eq!(steps, [2.0]);
    assert_eq!(step(&mut i, 5.0), Err(Status::Error), "a refused call has no warning to give");
}

/// Guards against the warning being dropped at the C boundary: the exported fmi2DoStep
/// returns fmi2Warning.
#[test]
fn the_exported_do_step_returns_fmi2_warning() {
    let log = Arc::new(Collect::default());
    let c = frame::register(warner(&log));
    unsafe {
        assert_eq!(fmi2DoStep(c, 0.0, 1.0, 0), OK);
        assert_eq!(fmi2DoStep(c, 1.0, 1.0, 0), WARNING);
        assert_eq!(fmi2DoStep(c, 2.0, 1.0, 0), OK);
        assert_eq!(fmi2DoStep(c, 3.0, 1.0, 0), WARNING);
        fmi2FreeInstance(c);
    }
    let warnings = log.0.lock().unwrap().iter().filter(|(s, _, _)| *s == Status::Warning).count();
    assert_eq!(warnings, 2);
}

/// Guards against a warning hiding a worse status: a discarded call (a status kind not
/// provided) stays `fmi2Discard` when the model also has a warning; an OK call becomes
/// `fmi2Warning`.
#[test]
fn a_worse_status_of_the_call_wins_over_a_warning() {
    let log = Arc::new(Collect::default());
    let c = frame::register(warner(&log));
    let (mut st, mut t) = (0, 0.0);
    unsafe {
        for k in 0..5 {
            assert!(fmi2DoStep(c, k as f64, 1.0, 0) <= WARNING);
        }
        assert_eq!(fmi2GetStatus(c, 0, &mut st), DISCARD, "fmi2DoStepStatus is not provided");
        assert_eq!(fmi2GetRealStatus(c, 2, &mut t), WARNING);
        assert_eq!(t, 5.0);
        fmi2FreeInstance(c);
    }
}
