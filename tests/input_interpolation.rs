//! An edge stress linear in time over a step (`fmi2SetRealInputDerivatives`,
//! `canInterpolateInputs`): the modal step is exact for it (closed form in
//! `solver/exact_time.rs`), so splitting a step changes nothing beyond rounding, and many
//! small held steps converge to it; through FMI the input ends the step at its value
//! there; refusals and FMU states. The coupling order it buys: tests/python/test_coupling.py.

mod common;

use common::fmi::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::Vr;
use wound_opening::solver::{Params, Settings, Solver};

fn solver(lambda: f64) -> Solver {
    let params = Params { lambda, sigma: 1.0, r_inf: 10.0 };
    Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap()
}

/// Exact in time: one step of h equals two of h/2 (the second starting from the stress the
/// first ends at) to rounding, 1e-14 of the radius, for every lambda of the paper.
#[test]
fn a_linear_step_splits_exactly() {
    let (h, p0, p1) = (0.7, 0.2, -0.5);
    for lambda in [0.0, 0.1, 1.0, 10.0] {
        let (mut one, mut two) = (solver(lambda), solver(lambda));
        one.advance(0.3, 0.1).unwrap();
        two.advance(0.3, 0.1).unwrap();
        one.advance_linear(h, p0, p1).unwrap();
        two.advance_linear(h / 2.0, p0, p1).unwrap();
        two.advance_linear(h / 2.0, p0 + p1 * h / 2.0, p1).unwrap();
        let (a, b) = (one.wound_radius(), two.wound_radius());
        assert!((a - b).abs() < 1e-14, "lambda = {lambda}: {a} vs {b}");
        // The velocity split's reference is the final stress: velocities agree too.
        let p_end = p0 + p1 * h;
        let (va, vb) = (one.edge_velocity(p_end), two.edge_velocity(p_end));
        assert!((va - vb).abs() < 1e-12 * va.abs().max(1.0), "lambda = {lambda}: {va} vs {vb}");
    }
}

/// Held steps at the midpoint stress converge to the linear step with order 2 (measured:
/// 1.16e-5 with 40 substeps, 1.16e-7 with 400, order 2.000): the linear step is their
/// limit, not an approximation of its own. Order within 0.05 of 2.
#[test]
fn midpoint_held_steps_converge_to_the_linear_step_with_order_two() {
    let (h, p0, p1, lambda) = (2.0, 0.0, 0.4, 1.0);
    let mut exact = solver(lambda);
    exact.advance_linear(h, p0, p1).unwrap();
    let held = |n: usize| {
        let mut s = solver(lambda);
        let dt = h / n as f64;
        for i in 0..n {
            s.advance(dt, p0 + p1 * (i as f64 + 0.5) * dt).unwrap();
        }
        (s.wound_radius() - exact.wound_radius()).abs()
    };
    let (e40, e400) = (held(40), held(400));
    let order = (e40 / e400).log10();
    println!("held midpoint steps: error {e40:.3e} (40), {e400:.3e} (400), order {order:.3}");
    assert!((order - 2.0).abs() < 0.05, "{order}");
    assert!(e400 < 1e-6);
}

fn set_rate(c: fmi2Component, vr: u32, order: i32, rate: f64) -> fmi2Status {
    unsafe { fmi2SetRealInputDerivatives(c, &vr, 1, &order, &rate) }
}

/// Through FMI: the step follows the ramp (same radius as the solver's linear step, in
/// physical units), edge_stress ends at p0 + rate h, fmi2SetReal of the input resets the
/// rate, and an FMU state carries the rate.
#[test]
fn fmu_follows_the_ramp_and_resets_it_on_set() {
    let (t_scale, g) = (10.0, 100.0);
    let params =
        [(Vr::TimeScale as u32, t_scale), (Vr::StressScale as u32, g), (Vr::Lambda as u32, 0.5)];
    let c = initialized(WOUND, 0.0, &params);
    let es = Vr::EdgeStress as u32;
    assert_eq!(set_real(c, es, 10.0), OK);
    assert_eq!(set_rate(c, es, 1, 4.0), OK);
    let (s, state) = get_state(c);
    assert_eq!(s, OK);
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 5.0, 1) }, OK);
    assert_eq!(get_real(c, es), (OK, 30.0), "10 Pa + 4 Pa/s * 5 s");
    let (_, r) = get_real(c, Vr::WoundRadius as u32);
    let mut s = solver(0.5);
    s.advance_linear(0.5, 0.1, 4.0 * t_scale / g).unwrap();
    assert!((r - s.wound_radius()).abs() < 1e-15, "{r} vs {}", s.wound_radius());
    // The rate persists: the next step continues the ramp.
    assert_eq!(unsafe { fmi2DoStep(c, 5.0, 5.0, 1) }, OK);
    assert_eq!(get_real(c, es), (OK, 50.0));
    // fmi2SetReal resets it: held from here.
    assert_eq!(set_real(c, es, 50.0), OK);
    assert_eq!(unsafe { fmi2DoStep(c, 10.0, 5.0, 1) }, OK);
    assert_eq!(get_real(c, es), (OK, 50.0));
    // Back to the saved state (rate 4 Pa/s set): the first step again.
    assert_eq!(unsafe { fmi2SetFMUstate(c, state) }, OK);
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 5.0, 1) }, OK);
    assert_eq!(get_real(c, es), (OK, 30.0));
    assert_eq!(get_real(c, Vr::WoundRadius as u32), (OK, r));
    unsafe { fmi2FreeInstance(c) };
}

/// Refused: order 2, a non-input, NaN, a ramp leaving the accepted edge stress range in
/// the step (the step is refused and nothing changes), method 1 (held steps only).
#[test]
fn refuses_what_it_cannot_integrate_exactly() {
    let c = initialized(WOUND, 0.0, &[]);
    let es = Vr::EdgeStress as u32;
    assert_eq!(set_rate(c, es, 2, 1.0), ERROR, "order 2");
    assert_eq!(set_rate(c, Vr::WoundRadius as u32, 1, 1.0), ERROR, "an output");
    assert_eq!(set_rate(c, Vr::Lambda as u32, 1, 1.0), ERROR, "a parameter");
    assert_eq!(set_rate(c, es, 1, f64::NAN), ERROR, "NaN");
    assert_eq!(set_rate(c, es, 1, 1e300), OK);
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 1.0, 1) }, ERROR, "ends outside |edge_stress| <= 1e6 G");
    assert_eq!(last_successful_time(c), (OK, 0.0));
    assert_eq!(get_real(c, es), (OK, 0.0));
    unsafe { fmi2FreeInstance(c) };
    let c = instantiate(WOUND, "method 1");
    unsafe {
        let (vr, one) = (Vr::Method as u32, 1);
        assert_eq!(fmi2SetInteger(c, &vr, 1, &one), OK);
    }
    assert_eq!(set_rate(c, es, 1, 1.0), ERROR, "method 1 holds the input");
    unsafe { fmi2FreeInstance(c) };
    // PurseString moves its wound_radius input along the rate.
    let p = initialized(PURSE, 0.0, &[]);
    assert_eq!(set_rate(p, 4, 1, -0.5), OK);
    assert_eq!(unsafe { fmi2DoStep(p, 0.0, 2.0, 1) }, OK);
    assert_eq!(get_real(p, 4), (OK, 9.0));
    unsafe { fmi2FreeInstance(p) };
}
