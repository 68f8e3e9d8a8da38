//! The direct C API's boundary from Rust, through the exported `wo_*` functions: the
//! thread-local last error and the handle tables (the panic boundary, which needs a hook
//! into a solver's lock, is tested inside the crate: src/capi/panic_tests.rs). (tests/c/direct_api.c covers the
//! numbers and the bad input from C; tests/fuzz_capi.rs random call sequences.)

use std::ffi::CStr;
use wound_opening::capi::error::{Failure, WoStatus, run};
use wound_opening::capi::solver::live_handles;
use wound_opening::capi::solver_c::*;

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
fn the_last_error_belongs_to_the_calling_thread_and_a_success_clears_it() {
    let status = run("wo_here", || Err(Failure::invalid("something specific")));
    assert_eq!(status, WoStatus::WoInvalidArgument);
    assert_eq!(last_error(), "wo_here: something specific");
    let elsewhere = std::thread::spawn(|| {
        let before = last_error();
        let status = run("wo_there", || Err(Failure::null("thing")));
        (before, status, last_error())
    })
    .join()
    .unwrap();
    assert_eq!(
        elsewhere,
        (
            String::new(),
            WoStatus::WoNullPointer,
            "wo_there: thing is NULL (expected a valid pointer)".into()
        )
    );
    assert_eq!(last_error(), "wo_here: something specific", "another thread's error is not ours");
    assert_eq!(run("wo_fine", || Ok(())), WoStatus::WoOk);
    assert_eq!(last_error(), "");
}

#[test]
fn handles_are_never_reused_and_freed_ones_stay_unknown() {
    let a = new_solver();
    unsafe { assert_eq!(wo_solver_free(a), WoStatus::WoOk) };
    let b = new_solver();
    assert_ne!(a, b, "a freed handle is not handed out again");
    assert_eq!(radius(a).unwrap_err().0, WoStatus::WoUnknownHandle);
    assert!(radius(b).is_ok());
    let (solvers, _) = live_handles();
    assert!(solvers >= 1);
    unsafe { assert_eq!(wo_solver_free(b), WoStatus::WoOk) };
}

#[test]
fn status_names_match_the_enum() {
    let all = [
        WoStatus::WoOk,
        WoStatus::WoNullPointer,
        WoStatus::WoInvalidArgument,
        WoStatus::WoUnknownHandle,
        WoStatus::WoIncompatibleState,
        WoStatus::WoSolverFailed,
        WoStatus::WoInternalError,
        WoStatus::WoUndefined,
    ];
    for (i, s) in all.iter().enumerate() {
        assert_eq!(*s as i32, i as i32);
        let name = unsafe { CStr::from_ptr(wo_status_name(i as i32)) }.to_str().unwrap();
        let rust = format!("{s:?}");
        // WoInvalidArgument <-> WO_INVALID_ARGUMENT
        let screaming: String = rust
            .chars()
            .enumerate()
            .flat_map(|(j, c)| {
                if c.is_uppercase() && j > 0 { vec!['_', c] } else { vec![c.to_ascii_uppercase()] }
            })
            .collect();
        assert_eq!(name, screaming);
    }
}

/// At lambda = 0 the edge velocity at the cut is infinite in the model (it decays like
/// t^(-1/2)): refused with WO_UNDEFINED and nothing written, not a finite mesh value with
/// WO_OK. After the first advance it is finite and returned.
#[test]
fn an_infinite_velocity_is_refused_not_returned() {
    let mut s = std::ptr::null_mut();
    assert_eq!(unsafe { wo_solver_new(0.0, 1.0, 10.0, 1e-8, &mut s) }, WoStatus::WoOk);
    let mut v = -7.0;
    assert_eq!(unsafe { wo_solver_edge_velocity(s, &mut v) }, WoStatus::WoUndefined);
    assert!(last_error().contains("infinite at lambda = 0"), "{}", last_error());
    assert_eq!(v, -7.0, "nothing written");
    let (radii, mut out) = ([1.0, 2.0], [0.0; 2]);
    assert_eq!(
        unsafe { wo_solver_velocity(s, radii.as_ptr(), out.as_mut_ptr(), 2) },
        WoStatus::WoUndefined
    );
    assert_eq!(unsafe { wo_solver_advance(s, 0.01, 0.0) }, WoStatus::WoOk);
    assert_eq!(unsafe { wo_solver_edge_velocity(s, &mut v) }, WoStatus::WoOk);
    // The exact value at t = 0.01 (tests/solver_exact.rs LAPLACE_REFERENCE); at tolerance
    // 1e-8 (a radius contract) the velocity there measures 4.1e-8 relative: asserted at 1e-7.
    assert!((v - 1.4007729175076447).abs() < 1e-7 * 1.4, "{v}");
    assert_eq!(unsafe { wo_solver_free(s) }, WoStatus::WoOk);
}
