//! The panic boundary of the direct C API, through the exported `wo_*` functions: a solver
//! whose call panicked refuses use until a state is restored, and can still be freed. The
//! panic is raised by a hook that runs inside a solver's lock ([`super::solver::with_solver_for_tests`]),
//! which exists only in test builds.

use super::error::{WoStatus, run};
use super::solver;
use super::solver_c::*;
use crate::boundary::caught_panics;
use std::ffi::CStr;

fn last_error() -> String {
    unsafe { CStr::from_ptr(wo_last_error()) }.to_string_lossy().into_owned()
}

fn new_solver() -> *mut WoSolver {
    let mut s = std::ptr::null_mut();
    assert_eq!(
        unsafe { wo_solver_new(1.0, 1.0, 10.0, 1e-8, &mut s) },
        WoStatus::WoOk,
        "{}",
        last_error()
    );
    s
}

fn radius(s: *mut WoSolver) -> Result<f64, (WoStatus, String)> {
    let mut r = f64::NAN;
    match unsafe { wo_solver_wound_radius(s, &mut r) } {
        WoStatus::WoOk => Ok(r),
        e => Err((e, last_error())),
    }
}

#[test]
fn a_panic_inside_a_call_is_an_internal_error_and_the_solver_waits_for_a_restore() {
    let s = new_solver();
    let mut saved = std::ptr::null_mut();
    unsafe {
        assert_eq!(wo_solver_advance(s, 1.0, 0.0), WoStatus::WoOk);
        assert_eq!(wo_solver_save_state(s, &mut saved), WoStatus::WoOk);
    }
    let r1 = radius(s).unwrap();
    let panics = caught_panics();

    // A panic while the solver is locked: what a bug in the solver would do.
    let status = run("wo_test", || {
        solver::with_solver_for_tests(s as usize as u64, || panic!("deliberate test panic"))
    });
    assert_eq!(status, WoStatus::WoInternalError);
    let msg = last_error();
    assert!(msg.starts_with("wo_test: internal error (caught panic: "), "{msg}");
    assert!(msg.contains("deliberate test panic"), "{msg}");
    assert!(caught_panics() > panics, "the panic was counted");

    // Its data may be half-updated: every use is refused, saying what to do.
    let (status, msg) = radius(s).unwrap_err();
    assert_eq!(status, WoStatus::WoInternalError);
    assert!(
        msg.contains(
            "is unusable after an internal error in an earlier call: restore a saved state"
        ),
        "{msg}"
    );
    let mut again = std::ptr::null_mut();
    assert_eq!(unsafe { wo_solver_save_state(s, &mut again) }, WoStatus::WoInternalError);
    assert_eq!(unsafe { wo_solver_advance(s, 2.0, 0.0) }, WoStatus::WoInternalError);

    // Restoring a state brings it back, exactly where the state was.
    unsafe {
        assert_eq!(wo_solver_restore_state(s, saved), WoStatus::WoOk, "{}", last_error());
        assert_eq!(radius(s), Ok(r1));
        assert_eq!(wo_solver_advance(s, 2.0, 0.0), WoStatus::WoOk);
        assert_eq!(wo_state_free(saved), WoStatus::WoOk);
        assert_eq!(wo_solver_free(s), WoStatus::WoOk);
    }
}

#[test]
fn a_solver_that_panicked_can_still_be_freed() {
    let s = new_solver();
    let status = run("wo_test", || {
        solver::with_solver_for_tests(s as usize as u64, || panic!("deliberate test panic"))
    });
    assert_eq!(status, WoStatus::WoInternalError);
    assert_eq!(unsafe { wo_solver_free(s) }, WoStatus::WoOk);
    assert_eq!(radius(s).unwrap_err().0, WoStatus::WoUnknownHandle);
}
