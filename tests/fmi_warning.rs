//! The glue's warning channel ([`FmuModel::take_warning`]), with a test-only model that
//! warns after every second step (and after every call from the fifth step on): the call
//! returns `fmi2Warning` and the warning is logged under `logStatusWarning`; a worse status
//! of the call wins; a call without a warning is OK.

mod common;

use common::fmi::*;
use std::sync::{Arc, Mutex};
use wound_opening::fmi::common::instance::{Call, Instance, Logger, Status};
use wound_opening::fmi::common::model::{Description, Experiment, FmuModel, Rejected, Variable};
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::frame;

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
        if self.steps.is_multiple_of(2) {
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
    assert_eq!(
        i.call(Call::Get, String::new, |i| i.get_real(&[0], &mut steps)),
        Ok(((), Status::Ok)),
        "taken once"
    );
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

mod wound {
    //! The wound model's validity crossing (lambda = 0.3, sigma = 2, R_inf = 20 leaves an edge
    //! strain of 1 at t = 3 s), reported as `validity_warning` says, and a master's
    //! tolerance 0 taken as none given.
    use super::Collect;
    use std::sync::Arc;
    use wound_opening::fmi::common::instance::{Call, Instance, Status};
    use wound_opening::models::wound::WoundModel;
    use wound_opening::models::wound::variables::Vr;
    use wound_opening::solver::exact;

    const CASE: [(Vr, f64); 3] = [(Vr::Lambda, 0.3), (Vr::Sigma, 2.0), (Vr::RInf, 20.0)];

    /// An initialized instance of CASE with `validity_warning` set (or left at its start).
    fn strict_case(validity_warning: Option<i32>, log: &Arc<Collect>) -> Instance {
        let mut i = Instance::new(WoundModel::fresh, "wound", log.clone(), false);
        let ok = |r: Result<((), Status), Status>| assert_eq!(r, Ok(((), Status::Ok)));
        ok(i.call(Call::SetupExperiment, String::new, |i| i.setup_experiment(None, 0.0, None)));
        for (vr, x) in CASE {
            ok(i.call(Call::Set, String::new, |i| i.set_real(&[vr as u32], &[x])));
        }
        if let Some(v) = validity_warning {
            ok(i.call(Call::Set, String::new, |i| {
                i.set_integer(&[Vr::ValidityWarning as u32], &[v])
            }));
        }
        ok(i.call(Call::EnterInitializationMode, String::new, |i| i.enter_initialization_mode()));
        ok(i.call(Call::ExitInitializationMode, String::new, |i| i.exit_initialization_mode()));
        i
    }

    /// Steps of 1 s to t = 10, then one to 1e7 s (the final state): the statuses, and the
    /// final radius's error relative to the opening against the exact final state.
    fn run(i: &mut Instance) -> (Vec<Status>, f64) {
        let mut statuses = Vec::new();
        for (t, h) in (0..10).map(|k| (k as f64, 1.0)).chain([(10.0, 1e7)]) {
            statuses.push(
                i.call(Call::DoStep, String::new, |i| i.do_step(t, h)).expect("the step is done").1,
            );
        }
        let mut r = [f64::NAN];
        assert_eq!(
            i.call(Call::Get, String::new, |i| i.get_real(&[Vr::WoundRadius as u32], &mut r)),
            Ok(((), Status::Ok))
        );
        let (want, r1) = (exact::final_radius(2.0, 20.0), exact::initial_radius(2.0));
        (statuses, (r[0] - want).abs() / (want - r1))
    }

    fn logged(log: &Collect) -> Vec<(Status, String, String)> {
        log.0.lock().unwrap().clone()
    }

    /// Guards against a strict master having no way on: by default the step to t = 3 s
    /// answers Warning and its text names `validity_warning` and the value to set; with
    /// `validity_warning = 0` every step is OK, the same crossing logged under
    /// logStatusWarning with status OK, and the run reaches the exact final state.
    #[test]
    fn a_validity_crossing_warns_by_default_and_is_a_logged_note_with_validity_warning_0() {
        let log = Arc::new(Collect::default());
        let (statuses, _) = run(&mut strict_case(None, &log));
        let mut want = vec![Status::Ok; 11];
        want[2] = Status::Warning;
        assert_eq!(statuses, want, "the step ending at t = 3 s");
        let warned: Vec<_> =
            logged(&log).into_iter().filter(|(s, _, _)| *s == Status::Warning).collect();
        assert_eq!(warned.len(), 1);
        let (_, category, text) = &warned[0];
        assert_eq!(category, "logStatusWarning");
        assert!(
            text.contains(
                "at t = 3 s the run leaves the model's validity: the strain at the wound edge"
            ),
            "{text}"
        );
        assert!(text.contains("validity_warning is set to 0"), "{text}");

        let log = Arc::new(Collect::default());
        let mut i = strict_case(Some(0), &log);
        let (statuses, error) = run(&mut i);
        assert_eq!(statuses, vec![Status::Ok; 11]);
        assert!(error < 1e-10, "final radius error {error:e} of the opening");
        let notes: Vec<_> =
            logged(&log).into_iter().filter(|(_, c, _)| c == "logStatusWarning").collect();
        assert_eq!(notes.len(), 1, "{notes:?}");
        let (status, _, text) = &notes[0];
        assert_eq!(*status, Status::Ok);
        assert!(
            text.contains(
                "at t = 3 s the run leaves the model's validity: the strain at the wound edge"
            ),
            "{text}"
        );
        let mut v = [7];
        assert_eq!(
            i.call(Call::Get, String::new, |i| i
                .get_integer(&[Vr::ValidityWarning as u32], &mut v)),
            Ok(((), Status::Ok))
        );
        assert_eq!(v, [0]);
    }

    /// Guards against a value outside 0..1 being taken, and against the parameter being
    /// set after initialization (it is fixed).
    #[test]
    fn validity_warning_is_0_or_1_and_fixed() {
        let log = Arc::new(Collect::default());
        let mut i = Instance::new(WoundModel::fresh, "wound", log.clone(), false);
        assert_eq!(
            i.call(Call::Set, String::new, |i| i.set_integer(&[Vr::ValidityWarning as u32], &[2])),
            Err(Status::Error)
        );
        assert!(
            logged(&log)
                .last()
                .unwrap()
                .2
                .contains("validity_warning = 2 is invalid: it must be in 0 ..= 1")
        );
        let mut i = strict_case(Some(1), &log);
        assert_eq!(
            i.call(Call::Set, String::new, |i| i.set_integer(&[Vr::ValidityWarning as u32], &[0])),
            Err(Status::Error)
        );
        assert!(logged(&log).last().unwrap().2.contains("validity_warning is a fixed parameter"));
    }

    /// Guards against OMSimulator's tolerance 0 (an SSP without one) failing the
    /// instantiation: it is taken as none given, with a log line, status OK; NaN, negative
    /// and infinite tolerances stay refused.
    #[test]
    fn a_tolerance_of_0_is_none_given_and_other_invalid_ones_are_refused() {
        let log = Arc::new(Collect::default());
        let mut i = Instance::new(WoundModel::fresh, "wound", log.clone(), false);
        let setup = |i: &mut Instance, tol: f64| {
            i.call(Call::SetupExperiment, String::new, |i| i.setup_experiment(Some(tol), 0.0, None))
        };
        for tol in [f64::NAN, -1e-6, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(setup(&mut i, tol), Err(Status::Error), "{tol}");
            assert!(logged(&log).last().unwrap().2.contains("it must be finite and > 0"));
        }
        assert_eq!(setup(&mut i, 0.0), Ok(((), Status::Ok)));
        let (status, category, text) = logged(&log).last().cloned().unwrap();
        assert_eq!((status, category.as_str()), (Status::Ok, "logStatusWarning"));
        assert!(
            text.contains("tolerance = 0 with toleranceDefined is taken as no tolerance given"),
            "{text}"
        );
        // The tolerance parameter (1e-10) is in force: sigma = 2e-5 >= 6 eps / 1e-10 runs.
        let sigma = [2e-5];
        assert_eq!(
            i.call(Call::Set, String::new, |i| i.set_real(&[Vr::Sigma as u32], &sigma)),
            Ok(((), Status::Ok))
        );
        assert_eq!(
            i.call(Call::EnterInitializationMode, String::new, |i| i.enter_initialization_mode()),
            Ok(((), Status::Ok))
        );
        assert_eq!(
            i.call(Call::ExitInitializationMode, String::new, |i| i.exit_initialization_mode()),
            Ok(((), Status::Ok))
        );
    }
}
