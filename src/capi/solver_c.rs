//! The exported `wo_*` functions: thin `extern "C"` shims over [`super::solver`]. Each
//! converts its pointers (NULL is refused with `WO_NULL_POINTER`, never dereferenced) and
//! runs inside [`run`]: panic boundary, status, the thread's last error message.
//!
//! Output arguments are written only on success. Arrays are `(pointer, count)` pairs; a
//! NULL pointer is accepted only with `count = 0`. An input and an output array may be the
//! same array (the input is copied first).
#![allow(clippy::missing_safety_doc)]

use super::error::{Failure, WoStatus, last_error_ptr, run};
use super::solver;
use crate::boundary::pointers::{self, BadArray};
use crate::solver::{MeshSpec, Params};
use std::ffi::{c_char, c_int};

/// A solver, as seen from C: an opaque handle (never an address), created by
/// `wo_solver_new` or `wo_solver_new_grid` and released by `wo_solver_free`.
pub struct WoSolver {
    _opaque: [u8; 0],
}

/// A saved solver state, as seen from C: an opaque handle created by
/// `wo_solver_save_state` and released by `wo_state_free`.
pub struct WoState {
    _opaque: [u8; 0],
}

fn handle<T>(p: *const T, what: &str) -> Result<u64, Failure> {
    if p.is_null() { Err(Failure::null(what)) } else { Ok(p as usize as u64) }
}

fn as_ptr<T>(handle: u64) -> *mut T {
    handle as usize as *mut T
}

/// Write `value` through an output pointer (checked for NULL by the caller's `slot`).
fn slot<'a, T>(p: *mut T, what: &str) -> Result<&'a mut T, Failure> {
    // SAFETY: the C caller passes NULL or a valid, writable pointer.
    unsafe { pointers::slot(p) }.ok_or_else(|| Failure::null(what))
}

fn null_array(what: &str, e: BadArray) -> Failure {
    match e {
        BadArray::Null { count } => Failure::null(&format!("{what} (with count = {count})")),
        BadArray::TooLong { .. } => Failure::invalid(e.reason(what)),
    }
}

/// An input array as an owned copy (so that it may alias an output array), its count
/// checked before anything is read and the copy allocated fallibly.
pub(super) fn input(p: *const f64, count: usize, what: &str) -> Result<Vec<f64>, Failure> {
    // SAFETY: the C caller passes NULL or `count` readable values.
    let values = unsafe { pointers::slice(p, count) }.map_err(|e| null_array(what, e))?;
    pointers::try_copy(values).ok_or_else(|| too_large(what, count))
}

/// `count` values that the address space could hold but the memory cannot.
pub(super) fn too_large(what: &str, count: usize) -> Failure {
    Failure::invalid(format!(
        "{what}: count = {count} is invalid: {count} values ({:.3e} bytes) cannot be allocated",
        count as f64 * 8.0
    ))
}

/// `count` zeros, allocated fallibly (a working array as large as a caller's output).
pub(super) fn zeros(count: usize, what: &str) -> Result<Vec<f64>, Failure> {
    let mut out = Vec::new();
    out.try_reserve_exact(count).map_err(|_| too_large(what, count))?;
    out.resize(count, 0.0);
    Ok(out)
}

pub(super) fn output<'a>(p: *mut f64, count: usize, what: &str) -> Result<&'a mut [f64], Failure> {
    // SAFETY: the C caller passes NULL or `count` writable values.
    unsafe { pointers::slice_mut(p, count) }.map_err(|e| null_array(what, e))
}

