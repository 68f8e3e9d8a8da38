//! The FMI 3.0 functions (src/fmi/fmi3/) through their C signatures: instantiation
//! checks, co-simulation and Model Exchange on the same instances and models as FMI 2.0
//! (bit-identical results), `nValues` checks, FMU states that move between the FMI 2.0 and
//! 3.0 interfaces, and every function on NULL, made-up and freed instances (an error, never
//! a crash: the handle table of fmi/frame.rs). fmpy runs the archives: tests/python/test_fmi3.py.

mod common;

use common::fmi::{ERROR, OK, PURSE, WOUND};
use std::ffi::CString;
use wound_opening::boundary::caught_panics;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::fmi2Component;
use wound_opening::fmi::fmi3::exchange::*;
use wound_opening::fmi::fmi3::functions::*;
use wound_opening::fmi::fmi3::types::*;
use wound_opening::fmi::fmi3::unsupported::*;
use wound_opening::models::wound::variables::{MODEL_EXCHANGE_STATES, Vr};

fn cs(token: &str, event_mode: u8) -> fmi3Instance {
    let (name, token) = (CString::new("cs3").unwrap(), CString::new(token).unwrap());
    unsafe {
        fmi3InstantiateCoSimulation(
            name.as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            0,
            0,
            event_mode,
            0,
            std::ptr::null(),
            0,
            std::ptr::null_mut(),
            None,
            None,
        )
    }
}

fn me(token: &str) -> fmi3Instance {
    let (name, token) = (CString::new("me3").unwrap(), CString::new(token).unwrap());
    unsafe {
        fmi3InstantiateModelExchange(
            name.as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            0,
            0,
            std::ptr::null_mut(),
            None,
        )
    }
}

fn get(i: fmi3Instance, vr: u32) -> (fmi3Status, f64) {
    let mut x = f64::NAN;
    (unsafe { fmi3GetFloat64(i, &vr, 1, &mut x, 1) }, x)
}

#[test]
fn instantiation_checks_the_token_and_refuses_event_mode() {
    assert!(cs("{not-a-token}", 0).is_null());
    assert!(cs(WOUND, 1).is_null(), "eventModeUsed without hasEventMode");
    let token = CString::new(WOUND).unwrap();
    let vr = 0u32;
    let null = unsafe {
        fmi3InstantiateCoSimulation(
            c"x".as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            0,
            0,
            0,
            0,
            &vr,
            1,
            std::ptr::null_mut(),
            None,
            None,
        )
    };
    assert!(null.is_null(), "required intermediate variables");
    let se = unsafe {
        fmi3InstantiateScheduledExecution(
            c"x".as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            0,
            0,
            std::ptr::null_mut(),
            None,
            None,
            None,
            None,
        )
    };
    assert!(se.is_null());
    let (a, b) = (cs(WOUND, 0), me(PURSE));
    assert!(!a.is_null() && !b.is_null());
    unsafe {
        fmi3FreeInstance(a);
        fmi3FreeInstance(b);
    }
}

