//! The safe FMU instance: state machine, rejected calls that change nothing, messages
//! that name what was wrong, FMU states. (The C boundary itself is driven by fmpy in
//! tests/python.)

use std::sync::{Arc, Mutex};
use wound_opening::fmi::common::instance::{Call, Instance, Logger, Status};
use wound_opening::fmi::common::machine::Machine;
use wound_opening::models::wound::WoundModel;
use wound_opening::models::wound::variables::Vr;

#[derive(Clone, Default)]
struct Collect(Arc<Mutex<Vec<(Status, String, String)>>>);

impl Logger for Collect {
    fn log(&self, status: Status, category: &str, message: &str) {
        self.0.lock().unwrap().push((status, category.into(), message.into()));
    }
}

impl Collect {
    fn last_error(&self) -> String {
        let log = self.0.lock().unwrap();
        let (status, cat, msg) = log.last().expect("a message was logged").clone();
        assert_eq!((status, cat.as_str()), (Status::Error, "logStatusError"));
        msg
    }
}

fn instance() -> (Instance, Collect) {
    let log = Collect::default();
    (Instance::new(WoundModel::fresh, "test", Arc::new(log.clone()), false), log)
}

fn run<T>(
    i: &mut Instance,
    call: Call,
    body: impl FnOnce(&mut Instance) -> Result<T, String>,
) -> Result<T, Status> {
    i.call(call, || format!("{call:?}"), body).map(|(value, _)| value)
}

