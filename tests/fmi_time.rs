//! Master time through the exported functions: the master's communication points are
//! taken as the truth within a tolerance (not compared with a sum of step sizes), the stop
//! time is checked with the same tolerance, and every model counts its time from
//! `startTime` (the cut). Release mode: `cargo test --release --test fmi_time`.

mod common;

use common::fmi::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::purse_string::variables::Vr as P;
use wound_opening::models::wound::variables::Vr as W;

/// Guards against refusing a master that computes its points as t_n = n h: the instance
/// summed the step sizes and demanded the point within 1e-12 relative of that sum, which
/// drifts apart from n h and was refused at step 66,460 (h = 0.1). All 10^6 steps are
/// accepted, and the clock ends at the master's own last point plus the last step,
/// (n - 1) h + h, which is n h to one unit in the last place (the master's next point
/// n h would be accepted and adopted).
#[test]
fn a_million_steps_at_points_n_h_are_all_accepted() {
    let c = initialized(WOUND, 0.0, &[]);
    let (n, h) = (1_000_000u32, 0.1);
    for k in 0..n {
        let t = k as f64 * h;
        let s = unsafe { fmi2DoStep(c, t, h, 1) };
        assert_eq!(s, OK, "fmi2DoStep at step {k}, t = {t}");
    }
    let (s, last) = last_successful_time(c);
    assert_eq!(s, OK);
    assert_eq!(last, (n - 1) as f64 * h + h, "the master's last point plus its step");
    let want = n as f64 * h;
    assert!((last - want).abs() <= want * f64::EPSILON, "{last} is n h = {want} to one ulp");
    let (s, r) = get_real(c, W::WoundRadius as u32);
    assert!(s == OK && r.is_finite(), "{s} {r}");
    unsafe { fmi2FreeInstance(c) };
}

/// Guards against a tolerance so loose that a wrong point is accepted: a point off by
/// more than 1e-6 h (plus 4 eps |t|) is refused, one within it is adopted.
#[test]
fn a_point_off_by_more_than_the_tolerance_is_refused_and_one_within_it_adopted() {
    let c = initialized(WOUND, 0.0, &[]);
    let h = 0.5;
    unsafe {
        assert_eq!(fmi2DoStep(c, 0.0, h, 1), OK);
        assert_eq!(fmi2DoStep(c, h + 2e-6 * h, h, 1), ERROR);
        assert_eq!(fmi2DoStep(c, h - 2e-6 * h, h, 1), ERROR);
        assert_eq!(last_successful_time(c), (OK, h));
        let near = h + 0.5e-6 * h;
        assert_eq!(fmi2DoStep(c, near, h, 1), OK);
        assert_eq!(last_successful_time(c), (OK, near + h), "the master's point is adopted");
        fmi2FreeInstance(c);
    }
}

/// Guards against a stop-time check with another rule than the communication point's:
/// steps t_n = n h reach stopTime = 100 exactly as the master counts (the last ends a few
/// ulps from 100), a step beyond it by more than the tolerance is refused.
#[test]
fn the_stop_time_is_checked_with_the_same_tolerance() {
    let c = instantiate(WOUND, "stop");
    let h = 0.1;
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 1, 100.0), OK);
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
        for k in 0..1000 {
            assert_eq!(fmi2DoStep(c, k as f64 * h, h, 1), OK, "step {k}");
        }
        let mut done = FMI2_FALSE;
        assert_eq!(fmi2GetBooleanStatus(c, FMI2_TERMINATED, &mut done), OK);
        assert_eq!(done, FMI2_TRUE, "stop time reached");
        assert_eq!(fmi2DoStep(c, 100.0, h, 1), ERROR, "past the stop time");
        fmi2FreeInstance(c);
    }
    let c = instantiate(WOUND, "stop");
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 1, 1.0), OK);
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
        assert_eq!(fmi2DoStep(c, 0.0, 1.0 + 2e-6, 1), ERROR, "beyond stopTime by 2e-6 h");
        assert_eq!(fmi2DoStep(c, 0.0, 1.0 + 0.5e-6, 1), OK, "within the tolerance");
        fmi2FreeInstance(c);
    }
}

/// Outputs after stepping from `start` in steps `h`, at each point.
fn run(
    guid: &str,
    start: f64,
    params: &[(u32, f64)],
    h: f64,
    n: u32,
    outputs: &[u32],
) -> Vec<Vec<f64>> {
    let c = initialized(guid, start, params);
    let rows = (0..n)
        .map(|k| {
            assert_eq!(unsafe { fmi2DoStep(c, start + k as f64 * h, h, 1) }, OK);
            outputs.iter().map(|&vr| get_real(c, vr).1).collect()
        })
        .collect();
    unsafe { fmi2FreeInstance(c) };
    rows
}

/// Guards against the two FMUs disagreeing on when the cut is: PurseString counted its
/// delay from master time 0, WoundOpening from startTime. With startTime = 5 the cable
/// starts at 5 + t_delay and reaches 1 - 1/e of T_max one t_assembly later, and the
/// wound is the same as with startTime = 0, shifted by 5, bit for bit.
#[test]
fn both_models_count_time_from_the_start_time() {
    let (t_max, t_delay, t_assembly) = (6500.0, 20.0, 30.0);
    let params = [
        (P::MaxTension as u32, t_max),
        (P::Delay as u32, t_delay),
        (P::AssemblyTime as u32, t_assembly),
    ];
    let h = 0.5;
    let tension = run(PURSE, 5.0, &params, h, 100, &[P::LineTension as u32]);
    let at = |t: f64| tension[((t - 5.0) / h) as usize - 1][0];
    assert_eq!(at(5.0 + t_delay), 0.0, "no tension until t_delay after startTime");
    assert!(at(5.0 + t_delay + h) > 0.0);
    let want = t_max * (1.0 - (-1.0f64).exp());
    let got = at(5.0 + t_delay + t_assembly);
    assert!(
        (got - want).abs() <= 1e-12 * want,
        "T_c(startTime + t_delay + t_assembly) = {got}, expected {want}"
    );

    let outputs = [W::WoundRadius as u32, W::EdgeVelocity as u32];
    let shifted = run(WOUND, 5.0, &[], 0.25, 40, &outputs);
    assert_eq!(shifted, run(WOUND, 0.0, &[], 0.25, 40, &outputs));
}
