//! wo_series and wo_profile_series: the same numbers as the step-by-step handle API, values
//! at current positions consistent with the reference-radius profiles, and every kind of
//! bad input refused with a message and nothing written. (The sensitivities and rates of
//! the series are in rates.rs.)

mod rates;

use std::ffi::CStr;
use std::ptr::{null, null_mut};
use wound_opening::capi::error::WoStatus;
use wound_opening::capi::series_c::*;
use wound_opening::capi::solver_c::*;

fn last_error() -> String {
    unsafe { CStr::from_ptr(wo_last_error()) }.to_string_lossy().into_owned()
}

const TOL: f64 = 1e-9;

fn pb(lambda: f64, sigma: f64, r_inf: f64, tolerance: f64, edge_stress: f64) -> WoProblem {
    WoProblem { lambda, sigma, r_inf, tolerance, edge_stress }
}

/// Radius and velocity through a handle, advanced to each time in turn.
fn stepwise(lambda: f64, sigma: f64, r_inf: f64, p: f64, times: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let mut s = null_mut();
    let (mut r, mut v) = (vec![], vec![]);
    unsafe {
        assert_eq!(wo_solver_new(lambda, sigma, r_inf, TOL, &mut s), WoStatus::WoOk);
        for &t in times {
            assert_eq!(wo_solver_advance(s, t, p), WoStatus::WoOk, "{}", last_error());
            let (mut a, mut b) = (0.0, 0.0);
            assert_eq!(wo_solver_wound_radius(s, &mut a), WoStatus::WoOk);
            assert_eq!(wo_solver_edge_velocity(s, &mut b), WoStatus::WoOk);
            r.push(a);
            v.push(b);
        }
        assert_eq!(wo_solver_free(s), WoStatus::WoOk);
    }
    (r, v)
}

#[test]
fn a_series_is_the_handle_api_bit_for_bit() {
    let times = [0.0, 0.01, 0.5, 0.5, 2.0, 30.0];
    for (lambda, p) in [(0.3, 0.0), (2.0, 0.4), (0.0, 1.0)] {
        let (want_r, want_v) = stepwise(lambda, 1.0, 10.0, p, &times);
        let (mut r, mut v) = (vec![0.0; 6], vec![0.0; 6]);
        let status = unsafe {
            wo_series(
                pb(lambda, 1.0, 10.0, TOL, p),
                times.as_ptr(),
                6,
                r.as_mut_ptr(),
                v.as_mut_ptr(),
            )
        };
        assert_eq!(status, WoStatus::WoOk, "{}", last_error());
        assert_eq!(r, want_r);
        assert_eq!(v, want_v);
        // Radius only: the same radii.
        let mut r2 = vec![0.0; 6];
        assert_eq!(
            unsafe {
                wo_series(
                    pb(lambda, 1.0, 10.0, TOL, p),
                    times.as_ptr(),
                    6,
                    r2.as_mut_ptr(),
                    null_mut(),
                )
            },
            WoStatus::WoOk
        );
        assert_eq!(r2, want_r);
    }
}

#[test]
fn lambda_zero_velocity_at_the_cut_is_undefined_and_nothing_is_written() {
    let times = [0.0, 1.0];
    let (mut r, mut v) = ([7.0; 2], [7.0; 2]);
    let status = unsafe {
        wo_series(pb(0.0, 1.0, 10.0, TOL, 0.0), times.as_ptr(), 2, r.as_mut_ptr(), v.as_mut_ptr())
    };
    assert_eq!(status, WoStatus::WoUndefined);
    assert!(last_error().contains("times[0] = 0 is infinite"), "{}", last_error());
    assert_eq!((r, v), ([7.0; 2], [7.0; 2]));
    // The radius alone is defined there: R(0) = 1 + sigma / 6.
    assert_eq!(
        unsafe {
            wo_series(pb(0.0, 1.0, 10.0, TOL, 0.0), times.as_ptr(), 2, r.as_mut_ptr(), null_mut())
        },
        WoStatus::WoOk
    );
    assert!((r[0] - 7.0 / 6.0).abs() < 1e-12, "{}", r[0]);
}

