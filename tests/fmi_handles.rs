//! Instances and FMU states are handles, never addresses: what a master may pass that is
//! not (or no longer) a live instance of ours, or not this instance's state, is refused
//! with `fmi2Error`, and nothing is read through it.

mod common;

use common::fmi::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::Vr;

/// Guards against a use-after-free (a call on a freed instance read freed memory) and an
/// abort on a second `fmi2FreeInstance` of the same instance (a double free); also that
/// the freed handle is never given to a new instance, so a stale handle cannot reach it.
#[test]
fn calls_on_a_freed_instance_are_errors_and_a_second_free_is_ignored() {
    let a = initialized(WOUND, 0.0, &[]);
    unsafe { fmi2FreeInstance(a) };
    let b = initialized(WOUND, 0.0, &[]);
    assert_ne!(a, b, "a freed instance's handle is never reused");
    for (name, status) in every_call(a) {
        assert_eq!(status, ERROR, "{name} on a freed instance");
    }
    unsafe {
        fmi2FreeInstance(a);
        fmi2FreeInstance(a);
    }
    // The live instance was not touched by any of it.
    assert_eq!(last_successful_time(b), (OK, 0.0));
    assert_eq!(unsafe { fmi2DoStep(b, 0.0, 0.5, 0) }, OK);
    assert_eq!(last_successful_time(b), (OK, 0.5));
    unsafe { fmi2FreeInstance(b) };
}

/// Guards against dereferencing a component that `fmi2Instantiate` never returned: NULL,
/// a made-up number, the address of the caller's own memory, a direct-API solver handle.
#[test]
fn null_and_forged_components_are_errors() {
    let mut own = [0u64; 512];
    let mut solver = std::ptr::null_mut();
    let made =
        unsafe { wound_opening::capi::solver_c::wo_solver_new(1.0, 1.0, 10.0, 1e-6, &mut solver) };
    assert_eq!(made, wound_opening::capi::error::WoStatus::WoOk);
    let forged: [fmi2Component; 5] = [
        std::ptr::null_mut(),
        0xdead_beef as fmi2Component,
        own.as_mut_ptr() as fmi2Component,
        usize::MAX as fmi2Component,
        solver as fmi2Component,
    ];
    for c in forged {
        for (name, status) in every_call(c) {
            assert_eq!(status, ERROR, "{name} on component {c:p}");
        }
        unsafe { fmi2FreeInstance(c) };
    }
    assert!(own.iter().all(|&w| w == 0), "nothing was written through a forged component");
    unsafe { wound_opening::capi::solver_c::wo_solver_free(solver) };
}

/// Guards against per-instance state counters: instance B accepted A's first state handle
/// (its own handle had the same number) and silently restored or freed its own state.
/// FMU states of another instance, of a freed instance, of another model, and made-up
/// handles are refused, and B's own state is untouched by every refused call.
#[test]
fn fmu_states_of_another_instance_are_refused() {
    let a = initialized(WOUND, 0.0, &[]);
    let b = initialized(WOUND, 0.0, &[]);
    let (s, mut ours) = get_state(b);
    assert_eq!(s, OK);
    let (s, mut theirs) = get_state(a);
    assert_eq!(s, OK);
    assert_ne!(theirs, ours, "state handles are unique in the process");
    let gone = initialized(WOUND, 0.0, &[]);
    let (_, of_freed) = get_state(gone);
    unsafe { fmi2FreeInstance(gone) };
    let purse = initialized(PURSE, 0.0, &[]);
    let (_, of_purse) = get_state(purse);
    assert_eq!(unsafe { fmi2DoStep(b, 0.0, 1.0, 0) }, OK);
    let radius = get_real(b, Vr::WoundRadius as u32);

    for foreign in [theirs, of_freed, of_purse, 0x1234 as fmi2FMUstate] {
        let mut slot = foreign;
        let mut size = 0usize;
        let mut bytes = vec![0 as fmi2Byte; 4096];
        unsafe {
            assert_eq!(fmi2SetFMUstate(b, foreign), ERROR, "set {foreign:p}");
            assert_eq!(fmi2GetFMUstate(b, &mut slot), ERROR, "get into {foreign:p}");
            assert_eq!(
                fmi2SerializedFMUstateSize(b, foreign, &mut size),
                ERROR,
                "size of {foreign:p}"
            );
            assert_eq!(
                fmi2SerializeFMUstate(b, foreign, bytes.as_mut_ptr(), bytes.len()),
                ERROR,
                "serialize {foreign:p}"
            );
            assert_eq!(fmi2FreeFMUstate(b, &mut slot), ERROR, "free {foreign:p}");
        }
        assert_eq!(slot, foreign, "a refused call leaves the handle as it was");
        assert_eq!(last_successful_time(b), (OK, 1.0), "B's time after {foreign:p}");
        assert_eq!(get_real(b, Vr::WoundRadius as u32), radius);
    }
    // B's own state is still there and still B's: back to t = 0.
    unsafe {
        assert_eq!(fmi2SetFMUstate(b, ours), OK);
        assert_eq!(last_successful_time(b), (OK, 0.0));
        assert_eq!(fmi2FreeFMUstate(b, &mut ours), OK);
        // And A's state is still A's.
        assert_eq!(fmi2SetFMUstate(a, theirs), OK);
        assert_eq!(fmi2FreeFMUstate(a, &mut theirs), OK);
        for c in [a, b, purse] {
            fmi2FreeInstance(c);
        }
    }
}
