//! The direct API in safe Rust: solvers and saved states behind handles, every argument
//! checked before anything changes. The `extern "C"` shims of `solver_c.rs` only turn
//! pointers into handles, slices and output slots.
//!
//! A solver holds one problem (lambda, sigma, R_inf and a grid), its time `t` and the edge
//! stress `p` of its last advance (0 before the first):
//!
//! ```text
//! wound radius    R(t)   = 1 + u(1, t)
//! edge velocity   dR/dt  = u_t(1, t)   with p applied
//! profiles        u(r, t), u_t(r, t)   at radii 1 <= r <= R_inf, u_t with p applied
//! advance(t_end, p): t -> t_end >= t with p held constant over [t, t_end], exact in time
//! ```
//!
//! A refused call changes nothing. A saved state is a copy of `(t, p, solution)`; it can
//! be restored into any solver of the same problem (same parameters and grid, bit for bit),
//! any number of times, until freed.

use super::error::{Failure, WoStatus};
use crate::boundary::registry::Table;
use crate::solver::{Mesh, MeshSpec, Params, Settings, Solver, SolverState, check_edge_stress};
use std::sync::{Mutex, MutexGuard};

/// Largest polynomial degree of a grid: beyond it the barycentric weights of the Lagrange
/// basis on GLL nodes lose their accuracy; degree 8 (the default) is the tested optimum.
pub const MAX_DEGREE: usize = 32;
/// Largest number of unknowns `degree * elements + 1` of a grid (dense modal transform).
pub const MAX_UNKNOWNS: usize = 4001;

/// One solver and what the C caller sees of it.
struct Live {
    params: Params,
    settings: Settings,
    solver: Solver,
    /// Radii of the grid nodes, ascending from 1 to R_inf.
    nodes: Vec<f64>,
    /// Time, exactly as the caller last asked for it.
    time: f64,
    /// Edge stress of the last advance, applied "now" for velocities.
    edge_stress: f64,
    /// Set when a call panicked while using this solver: its data may be half-updated.
    failed: bool,
}

/// A saved state: a copy of a solver's time, edge stress and solution.
struct Saved {
    params: Params,
    settings: Settings,
    time: f64,
    edge_stress: f64,
    state: SolverState,
}

static SOLVERS: Table<Mutex<Live>> = Table::new("solver");
static STATES: Table<Saved> = Table::new("state");

/// Live solvers and saved states (for tests: 0 and 0 once a program freed everything).
pub fn live_handles() -> (usize, usize) {
    (SOLVERS.len(), STATES.len())
}

/// Check a grid before anything is built from it: degree and element counts in range (no
/// overflow of their product), a grading length that keeps every node finite and the
/// nodes strictly ascending. Returns the node radii.
pub fn check_grid(spec: MeshSpec, r_inf: f64) -> Result<Vec<f64>, Failure> {
    let MeshSpec { degree, elements, edge_scale } = spec;
    if !(1..=MAX_DEGREE).contains(&degree) {
        return Err(Failure::invalid(format!(
            "degree = {degree} is invalid: expected 1 <= degree <= {MAX_DEGREE}"
        )));
    }
    let unknowns = elements.checked_mul(degree).and_then(|n| n.checked_add(1));
    if elements == 0 || unknowns.is_none_or(|n| n > MAX_UNKNOWNS) {
        return Err(Failure::invalid(format!(
            "elements = {elements} is invalid with degree = {degree}: expected elements >= 1 and \
             degree * elements + 1 <= {MAX_UNKNOWNS} unknowns"
        )));
    }
    let stretch = 1.0 + (r_inf - 1.0) / edge_scale;
    if !(edge_scale.is_finite() && edge_scale > 0.0 && stretch.is_finite()) {
        return Err(Failure::invalid(format!(
            "edge_scale = {edge_scale} is invalid: expected finite, > 0 and (R_inf - 1) / edge_scale finite"
        )));
    }
    let mesh = Mesh::new(spec, r_inf);
    let nodes = mesh.nodes();
    if let Some(i) = nodes.windows(2).position(|w| !(w[0].is_finite() && w[0] < w[1])) {
        return Err(Failure::invalid(format!(
            "edge_scale = {edge_scale} with {elements} elements gives nodes {} and {} at positions {i} and {}: \
             expected finite, strictly ascending nodes (choose a larger edge_scale)",
            nodes[i],
            nodes[i + 1],
            i + 1
        )));
    }
    Ok(nodes.to_vec())
}

