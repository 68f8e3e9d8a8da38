//! A refused Set call changes nothing: every value of the call is checked before any is
//! applied, in either order, FMI 2.0 and 3.0, co-simulation and Model Exchange (states set
//! with `fmi2SetReal` / `fmi3SetFloat64` among inputs, `fmi2SetContinuousStates`,
//! `fmi2SetTime`). What is compared after each refusal is everything the master can read:
//! the inputs, the states, their derivatives, the outputs.

mod common;

use common::fmi::*;
use std::ffi::CString;
use wound_opening::fmi::fmi2::exchange::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::fmi::fmi3::exchange::*;
use wound_opening::fmi::fmi3::functions::*;
use wound_opening::fmi::fmi3::types::*;
use wound_opening::fmi::fmi3::unsupported::{fmi3SetBoolean, fmi3SetString};
use wound_opening::models::wound::variables::{MODEL_EXCHANGE_STATES as NX, Vr};

const EDGE: u32 = Vr::EdgeStress as u32;
/// The first continuous state (value references after the table's first rows).
const STATE: u32 = Vr::StressScale as u32 + 1;
const OUTPUTS: [u32; 3] = [Vr::EdgeStress as u32, Vr::WoundRadius as u32, Vr::EdgeVelocity as u32];

/// An FMI 2.0 Model Exchange instance in Continuous-Time Mode at `t`, lambda 0.5, with the
/// edge stress changed after initialization and the states moved off 0.
fn me2(t: f64) -> fmi2Component {
    let c = continuous_time(&[(Vr::Lambda as u32, 0.5)]);
    unsafe {
        assert_eq!(fmi2SetTime(c, t), OK);
        assert_eq!(set_real(c, EDGE, 0.2), OK);
        let x: Vec<f64> = (0..NX).map(|k| 1e-3 / (k + 1) as f64).collect();
        assert_eq!(fmi2SetContinuousStates(c, x.as_ptr(), NX), OK);
    }
    c
}

/// What a master can read of an FMI 2.0 instance: outputs and input, states, derivatives.
fn seen2(c: fmi2Component) -> Vec<f64> {
    let mut v = vec![f64::NAN; OUTPUTS.len() + 2 * NX];
    unsafe {
        assert_eq!(fmi2GetReal(c, OUTPUTS.as_ptr(), OUTPUTS.len(), v.as_mut_ptr()), OK);
        assert_eq!(fmi2GetContinuousStates(c, v[3..].as_mut_ptr(), NX), OK);
        assert_eq!(fmi2GetDerivatives(c, v[3 + NX..].as_mut_ptr(), NX), OK);
    }
    v
}

fn same(a: &[f64], b: &[f64], what: &str) {
    let differ: Vec<usize> = (0..a.len()).filter(|&i| a[i].to_bits() != b[i].to_bits()).collect();
    assert!(differ.is_empty(), "{what}: values changed at {differ:?}");
}

#[test]
fn fmi2_set_real_of_an_input_and_a_bad_state_sets_neither_in_either_order() {
    let c = me2(0.7);
    let before = seen2(c);
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for (vrs, xs) in [([EDGE, STATE], [0.3, bad]), ([STATE, EDGE], [bad, 0.3])] {
            assert_eq!(
                unsafe { fmi2SetReal(c, vrs.as_ptr(), 2, xs.as_ptr()) },
                ERROR,
                "{vrs:?} = {xs:?}"
            );
            same(&before, &seen2(c), &format!("after the refused fmi2SetReal({vrs:?}, {xs:?})"));
        }
    }
    // An input with a fixed parameter, an input out of range with a state: the same.
    for (vrs, xs) in [
        ([EDGE, Vr::Lambda as u32], [0.3, 2.0]),
        ([Vr::Lambda as u32, EDGE], [2.0, 0.3]),
        ([STATE, EDGE], [0.5, 1e300]),
        ([EDGE, STATE], [f64::NAN, 0.5]),
    ] {
        assert_eq!(
            unsafe { fmi2SetReal(c, vrs.as_ptr(), 2, xs.as_ptr()) },
            ERROR,
            "{vrs:?} = {xs:?}"
        );
        same(&before, &seen2(c), &format!("after the refused fmi2SetReal({vrs:?}, {xs:?})"));
    }
    // The values refused above are accepted on their own: it is the call that was refused.
    assert_eq!(unsafe { fmi2SetReal(c, [EDGE, STATE].as_ptr(), 2, [0.3, 0.5].as_ptr()) }, OK);
    let after = seen2(c);
    assert_eq!((after[0], after[3]), (0.3, 0.5));
    unsafe { fmi2FreeInstance(c) };
}