#[test]
fn values_at_current_positions_are_those_of_the_material_points_there() {
    let (lambda, sigma, r_inf, p) = (0.7, 0.8, 10.0, 0.1);
    let times = [0.0, 0.3, 4.0];
    let xs = [1.0, 1.3, 2.0, 5.0, 9.9, 10.0];
    let mut s = null_mut();
    unsafe { assert_eq!(wo_solver_new(lambda, sigma, r_inf, TOL, &mut s), WoStatus::WoOk) };
    for (i, &t) in times.iter().enumerate() {
        let (mut ux, mut vx) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
        unsafe {
            assert_eq!(wo_solver_advance(s, t, p), WoStatus::WoOk);
            assert_eq!(
                wo_solver_displacement(s, xs.as_ptr(), ux.as_mut_ptr(), xs.len()),
                WoStatus::WoOk
            );
            assert_eq!(
                wo_solver_velocity(s, xs.as_ptr(), vx.as_mut_ptr(), xs.len()),
                WoStatus::WoOk
            );
        }
        // Current positions of the material points X, then back.
        let current: Vec<f64> = xs.iter().zip(&ux).map(|(x, u)| x + u).collect();
        let (mut u, mut v) = (vec![0.0; xs.len()], vec![0.0; xs.len()]);
        let status = unsafe {
            wo_profile_series(
                pb(lambda, sigma, r_inf, TOL, p),
                &times[i],
                1,
                current.as_ptr(),
                xs.len(),
                u.as_mut_ptr(),
                v.as_mut_ptr(),
            )
        };
        assert_eq!(status, WoStatus::WoOk, "{}", last_error());
        let row = 0..xs.len();
        for j in 0..xs.len() {
            // The inverse is solved to a few ulps of X; u and u_t change by their slope times that.
            assert!(
                (u[row.start + j] - ux[j]).abs() < 1e-13,
                "u at X = {}: {} vs {}",
                xs[j],
                u[row.start + j],
                ux[j]
            );
            assert!(
                (v[row.start + j] - vx[j]).abs() < 1e-12 * (1.0 + vx[j].abs()),
                "v at X = {}",
                xs[j]
            );
        }
        // Only the displacement: the same numbers.
        let mut u2 = vec![0.0; xs.len()];
        let status = unsafe {
            wo_profile_series(
                pb(lambda, sigma, r_inf, TOL, p),
                &times[i],
                1,
                current.as_ptr(),
                xs.len(),
                u2.as_mut_ptr(),
                null_mut(),
            )
        };
        assert_eq!(status, WoStatus::WoOk);
        assert_eq!(u2[row.clone()], u[row]);
    }
    unsafe { assert_eq!(wo_solver_free(s), WoStatus::WoOk) };
}

fn series_error(times: &[f64], tolerance: f64) -> (WoStatus, String) {
    let mut r = vec![5.0; times.len().max(1)];
    let status = unsafe {
        wo_series(
            pb(1.0, 1.0, 10.0, tolerance, 0.0),
            times.as_ptr(),
            times.len(),
            r.as_mut_ptr(),
            null_mut(),
        )
    };
    assert!(r.iter().all(|&x| x == 5.0), "written on failure");
    (status, last_error())
}

#[test]
fn bad_series_input_is_refused_with_the_reason() {
    let cases: [(&[f64], f64, &str); 5] = [
        (
            &[0.0, 2.0, 1.0],
            TOL,
            "wo_series: times[2] = 1 is before times[1] = 2: expected ascending times",
        ),
        (&[-1.0], TOL, "times[0] = -1 is invalid: expected a finite time >= 0"),
        (&[0.0, f64::NAN], TOL, "times[1] = NaN is invalid"),
        (&[1.0], 0.0, "tolerance"),
        (&[1.0], f64::INFINITY, "tolerance"),
    ];
    for (times, tol, needle) in cases {
        let (status, msg) = series_error(times, tol);
        assert_eq!(status, WoStatus::WoInvalidArgument, "{msg}");
        assert!(msg.contains(needle), "{msg} lacks {needle}");
    }
    let mut r = [0.0];
    unsafe {
        assert_eq!(
            wo_series(pb(-1.0, 1.0, 10.0, TOL, 0.0), [1.0].as_ptr(), 1, r.as_mut_ptr(), null_mut()),
            WoStatus::WoInvalidArgument
        );
        assert!(last_error().contains("lambda"), "{}", last_error());
        assert_eq!(
            wo_series(pb(1.0, 1.0, 10.0, TOL, 2e6), [1.0].as_ptr(), 1, r.as_mut_ptr(), null_mut()),
            WoStatus::WoInvalidArgument
        );
        assert_eq!(
            wo_series(pb(1.0, 1.0, 10.0, TOL, 0.0), null(), 1, r.as_mut_ptr(), null_mut()),
            WoStatus::WoNullPointer
        );
        assert!(last_error().contains("times (with count = 1) is NULL"), "{}", last_error());
        assert_eq!(
            wo_series(pb(1.0, 1.0, 10.0, TOL, 0.0), [1.0].as_ptr(), 1, null_mut(), null_mut()),
            WoStatus::WoNullPointer
        );
        assert_eq!(
            wo_series(pb(1.0, 1.0, 10.0, TOL, 0.0), null(), 0, null_mut(), null_mut()),
            WoStatus::WoOk
        );
    }
}

