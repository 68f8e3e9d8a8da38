//! What the C boundary's guard costs per step: `fmi2DoStep` + `fmi2GetReal` of both outputs
//! through the exported functions (handle lookup in the table of live instances, the
//! instance's lock, two panic guards) against the same two calls through the safe
//! `Instance` API (state machine and logging, no lookup, lock or guard). Same model
//! (WoundOpening, lambda = 1, tolerance 1e-9), same steps (1e-4).
//!
//! Usage: `cargo run --release --example guard_cost`; prints ns per step + read (best CPU
//! time of several repeats of 100,000).

#[path = "common/bench_util.rs"]
mod bench_util;

use bench_util::best_cpu;
use std::ffi::CString;
use std::sync::Arc;
use wound_opening::fmi::ffi::*;
use wound_opening::fmi::wound::WoundModel;
use wound_opening::fmi::instance::{Call, Instance, Logger, Status};
use wound_opening::fmi::types::*;
use wound_opening::fmi::wound::variables::{GUID, Vr};

const STEPS: usize = 100_000;
const H: f64 = 1e-4;
const OUTPUTS: [u32; 2] = [Vr::WoundRadius as u32, Vr::EdgeVelocity as u32];

struct Silent;

impl Logger for Silent {
    fn log(&self, _status: Status, _category: &str, _message: &str) {}
}

fn safe_api() -> f64 {
    let mut i = Instance::new(WoundModel::fresh, "bench", Arc::new(Silent), false);
    let ok = |r: Result<((), Status), Status>| assert_eq!(r, Ok(((), Status::Ok)));
    ok(i.call(Call::SetupExperiment, String::new, |i| i.setup_experiment(Some(1e-9), 0.0, None)));
    ok(i.call(Call::EnterInitializationMode, String::new, |i| i.enter_initialization_mode()));
    ok(i.call(Call::ExitInitializationMode, String::new, |i| i.exit_initialization_mode()));
    let (mut t, mut out) = (0.0, [0.0; 2]);
    let (cpu, _) = best_cpu(|| {
        for _ in 0..STEPS {
            ok(i.call(Call::DoStep, String::new, |i| i.do_step(t, H)));
            t += H;
            ok(i.call(Call::Get, String::new, |i| i.get_real(&OUTPUTS, &mut out)));
        }
        out[0]
    });
    cpu / STEPS as f64
}

fn exported() -> f64 {
    let (name, guid) = (CString::new("bench").unwrap(), CString::new(GUID).unwrap());
    let callbacks = fmi2CallbackFunctions::NONE;
    // SAFETY: valid strings, callbacks and arrays; the instance is freed at the end.
    unsafe {
        let c = fmi2Instantiate(name.as_ptr(), FMI2_CO_SIMULATION, guid.as_ptr(), std::ptr::null(), &callbacks, 0, 0);
        assert!(!c.is_null());
        assert_eq!(fmi2SetupExperiment(c, 1, 1e-9, 0.0, 0, 0.0), 0);
        assert_eq!(fmi2EnterInitializationMode(c), 0);
        assert_eq!(fmi2ExitInitializationMode(c), 0);
        let (mut t, mut out) = (0.0, [0.0; 2]);
        let (cpu, _) = best_cpu(|| {
            for _ in 0..STEPS {
                assert_eq!(fmi2DoStep(c, t, H, 1), 0);
                t += H;
                assert_eq!(fmi2GetReal(c, OUTPUTS.as_ptr(), 2, out.as_mut_ptr()), 0);
            }
            out[0]
        });
        fmi2FreeInstance(c);
        cpu / STEPS as f64
    }
}

fn main() {
    let (safe, c) = (safe_api(), exported());
    println!("fmi2DoStep + fmi2GetReal, per step:");
    println!("  safe Instance API      {:7.1} ns", safe * 1e9);
    println!("  exported C functions   {:7.1} ns", c * 1e9);
    println!("  guard (difference)     {:7.1} ns per step, {:.1} ns per call", (c - safe) * 1e9, (c - safe) * 1e9 / 2.0);
}
