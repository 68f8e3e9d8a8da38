//! Many instances at once: 64 FMU instances (through the exported `fmi2*` functions) and
//! 64 direct-API solvers (through `wo_*`), advanced from 8 threads at the same time. Each
//! must produce exactly, bit for bit, what it produces when run alone on one thread:
//! instances share nothing mutable, and nothing depends on scheduling.

use std::sync::{Arc, Barrier};
use wound_opening::capi::error::WoStatus;
use wound_opening::capi::solver_c::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::{GUID, Vr};

const INSTANCES: usize = 64;
const THREADS: usize = 8;
const STEPS: usize = 40;

/// The parameters and inputs of instance `k`: every one a different problem (all inside
/// the model's validity: edge strains below 1).
fn problem(k: usize) -> (f64, f64, f64) {
    let lambdas = [0.0, 0.1, 1.0, 10.0];
    (lambdas[k % 4], 0.5 + (k % 5) as f64 * 0.1, 2.0 + (k % 7) as f64 * 3.0)
}

/// Step `i` of instance `k`: its size and the edge stress held over it.
fn step(k: usize, i: usize) -> (f64, f64) {
    (0.001 * (1 + (i * 7 + k) % 13) as f64 * (1.0 + i as f64), 0.1 * ((i + k) % 3) as f64)
}

/// An FMU instance, movable to another thread (the FMI standard allows an instance to be
/// used from any thread, one call at a time).
struct Fmu(fmi2Component);
unsafe impl Send for Fmu {}

fn check(status: fmi2Status, what: &str) {
    assert_eq!(status, 0, "{what} returned {status}");
}

fn fmu_new(k: usize) -> Fmu {
    let callbacks = fmi2CallbackFunctions::NONE;
    let name = std::ffi::CString::new(format!("instance{k}")).unwrap();
    let guid = std::ffi::CString::new(GUID).unwrap();
    unsafe {
        let c = fmi2Instantiate(name.as_ptr(), 1, guid.as_ptr(), c"".as_ptr(), &callbacks, 0, 0);
        assert!(!c.is_null(), "fmi2Instantiate {k}");
        let (lambda, sigma, r_inf) = problem(k);
        let vr = [Vr::Lambda as u32, Vr::Sigma as u32, Vr::RInf as u32];
        check(fmi2SetReal(c, vr.as_ptr(), 3, [lambda, sigma, r_inf].as_ptr()), "fmi2SetReal");
        check(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), "fmi2SetupExperiment");
        check(fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode");
        check(fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode");
        Fmu(c)
    }
}

/// One step of FMU `k` from `t`; returns the bits of (R, dR/dt) after it.
fn fmu_step(fmu: &Fmu, k: usize, i: usize, t: &mut f64) -> [u64; 2] {
    let (h, p) = step(k, i);
    let mut out = [0.0; 2];
    unsafe {
        check(fmi2SetReal(fmu.0, &(Vr::EdgeStress as u32), 1, &p), "fmi2SetReal(edge_stress)");
        check(fmi2DoStep(fmu.0, *t, h, 1), "fmi2DoStep");
        let vr = [Vr::WoundRadius as u32, Vr::EdgeVelocity as u32];
        check(fmi2GetReal(fmu.0, vr.as_ptr(), 2, out.as_mut_ptr()), "fmi2GetReal");
    }
    *t += h;
    out.map(f64::to_bits)
}

/// A direct-API solver, movable to another thread.
struct Direct(*mut WoSolver);
unsafe impl Send for Direct {}

fn wo_check(status: WoStatus, what: &str) {
    assert_eq!(status, WoStatus::WoOk, "{what}");
}

fn direct_new(k: usize) -> Direct {
    let (lambda, sigma, r_inf) = problem(k);
    let mut s = std::ptr::null_mut();
    unsafe { wo_check(wo_solver_new(lambda, sigma, r_inf, 1e-8, &mut s), "wo_solver_new") };
    Direct(s)
}

fn direct_step(s: &Direct, k: usize, i: usize, t: &mut f64) -> [u64; 2] {
    let (h, p) = step(k, i);
    *t += h;
    let mut out = [0.0; 2];
    unsafe {
        wo_check(wo_solver_advance(s.0, *t, p), "wo_solver_advance");
        wo_check(wo_solver_wound_radius(s.0, &mut out[0]), "wo_solver_wound_radius");
        wo_check(wo_solver_edge_velocity(s.0, &mut out[1]), "wo_solver_edge_velocity");
    }
    out.map(f64::to_bits)
}

/// Run instance `k` alone, start to end, on this thread.
fn alone<T>(
    k: usize,
    new: fn(usize) -> T,
    advance: fn(&T, usize, usize, &mut f64) -> [u64; 2],
) -> (T, Vec<[u64; 2]>) {
    let x = new(k);
    let mut t = 0.0;
    let trace = (0..STEPS).map(|i| advance(&x, k, i, &mut t)).collect();
    (x, trace)
}

/// All instances at once: thread `j` owns instances `j, j + 8, ...` and advances them in
/// turns, one step each, so that every thread's instances are interleaved in time with
/// every other thread's.
fn together<T: Send + 'static>(
    new: fn(usize) -> T,
    advance: fn(&T, usize, usize, &mut f64) -> [u64; 2],
) -> Vec<(usize, T, Vec<[u64; 2]>)> {
    let start = Arc::new(Barrier::new(THREADS));
    let handles: Vec<_> = (0..THREADS)
        .map(|j| {
            let start = Arc::clone(&start);
            std::thread::spawn(move || {
                let mine: Vec<usize> = (j..INSTANCES).step_by(THREADS).collect();
                let xs: Vec<T> = mine.iter().map(|&k| new(k)).collect();
                let mut times = vec![0.0; mine.len()];
                let mut traces = vec![Vec::new(); mine.len()];
                start.wait();
                for i in 0..STEPS {
                    for (n, &k) in mine.iter().enumerate() {
                        traces[n].push(advance(&xs[n], k, i, &mut times[n]));
                    }
                }
                mine.into_iter()
                    .zip(xs)
                    .zip(traces)
                    .map(|((k, x), tr)| (k, x, tr))
                    .collect::<Vec<_>>()
            })
        })
        .collect();
    handles.into_iter().flat_map(|h| h.join().expect("a worker thread panicked")).collect()
}

