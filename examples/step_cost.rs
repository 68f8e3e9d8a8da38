//! Cost of one communication step and of the whole scenario, in-process: through the
//! solver API and through the exported FMI functions (as a C master would call them).
//!
//! Usage: `cargo run --release --example step_cost -- DIR`; writes DIR/step_cost.csv
//! (`what,seconds`: CPU seconds per step or per scenario, best of several repeats).

#[path = "common/bench_util.rs"]
mod bench_util;

use bench_util::*;
use std::ffi::CString;
use std::io::Write;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::GUID;
use wound_opening::solver::{Params, Scheme, Settings, Solver};

const STEPS_TIMED: usize = 100_000;

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: step_cost DIR"));
    let mut csv = std::fs::File::create(dir.join("step_cost.csv")).expect("writable DIR");
    writeln!(csv, "what,seconds").unwrap();
    let mut row = |what: &str, seconds: f64| {
        writeln!(csv, "{what},{seconds:e}").unwrap();
        println!("{what:<40} {:>10.1} ns", seconds * 1e9);
    };
    let params = Params { lambda: 1.0, sigma: SIGMA, r_inf: R_INF };
    let settings = Settings::for_tolerance(&params, 1e-9).expect("valid");

    // The whole scenario at tolerance 1e-9: set-up (assembly, eigen-decomposition) + 1000 steps.
    let (cpu, _) = best_cpu(|| scenario(1.0, &Scheme::Modal(settings)));
    row("modal_scenario_in_process", cpu);
    // Set-up from scratch (assembly and decomposition), and with the basis cached (a new
    // lambda or instance at a known outer radius: src/solver/basis.rs).
    let (cpu, _) = best_cpu(|| {
        wound_opening::solver::basis::clear();
        Solver::new(&params, &settings).expect("valid")
    });
    row("modal_setup_in_process_cold", cpu);
    let (cpu, _) = best_cpu(|| Solver::new(&params, &settings).expect("valid"));
    row("modal_setup_in_process_cached_basis", cpu);

    // One step through the solver API.
    let mut s = Solver::new(&params, &settings).expect("valid");
    let (cpu, _) = best_cpu(|| {
        for _ in 0..STEPS_TIMED {
            s.advance(1e-4, 0.0).expect("valid");
        }
        s.wound_radius()
    });
    row("modal_advance_in_process", cpu / STEPS_TIMED as f64);

    // One fmi2DoStep + fmi2GetReal of both outputs through the C ABI.
    let name = CString::new("bench").unwrap();
    let guid = CString::new(GUID).unwrap();
    let callbacks = fmi2CallbackFunctions::NONE;
    // SAFETY: valid strings and callbacks; the instance is freed at the end.
    unsafe {
        let c = fmi2Instantiate(
            name.as_ptr(),
            FMI2_CO_SIMULATION,
            guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            0,
            0,
        );
        assert!(!c.is_null());
        let tol = 1e-9;
        assert_eq!(fmi2SetupExperiment(c, 1, tol, 0.0, 0, 0.0), 0);
        assert_eq!(fmi2EnterInitializationMode(c), 0);
        assert_eq!(fmi2ExitInitializationMode(c), 0);
        row("modal_doStep_getReal_in_process", exported_step_seconds(c, 0.0, STEPS_TIMED));
        fmi2FreeInstance(c);
    }
}