#[test]
fn current_radii_inside_the_wound_or_beyond_the_tissue_are_refused() {
    let times = [0.0, 5.0];
    let mut u = [3.0; 2];
    let mut refuse = |r: f64, needle: &str| {
        let status = unsafe {
            wo_profile_series(
                pb(1.0, 1.0, 10.0, TOL, 0.0),
                times.as_ptr(),
                2,
                [r].as_ptr(),
                1,
                u.as_mut_ptr(),
                null_mut(),
            )
        };
        assert_eq!(status, WoStatus::WoInvalidArgument, "{r}");
        let msg = last_error();
        assert!(msg.contains(needle), "{msg} lacks {needle}");
        assert_eq!(u, [3.0; 2]);
    };
    // Just after the cut the wound edge is at 1 + 1/6; the outer edge at 10 (1 + 1/6).
    refuse(
        1.1,
        "radii[0] = 1.1 is inside the wound at times[0] = 0: the tissue spans current radii [1.1666",
    );
    refuse(11.7, "radii[0] = 11.7 is outside the tissue at times[0] = 0");
    refuse(f64::NAN, "radii[0] = NaN is invalid: expected a finite radius");
    // Later the wound has opened past 1.2.
    refuse(1.2, "radii[0] = 1.2 is inside the wound at times[1] = 5");
    let status = unsafe {
        wo_profile_series(
            pb(1.0, 1.0, 10.0, TOL, 0.0),
            null(),
            usize::MAX,
            [2.0].as_ptr(),
            2,
            null_mut(),
            null_mut(),
        )
    };
    assert_eq!(status, WoStatus::WoInvalidArgument);
    assert!(last_error().contains("overflows"), "{}", last_error());
}

/// The searches of many radii side by side give, bit for bit, what each radius's search
/// gives alone, and X + u(X, t) is the current radius to a few ulps: with the modal
/// scheme's slope (Newton's steps inside the bracket) and with a scheme that has none
/// (TR-BDF2 here: regula falsi alone).
#[test]
fn reference_radii_side_by_side_equal_those_found_one_at_a_time() {
    use wound_opening::solver::{MeshSpec, Params, Scheme, Settings, Solver};
    let params = Params { lambda: 0.8, sigma: 0.6, r_inf: 12.0 };
    let modal = Solver::new(&params, &Settings::for_tolerance(&params, 1e-11).unwrap()).unwrap();
    let mesh = MeshSpec { degree: 4, elements: 6, edge_scale: 0.1 };
    let stepped = Solver::with_scheme(&params, &Scheme::TrBdf2 { mesh, max_step: 0.05 }).unwrap();
    for mut s in [modal, stepped] {
        s.advance(0.7, 0.1).unwrap();
        check_reference_radii(&s);
    }
}

fn check_reference_radii(s: &wound_opening::solver::Solver) {
    use wound_opening::capi::series::reference_radii;
    let ends = s.displacement(&[1.0, 12.0]);
    let (lo, hi) = (1.0 + ends[0], 12.0 + ends[1]);
    let radii: Vec<f64> = (0..=300)
        .map(|j| lo + (hi - lo) * (j as f64 / 300.0).powi(3))
        .chain([hi, lo, 3.0, 3.0])
        .collect();
    let together = reference_radii(s, &radii, 12.0, (lo, hi));
    for (&r, &x) in radii.iter().zip(&together) {
        assert_eq!(x.to_bits(), reference_radii(s, &[r], 12.0, (lo, hi))[0].to_bits(), "{r}");
        assert!((x + s.displacement(&[x])[0] - r).abs() <= 8.0 * f64::EPSILON * r, "{r}: {x}");
    }
}

