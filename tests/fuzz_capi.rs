//! Fuzzing the direct C API through the exported `wo_*` functions: random call sequences
//! with random arguments (special doubles, grids in and out of range including sizes whose
//! product overflows, NULL outputs and arrays, radii inside and outside the tissue, and
//! handles that are live, freed, made up, NULL or of the other kind). Time-bounded: see
//! tests/common/fuzz.rs.
//!
//! What must hold: no crash or hang; every status is a `wo_status`; the thread's last error
//! is empty exactly after a success; no call reaches the panic boundary; a refused call
//! changes nothing (a solver's time and radius are the same before and after it); and once
//! everything is freed the handle tables are empty.

mod common;

use common::fuzz::{Budget, Rng};
use std::collections::BTreeMap;
use std::ffi::CStr;
use wound_opening::boundary::caught_panics;
use wound_opening::capi::error::WoStatus;
use wound_opening::capi::solver::live_handles;
use wound_opening::capi::solver_c::*;

struct World {
    rng: Rng,
    solvers: Vec<*mut WoSolver>,
    states: Vec<*mut WoState>,
    freed: Vec<usize>,
    stats: BTreeMap<&'static str, [u64; 9]>,
}

impl World {
    fn record(&mut self, call: &'static str, status: WoStatus) {
        let message = unsafe { CStr::from_ptr(wo_last_error()) }.to_string_lossy().into_owned();
        assert_eq!(
            status == WoStatus::WoOk,
            message.is_empty(),
            "{call} returned {status:?} with message {message:?}"
        );
        if status != WoStatus::WoOk {
            assert!(
                message.starts_with(call),
                "{call}: message {message:?} does not name the call"
            );
        }
        self.stats.entry(call).or_default()[status as usize] += 1;
    }

    /// Any handle value: mostly live ones of the right kind, sometimes freed, made up,
    /// NULL, or of the other kind.
    fn any(&mut self, live: &[usize], other: &[usize]) -> usize {
        match self.rng.below(10) {
            0 => 0,
            1 if !self.freed.is_empty() => self.rng.pick(&self.freed),
            2 if !other.is_empty() => self.rng.pick(other),
            3 => self.rng.next_u64() as usize,
            _ if !live.is_empty() => self.rng.pick(live),
            _ => self.rng.below(64),
        }
    }

    fn solver(&mut self) -> *mut WoSolver {
        let (live, other) = (self.solver_ids(), self.state_ids());
        self.any(&live, &other) as *mut WoSolver
    }

    fn state(&mut self) -> *mut WoState {
        let (live, other) = (self.state_ids(), self.solver_ids());
        self.any(&live, &other) as *mut WoState
    }

    fn solver_ids(&self) -> Vec<usize> {
        self.solvers.iter().map(|&s| s as usize).collect()
    }

    fn state_ids(&self) -> Vec<usize> {
        self.states.iter().map(|&s| s as usize).collect()
    }

    /// A parameter: mostly a sensible one, sometimes anything.
    fn param(&mut self, sensible: &[f64]) -> f64 {
        if self.rng.chance(0.7) { self.rng.pick(sensible) } else { self.rng.real() }
    }

    fn create(&mut self) {
        if self.solvers.len() >= 8 {
            return;
        }
        let lambda = self.param(&[0.0, 0.1, 1.0, 10.0]);
        let sigma = self.param(&[1.0, -0.5, 2.0]);
        // R_inf stays at most 1e6 when valid: beyond, meshes grow to thousands of unknowns
        // and take seconds to minutes to build before the modal decomposition fails.
        let r_inf = match self.param(&[1.5, 2.0, 10.0, 100.0]) {
            r if r.is_finite() && r > 1e6 => 1e6,
            r => r,
        };
        // Half of the time one common problem, so that saved states fit other solvers.
        let (lambda, sigma, r_inf) =
            if self.rng.chance(0.5) { (1.0, 1.0, 10.0) } else { (lambda, sigma, r_inf) };
        let mut s = std::ptr::null_mut();
        let out: *mut *mut WoSolver =
            if self.rng.chance(0.03) { std::ptr::null_mut() } else { &mut s };
        let (name, status) = if self.rng.chance(0.5) {
            let tol = if (lambda, sigma, r_inf) == (1.0, 1.0, 10.0) {
                1e-9
            } else {
                self.param(&[1e-12, 1e-9, 1e-6, 1e-3, 0.5])
            };
            ("wo_solver_new", unsafe { wo_solver_new(lambda, sigma, r_inf, tol, out) })
        } else {
            let degree = if self.rng.chance(0.9) {
                self.rng.below(40)
            } else {
                self.rng.next_u64() as usize
            };
            let elements = if self.rng.chance(0.9) {
                self.rng.below(14)
            } else {
                self.rng.next_u64() as usize
            };
            let scale = self.param(&[0.05, 0.5, 5.0]);
            ("wo_solver_new_grid", unsafe {
                wo_solver_new_grid(lambda, sigma, r_inf, degree, elements, scale, out)
            })
        };
        self.record(name, status);
        assert_eq!(
            status == WoStatus::WoOk,
            !s.is_null(),
            "{name}: the solver is set exactly on success"
        );
        if !s.is_null() {
            self.solvers.push(s);
        }
    }