#[test]
fn sixty_four_fmu_instances_on_eight_threads_match_their_single_threaded_runs_bit_for_bit() {
    let reference: Vec<Vec<[u64; 2]>> = (0..INSTANCES)
        .map(|k| {
            let (fmu, trace) = alone(k, fmu_new, fmu_step);
            unsafe { fmi2FreeInstance(fmu.0) };
            trace
        })
        .collect();
    let finals: std::collections::BTreeSet<[u64; 2]> =
        reference.iter().map(|t| t[STEPS - 1]).collect();
    assert!(
        finals.len() >= 32,
        "the instances should be different problems: {} distinct end states",
        finals.len()
    );
    let results = together(fmu_new, fmu_step);
    assert_eq!(results.len(), INSTANCES);
    for (k, fmu, trace) in results {
        assert_eq!(
            trace,
            reference[k],
            "instance {k} {:?} differs from its single-threaded run",
            problem(k)
        );
        unsafe { fmi2FreeInstance(fmu.0) };
    }
}

#[test]
fn sixty_four_direct_solvers_on_eight_threads_match_their_single_threaded_runs_bit_for_bit() {
    let reference: Vec<Vec<[u64; 2]>> = (0..INSTANCES)
        .map(|k| {
            let (s, trace) = alone(k, direct_new, direct_step);
            unsafe { wo_check(wo_solver_free(s.0), "wo_solver_free") };
            trace
        })
        .collect();
    let results = together(direct_new, direct_step);
    assert_eq!(results.len(), INSTANCES);
    for (k, s, trace) in results {
        assert_eq!(
            trace,
            reference[k],
            "solver {k} {:?} differs from its single-threaded run",
            problem(k)
        );
        unsafe { wo_check(wo_solver_free(s.0), "wo_solver_free") };
    }
}