#[test]
fn fmi2_refused_states_and_times_change_nothing() {
    let c = me2(0.7);
    let before = seen2(c);
    let mut x = before[3..3 + NX].to_vec();
    x[NX - 1] = f64::NAN;
    assert_eq!(unsafe { fmi2SetContinuousStates(c, x.as_ptr(), NX) }, ERROR);
    same(&before, &seen2(c), "after a refused fmi2SetContinuousStates");
    for t in [f64::NAN, -1.0, f64::INFINITY] {
        assert_eq!(unsafe { fmi2SetTime(c, t) }, ERROR, "fmi2SetTime({t})");
        same(&before, &seen2(c), &format!("after the refused fmi2SetTime({t})"));
    }
    // Integers, Booleans and Strings: a refused call leaves the Reals as they were.
    let (vrs, is) = ([Vr::Method as u32, Vr::GridPoints as u32], [0, 7]);
    assert_eq!(
        unsafe { fmi2SetInteger(c, vrs.as_ptr(), 2, is.as_ptr()) },
        ERROR,
        "fixed after initialization"
    );
    let b = [1];
    assert_eq!(unsafe { fmi2SetBoolean(c, &EDGE, 1, b.as_ptr()) }, ERROR);
    let s = [c"1".as_ptr()];
    assert_eq!(unsafe { fmi2SetString(c, &EDGE, 1, s.as_ptr()) }, ERROR);
    same(&before, &seen2(c), "after refused Integer, Boolean and String sets");
    unsafe { fmi2FreeInstance(c) };
}

/// A time beyond the time scale's range is refused with that range, not as a state.
#[test]
fn fmi2_set_time_beyond_the_time_scale_is_refused_with_the_range() {
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
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(set_real(c, Vr::TimeScale as u32, 1e-12), OK);
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
        let mut info = std::mem::zeroed();
        assert_eq!(fmi2NewDiscreteStates(c, &mut info), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(c), OK);
        assert_eq!(fmi2SetTime(c, 1.0), OK);
        let before = seen2(c);
        assert_eq!(fmi2SetTime(c, 1e300), ERROR);
        same(&before, &seen2(c), "after the refused fmi2SetTime(1e300)");
        fmi2FreeInstance(c);
    }
    let mut model = wound_opening::models::wound::WoundModel::fresh();
    model.set(Vr::TimeScale as u32, 1e-12);
    model.prepare().unwrap();
    model.enter_model_exchange();
    let why = model.step(0.0, 1e300).unwrap_err();
    assert!(
        why.contains("a step of 1e300 s is beyond the range of the time scale T = 1e-12 s"),
        "{why}"
    );
    let why = model.set_time(1e300).unwrap_err();
    assert!(
        why.contains("beyond the range of the time scale T = 1e-12 s")
            && why.contains("1.798e296 s"),
        "{why}"
    );
}

#[test]
fn co_simulation_refused_sets_change_nothing() {
    let c = initialized(WOUND, 0.0, &[]);
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 0.5, 1) }, OK);
    assert_eq!(set_real(c, EDGE, 0.2), OK);
    let read = |c| {
        let mut v = [f64::NAN; 3];
        assert_eq!(unsafe { fmi2GetReal(c, OUTPUTS.as_ptr(), 3, v.as_mut_ptr()) }, OK);
        v
    };
    let before = read(c);
    for (vrs, xs) in [
        ([EDGE, Vr::Sigma as u32], [0.3, 2.0]),
        ([EDGE, EDGE], [0.3, f64::NAN]),
        ([EDGE, STATE], [0.3, 1.0]),
    ] {
        assert_eq!(
            unsafe { fmi2SetReal(c, vrs.as_ptr(), 2, xs.as_ptr()) },
            ERROR,
            "{vrs:?} = {xs:?}"
        );
        same(&before, &read(c), &format!("after the refused fmi2SetReal({vrs:?}, {xs:?})"));
    }
    unsafe { fmi2FreeInstance(c) };
}