    /// Time and radius of a live solver, to check that a refused call changed nothing.
    fn observe(&self, s: *mut WoSolver) -> Option<(u64, u64)> {
        let (mut t, mut r) = (f64::NAN, f64::NAN);
        let ok = unsafe {
            wo_solver_time(s, &mut t) == WoStatus::WoOk
                && wo_solver_wound_radius(s, &mut r) == WoStatus::WoOk
        };
        ok.then(|| (t.to_bits(), r.to_bits()))
    }

    fn step(&mut self) {
        match self.rng.below(16) {
            0 | 1 => self.create(),
            2 => {
                let s = self.solver();
                let status = unsafe { wo_solver_free(s) };
                self.record("wo_solver_free", status);
                if status == WoStatus::WoOk && !s.is_null() {
                    self.solvers.retain(|&x| x != s);
                    self.freed.push(s as usize);
                }
            }
            3..=6 => {
                let s = self.solver();
                let before = self.observe(s);
                let mut t = 0.0;
                unsafe { wo_solver_time(s, &mut t) };
                let t_end = if self.rng.chance(0.8) {
                    t + self.rng.unit() * self.rng.pick(&[0.01, 1.0, 100.0])
                } else {
                    self.rng.real()
                };
                let p = self.param(&[0.0, 0.2, -1.0]);
                let status = unsafe { wo_solver_advance(s, t_end, p) };
                self.record("wo_solver_advance", status);
                // WO_OUTSIDE_VALIDITY is a warning: the advance was done.
                if status != WoStatus::WoOk && status != WoStatus::WoOutsideValidity {
                    assert_eq!(
                        self.observe(s),
                        before,
                        "a refused wo_solver_advance changed the solver"
                    );
                }
            }
            7 | 8 => self.read_scalars(),
            9 | 10 => self.profiles(),
            11 | 12 => {
                let s = self.solver();
                let mut st = std::ptr::null_mut();
                let out: *mut *mut WoState =
                    if self.rng.chance(0.03) { std::ptr::null_mut() } else { &mut st };
                let status = unsafe { wo_solver_save_state(s, out) };
                self.record("wo_solver_save_state", status);
                if !st.is_null() {
                    self.states.push(st);
                }
            }
            13 | 14 => {
                let (s, st) = (self.solver(), self.state());
                let before = self.observe(s);
                let status = unsafe { wo_solver_restore_state(s, st) };
                self.record("wo_solver_restore_state", status);
                if status != WoStatus::WoOk {
                    assert_eq!(
                        self.observe(s),
                        before,
                        "a refused wo_solver_restore_state changed the solver"
                    );
                }
            }
            _ => {
                let st = self.state();
                let status = unsafe { wo_state_free(st) };
                self.record("wo_state_free", status);
                if status == WoStatus::WoOk && !st.is_null() {
                    self.states.retain(|&x| x != st);
                    self.freed.push(st as usize);
                }
            }
        }
    }

    fn read_scalars(&mut self) {
        let s = self.solver();
        let mut x = 0.0;
        let mut n = 0usize;
        let null = self.rng.chance(0.05);
        let px: *mut f64 = if null { std::ptr::null_mut() } else { &mut x };
        let (name, status) = match self.rng.below(4) {
            0 => ("wo_solver_time", unsafe { wo_solver_time(s, px) }),
            1 => ("wo_solver_wound_radius", unsafe { wo_solver_wound_radius(s, px) }),
            2 => ("wo_solver_edge_velocity", unsafe { wo_solver_edge_velocity(s, px) }),
            _ => ("wo_solver_node_count", unsafe {
                wo_solver_node_count(s, if null { std::ptr::null_mut() } else { &mut n })
            }),
        };
        self.record(name, status);
    }

