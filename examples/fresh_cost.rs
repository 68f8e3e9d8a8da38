//! What a fresh parameter set costs, side by side with one step, in one run, through the
//! exported FMI 2.0 functions (as a C master calls them): the measure of the
//! lambda-independent modal basis and its process-wide cache (src/solver/basis.rs).
//!
//! Usage: `cargo run --release --example fresh_cost -- DIR`; writes DIR/fresh_cost.csv
//! (`what,seconds,steps`: best CPU seconds of one operation over many repeats, and the same
//! in units of one `fmi2DoStep` + `fmi2GetReal`).
//!
//! - `step`: `fmi2DoStep` + `fmi2GetReal` of both outputs (R_inf = 10, tolerance 1e-10).
//! - `step_without_guard`: the same two calls through the safe `Instance` API: the
//!   difference is what the C boundary's guard costs (handle lookup, the instance's lock,
//!   the panic boundary).
//! - `fresh_instance`: `fmi2Instantiate`, `fmi2SetReal(lambda)` (a new lambda each time),
//!   initialization, `fmi2GetReal`, `fmi2FreeInstance`, at an outer radius already cached.
//! - `reset_new_lambda`: `fmi2Reset`, a new lambda, initialization, `fmi2GetReal`.
//! - `fresh_outer_radius`: the same as `fresh_instance` with a new R_inf each time (a cache
//!   miss: assembly and the Jacobi decomposition, 49 unknowns).

#[path = "common/bench_util.rs"]
mod bench_util;

use bench_util::{best_cpu, exported_step_seconds};
use std::ffi::{CString, c_void};
use std::io::Write;
use std::sync::Arc;
use wound_opening::fmi::common::instance::{Call, Instance, Logger, Status};
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::WoundModel;
use wound_opening::models::wound::variables::GUID;

const LAMBDA: u32 = 0;
const R_INF: u32 = 2;
const OUTPUTS: [u32; 2] = [4, 5];
const STEPS: usize = 100_000;
const FRESH: usize = 2_000;

fn instantiate() -> *mut c_void {
    let (name, guid) = (CString::new("bench").unwrap(), CString::new(GUID).unwrap());
    let callbacks = fmi2CallbackFunctions::NONE;
    // SAFETY: valid strings and callbacks.
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            FMI2_CO_SIMULATION,
            guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            0,
            0,
        )
    };
    assert!(!c.is_null());
    c
}

/// Set `(vr, value)` pairs, initialize, read the outputs.
///
/// # Safety
/// `c` is a live instance in the instantiated state.
unsafe fn initialize(c: *mut c_void, values: &[(u32, f64)]) -> f64 {
    let (vrs, xs): (Vec<u32>, Vec<f64>) = values.iter().copied().unzip();
    let mut out = [0.0; 2];
    unsafe {
        assert_eq!(fmi2SetReal(c, vrs.as_ptr(), vrs.len(), xs.as_ptr()), 0);
        assert_eq!(fmi2SetupExperiment(c, 1, 1e-10, 0.0, 0, 0.0), 0);
        assert_eq!(fmi2EnterInitializationMode(c), 0);
        assert_eq!(fmi2ExitInitializationMode(c), 0);
        assert_eq!(fmi2GetReal(c, OUTPUTS.as_ptr(), 2, out.as_mut_ptr()), 0);
    }
    out[1]
}

struct Silent;

impl Logger for Silent {
    fn log(&self, _status: Status, _category: &str, _message: &str) {}
}

/// One step and read through the safe API, without the C boundary.
fn step_without_guard() -> f64 {
    let mut i = Instance::new(WoundModel::fresh, "bench", Arc::new(Silent), false);
    let ok = |r: Result<((), Status), Status>| assert_eq!(r, Ok(((), Status::Ok)));
    ok(i.call(Call::SetupExperiment, String::new, |i| i.setup_experiment(Some(1e-10), 0.0, None)));
    ok(i.call(Call::EnterInitializationMode, String::new, |i| i.enter_initialization_mode()));
    ok(i.call(Call::ExitInitializationMode, String::new, |i| i.exit_initialization_mode()));
    let (mut t, mut out) = (0.0, [0.0; 2]);
    let (cpu, _) = best_cpu(|| {
        for _ in 0..STEPS {
            ok(i.call(Call::DoStep, String::new, |i| i.do_step(t, 1e-4)));
            t += 1e-4;
            ok(i.call(Call::Get, String::new, |i| i.get_real(&OUTPUTS, &mut out)));
        }
        out[0]
    });
    cpu / STEPS as f64
}

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: fresh_cost DIR"));
    let mut csv = std::fs::File::create(dir.join("fresh_cost.csv")).expect("writable DIR");
    writeln!(csv, "what,seconds,steps").unwrap();

    // SAFETY (all blocks): instances come from `instantiate` and are freed once.
    let step = unsafe {
        let c = instantiate();
        initialize(c, &[(LAMBDA, 1.0)]);
        let seconds = exported_step_seconds(c, 0.0, STEPS);
        fmi2FreeInstance(c);
        seconds
    };
    let mut row = |what: &str, seconds: f64| {
        writeln!(csv, "{what},{seconds:e},{:.1}", seconds / step).unwrap();
        println!("{what:<22} {:>10.0} ns  = {:>7.1} steps", seconds * 1e9, seconds / step);
    };
    row("step", step);
    row("step_without_guard", step_without_guard());

    let mut k = 0u64;
    let mut next_lambda = move || {
        k += 1;
        0.5 + (k % 997) as f64 * 1e-3
    };
    let (cpu, _) = best_cpu(|| {
        (0..FRESH)
            .map(|_| unsafe {
                let c = instantiate();
                let v = initialize(c, &[(LAMBDA, next_lambda())]);
                fmi2FreeInstance(c);
                v
            })
            .sum::<f64>()
    });
    row("fresh_instance", cpu / FRESH as f64);

    let c = instantiate();
    let (cpu, _) = best_cpu(|| {
        (0..FRESH)
            .map(|_| unsafe {
                assert_eq!(fmi2Reset(c), 0);
                initialize(c, &[(LAMBDA, next_lambda())])
            })
            .sum::<f64>()
    });
    unsafe { fmi2FreeInstance(c) };
    row("reset_new_lambda", cpu / FRESH as f64);

    let mut r = 10.0f64;
    let (cpu, _) = best_cpu(|| {
        (0..20)
            .map(|_| unsafe {
                r = r.next_up();
                let c = instantiate();
                let v = initialize(c, &[(R_INF, r)]);
                fmi2FreeInstance(c);
                v
            })
            .sum::<f64>()
    });
    row("fresh_outer_radius", cpu / 20.0);
}
