//! The validity check's three numbers, `u(1)`, `du/dr(1)` and `u(R_inf)`, read in O(modes)
//! from the modal state, against the exact solution: uniform tension `u = sigma r / 6` at the
//! cut and the final state `u = a r + b / r` (`du/dr(1) = a - b`) long after; and the check on
//! the other schemes (a difference quotient of their displacement).

use wound_opening::solver::validity::{STRAIN_MAX, violation};
use wound_opening::solver::{Params, Scheme, Settings, Solver, exact};

fn final_edges(sigma: f64, r_inf: f64) -> [f64; 3] {
    let u = |r: f64| exact::final_displacement(sigma, r_inf, r);
    // u = a r + b / r: du/dr(1) = a - b, from two values (u(1) = a + b, u(2) = 2 a + b / 2).
    let (u1, u2) = (u(1.0), u(2.0));
    let a = (2.0 * u2 - u1) / 3.0;
    let b = u1 - a;
    [u1, a - b, u(r_inf)]
}

#[test]
fn edges_at_the_cut_and_in_the_final_state_match_the_exact_solution() {
    for (lambda, sigma, r_inf) in
        [(0.3, 0.7, 6.2), (2.0, -1.1, 31.0), (0.0, 0.5, 1.7), (7.0, 0.2, 250.0)]
    {
        let params = Params { lambda, sigma, r_inf };
        let mut s =
            Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
        let e = s.edges(r_inf);
        let cut = [sigma / 6.0, sigma / 6.0, sigma * r_inf / 6.0];
        for (got, want) in [e.edge, e.edge_slope, e.outer].iter().zip(cut) {
            assert!((got - want).abs() < 1e-12 * (1.0 + want.abs()), "cut {got} {want}");
        }
        s.advance(1e9 * (1.0 + lambda * lambda) * r_inf * r_inf, 0.0).unwrap();
        let e = s.edges(r_inf);
        let want = final_edges(sigma, r_inf);
        for (got, want) in [e.edge, e.edge_slope, e.outer].iter().zip(want) {
            assert!(
                (got - want).abs() < 1e-8 * sigma.abs(),
                "final {got} {want} ({lambda}, {sigma}, {r_inf})"
            );
        }
        assert_eq!(s.validity_violation(r_inf), None);
    }
}

#[test]
fn a_closing_wound_and_a_thin_ring_leave_the_validity() {
    let run = |lambda, sigma, r_inf, t| {
        let params = Params { lambda, sigma, r_inf };
        let mut s = Solver::new(&params, &Settings::for_tolerance(&params, 1e-8).unwrap()).unwrap();
        s.advance(t, 0.0).unwrap();
        s.validity_violation(r_inf)
    };
    assert!(run(1.0, -2.0, 10.0, 1000.0).unwrap().contains("wound radius is -0.34"));
    let thin = run(1.0, 1.0, 1.01, 1000.0).unwrap();
    assert!(thin.contains("folds") || thin.contains("strain"), "{thin}");
    assert_eq!(run(1.0, 1.0, 10.0, 1000.0), None);
    assert_eq!(STRAIN_MAX, 1.0);
}

#[test]
fn the_comparison_schemes_check_by_difference() {
    let params = Params { lambda: 1.0, sigma: -2.0, r_inf: 10.0 };
    let mut s =
        Solver::with_scheme(&params, &Scheme::Paper { points: 201, max_step: 1e-2 }).unwrap();
    s.advance(200.0, 0.0).unwrap();
    let e = s.edges(10.0);
    assert!(e.edge < -1.0, "{e:?}");
    assert!(violation(e, 10.0).unwrap().contains("wound radius"));
}

#[test]
fn the_c_api_warns_once_with_its_own_status() {
    use std::ffi::CStr;
    use wound_opening::capi::error::WoStatus;
    use wound_opening::capi::solver_c::*;
    let last = || unsafe { CStr::from_ptr(wo_last_error()) }.to_string_lossy().into_owned();
    let mut s = std::ptr::null_mut();
    unsafe {
        assert_eq!(wo_solver_new(1.0, -2.0, 10.0, 1e-8, &mut s), WoStatus::WoOk);
        assert_eq!(wo_solver_advance(s, 1.0, 0.0), WoStatus::WoOk, "{}", last());
        assert_eq!(wo_solver_advance(s, 1000.0, 0.0), WoStatus::WoOutsideValidity);
        let message = last();
        assert!(
            message.contains("t = 1000") && message.contains("wound radius is -0.34"),
            "{message}"
        );
        let (mut t, mut r) = (0.0, 0.0);
        assert_eq!(wo_solver_time(s, &mut t), WoStatus::WoOk);
        assert_eq!(wo_solver_wound_radius(s, &mut r), WoStatus::WoOk);
        assert_eq!(t, 1000.0, "the advance was done");
        assert!(r < 0.0);
        assert_eq!(wo_solver_advance(s, 2000.0, 0.0), WoStatus::WoOk, "once, when it leaves");
        let name = CStr::from_ptr(wo_status_name(8)).to_str().unwrap();
        assert_eq!(name, "WO_OUTSIDE_VALIDITY");
        assert_eq!(wo_solver_free(s), WoStatus::WoOk);
    }
}