    fn profiles(&mut self) {
        let s = self.solver();
        let mut n = 0usize;
        let counted = unsafe { wo_solver_node_count(s, &mut n) } == WoStatus::WoOk;
        let count = if counted && self.rng.chance(0.7) { n } else { self.rng.below(12) };
        let mut radii: Vec<f64> =
            (0..count)
                .map(|_| {
                    if self.rng.chance(0.9) { 1.0 + 9.0 * self.rng.unit() } else { self.rng.real() }
                })
                .collect();
        let mut out = vec![0.0; count];
        let null_in = self.rng.chance(0.05);
        let null_out = self.rng.chance(0.05);
        let r: *const f64 = if null_in { std::ptr::null() } else { radii.as_ptr() };
        let o: *mut f64 = if null_out { std::ptr::null_mut() } else { out.as_mut_ptr() };
        let (name, status) = match self.rng.below(4) {
            0 => ("wo_solver_nodes", unsafe { wo_solver_nodes(s, o, count) }),
            1 => ("wo_solver_displacement", unsafe { wo_solver_displacement(s, r, o, count) }),
            2 => ("wo_solver_velocity", unsafe { wo_solver_velocity(s, r, o, count) }),
            // In place: the output array is the radii array.
            _ => ("wo_solver_displacement", unsafe {
                wo_solver_displacement(s, radii.as_ptr(), radii.as_mut_ptr(), count)
            }),
        };
        self.record(name, status);
    }
}

#[test]
fn random_direct_api_call_sequences_are_refused_cleanly_or_succeed() {
    let budget = Budget::from_env(0xCA_2024);
    let mut world = World {
        rng: Rng::new(budget.seed),
        solvers: Vec::new(),
        states: Vec::new(),
        freed: Vec::new(),
        stats: BTreeMap::new(),
    };
    let mut iterations = 0u64;
    while budget.left() {
        world.step();
        iterations += 1;
        assert_eq!(
            caught_panics(),
            0,
            "seed {}: iteration {iterations} reached the panic boundary",
            budget.seed
        );
    }
    for s in world.solvers.drain(..) {
        assert_eq!(unsafe { wo_solver_free(s) }, WoStatus::WoOk);
    }
    for st in world.states.drain(..) {
        assert_eq!(unsafe { wo_state_free(st) }, WoStatus::WoOk);
    }
    assert_eq!(live_handles(), (0, 0), "everything freed leaves the handle tables empty");
    println!("direct API call sequences: seed {}, {iterations} iterations", budget.seed);
    let names = [
        "ok",
        "null",
        "invalid",
        "unknown handle",
        "incompatible",
        "solver failed",
        "internal",
        "undefined",
    ];
    for (call, counts) in &world.stats {
        let text: Vec<String> = names
            .iter()
            .zip(counts)
            .filter(|(_, c)| **c > 0)
            .map(|(n, c)| format!("{n} {c}"))
            .collect();
        println!("  {call:26} {}", text.join(", "));
    }
    let advanced = world.stats.get("wo_solver_advance").map_or(0, |c| c[0]);
    let restored = world.stats.get("wo_solver_restore_state").map_or(0, |c| c[0]);
    assert!(
        iterations < 2000 || (advanced > 0 && restored > 0),
        "the fuzzer should reach advances and restores"
    );
}

#[test]
fn the_generator_is_deterministic_and_spreads() {
    let (mut a, mut b) = (common::fuzz::Rng::new(7), common::fuzz::Rng::new(7));
    let xs: Vec<u64> = (0..1000).map(|_| a.next_u64()).collect();
    assert!(xs.iter().all(|&x| x == b.next_u64()), "same seed, same sequence");
    let mut counts = [0usize; 10];
    (0..10_000).for_each(|_| counts[a.below(10)] += 1);
    // 10 000 draws in 10 bins: each near 1000 (5 standard deviations is about 150).
    assert!(counts.iter().all(|&c| (850..1150).contains(&c)), "{counts:?}");
}
