//! Model Exchange outputs are functions of (time, states, inputs) and the discrete
//! reference alone, whatever the sequence of Set calls; the directional derivatives match
//! difference quotients of them; an edge stress that jumps in Event Mode moves the
//! reference and says so (`valuesOfContinuousStatesChanged`, nominals only there), after
//! which the states are 0 and setting the time alone follows the exact-in-time
//! co-simulation under the same piecewise input (src/models/wound/exchange.rs).
//! fmpy's CVode and a master that restarts only when told: tests/python/test_me_events.py.

mod common;

use common::fmi::*;
use wound_opening::fmi::fmi2::exchange::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::{DESCRIPTION, MODEL_EXCHANGE_STATES as NX, Vr};

const EDGE: u32 = Vr::EdgeStress as u32;
const VELOCITY: u32 = Vr::EdgeVelocity as u32;
const RADIUS: u32 = Vr::WoundRadius as u32;

fn state_vr(k: usize) -> u32 {
    DESCRIPTION.first_state() + k as u32
}

/// `fmi2NewDiscreteStates` in Event Mode: (values changed, nominals changed).
fn event(c: fmi2Component) -> (bool, bool) {
    let mut info: fmi2EventInfo = unsafe { std::mem::zeroed() };
    assert_eq!(unsafe { fmi2NewDiscreteStates(c, &mut info) }, OK);
    assert_eq!(
        (info.newDiscreteStatesNeeded, info.terminateSimulation, info.nextEventTimeDefined),
        (0, 0, 0)
    );
    (info.valuesOfContinuousStatesChanged != 0, info.nominalsOfContinuousStatesChanged != 0)
}

fn states(c: fmi2Component) -> Vec<f64> {
    let mut x = vec![f64::NAN; NX];
    assert_eq!(unsafe { fmi2GetContinuousStates(c, x.as_mut_ptr(), NX) }, OK);
    x
}

fn nominals(c: fmi2Component) -> Vec<f64> {
    let mut x = vec![f64::NAN; NX];
    assert_eq!(unsafe { fmi2GetNominalsOfContinuousStates(c, x.as_mut_ptr(), NX) }, OK);
    x
}

fn real(c: fmi2Component, vr: u32) -> f64 {
    let (status, x) = get_real(c, vr);
    assert_eq!(status, OK);
    x
}

fn directional(c: fmi2Component, unknown: u32, known: u32) -> f64 {
    let (mut out, seed) = (f64::NAN, 1.0);
    assert_eq!(
        unsafe { fmi2GetDirectionalDerivative(c, &unknown, 1, &known, 1, &seed, &mut out) },
        OK
    );
    out
}

/// An evolved state at t = 0.6 under a changed edge stress: departures of every size.
fn evolve(c: fmi2Component, p: f64) {
    assert_eq!(set_real(c, EDGE, p), OK);
    assert_eq!(unsafe { fmi2SetTime(c, 0.6) }, OK);
    let x: Vec<f64> = (0..NX).map(|k| 1e-3 * (-0.1 * k as f64).exp()).collect();
    assert_eq!(unsafe { fmi2SetContinuousStates(c, x.as_ptr(), NX) }, OK);
}

/// The issue this guards: the edge velocity after an input change depended on whether
/// identical states were set again (-1249.9 then -88.8 at lambda 1e-4).
#[test]
fn outputs_do_not_depend_on_the_sequence_of_set_calls() {
    for lambda in [1e-4, 0.0, 0.1, 1.0] {
        let c = continuous_time(&[(Vr::Lambda as u32, lambda)]);
        assert_eq!(unsafe { fmi2SetTime(c, 0.5) }, OK);
        evolve(c, 0.1);
        let x = states(c);
        assert_eq!(set_real(c, EDGE, 0.6), OK);
        let first = [real(c, RADIUS), real(c, VELOCITY)];
        assert_eq!(unsafe { fmi2SetContinuousStates(c, x.as_ptr(), NX) }, OK);
        let again = [real(c, RADIUS), real(c, VELOCITY)];
        assert_eq!(unsafe { fmi2SetTime(c, 0.6) }, OK);
        let time_again = [real(c, RADIUS), real(c, VELOCITY)];
        // One state set alone, back to its value, and the input set twice.
        assert_eq!(set_real(c, state_vr(0), x[0] + 1e-3), OK);
        assert_eq!(set_real(c, state_vr(0), x[0]), OK);
        assert_eq!(set_real(c, EDGE, 0.3), OK);
        assert_eq!(set_real(c, EDGE, 0.6), OK);
        let one_by_one = [real(c, RADIUS), real(c, VELOCITY)];
        for (what, got) in [
            ("states set again", again),
            ("time set again", time_again),
            ("one state and the input", one_by_one),
        ] {
            for (a, b) in first.iter().zip(got) {
                assert!(
                    (a - b).abs() <= 1e-12 * a.abs().max(1e-300),
                    "lambda {lambda}, {what}: {a} vs {b}"
                );
            }
        }
        unsafe { fmi2FreeInstance(c) };
    }
}