/// Create a solver at t = 0 (just after the cut, in uniform tension) for lambda = 0 or in
/// [1e-150, 1e6], sigma in (-6, 1e6] and R_inf in [1.001, 1e6], on the cheapest grid whose wound radius stays within
/// `tolerance` (> 0) of the exact solution for t >= 0.01, relative to the larger of the free
/// opening and the one under the edge stress p applied: max(|sigma|, |sigma - p|) S with
/// S = 2 R_inf^2 / (3 (R_inf^2 - 1)) - 1/6. On success `*solver` is the new solver; on failure it is set to NULL.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_new(
    lambda: f64,
    sigma: f64,
    r_inf: f64,
    tolerance: f64,
    solver: *mut *mut WoSolver,
) -> WoStatus {
    run("wo_solver_new", || {
        let out = slot(solver, "solver")?;
        *out = std::ptr::null_mut();
        *out = as_ptr(solver::new_for_tolerance(Params { lambda, sigma, r_inf }, tolerance)?);
        Ok(())
    })
}

/// Create a solver at t = 0 on an explicit grid: `elements` spectral elements of
/// polynomial `degree` (1 to 32; `degree * elements + 1` unknowns, at most 4001), graded
/// geometrically from the wound edge with first-element scale `edge_scale` (in R0). The
/// shipped default is degree 8, 10 elements, edge_scale 0.05.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_new_grid(
    lambda: f64,
    sigma: f64,
    r_inf: f64,
    degree: usize,
    elements: usize,
    edge_scale: f64,
    solver: *mut *mut WoSolver,
) -> WoStatus {
    run("wo_solver_new_grid", || {
        let out = slot(solver, "solver")?;
        *out = std::ptr::null_mut();
        let mesh = MeshSpec { degree, elements, edge_scale };
        *out = as_ptr(solver::new_on_grid(Params { lambda, sigma, r_inf }, mesh)?);
        Ok(())
    })
}

/// Free a solver. NULL is a no-op (as for free()); an unknown or already freed solver is
/// `WO_UNKNOWN_HANDLE`. Saved states stay valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_free(solver: *mut WoSolver) -> WoStatus {
    run("wo_solver_free", || {
        if solver.is_null() { Ok(()) } else { solver::free(handle(solver, "solver")?) }
    })
}

/// Advance to the time `t_end` (>= the solver's time; equal is a no-op) with the edge
/// stress `edge_stress` held constant over the interval. Exact in time, for any interval.
/// `WO_OUTSIDE_VALIDITY` (a warning: the advance was done) when the state there has left
/// the model's validity.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_advance(
    solver: *mut WoSolver,
    t_end: f64,
    edge_stress: f64,
) -> WoStatus {
    run("wo_solver_advance", || solver::advance(handle(solver, "solver")?, t_end, edge_stress))
}

/// The solver's time (in T = zeta R0^2 / 4G).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_time(solver: *const WoSolver, time: *mut f64) -> WoStatus {
    run("wo_solver_time", || {
        let out = slot(time, "time")?;
        *out = solver::time(handle(solver, "solver")?)?;
        Ok(())
    })
}

/// The wound radius R(t) = 1 + u(1, t), in R0.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_wound_radius(
    solver: *const WoSolver,
    radius: *mut f64,
) -> WoStatus {
    run("wo_solver_wound_radius", || {
        let out = slot(radius, "radius")?;
        *out = solver::wound_radius(handle(solver, "solver")?)?;
        Ok(())
    })
}

/// The edge velocity dR/dt = u_t(1, t) with the edge stress of the last advance applied
/// (0 before the first), in R0 / T.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_edge_velocity(
    solver: *const WoSolver,
    velocity: *mut f64,
) -> WoStatus {
    run("wo_solver_edge_velocity", || {
        let out = slot(velocity, "velocity")?;
        *out = solver::edge_velocity(handle(solver, "solver")?)?;
        Ok(())
    })
}

/// The number of grid nodes (unknowns).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_node_count(
    solver: *const WoSolver,
    count: *mut usize,
) -> WoStatus {
    run("wo_solver_node_count", || {
        let out = slot(count, "count")?;
        *out = solver::node_count(handle(solver, "solver")?)?;
        Ok(())
    })
}