fn initialized(lambda: f64) -> (Instance, Collect) {
    let (mut i, log) = instance();
    run(&mut i, Call::Set, |i| i.set_real(&[Vr::Lambda as u32], &[lambda])).unwrap();
    run(&mut i, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
    run(&mut i, Call::ExitInitializationMode, |i| i.exit_initialization_mode()).unwrap();
    (i, log)
}

fn outputs(i: &mut Instance) -> [f64; 2] {
    let mut out = [0.0; 2];
    run(i, Call::Get, |i| i.get_real(&[Vr::WoundRadius as u32, Vr::EdgeVelocity as u32], &mut out))
        .unwrap();
    out
}

#[test]
fn invalid_parameters_are_rejected_by_name_and_change_nothing() {
    let cases: [(Vr, f64, &str); 6] = [
        (Vr::Lambda, -1.0, "lambda = -1 is outside the accepted range: 0 or [1e-150, 1e6]"),
        (Vr::Lambda, f64::NAN, "lambda = NaN is outside"),
        (Vr::RInf, 1.0, "R_inf = 1 is outside the accepted range [1.001, 1e6]"),
        (Vr::RInf, 0.5, "R_inf = 0.5 is outside"),
        (Vr::Sigma, f64::INFINITY, "sigma = inf is outside the accepted range (-6, 1e6]"),
        (Vr::EdgeStress, f64::NEG_INFINITY, "edge_stress = -inf Pa is outside the accepted range"),
    ];
    for (vr, value, message) in cases {
        let (mut i, log) = instance();
        // A valid value first in the same call: a rejected call sets none of its values.
        let r =
            run(&mut i, Call::Set, |i| i.set_real(&[Vr::Sigma as u32, vr as u32], &[2.0, value]));
        assert_eq!(r, Err(Status::Error));
        assert!(log.last_error().contains(message), "{}", log.last_error());
        assert_eq!(i.machine(), Machine::Instantiated);
        run(&mut i, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
        let mut sigma = [0.0];
        run(&mut i, Call::Get, |i| i.get_real(&[Vr::Sigma as u32], &mut sigma)).unwrap();
        assert_eq!(sigma[0], 1.0, "sigma keeps its start value");
    }
}

#[test]
fn illegal_sequences_are_errors_that_leave_the_instance_usable() {
    let (mut i, log) = instance();
    assert_eq!(run(&mut i, Call::DoStep, |i| i.do_step(0.0, 0.1)), Err(Status::Error));
    assert!(log.last_error().contains("fmi2DoStep is not allowed in state Instantiated"));
    let (mut i, log) = initialized(1.0);
    assert_eq!(
        run(&mut i, Call::Set, |i| i.set_real(&[Vr::Lambda as u32], &[2.0])),
        Err(Status::Error)
    );
    assert!(log.last_error().contains("lambda is a fixed parameter"), "{}", log.last_error());
    assert_eq!(run(&mut i, Call::DoStep, |i| i.do_step(0.5, 0.1)), Err(Status::Error));
    assert!(log.last_error().contains("Expected currentCommunicationPoint = 0 but was 0.5"));
    for h in [0.0, -0.1, f64::NAN] {
        assert_eq!(run(&mut i, Call::DoStep, |i| i.do_step(0.0, h)), Err(Status::Error));
        assert!(log.last_error().contains("communicationStepSize"), "{}", log.last_error());
    }
    assert_eq!(
        run(&mut i, Call::Set, |i| i.set_real(&[Vr::WoundRadius as u32], &[2.0])),
        Err(Status::Error)
    );
    assert_eq!(run(&mut i, Call::Set, |i| i.set_real(&[99], &[2.0])), Err(Status::Error));
    assert!(log.last_error().contains("value reference 99"));
    // Still usable after every rejection.
    run(&mut i, Call::DoStep, |i| i.do_step(0.0, 0.1)).unwrap();
    assert!(outputs(&mut i)[0] > 1.0 + 1.0 / 6.0);
}

#[test]
fn stop_time_is_enforced_and_reported() {
    let (mut i, log) = instance();
    run(&mut i, Call::SetupExperiment, |i| i.setup_experiment(None, 2.0, Some(2.5))).unwrap();
    run(&mut i, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
    run(&mut i, Call::ExitInitializationMode, |i| i.exit_initialization_mode()).unwrap();
    run(&mut i, Call::DoStep, |i| i.do_step(2.0, 0.5)).unwrap();
    assert!(i.wants_to_terminate());
    assert_eq!(i.last_successful_time(), 2.5);
    assert_eq!(run(&mut i, Call::DoStep, |i| i.do_step(2.5, 0.1)), Err(Status::Error));
    assert!(log.last_error().contains("stopTime = 2.5"));
    let r = run(&mut i, Call::SetupExperiment, |i| i.setup_experiment(None, 0.0, None));
    assert_eq!(r, Err(Status::Error), "setup only before initialization");
}

#[test]
fn fmu_states_restore_and_serialize_bit_for_bit() {
    let (mut i, log) = initialized(0.1);
    run(&mut i, Call::DoStep, |i| i.do_step(0.0, 0.3)).unwrap();
    let saved = run(&mut i, Call::GetFmuState, |i| i.get_fmu_state(None)).unwrap();
    let bytes = run(&mut i, Call::SerializeFmuState, |i| i.serialize_fmu_state(saved)).unwrap();
    let mut first = Vec::new();
    for k in 0..5 {
        run(&mut i, Call::Set, |i| i.set_real(&[Vr::EdgeStress as u32], &[0.1 * k as f64]))
            .unwrap();
        run(&mut i, Call::DoStep, |i| i.do_step(0.3 + 0.2 * k as f64, 0.2)).unwrap();
        first.push(outputs(&mut i));
    }
    let replay = |i: &mut Instance| {
        (0..5)
            .map(|k| {
                run(i, Call::Set, |i| i.set_real(&[Vr::EdgeStress as u32], &[0.1 * k as f64]))
                    .unwrap();
                run(i, Call::DoStep, |i| i.do_step(0.3 + 0.2 * k as f64, 0.2)).unwrap();
                outputs(i)
            })
            .collect::<Vec<_>>()
    };
    run(&mut i, Call::SetFmuState, |i| i.set_fmu_state(saved)).unwrap();
    run(&mut i, Call::Set, |i| i.set_real(&[Vr::EdgeStress as u32], &[0.0])).unwrap();
    assert_eq!(replay(&mut i), first);
    let back =
        run(&mut i, Call::DeSerializeFmuState, |i| i.deserialize_fmu_state(&bytes, None)).unwrap();
    run(&mut i, Call::SetFmuState, |i| i.set_fmu_state(back)).unwrap();
    assert_eq!(replay(&mut i), first);
    // Double free and unknown handles are errors, not crashes.
    run(&mut i, Call::FreeFmuState, |i| i.free_fmu_state(saved)).unwrap();
    assert_eq!(run(&mut i, Call::FreeFmuState, |i| i.free_fmu_state(saved)), Err(Status::Error));
    assert!(log.last_error().contains("unknown"));
    assert_eq!(run(&mut i, Call::SetFmuState, |i| i.set_fmu_state(12345)), Err(Status::Error));
}

#[test]
fn serialized_state_from_other_parameters_is_refused_by_name() {
    let (mut a, _) = initialized(0.1);
    let h = run(&mut a, Call::GetFmuState, |i| i.get_fmu_state(None)).unwrap();
    let bytes = run(&mut a, Call::SerializeFmuState, |i| i.serialize_fmu_state(h)).unwrap();
    let (mut b, log) = initialized(1.0);
    assert_eq!(
        run(&mut b, Call::DeSerializeFmuState, |i| i.deserialize_fmu_state(&bytes, None)),
        Err(Status::Error)
    );
    assert!(
        log.last_error().contains("lambda = 0.1 but this instance has lambda = 1"),
        "{}",
        log.last_error()
    );
    assert_eq!(
        run(&mut b, Call::DeSerializeFmuState, |i| i.deserialize_fmu_state(&bytes[..20], None)),
        Err(Status::Error)
    );
    assert!(log.last_error().contains("truncated") || log.last_error().contains("announces"));
}

#[test]
fn reset_returns_to_the_start_values() {
    let (mut i, _) = initialized(0.1);
    run(&mut i, Call::DoStep, |i| i.do_step(0.0, 1.0)).unwrap();
    let end = outputs(&mut i);
    run(&mut i, Call::Reset, |i| i.reset()).unwrap();
    assert_eq!(i.machine(), Machine::Instantiated);
    let mut lambda = [0.0];
    run(&mut i, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
    run(&mut i, Call::Get, |i| i.get_real(&[Vr::Lambda as u32], &mut lambda)).unwrap();
    assert_eq!(lambda[0], 1.0);
    run(&mut i, Call::Set, |i| i.set_real(&[Vr::Lambda as u32], &[0.1])).unwrap();
    run(&mut i, Call::ExitInitializationMode, |i| i.exit_initialization_mode()).unwrap();
    run(&mut i, Call::DoStep, |i| i.do_step(0.0, 1.0)).unwrap();
    assert_eq!(outputs(&mut i), end);
}

#[test]
fn debug_logging_switches_categories_and_rejects_unknown_ones() {
    let (mut i, log) = instance();
    i.set_debug_logging(true, &["logCalls".into()]).unwrap();
    run(&mut i, Call::SetupExperiment, |i| i.setup_experiment(None, 0.0, None)).unwrap();
    assert!(
        log.0
            .lock()
            .unwrap()
            .iter()
            .any(|(_, c, m)| c == "logCalls" && m.contains("SetupExperiment"))
    );
    let err = i.set_debug_logging(true, &["logNothing".into()]).unwrap_err();
    assert!(err.contains("logNothing") && err.contains("logCalls"), "{err}");
}

#[test]
fn method_is_an_integer_parameter_checked_by_range_and_type() {
    let (mut i, log) = instance();
    let method = Vr::Method as u32;
    assert_eq!(run(&mut i, Call::Set, |i| i.set_integer(&[method], &[4])), Err(Status::Error));
    assert!(
        log.last_error().contains("method = 4 is invalid: it must be in 0 ..= 3"),
        "{}",
        log.last_error()
    );
    assert_eq!(run(&mut i, Call::Set, |i| i.set_real(&[method], &[2.0])), Err(Status::Error));
    assert!(
        log.last_error().contains("method (value reference 7) is Integer, not Real"),
        "{}",
        log.last_error()
    );
    assert_eq!(
        run(&mut i, Call::Set, |i| i.set_integer(&[Vr::Lambda as u32], &[1])),
        Err(Status::Error)
    );
    assert_eq!(
        run(&mut i, Call::Set, |i| i.set_integer(&[Vr::GridPoints as u32], &[2])),
        Err(Status::Error)
    );
    // The paper's scheme, selected through the FMU, gives its first-order result: at
    // N = 101 it is 4.6 % of the amplitude away from the exact R(1) (10-20 % at worst
    // over time); the default scheme is exact to 1e-12. 2 % tells them apart.
    run(&mut i, Call::Set, |i| i.set_integer(&[method], &[2])).unwrap();
    run(&mut i, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
    let mut got = [0];
    run(&mut i, Call::Get, |i| i.get_integer(&[method], &mut got)).unwrap();
    assert_eq!(got, [2]);
    run(&mut i, Call::ExitInitializationMode, |i| i.exit_initialization_mode()).unwrap();
    run(&mut i, Call::DoStep, |i| i.do_step(0.0, 1.0)).unwrap();
    let paper = outputs(&mut i)[0];
    let (mut d, _) = initialized(1.0);
    run(&mut d, Call::DoStep, |i| i.do_step(0.0, 1.0)).unwrap();
    let default = outputs(&mut d)[0];
    let amp = 2.0 / 3.0 * 100.0 / 99.0 - 1.0 / 6.0;
    assert!((paper - default).abs() > 0.02 * amp, "{paper} vs {default}");
    assert_eq!(
        run(&mut i, Call::Set, |i| i.set_integer(&[method], &[0])),
        Err(Status::Error),
        "fixed after init"
    );
}

#[test]
fn a_state_saved_before_initialization_round_trips() {
    let (mut i, _) = instance();
    run(&mut i, Call::Set, |i| i.set_real(&[Vr::Lambda as u32], &[0.3])).unwrap();
    let h = run(&mut i, Call::GetFmuState, |i| i.get_fmu_state(None)).unwrap();
    let bytes = run(&mut i, Call::SerializeFmuState, |i| i.serialize_fmu_state(h)).unwrap();
    let back =
        run(&mut i, Call::DeSerializeFmuState, |i| i.deserialize_fmu_state(&bytes, None)).unwrap();
    run(&mut i, Call::SetFmuState, |i| i.set_fmu_state(back)).unwrap();
    assert_eq!(i.machine(), Machine::Instantiated);
}

#[test]
fn a_state_of_another_method_deserializes_into_a_fresh_instance() {
    let with_paper = |i: &mut Instance| {
        run(i, Call::Set, |i| i.set_integer(&[Vr::Method as u32], &[2])).unwrap()
    };
    let (mut a, _) = instance();
    with_paper(&mut a);
    run(&mut a, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
    run(&mut a, Call::ExitInitializationMode, |i| i.exit_initialization_mode()).unwrap();
    run(&mut a, Call::DoStep, |i| i.do_step(0.0, 0.5)).unwrap();
    let h = run(&mut a, Call::GetFmuState, |i| i.get_fmu_state(None)).unwrap();
    let bytes = run(&mut a, Call::SerializeFmuState, |i| i.serialize_fmu_state(h)).unwrap();
    run(&mut a, Call::DoStep, |i| i.do_step(0.5, 0.5)).unwrap();
    let want = outputs(&mut a);
    // A fresh instance with the same parameters has no solver yet: it must build the
    // paper's scheme, not the default one, to take the state.
    let (mut b, _) = instance();
    with_paper(&mut b);
    let back =
        run(&mut b, Call::DeSerializeFmuState, |i| i.deserialize_fmu_state(&bytes, None)).unwrap();
    run(&mut b, Call::SetFmuState, |i| i.set_fmu_state(back)).unwrap();
    run(&mut b, Call::DoStep, |i| i.do_step(0.5, 0.5)).unwrap();
    assert_eq!(outputs(&mut b), want);
}

/// Guards against one instance taking another's FMU state (handles were per-instance
/// counters, so B's first state had the number of A's): refused, with the way to move a
/// state between instances in the message, and nothing changed.
#[test]
fn a_state_of_another_instance_is_refused_with_the_way_to_move_it() {
    let (mut a, _) = initialized(1.0);
    let (mut b, log) = initialized(1.0);
    let theirs = run(&mut a, Call::GetFmuState, |i| i.get_fmu_state(None)).unwrap();
    let ours = run(&mut b, Call::GetFmuState, |i| i.get_fmu_state(None)).unwrap();
    assert_ne!(theirs, ours, "handles are unique in the process");
    run(&mut b, Call::DoStep, |i| i.do_step(0.0, 1.0)).unwrap();
    let bytes = run(&mut b, Call::SerializeFmuState, |i| i.serialize_fmu_state(ours)).unwrap();
    let refusals: [Result<(), Status>; 5] = [
        run(&mut b, Call::SetFmuState, |i| i.set_fmu_state(theirs)),
        run(&mut b, Call::FreeFmuState, |i| i.free_fmu_state(theirs)),
        run(&mut b, Call::GetFmuState, |i| i.get_fmu_state(Some(theirs)).map(drop)),
        run(&mut b, Call::SerializeFmuState, |i| i.serialize_fmu_state(theirs).map(drop)),
        run(&mut b, Call::DeSerializeFmuState, |i| {
            i.deserialize_fmu_state(&bytes, Some(theirs)).map(drop)
        }),
    ];
    for r in refusals {
        assert_eq!(r, Err(Status::Error));
        let msg = log.last_error();
        assert!(
            msg.contains(&format!("FMU state {theirs:#x} is unknown to this instance")),
            "{msg}"
        );
        assert!(
            msg.contains("move it with fmi2SerializeFMUstate and fmi2DeSerializeFMUstate"),
            "{msg}"
        );
    }
    assert_eq!(b.last_successful_time(), 1.0, "B's time is untouched");
    run(&mut b, Call::SetFmuState, |i| i.set_fmu_state(ours)).unwrap();
    assert_eq!(b.last_successful_time(), 0.0, "B's own state is still B's");
    run(&mut a, Call::SetFmuState, |i| i.set_fmu_state(theirs)).unwrap();
}

/// Guards against the communication-point tolerance hiding a wrong point: off by twice the
/// tolerance (2e-6 h) it is refused, naming the instance's time and the master's point.
#[test]
fn a_point_off_by_more_than_the_tolerance_is_refused_with_both_values() {
    let (mut i, log) = initialized(1.0);
    run(&mut i, Call::DoStep, |i| i.do_step(0.0, 0.1)).unwrap();
    let off = 0.1 + 2e-6 * 0.1;
    assert_eq!(run(&mut i, Call::DoStep, |i| i.do_step(off, 0.1)), Err(Status::Error));
    let msg = log.last_error();
    assert!(
        msg.starts_with(&format!(
            "fmi2DoStep: Expected currentCommunicationPoint = 0.1 but was {off}"
        )),
        "{msg}"
    );
    assert_eq!(i.last_successful_time(), 0.1);
}

/// An FMI 3.0 instance's messages are in FMI 3.0's words: the directional derivative's
/// arguments as fmi3GetDirectionalDerivative names them, no FMI 2.0 name.
#[test]
fn fmi3_messages_use_fmi3_words() {
    use wound_opening::fmi::common::machine::Interface;
    use wound_opening::fmi::fmi3::names::FMI3;
    let log = Collect::default();
    let mut i = Instance::of_interface(
        Interface::CoSimulation,
        FMI3,
        WoundModel::fresh,
        "fmi3",
        Arc::new(log.clone()),
        false,
    );
    run(&mut i, Call::EnterInitializationMode, |i| i.enter_initialization_mode()).unwrap();
    run(&mut i, Call::ExitInitializationMode, |i| i.exit_initialization_mode()).unwrap();
    let (edge, lambda, velocity) =
        (Vr::EdgeStress as u32, Vr::Lambda as u32, Vr::EdgeVelocity as u32);
    let calls: [(&[u32], &[u32], f64, &str); 3] = [
        (
            &[velocity],
            &[lambda],
            1.0,
            "lambda (value reference 0) is a parameter but a knowns entry must be a Real input",
        ),
        (
            &[edge],
            &[edge],
            1.0,
            "edge_stress (value reference 3) is an input but an unknowns entry must be a Real output",
        ),
        (&[velocity], &[edge], f64::NAN, "seed = NaN is invalid: it must be finite"),
    ];
    for (unknowns, knowns, seed, want) in calls {
        assert!(
            run(&mut i, Call::GetDirectionalDerivative, |i| i.directional_derivative(
                unknowns,
                knowns,
                &[seed]
            ))
            .is_err()
        );
        let message = log.last_error();
        assert!(message.contains(want), "{message}");
        assert!(
            !message.contains("fmi2")
                && !message.contains("vKnown")
                && !message.contains("dvKnown"),
            "{message}"
        );
    }
}
