//! Helpers for the tests that drive the exported FMI functions from Rust, as a C master
//! would. Rust cannot define the variadic C logger, so these
//! instances have no logger: what is logged is checked through the safe API
//! (`tests/fmi_instance.rs`) and from C (`tests/c`).
#![allow(dead_code)]

use std::ffi::CString;
use wound_opening::fmi::fmi2::exchange::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;

pub const OK: fmi2Status = 0;
pub const WARNING: fmi2Status = 1;
pub const DISCARD: fmi2Status = 2;
pub const ERROR: fmi2Status = 3;

pub const WOUND: &str = wound_opening::models::wound::variables::GUID;
pub const PURSE: &str = wound_opening::models::purse_string::variables::GUID;

/// A new instance of the model with this GUID (asserted non-NULL).
pub fn instantiate(guid: &str, name: &str) -> fmi2Component {
    let (name, guid) = (CString::new(name).unwrap(), CString::new(guid).unwrap());
    let callbacks = fmi2CallbackFunctions::NONE;
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            FMI2_CO_SIMULATION,
            guid.as_ptr(),
            c"".as_ptr(),
            &callbacks,
            0,
            0,
        )
    };
    assert!(!c.is_null(), "fmi2Instantiate({name:?})");
    c
}

/// An instance set up at `start` (no stop time), its Real parameters `params` set, initialized.
pub fn initialized(guid: &str, start: f64, params: &[(u32, f64)]) -> fmi2Component {
    let c = instantiate(guid, "test");
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, start, 0, 0.0), OK, "fmi2SetupExperiment");
        for &(vr, x) in params {
            assert_eq!(fmi2SetReal(c, &vr, 1, &x), OK, "fmi2SetReal({vr}, {x})");
        }
        assert_eq!(fmi2EnterInitializationMode(c), OK, "fmi2EnterInitializationMode");
        assert_eq!(fmi2ExitInitializationMode(c), OK, "fmi2ExitInitializationMode");
    }
    c
}

/// A Model Exchange instance of WoundOpening in Continuous-Time Mode at t = 0, its Real
/// parameters `params` set.
pub fn continuous_time(params: &[(u32, f64)]) -> fmi2Component {
    let (name, guid) = (CString::new("me").unwrap(), CString::new(WOUND).unwrap());
    let callbacks = fmi2CallbackFunctions::NONE;
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            FMI2_MODEL_EXCHANGE,
            guid.as_ptr(),
            c"".as_ptr(),
            &callbacks,
            0,
            0,
        )
    };
    assert!(!c.is_null());
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), OK);
        for &(vr, x) in params {
            assert_eq!(fmi2SetReal(c, &vr, 1, &x), OK, "fmi2SetReal({vr}, {x})");
        }
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
        let mut info: fmi2EventInfo = std::mem::zeroed();
        assert_eq!(fmi2NewDiscreteStates(c, &mut info), OK);
        assert_eq!(
            (info.valuesOfContinuousStatesChanged, info.nominalsOfContinuousStatesChanged),
            (0, 0),
            "no event at the start"
        );
        assert_eq!(fmi2EnterContinuousTimeMode(c), OK);
    }
    c
}

/// `fmi2GetReal` of one variable: (status, value).
pub fn get_real(c: fmi2Component, vr: u32) -> (fmi2Status, f64) {
    let mut x = f64::NAN;
    let s = unsafe { fmi2GetReal(c, &vr, 1, &mut x) };
    (s, x)
}

/// `fmi2SetReal` of one variable.
pub fn set_real(c: fmi2Component, vr: u32, x: f64) -> fmi2Status {
    unsafe { fmi2SetReal(c, &vr, 1, &x) }
}

/// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`: (status, time).
pub fn last_successful_time(c: fmi2Component) -> (fmi2Status, f64) {
    let mut t = f64::NAN;
    let s = unsafe { fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut t) };
    (s, t)
}

/// `fmi2GetFMUstate` into a new state: (status, handle).
pub fn get_state(c: fmi2Component) -> (fmi2Status, fmi2FMUstate) {
    let mut st: fmi2FMUstate = std::ptr::null_mut();
    let s = unsafe { fmi2GetFMUstate(c, &mut st) };
    (s, st)
}