fn create(params: Params, settings: Settings) -> Result<u64, Failure> {
    let nodes = check_grid(settings.mesh, params.r_inf)?;
    let solver = Solver::new(&params, &settings)?;
    let live = Live { params, settings, solver, nodes, time: 0.0, edge_stress: 0.0, failed: false };
    Ok(SOLVERS.insert(Mutex::new(live)))
}

/// A solver at t = 0 (just after the cut) on the cheapest grid whose wound radius stays
/// within `tolerance` of the exact one, relative to the opening amplitude, for t >= 0.01.
pub fn new_for_tolerance(params: Params, tolerance: f64) -> Result<u64, Failure> {
    params.validate().map_err(|e| Failure::invalid(e.to_string()))?;
    create(params, Settings::for_tolerance(&params, tolerance)?)
}

/// A solver at t = 0 on the given grid.
pub fn new_on_grid(params: Params, mesh: MeshSpec) -> Result<u64, Failure> {
    params.validate().map_err(|e| Failure::invalid(e.to_string()))?;
    create(params, Settings { mesh })
}

pub fn free(solver: u64) -> Result<(), Failure> {
    SOLVERS.remove(solver).map(drop).map_err(Failure::from)
}

/// Run `f` on a solver. A solver whose earlier call panicked is refused unless
/// `recovering` (restoring a state into it).
fn with_solver<R>(
    handle: u64,
    recovering: bool,
    f: impl FnOnce(&mut Live) -> Result<R, Failure>,
) -> Result<R, Failure> {
    let entry = SOLVERS.get(handle)?;
    let mut live: MutexGuard<'_, Live> = entry.lock().unwrap_or_else(|poisoned| {
        entry.clear_poison();
        let mut live = poisoned.into_inner();
        live.failed = true;
        live
    });
    if live.failed && !recovering {
        return Err(Failure::new(
            WoStatus::WoInternalError,
            format!(
                "solver {handle:#x} is unusable after an internal error in an earlier call: \
                 restore a saved state into it (wo_solver_restore_state) or free it"
            ),
        ));
    }
    f(&mut live)
}

/// Advance to `t_end >= t` with the edge stress `p` held over `[t, t_end]`.
pub fn advance(solver: u64, t_end: f64, p: f64) -> Result<(), Failure> {
    with_solver(solver, false, |s| {
        if !(t_end.is_finite() && t_end >= s.time) {
            return Err(Failure::invalid(format!(
                "t_end = {t_end} is invalid: expected a finite time >= the solver's time {}",
                s.time
            )));
        }
        check_edge_stress(p).map_err(|e| Failure::invalid(e.to_string()))?;
        let r_inf = s.params.r_inf;
        let was_valid = s.time == 0.0 || s.solver.validity_violation(r_inf).is_none();
        if t_end > s.time {
            s.solver.advance(t_end - s.time, p)?;
        }
        s.time = t_end;
        s.edge_stress = p;
        match s.solver.validity_violation(r_inf).filter(|_| was_valid) {
            Some(why) => Err(Failure::new(
                WoStatus::WoOutsideValidity,
                format!(
                    "advanced to t = {t_end}, where the run leaves the model's validity: {why}"
                ),
            )),
            None => Ok(()),
        }
    })
}

pub fn time(solver: u64) -> Result<f64, Failure> {
    with_solver(solver, false, |s| Ok(s.time))
}

pub fn wound_radius(solver: u64) -> Result<f64, Failure> {
    with_solver(solver, false, |s| Ok(s.solver.wound_radius()))
}

/// Refuse a velocity that is infinite in the model (lambda = 0 at the cut, where the edge
/// stress applied differs from the uniform tension's).
fn check_velocity_defined(s: &Live) -> Result<(), Failure> {
    if s.solver.edge_velocity_defined(s.edge_stress) {
        return Ok(());
    }
    Err(Failure::new(
        WoStatus::WoUndefined,
        format!(
            "the velocity is infinite at lambda = 0 at the cut (edge stress {} against the tension {}): it decays like t^(-1/2); advance first",
            s.edge_stress, s.params.sigma
        ),
    ))
}