/// An FMI 3.0 Model Exchange instance as [`me2`].
fn me3() -> fmi3Instance {
    let (name, token) = (CString::new("me3").unwrap(), CString::new(WOUND).unwrap());
    let i = unsafe {
        fmi3InstantiateModelExchange(
            name.as_ptr(),
            token.as_ptr(),
            std::ptr::null(),
            0,
            0,
            std::ptr::null_mut(),
            None,
        )
    };
    assert!(!i.is_null());
    unsafe {
        assert_eq!(fmi3SetFloat64(i, &(Vr::Lambda as u32), 1, &0.5, 1), OK);
        assert_eq!(fmi3EnterInitializationMode(i, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi3ExitInitializationMode(i), OK);
        let (mut a, mut b, mut c, mut d, mut e, mut t) = (9u8, 9u8, 9u8, 9u8, 9u8, f64::NAN);
        assert_eq!(fmi3UpdateDiscreteStates(i, &mut a, &mut b, &mut c, &mut d, &mut e, &mut t), OK);
        assert_eq!(fmi3EnterContinuousTimeMode(i), OK);
        assert_eq!(fmi3SetTime(i, 0.7), OK);
        assert_eq!(fmi3SetFloat64(i, &EDGE, 1, &0.2, 1), OK);
        let x: Vec<f64> = (0..NX).map(|k| 1e-3 / (k + 1) as f64).collect();
        assert_eq!(fmi3SetContinuousStates(i, x.as_ptr(), NX), OK);
    }
    i
}

fn seen3(i: fmi3Instance) -> Vec<f64> {
    let mut v = vec![f64::NAN; OUTPUTS.len() + 2 * NX];
    unsafe {
        assert_eq!(fmi3GetFloat64(i, OUTPUTS.as_ptr(), 3, v.as_mut_ptr(), 3), OK);
        assert_eq!(fmi3GetContinuousStates(i, v[3..].as_mut_ptr(), NX), OK);
        assert_eq!(fmi3GetContinuousStateDerivatives(i, v[3 + NX..].as_mut_ptr(), NX), OK);
    }
    v
}

#[test]
fn fmi3_set_float64_of_an_input_and_a_bad_state_sets_neither_in_either_order() {
    let i = me3();
    let before = seen3(i);
    for bad in [f64::NAN, f64::INFINITY] {
        for (vrs, xs) in [([EDGE, STATE], [0.3, bad]), ([STATE, EDGE], [bad, 0.3])] {
            assert_eq!(
                unsafe { fmi3SetFloat64(i, vrs.as_ptr(), 2, xs.as_ptr(), 2) },
                ERROR,
                "{vrs:?} = {xs:?}"
            );
            same(&before, &seen3(i), &format!("after the refused fmi3SetFloat64({vrs:?}, {xs:?})"));
        }
    }
    for (vrs, xs) in [([EDGE, Vr::Lambda as u32], [0.3, 2.0]), ([STATE, EDGE], [0.5, 1e300])] {
        assert_eq!(
            unsafe { fmi3SetFloat64(i, vrs.as_ptr(), 2, xs.as_ptr(), 2) },
            ERROR,
            "{vrs:?} = {xs:?}"
        );
        same(&before, &seen3(i), &format!("after the refused fmi3SetFloat64({vrs:?}, {xs:?})"));
    }
    let mut x = before[3..3 + NX].to_vec();
    x[0] = f64::NAN;
    assert_eq!(unsafe { fmi3SetContinuousStates(i, x.as_ptr(), NX) }, ERROR);
    assert_eq!(unsafe { fmi3SetTime(i, f64::NAN) }, ERROR);
    let is = [0i32, 7];
    assert_eq!(
        unsafe {
            fmi3SetInt32(i, [Vr::Method as u32, Vr::GridPoints as u32].as_ptr(), 2, is.as_ptr(), 2)
        },
        ERROR
    );
    assert_eq!(unsafe { fmi3SetBoolean(i, &EDGE, 1, [true as u8].as_ptr() as _, 1) }, ERROR);
    assert_eq!(unsafe { fmi3SetString(i, &EDGE, 1, [c"1".as_ptr()].as_ptr(), 1) }, ERROR);
    same(&before, &seen3(i), "after refused states, time, Int32, Boolean and String sets");
    assert_eq!(unsafe { fmi3SetFloat64(i, [STATE, EDGE].as_ptr(), 2, [0.5, 0.3].as_ptr(), 2) }, OK);
    let after = seen3(i);
    assert_eq!((after[0], after[3]), (0.3, 0.5));
    unsafe { fmi3FreeInstance(i) };
}