/// d edge_velocity / d edge_stress and d output / d state against central differences of
/// the outputs, at the cut (the closed-form instantaneous response) and after it (the ODE's
/// own dR/dt, affine in the edge stress and the states).
#[test]
fn directional_derivatives_match_differences_of_the_outputs() {
    for lambda in [1e-4, 0.1, 1.0] {
        let c = continuous_time(&[(Vr::Lambda as u32, lambda)]);
        for t in [0.0, 0.5] {
            if t > 0.0 {
                assert_eq!(unsafe { fmi2SetTime(c, t) }, OK);
                evolve(c, 0.2);
            }
            let (p, h) = (real(c, EDGE), 1e-3);
            let v = |p: f64| {
                assert_eq!(set_real(c, EDGE, p), OK);
                real(c, VELOCITY)
            };
            let fd = (v(p + h) - v(p - h)) / (2.0 * h);
            v(p);
            let dd = directional(c, VELOCITY, EDGE);
            assert!(
                (dd - fd).abs() <= 1e-7 * fd.abs(),
                "lambda {lambda}, t {t}: d edge_velocity / d edge_stress {dd} vs {fd}"
            );
            let x = states(c);
            let (k, dy) = (0, 1e-6);
            let out = |y: f64| {
                assert_eq!(set_real(c, state_vr(k), y), OK);
                [real(c, RADIUS), real(c, VELOCITY)]
            };
            let (up, down) = (out(x[k] + dy), out(x[k] - dy));
            out(x[k]);
            for (i, vr) in [RADIUS, VELOCITY].into_iter().enumerate() {
                let fd = (up[i] - down[i]) / (2.0 * dy);
                let dd = directional(c, vr, state_vr(k));
                assert!(
                    (dd - fd).abs() <= 1e-6 * fd.abs().max(1e-3),
                    "lambda {lambda}, t {t}, output {vr} / state {k}: {dd} vs {fd}"
                );
            }
        }
        unsafe { fmi2FreeInstance(c) };
    }
}

/// A piecewise-constant edge stress with an event at each jump: the reference moves, the
/// flags say so, the states are 0 after each event, and setting the time alone follows the
/// co-simulation under the same input (exact in time) to rounding.
#[test]
fn a_jump_in_event_mode_moves_the_reference_and_says_so() {
    let pieces = [(0.0, 0.0), (0.8, 3.0), (2.0, -0.5), (3.5, 0.5)];
    for lambda in [0.0, 1e-4, 1.0] {
        let me = continuous_time(&[(Vr::Lambda as u32, lambda)]);
        let cs = initialized(WOUND, 0.0, &[(Vr::Lambda as u32, lambda)]);
        let mut now = 0.0;
        for (n, &(start, p)) in pieces.iter().enumerate() {
            if n > 0 {
                // At the jump, the input held up to it: the states are 0.
                assert_eq!(now, start);
                assert!(states(me).iter().all(|&y| y == 0.0));
                let (r_before, n_before) = (real(me, RADIUS), nominals(me));
                assert_eq!(unsafe { fmi2EnterEventMode(me) }, OK);
                assert_eq!(set_real(me, EDGE, p), OK);
                // The states were 0 and are 0 under the new reference: their values did not
                // change (and their derivatives stay 0: the integrator meets no jump).
                let (values, nominal) = event(me);
                assert!(!values, "lambda {lambda}: the states stay 0 at the jump to {p}");
                assert_eq!(
                    nominal,
                    nominals(me) != n_before,
                    "lambda {lambda}: the nominals flag says whether they moved"
                );
                assert_eq!(event(me), (false, false), "nothing more to update");
                assert_eq!(unsafe { fmi2EnterContinuousTimeMode(me) }, OK);
                assert!(states(me).iter().all(|&y| y == 0.0), "0 after the event");
                assert_eq!(real(me, RADIUS), r_before, "the radius is continuous");
                assert_eq!(set_real(cs, EDGE, p), OK);
            }
            let end = pieces.get(n + 1).map_or(5.0, |q| q.0);
            for k in 1..=4 {
                let t = now + (end - now) * k as f64 / 4.0;
                assert_eq!(unsafe { fmi2SetTime(me, t) }, OK);
            }
            assert_eq!(unsafe { fmi2DoStep(cs, now, end - now, 1) }, OK);
            now = end;
            let (r_me, r_cs) = (real(me, RADIUS), real(cs, RADIUS));
            assert!(
                (r_me - r_cs).abs() <= 1e-13,
                "lambda {lambda}, t {end}: ME {r_me} vs co-simulation {r_cs}"
            );
            let mut dx = vec![f64::NAN; NX];
            assert_eq!(unsafe { fmi2GetDerivatives(me, dx.as_mut_ptr(), NX) }, OK);
            assert!(dx.iter().all(|&d| d == 0.0), "nothing to integrate while the input is held");
        }
        // States that departed (an integrator under an input that varied continuously): an
        // event sets them to 0 under the new reference and says so; the radius stays.
        let x: Vec<f64> = (0..NX).map(|k| 1e-3 * (-0.1 * k as f64).exp()).collect();
        assert_eq!(unsafe { fmi2SetContinuousStates(me, x.as_ptr(), NX) }, OK);
        let r_before = real(me, RADIUS);
        assert_eq!(unsafe { fmi2EnterEventMode(me) }, OK);
        assert_eq!(event(me), (false, false), "the same edge stress: no new reference");
        assert_eq!(set_real(me, EDGE, 1.5), OK);
        assert_eq!(event(me), (true, true), "lambda {lambda}: states and nominals changed");
        // The mesh's modes are 0 under the new reference; the inert spare states stay as set.
        let y = states(me);
        let used = y.iter().position(|&v| v != 0.0).unwrap_or(NX);
        assert!(
            used >= 40 && y[used..] == x[used..],
            "lambda {lambda}: modes 0 up to {used}, then the spare states"
        );
        assert_eq!(real(me, RADIUS), r_before, "the radius is continuous");
        unsafe {
            fmi2FreeInstance(me);
            fmi2FreeInstance(cs);
        }
    }
}