/// The same steps through FMI 2.0 and FMI 3.0 give the same bits; `nValues` must match.
#[test]
fn co_simulation_is_the_fmi2_co_simulation() {
    let i = cs(WOUND, 0);
    let c2 = common::fmi::initialized(WOUND, 0.0, &[(Vr::Lambda as u32, 0.3)]);
    unsafe {
        let (vr, lambda) = (Vr::Lambda as u32, 0.3);
        assert_eq!(fmi3SetFloat64(i, &vr, 1, &lambda, 1), OK);
        assert_eq!(fmi3SetFloat64(i, &vr, 1, &lambda, 2), ERROR, "nValues");
        assert_eq!(fmi3EnterInitializationMode(i, 0, 0.0, 0.0, 1, 10.0), OK);
        assert_eq!(fmi3ExitInitializationMode(i), OK);
        let (mut ev, mut term, mut early, mut last) = (9u8, 9u8, 9u8, f64::NAN);
        for n in 0..10 {
            let t = n as f64;
            assert_eq!(fmi3DoStep(i, t, 1.0, 0, &mut ev, &mut term, &mut early, &mut last), OK);
            assert_eq!(fmi2DoStep(c2, t, 1.0, 0), OK);
            assert_eq!((ev, early, last), (0, 0, t + 1.0));
            assert_eq!(term, (n == 9) as u8, "terminateSimulation at the stop time");
        }
        assert_eq!(
            fmi3DoStep(i, 10.0, 1.0, 0, &mut ev, &mut term, &mut early, &mut last),
            ERROR,
            "past stopTime"
        );
        assert_eq!(last, 10.0);
        assert_eq!(
            get(i, Vr::WoundRadius as u32),
            (OK, common::fmi::get_real(c2, Vr::WoundRadius as u32).1)
        );
        let mut method = -1;
        assert_eq!(fmi3GetInt32(i, &(Vr::Method as u32), 1, &mut method, 1), OK);
        assert_eq!(method, 0);
        let b = 0u8;
        assert_eq!(
            fmi3GetBoolean(i, std::ptr::null(), 0, std::ptr::null_mut(), 0),
            OK,
            "no variables named"
        );
        assert_eq!(fmi3SetBoolean(i, &vr, 1, &b, 1), ERROR, "no Boolean variables");
        assert_eq!(fmi3EnterStepMode(i), ERROR);
        assert_eq!(fmi3EnterConfigurationMode(i), ERROR);
        // An FMU state serialized by the FMI 2.0 instance restores into the FMI 3.0 one.
        let mut st: *mut std::ffi::c_void = std::ptr::null_mut();
        assert_eq!(fmi2GetFMUstate(c2, &mut st), OK);
        let mut size = 0usize;
        assert_eq!(fmi2SerializedFMUstateSize(c2, st, &mut size), OK);
        let mut bytes = vec![0i8; size];
        assert_eq!(fmi2SerializeFMUstate(c2, st, bytes.as_mut_ptr(), size), OK);
        let mut into: fmi3FMUState = std::ptr::null_mut();
        assert_eq!(fmi3DeserializeFMUState(i, bytes.as_ptr() as *const u8, size, &mut into), OK);
        assert_eq!(fmi3SetFMUState(i, into), OK);
        assert_eq!(fmi3FreeFMUState(i, &mut into), OK);
        assert!(into.is_null());
        assert_eq!(fmi3Terminate(i), OK);
        fmi3FreeInstance(i);
        fmi2FreeInstance(c2);
    }
}