/// The grid's node radii, ascending from 1 to R_inf, into `radii[0 .. count)`; `count`
/// must equal `wo_solver_node_count`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_nodes(
    solver: *const WoSolver,
    radii: *mut f64,
    count: usize,
) -> WoStatus {
    run("wo_solver_nodes", || {
        solver::nodes(handle(solver, "solver")?, output(radii, count, "radii")?)
    })
}

/// Reads a profile of a solver at radii into an array (safe part).
type ProfileReader = fn(u64, &[f64], &mut [f64]) -> Result<(), Failure>;

/// A profile at caller-given radii: the shared body of the two functions below.
fn profile(
    name: &str,
    solver: *const WoSolver,
    radii: *const f64,
    out: *mut f64,
    count: usize,
    out_name: &str,
    read: ProfileReader,
) -> WoStatus {
    run(name, || {
        let h = handle(solver, "solver")?;
        let r = input(radii, count, "radii")?;
        read(h, &r, output(out, count, out_name)?)
    })
}

/// The displacement profile u(r, t) at `radii[i]` (each in [1, R_inf]) into `u[i]`, for
/// `i < count`. `u` may be `radii` itself.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_displacement(
    solver: *const WoSolver,
    radii: *const f64,
    u: *mut f64,
    count: usize,
) -> WoStatus {
    profile("wo_solver_displacement", solver, radii, u, count, "u", solver::displacement)
}

/// The velocity profile u_t(r, t) at `radii[i]` (each in [1, R_inf]) into `v[i]`, with the
/// edge stress of the last advance applied. `v` may be `radii` itself.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_velocity(
    solver: *const WoSolver,
    radii: *const f64,
    v: *mut f64,
    count: usize,
) -> WoStatus {
    profile("wo_solver_velocity", solver, radii, v, count, "v", solver::velocity)
}

/// Copy the solver's state (time, edge stress, solution) into a new saved state.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_save_state(
    solver: *const WoSolver,
    state: *mut *mut WoState,
) -> WoStatus {
    run("wo_solver_save_state", || {
        let out = slot(state, "state")?;
        *out = std::ptr::null_mut();
        *out = as_ptr(solver::save_state(handle(solver, "solver")?)?);
        Ok(())
    })
}

/// Restore a saved state into a solver of the same problem (same lambda, sigma, R_inf and
/// grid; otherwise `WO_INCOMPATIBLE_STATE`). The state stays valid.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_solver_restore_state(
    solver: *mut WoSolver,
    state: *const WoState,
) -> WoStatus {
    run("wo_solver_restore_state", || {
        solver::restore_state(handle(solver, "solver")?, handle(state, "state")?)
    })
}

/// Free a saved state. NULL is a no-op; an unknown or already freed state is
/// `WO_UNKNOWN_HANDLE`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_state_free(state: *mut WoState) -> WoStatus {
    run("wo_state_free", || {
        if state.is_null() { Ok(()) } else { solver::free_state(handle(state, "state")?) }
    })
}

/// The calling thread's message of its last `wo_*` call: what was wrong, with the expected
/// and actual values, or "" if that call succeeded. Valid until the thread's next `wo_*`
/// call (this one excepted); never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn wo_last_error() -> *const c_char {
    last_error_ptr()
}

/// The name of a status code ("WO_OK", ...), or "unknown status" for any other number.
#[unsafe(no_mangle)]
pub extern "C" fn wo_status_name(status: c_int) -> *const c_char {
    let names = [
        c"WO_OK",
        c"WO_NULL_POINTER",
        c"WO_INVALID_ARGUMENT",
        c"WO_UNKNOWN_HANDLE",
        c"WO_INCOMPATIBLE_STATE",
        c"WO_SOLVER_FAILED",
        c"WO_INTERNAL_ERROR",
        c"WO_UNDEFINED",
        c"WO_OUTSIDE_VALIDITY",
    ];
    usize::try_from(status)
        .ok()
        .and_then(|i| names.get(i))
        .map_or(c"unknown status".as_ptr(), |n| n.as_ptr())
}
