//! Shared by the benchmark examples (included with `#[path]`): CPU time, CSV reading, the
//! benchmark scenario and its error measure.
#![allow(dead_code)]

use std::path::Path;
pub use wound_opening::solver::stability::{self, RunStatus as Status};
use wound_opening::solver::{Params, Scheme, Solver, exact};

/// CPU time of this process, in seconds (CLOCK_PROCESS_CPUTIME_ID).
pub fn cpu_seconds() -> f64 {
    let mut ts = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: a valid clock id and a valid out-pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// CPU seconds of one `fmi2DoStep` (a step of 1e-4 from the instance's time `t`) and one
/// `fmi2GetReal` of both WoundOpening outputs, through the exported functions: best of
/// repeats of `steps` each.
///
/// # Safety
/// `c` is a live, initialized WoundOpening instance at time `t`.
pub unsafe fn exported_step_seconds(
    c: wound_opening::fmi::fmi2::types::fmi2Component,
    mut t: f64,
    steps: usize,
) -> f64 {
    use wound_opening::fmi::fmi2::functions::{fmi2DoStep, fmi2GetReal};
    let (outputs, mut out) = ([4u32, 5u32], [0.0f64; 2]);
    let (cpu, _) = best_cpu(|| {
        for _ in 0..steps {
            // SAFETY: as promised by the caller; `outputs` and `out` hold two elements.
            unsafe {
                assert_eq!(fmi2DoStep(c, t, 1e-4, 1), 0);
                assert_eq!(fmi2GetReal(c, outputs.as_ptr(), 2, out.as_mut_ptr()), 0);
            }
            t += 1e-4;
        }
        out[0]
    });
    cpu / steps as f64
}

/// Best CPU time of `f` over repeats (at least 3, until 0.3 s are spent, at most 50).
pub fn best_cpu<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let (mut best, mut spent, mut out) = (f64::INFINITY, 0.0, None);
    for k in 0..50 {
        let t0 = cpu_seconds();
        let r = f();
        let dt = cpu_seconds() - t0;
        best = best.min(dt);
        spent += dt;
        out = Some(r);
        if k >= 2 && spent > 0.3 {
            break;
        }
    }
    (best, out.expect("ran at least once"))
}

/// Rows of a headerless numeric CSV.
pub fn read_csv(path: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split(',').map(|x| x.trim().parse().expect("number")).collect())
        .collect()
}

pub const SCENARIO_STEPS: usize = 1000;
pub const SCENARIO_STEP: f64 = 0.1;
pub const SIGMA: f64 = 1.0;
pub const R_INF: f64 = 10.0;

pub fn amplitude(r_inf: f64) -> f64 {
    exact::final_radius(SIGMA, r_inf) - exact::initial_radius(SIGMA)
}

/// The whole scenario (set-up and 1000 steps of 0.1): wound radius at each point, or
/// `None` if the scheme cannot be built.
///
/// The modal-basis cache is emptied first, so that every timed run pays the whole set-up
/// (assembly and decomposition), as a first run in a process does.
pub fn scenario(lambda: f64, scheme: &Scheme) -> Option<Vec<f64>> {
    wound_opening::solver::basis::clear();
    let params = Params { lambda, sigma: SIGMA, r_inf: R_INF };
    let mut s = Solver::with_scheme(&params, scheme).ok()?;
    let mut out = Vec::with_capacity(SCENARIO_STEPS);
    for _ in 0..SCENARIO_STEPS {
        s.advance(SCENARIO_STEP, 0.0).ok()?;
        out.push(s.wound_radius());
    }
    Some(out)
}

/// Max |R - R_exact| / amplitude (infinite when anything is not finite).
pub fn error(radius: &[f64], reference: &[f64]) -> f64 {
    let amp = amplitude(R_INF);
    radius.iter().zip(reference).fold(0.0f64, |m, (r, e)| {
        let d = (r - e).abs() / amp;
        if d.is_finite() && m.is_finite() { m.max(d) } else { f64::INFINITY }
    })
}

/// Stability status of `steps` steps of size `dt` on the scenario's problem
/// ([`wound_opening::solver::stability::classify`]).
pub fn classify(lambda: f64, scheme: &Scheme, dt: f64, steps: usize) -> Status {
    stability::classify(&Params { lambda, sigma: SIGMA, r_inf: R_INF }, scheme, dt, steps)
}