/// Counts checked before anything is copied: bytes beyond the address space, or beyond
/// what any allocation holds, are `WO_INVALID_ARGUMENT` with the reason (no source path),
/// the arrays passed never read past, the process alive; FMI arrays likewise.
#[test]
fn huge_counts_are_invalid_arguments_and_the_process_lives() {
    let p = pb(1.0, 1.0, 10.0, TOL, 0.0);
    let (times, mut radius, radii) = ([0.5, 1.0], [0.0; 2], [2.0, 3.0]);
    let big = 1usize << 57;
    unsafe {
        for (count, reason) in [
            (
                usize::MAX,
                "times: count = 18446744073709551615 is invalid: 18446744073709551615 elements of 8 bytes exceed the largest array the address space can hold (9223372036854775807 bytes)",
            ),
            (
                big,
                "times: count = 144115188075855872 is invalid: 144115188075855872 values (1.153e18 bytes) cannot be allocated",
            ),
        ] {
            assert_eq!(
                wo_series(p, times.as_ptr(), count, radius.as_mut_ptr(), null_mut()),
                WoStatus::WoInvalidArgument
            );
            assert!(last_error().contains(reason), "{}", last_error());
            assert!(!last_error().contains(".rs"), "{}", last_error());
        }
        let status = wo_profile_series(
            p,
            times.as_ptr(),
            1,
            radii.as_ptr(),
            big,
            radius.as_mut_ptr(),
            null_mut(),
        );
        assert_eq!(status, WoStatus::WoInvalidArgument, "{}", last_error());
        assert!(
            last_error().starts_with("wo_profile_series: radii: count = 144115188075855872"),
            "{}",
            last_error()
        );
        assert_eq!(
            wo_series(p, times.as_ptr(), 2, radius.as_mut_ptr(), null_mut()),
            WoStatus::WoOk
        );
    }
    // FMI: a count beyond the address space is refused by name, not a panic.
    use wound_opening::fmi::fmi2::functions::*;
    use wound_opening::fmi::fmi2::types::*;
    let (name, guid) =
        (c"huge", std::ffi::CString::new(wound_opening::models::wound::variables::GUID).unwrap());
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            FMI2_CO_SIMULATION,
            guid.as_ptr(),
            c"".as_ptr(),
            &fmi2CallbackFunctions::NONE,
            0,
            0,
        )
    };
    let (vr, mut x) = ([0u32], [0.0f64]);
    let panics = wound_opening::boundary::caught_panics();
    assert_eq!(unsafe { fmi2GetReal(c, vr.as_ptr(), usize::MAX, x.as_mut_ptr()) }, 3);
    assert_eq!(unsafe { fmi2SetReal(c, vr.as_ptr(), usize::MAX, x.as_ptr()) }, 3);
    assert_eq!(wound_opening::boundary::caught_panics(), panics, "refused, not caught");
    unsafe { fmi2FreeInstance(c) };
}

/// wo_series reports leaving the model's validity as the step API does: the same
/// `WO_OUTSIDE_VALIDITY` (a warning), here with every output written and the first time
/// named; a run that stays valid is OK.
#[test]
fn leaving_the_validity_is_reported_with_the_outputs() {
    let times = [0.5, 1.0, 3.0, 10.0];
    let (mut r, mut v) = ([f64::NAN; 4], [f64::NAN; 4]);
    let status = unsafe {
        wo_series(pb(1.0, 2.0, 10.0, TOL, 0.0), times.as_ptr(), 4, r.as_mut_ptr(), v.as_mut_ptr())
    };
    assert_eq!(status, WoStatus::WoOutsideValidity, "{}", last_error());
    assert!(
        last_error().starts_with("wo_series: times[")
            && last_error().contains("leaves the model's validity"),
        "{}",
        last_error()
    );
    let mut s = null_mut();
    unsafe {
        assert_eq!(wo_solver_new(1.0, 2.0, 10.0, TOL, &mut s), WoStatus::WoOk);
        let mut first = None;
        for (k, &t) in times.iter().enumerate() {
            let status = wo_solver_advance(s, t, 0.0);
            if status == WoStatus::WoOutsideValidity && first.is_none() {
                first = Some(k);
                assert!(last_error().contains(&format!("t = {t}")), "{}", last_error());
            }
            let (mut a, mut b) = (f64::NAN, f64::NAN);
            assert_eq!(wo_solver_wound_radius(s, &mut a), WoStatus::WoOk);
            assert_eq!(wo_solver_edge_velocity(s, &mut b), WoStatus::WoOk);
            assert_eq!((r[k], v[k]), (a, b), "every output written, as the step API's");
        }
        let first = first.expect("the step API warns");
        assert!(
            wo_series(pb(1.0, 2.0, 10.0, TOL, 0.0), times.as_ptr(), 4, r.as_mut_ptr(), null_mut())
                == WoStatus::WoOutsideValidity
        );
        assert!(
            last_error().contains(&format!("times[{first}] = {}", times[first])),
            "{}",
            last_error()
        );
        assert_eq!(wo_solver_free(s), WoStatus::WoOk);
        assert_eq!(
            wo_series(pb(1.0, 1.0, 10.0, TOL, 0.0), times.as_ptr(), 4, r.as_mut_ptr(), null_mut()),
            WoStatus::WoOk
        );
    }
}