#[test]
fn model_exchange_declares_and_serves_the_states() {
    let i = me(WOUND);
    let nx = MODEL_EXCHANGE_STATES;
    unsafe {
        let mut n = 0usize;
        assert_eq!(fmi3GetNumberOfContinuousStates(i, &mut n), OK);
        assert_eq!(n, nx);
        assert_eq!(fmi3GetNumberOfEventIndicators(i, &mut n), OK);
        assert_eq!(n, 0);
        assert_eq!(fmi3EnterInitializationMode(i, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi3ExitInitializationMode(i), OK);
        let (mut a, mut b, mut c, mut d, mut e, mut t) = (9u8, 9u8, 9u8, 9u8, 9u8, f64::NAN);
        assert_eq!(fmi3UpdateDiscreteStates(i, &mut a, &mut b, &mut c, &mut d, &mut e, &mut t), OK);
        assert_eq!((a, b, c, d, e), (0, 0, 0, 0, 0));
        assert_eq!(fmi3EnterContinuousTimeMode(i), OK);
        let mut dx = vec![f64::NAN; nx];
        assert_eq!(fmi3GetContinuousStateDerivatives(i, dx.as_mut_ptr(), nx), OK);
        // The states depart from the closed-form response to the edge stress held from
        // the cut (src/models/wound/exchange.rs): none at the cut, none while it is held.
        assert!(dx.iter().all(|&v| v == 0.0));
        assert_eq!(fmi3SetTime(i, 0.5), OK);
        assert_eq!(fmi3SetContinuousStates(i, dx.as_ptr(), nx - 1), ERROR, "nx");
        let (mut enter, mut term) = (9u8, 9u8);
        assert_eq!(fmi3CompletedIntegratorStep(i, 1, &mut enter, &mut term), OK);
        assert_eq!((enter, term), (0, 0));
        let mut ev = 0u8;
        let mut last = 0.0;
        assert_eq!(
            fmi3DoStep(i, 0.0, 1.0, 0, &mut ev, &mut ev.clone(), &mut ev.clone(), &mut last),
            ERROR,
            "DoStep on ME"
        );
        fmi3FreeInstance(i);
    }
}

/// Every FMI 3.0 function that takes an instance, on NULL, made-up and freed instances:
/// fmi3Error (or nothing, for fmi3FreeInstance), no panic reaching the boundary.
#[test]
fn every_function_refuses_what_is_no_live_instance() {
    let freed = cs(WOUND, 0);
    unsafe { fmi3FreeInstance(freed) };
    let mut own = 0u64;
    let bogus: [fmi3Instance; 4] = [
        std::ptr::null_mut(),
        0xdead_beef as fmi3Instance,
        freed,
        &mut own as *mut u64 as fmi3Instance,
    ];
    let before = caught_panics();
    for i in bogus {
        for (name, status) in every_call3(i) {
            assert_eq!(status, ERROR, "{name} on {i:?}");
        }
        unsafe { fmi3FreeInstance(i) };
    }
    assert_eq!(caught_panics(), before);
    assert_eq!(own, 0, "nothing was written through the caller's memory");
}

fn every_call3(i: fmi2Component) -> Vec<(&'static str, fmi3Status)> {
    let vr = [0u32];
    let (mut r, mut n, mut b, mut u) = ([0.0f64; 1], [0i32; 1], [0u8; 6], 0usize);
    let mut st: fmi3FMUState = std::ptr::null_mut();
    let mut t = 0.0;
    unsafe {
        vec![
            ("fmi3SetDebugLogging", fmi3SetDebugLogging(i, 1, 0, std::ptr::null())),
            ("fmi3EnterInitializationMode", fmi3EnterInitializationMode(i, 0, 0.0, 0.0, 0, 0.0)),
            ("fmi3ExitInitializationMode", fmi3ExitInitializationMode(i)),
            ("fmi3EnterEventMode", fmi3EnterEventMode(i)),
            ("fmi3Terminate", fmi3Terminate(i)),
            ("fmi3Reset", fmi3Reset(i)),
            ("fmi3GetFloat64", fmi3GetFloat64(i, vr.as_ptr(), 1, r.as_mut_ptr(), 1)),
            ("fmi3SetFloat64", fmi3SetFloat64(i, vr.as_ptr(), 1, r.as_ptr(), 1)),
            ("fmi3GetInt32", fmi3GetInt32(i, vr.as_ptr(), 1, n.as_mut_ptr(), 1)),
            ("fmi3SetInt32", fmi3SetInt32(i, vr.as_ptr(), 1, n.as_ptr(), 1)),
            ("fmi3GetBoolean", fmi3GetBoolean(i, vr.as_ptr(), 1, b.as_mut_ptr(), 1)),
            ("fmi3GetFMUState", fmi3GetFMUState(i, &mut st)),
            ("fmi3SetFMUState", fmi3SetFMUState(i, 1 as fmi3FMUState)),
            ("fmi3FreeFMUState", fmi3FreeFMUState(i, &mut (1 as fmi3FMUState))),
            (
                "fmi3SerializedFMUStateSize",
                fmi3SerializedFMUStateSize(i, 1 as fmi3FMUState, &mut u),
            ),
            ("fmi3DeserializeFMUState", fmi3DeserializeFMUState(i, b.as_ptr(), 6, &mut st)),
            (
                "fmi3GetDirectionalDerivative",
                fmi3GetDirectionalDerivative(
                    i,
                    vr.as_ptr(),
                    1,
                    vr.as_ptr(),
                    1,
                    r.as_ptr(),
                    1,
                    r.as_mut_ptr(),
                    1,
                ),
            ),
            ("fmi3DoStep", fmi3DoStep(i, 0.0, 1.0, 0, &mut b[0], &mut b[1], &mut b[2], &mut t)),
            ("fmi3EnterContinuousTimeMode", fmi3EnterContinuousTimeMode(i)),
            ("fmi3SetTime", fmi3SetTime(i, 0.0)),
            ("fmi3SetContinuousStates", fmi3SetContinuousStates(i, r.as_ptr(), 1)),
            (
                "fmi3GetContinuousStateDerivatives",
                fmi3GetContinuousStateDerivatives(i, r.as_mut_ptr(), 1),
            ),
            ("fmi3GetContinuousStates", fmi3GetContinuousStates(i, r.as_mut_ptr(), 1)),
            (
                "fmi3GetNominalsOfContinuousStates",
                fmi3GetNominalsOfContinuousStates(i, r.as_mut_ptr(), 1),
            ),
            ("fmi3GetEventIndicators", fmi3GetEventIndicators(i, r.as_mut_ptr(), 1)),
            ("fmi3GetNumberOfContinuousStates", fmi3GetNumberOfContinuousStates(i, &mut u)),
            ("fmi3GetNumberOfEventIndicators", fmi3GetNumberOfEventIndicators(i, &mut u)),
            (
                "fmi3CompletedIntegratorStep",
                fmi3CompletedIntegratorStep(i, 1, &mut b[0], &mut b[1]),
            ),
            ("fmi3UpdateDiscreteStates", {
                let (x0, rest) = b.split_at_mut(1);
                let (x1, rest) = rest.split_at_mut(1);
                let (x2, rest) = rest.split_at_mut(1);
                let (x3, x4) = rest.split_at_mut(1);
                fmi3UpdateDiscreteStates(
                    i, &mut x0[0], &mut x1[0], &mut x2[0], &mut x3[0], &mut x4[0], &mut t,
                )
            }),
            ("fmi3EnterStepMode", fmi3EnterStepMode(i)),
            ("fmi3EnterConfigurationMode", fmi3EnterConfigurationMode(i)),
            (
                "fmi3GetOutputDerivatives",
                fmi3GetOutputDerivatives(i, vr.as_ptr(), 1, n.as_ptr(), r.as_mut_ptr(), 1),
            ),
            (
                "fmi3GetAdjointDerivative",
                fmi3GetAdjointDerivative(
                    i,
                    vr.as_ptr(),
                    1,
                    vr.as_ptr(),
                    1,
                    r.as_ptr(),
                    1,
                    r.as_mut_ptr(),
                    1,
                ),
            ),
            ("fmi3GetClock", fmi3GetClock(i, vr.as_ptr(), 1, b.as_mut_ptr())),
            (
                "fmi3GetIntervalDecimal",
                fmi3GetIntervalDecimal(i, vr.as_ptr(), 1, r.as_mut_ptr(), n.as_mut_ptr()),
            ),
            ("fmi3EvaluateDiscreteStates", fmi3EvaluateDiscreteStates(i)),
            ("fmi3ActivateModelPartition", fmi3ActivateModelPartition(i, 0, 0.0)),
        ]
    }
}

/// FMI 3.0 (section 2.3.2) lets fmi3Get* read start values before initialization (FMI 2.0
/// does not): parameters and inputs yes, outputs and states are refused (they have none).
#[test]
fn start_values_are_readable_before_initialization() {
    let i = cs(WOUND, 0);
    let c2 = common::fmi::instantiate(WOUND, "fmi2");
    assert_eq!(get(i, Vr::Lambda as u32), (OK, 1.0));
    assert_eq!(get(i, Vr::EdgeStress as u32), (OK, 0.0));
    assert_eq!(get(i, Vr::WoundRadius as u32).0, ERROR, "an output has no start value");
    assert_eq!(get(i, 13).0, ERROR, "nor a state");
    assert_eq!(
        common::fmi::get_real(c2, Vr::Lambda as u32).0,
        ERROR,
        "FMI 2.0: not in Instantiated"
    );
    unsafe {
        fmi3FreeInstance(i);
        fmi2FreeInstance(c2);
    }
}

mod intermediate {
    //! Intermediate Update Mode (FMI 3.0's replacement of input derivatives): the importer
    //! sets `edge_stress` at the end of the step from inside `intermediateUpdate`; the step
    //! is then the linear-in-time one, as `fmi2SetRealInputDerivatives` gives in FMI 2.0.
    use super::*;
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The instance the callback talks to, the ramp it follows, and what it saw.
    static INSTANCE: AtomicUsize = AtomicUsize::new(0);
    static SEEN: Mutex<Vec<(f64, fmi3Status, fmi3Status, fmi3Status)>> = Mutex::new(Vec::new());
    const P0: f64 = 0.5;
    const RATE: f64 = 0.25;

    unsafe extern "C" fn update(
        _: fmi3InstanceEnvironment,
        time: f64,
        set: u8,
        _: u8,
        _: u8,
        _: u8,
        _: *mut u8,
        _: *mut f64,
    ) {
        let i = INSTANCE.load(Ordering::SeqCst) as fmi3Instance;
        let (es, lambda) = (Vr::EdgeStress as u32, Vr::Lambda as u32);
        let p = P0 + RATE * time;
        let mut x = 0.0;
        let statuses = unsafe {
            (
                if set != 0 { fmi3SetFloat64(i, &es, 1, &p, 1) } else { ERROR },
                fmi3SetFloat64(i, &lambda, 1, &0.5, 1),
                fmi3GetFloat64(i, &es, 1, &mut x, 1),
            )
        };
        SEEN.lock().unwrap().push((time, statuses.0, statuses.1, statuses.2));
    }

    #[test]
    fn the_importer_sets_the_ramp_at_the_end_of_each_step() {
        let token = CString::new(WOUND).unwrap();
        let es = Vr::EdgeStress as u32;
        let i = unsafe {
            fmi3InstantiateCoSimulation(
                c"iu".as_ptr(),
                token.as_ptr(),
                std::ptr::null(),
                0,
                0,
                0,
                0,
                &es,
                1,
                std::ptr::null_mut(),
                None,
                Some(update),
            )
        };
        assert!(!i.is_null());
        INSTANCE.store(i as usize, Ordering::SeqCst);
        let lambda = Vr::Lambda as u32;
        let c2 = common::fmi::initialized(WOUND, 0.0, &[(lambda, 0.3)]);
        unsafe {
            assert_eq!(fmi3SetFloat64(i, &lambda, 1, &0.3, 1), OK);
            assert_eq!(fmi3SetFloat64(i, &es, 1, &P0, 1), OK);
            assert_eq!(fmi3EnterInitializationMode(i, 0, 0.0, 0.0, 0, 0.0), OK);
            assert_eq!(fmi3ExitInitializationMode(i), OK);
            // FMI 2.0 with the input derivative, for comparison.
            assert_eq!(common::fmi::set_real(c2, es, P0), OK);
            let one = 1;
            assert_eq!(fmi2SetRealInputDerivatives(c2, &es, 1, &one, &RATE), OK);
            let (mut a, mut b, mut e, mut last) = (0u8, 0u8, 0u8, 0.0);
            for n in 0..3 {
                let t = n as f64 * 0.5;
                assert_eq!(fmi3DoStep(i, t, 0.5, 0, &mut a, &mut b, &mut e, &mut last), OK);
                assert_eq!(fmi2DoStep(c2, t, 0.5, 0), OK);
                assert_eq!(last, t + 0.5);
            }
        }
        let seen = SEEN.lock().unwrap().clone();
        assert_eq!(seen.len(), 3);
        for (k, (time, set, other, get)) in seen.into_iter().enumerate() {
            assert_eq!(time, 0.5 * (k + 1) as f64, "asked at the end of the step");
            assert_eq!(
                (set, other, get),
                (OK, ERROR, ERROR),
                "only the required input may be set, nothing read"
            );
        }
        let (r3, r2) =
            (get(i, Vr::WoundRadius as u32).1, common::fmi::get_real(c2, Vr::WoundRadius as u32).1);
        assert!(
            (r3 - r2).abs() < 1e-14,
            "{r3} vs {r2}: the same ramp as fmi2SetRealInputDerivatives"
        );
        assert_eq!(get(i, es), (OK, P0 + RATE * 1.5));
        unsafe {
            fmi3FreeInstance(i);
            fmi2FreeInstance(c2);
        }
    }

    #[test]
    fn only_continuous_inputs_with_a_callback_can_be_intermediate() {
        let token = CString::new(WOUND).unwrap();
        let lambda = Vr::Lambda as u32;
        let refused = unsafe {
            fmi3InstantiateCoSimulation(
                c"x".as_ptr(),
                token.as_ptr(),
                std::ptr::null(),
                0,
                0,
                0,
                0,
                &lambda,
                1,
                std::ptr::null_mut(),
                None,
                Some(update),
            )
        };
        assert!(refused.is_null(), "a parameter is no intermediate variable");
        let es = Vr::EdgeStress as u32;
        let refused = unsafe {
            fmi3InstantiateCoSimulation(
                c"x".as_ptr(),
                token.as_ptr(),
                std::ptr::null(),
                0,
                0,
                0,
                0,
                &es,
                1,
                std::ptr::null_mut(),
                None,
                None,
            )
        };
        assert!(refused.is_null(), "no callback");
    }
}