/// Every FMI function that takes a component, called on `c` with valid other arguments:
/// the statuses, by function name.
pub fn every_call(c: fmi2Component) -> Vec<(&'static str, fmi2Status)> {
    let vr = [0u32];
    let (mut r, mut i, mut b, mut st) = ([0.0f64], [0i32], [0i32], 0i32);
    let mut s: [fmi2String; 1] = [c"x".as_ptr()];
    let mut state: fmi2FMUstate = std::ptr::null_mut();
    let (mut size, mut byte) = (0usize, [0 as fmi2Byte; 64]);
    let cats = [c"logCalls".as_ptr()];
    unsafe {
        vec![
            ("fmi2SetDebugLogging", fmi2SetDebugLogging(c, 1, 1, cats.as_ptr())),
            ("fmi2SetupExperiment", fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0)),
            ("fmi2EnterInitializationMode", fmi2EnterInitializationMode(c)),
            ("fmi2ExitInitializationMode", fmi2ExitInitializationMode(c)),
            ("fmi2GetReal", fmi2GetReal(c, vr.as_ptr(), 1, r.as_mut_ptr())),
            ("fmi2SetReal", fmi2SetReal(c, vr.as_ptr(), 1, r.as_ptr())),
            ("fmi2GetInteger", fmi2GetInteger(c, vr.as_ptr(), 1, i.as_mut_ptr())),
            ("fmi2SetInteger", fmi2SetInteger(c, vr.as_ptr(), 1, i.as_ptr())),
            ("fmi2GetBoolean", fmi2GetBoolean(c, vr.as_ptr(), 1, b.as_mut_ptr())),
            ("fmi2SetBoolean", fmi2SetBoolean(c, vr.as_ptr(), 1, b.as_ptr())),
            ("fmi2GetString", fmi2GetString(c, vr.as_ptr(), 1, s.as_mut_ptr())),
            ("fmi2SetString", fmi2SetString(c, vr.as_ptr(), 1, s.as_ptr())),
            ("fmi2GetFMUstate", fmi2GetFMUstate(c, &mut state)),
            ("fmi2SetFMUstate", fmi2SetFMUstate(c, 1 as fmi2FMUstate)),
            (
                "fmi2SerializedFMUstateSize",
                fmi2SerializedFMUstateSize(c, 1 as fmi2FMUstate, &mut size),
            ),
            (
                "fmi2SerializeFMUstate",
                fmi2SerializeFMUstate(c, 1 as fmi2FMUstate, byte.as_mut_ptr(), 64),
            ),
            ("fmi2DeSerializeFMUstate", fmi2DeSerializeFMUstate(c, byte.as_ptr(), 64, &mut state)),
            ("fmi2FreeFMUstate", fmi2FreeFMUstate(c, &mut (1 as fmi2FMUstate))),
            (
                "fmi2GetDirectionalDerivative",
                fmi2GetDirectionalDerivative(
                    c,
                    vr.as_ptr(),
                    1,
                    vr.as_ptr(),
                    1,
                    r.as_ptr(),
                    r.as_mut_ptr(),
                ),
            ),
            (
                "fmi2SetRealInputDerivatives",
                fmi2SetRealInputDerivatives(c, vr.as_ptr(), 1, i.as_ptr(), r.as_ptr()),
            ),
            (
                "fmi2GetRealOutputDerivatives",
                fmi2GetRealOutputDerivatives(c, vr.as_ptr(), 1, i.as_ptr(), r.as_mut_ptr()),
            ),
            ("fmi2DoStep", fmi2DoStep(c, 0.0, 0.1, 0)),
            ("fmi2CancelStep", fmi2CancelStep(c)),
            ("fmi2GetStatus", fmi2GetStatus(c, FMI2_TERMINATED, &mut st)),
            ("fmi2GetRealStatus", fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, r.as_mut_ptr())),
            ("fmi2GetIntegerStatus", fmi2GetIntegerStatus(c, FMI2_TERMINATED, i.as_mut_ptr())),
            ("fmi2GetBooleanStatus", fmi2GetBooleanStatus(c, FMI2_TERMINATED, b.as_mut_ptr())),
            ("fmi2GetStringStatus", fmi2GetStringStatus(c, FMI2_TERMINATED, s.as_mut_ptr())),
            ("fmi2EnterEventMode", fmi2EnterEventMode(c)),
            ("fmi2NewDiscreteStates", fmi2NewDiscreteStates(c, &mut std::mem::zeroed())),
            ("fmi2EnterContinuousTimeMode", fmi2EnterContinuousTimeMode(c)),
            ("fmi2CompletedIntegratorStep", fmi2CompletedIntegratorStep(c, 1, &mut b[0], &mut st)),
            ("fmi2SetTime", fmi2SetTime(c, 0.0)),
            ("fmi2SetContinuousStates", fmi2SetContinuousStates(c, r.as_ptr(), 1)),
            ("fmi2GetDerivatives", fmi2GetDerivatives(c, r.as_mut_ptr(), 1)),
            ("fmi2GetEventIndicators", fmi2GetEventIndicators(c, r.as_mut_ptr(), 1)),
            ("fmi2GetContinuousStates", fmi2GetContinuousStates(c, r.as_mut_ptr(), 1)),
            (
                "fmi2GetNominalsOfContinuousStates",
                fmi2GetNominalsOfContinuousStates(c, r.as_mut_ptr(), 1),
            ),
            ("fmi2Terminate", fmi2Terminate(c)),
            ("fmi2Reset", fmi2Reset(c)),
        ]
    }
}