pub fn edge_velocity(solver: u64) -> Result<f64, Failure> {
    with_solver(solver, false, |s| {
        check_velocity_defined(s)?;
        Ok(s.solver.edge_velocity(s.edge_stress))
    })
}

pub fn node_count(solver: u64) -> Result<usize, Failure> {
    with_solver(solver, false, |s| Ok(s.nodes.len()))
}

/// The grid's node radii, ascending from 1 to R_inf; `out` must have one slot per node.
pub fn nodes(solver: u64, out: &mut [f64]) -> Result<(), Failure> {
    with_solver(solver, false, |s| {
        let nodes = &s.nodes;
        if out.len() != nodes.len() {
            return Err(Failure::invalid(format!(
                "count = {} is invalid: the solver has {} nodes (see wo_solver_node_count)",
                out.len(),
                nodes.len()
            )));
        }
        out.copy_from_slice(nodes);
        Ok(())
    })
}

fn check_radii(radii: &[f64], r_inf: f64) -> Result<(), Failure> {
    match radii.iter().position(|r| !(1.0..=r_inf).contains(r)) {
        None => Ok(()),
        Some(i) => Err(Failure::invalid(format!(
            "radii[{i}] = {} is outside the tissue: expected 1 <= r <= R_inf = {r_inf}",
            radii[i]
        ))),
    }
}

/// Displacement `u(r, t)` at each radius (`out.len() == radii.len()`).
pub fn displacement(solver: u64, radii: &[f64], out: &mut [f64]) -> Result<(), Failure> {
    with_solver(solver, false, |s| {
        check_radii(radii, s.params.r_inf)?;
        out.copy_from_slice(&s.solver.displacement(radii));
        Ok(())
    })
}

/// Velocity `u_t(r, t)` at each radius, with the current edge stress applied.
pub fn velocity(solver: u64, radii: &[f64], out: &mut [f64]) -> Result<(), Failure> {
    with_solver(solver, false, |s| {
        check_radii(radii, s.params.r_inf)?;
        check_velocity_defined(s)?;
        out.copy_from_slice(&s.solver.velocity(s.edge_stress, radii));
        Ok(())
    })
}

/// Copy the solver's state into a new saved state.
pub fn save_state(solver: u64) -> Result<u64, Failure> {
    let saved = with_solver(solver, false, |s| {
        Ok(Saved {
            params: s.params,
            settings: s.settings,
            time: s.time,
            edge_stress: s.edge_stress,
            state: s.solver.state(),
        })
    })?;
    Ok(STATES.insert(saved))
}

/// Restore a saved state of the same problem; also brings a failed solver back.
pub fn restore_state(solver: u64, state: u64) -> Result<(), Failure> {
    let saved = STATES.get(state)?;
    with_solver(solver, true, |s| {
        let (mine, theirs) = (s.params, saved.params);
        for (name, a, b) in [
            ("lambda", mine.lambda, theirs.lambda),
            ("sigma", mine.sigma, theirs.sigma),
            ("R_inf", mine.r_inf, theirs.r_inf),
        ] {
            if a.to_bits() != b.to_bits() {
                return Err(Failure::new(
                    WoStatus::WoIncompatibleState,
                    format!(
                        "state {state:#x} was saved with {name} = {b} but this solver has {name} = {a}"
                    ),
                ));
            }
        }
        if saved.settings != s.settings {
            return Err(Failure::new(
                WoStatus::WoIncompatibleState,
                format!(
                    "state {state:#x} was saved on grid {:?} but this solver uses {:?}",
                    saved.settings.mesh, s.settings.mesh
                ),
            ));
        }
        s.solver.restore(&saved.state)?;
        s.time = saved.time;
        s.edge_stress = saved.edge_stress;
        s.failed = false;
        Ok(())
    })
}

pub fn free_state(state: u64) -> Result<(), Failure> {
    STATES.remove(state).map(drop).map_err(Failure::from)
}

/// Run `f` on the solver's data while holding its lock (for tests of the panic
/// boundary: a panic in `f` must leave the solver refusing use until restored).
#[cfg(test)]
pub(crate) fn with_solver_for_tests(solver: u64, f: impl FnOnce()) -> Result<(), Failure> {
    with_solver(solver, false, |_| {
        f();
        Ok(())
    })
}
