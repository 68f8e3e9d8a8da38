//! The corners of the accepted domain through the direct C API: every output finite, at the
//! cut and from t = 1e-14 to 1e6, with the edge stress at both bounds; just outside each
//! corner the parameters are refused with the range. (The C API is dimensionless: the largest
//! output is the initial edge velocity |sigma - p| / (4 lambda) = 5e155 at lambda = 1e-150.
//! tests/python/test_domain.py runs the same corners through the FMU with the largest scales.)

use std::ffi::CStr;
use wound_opening::capi::error::WoStatus;
use wound_opening::capi::solver_c::*;

fn last_error() -> String {
    unsafe { CStr::from_ptr(wo_last_error()) }.to_string_lossy().into_owned()
}

#[test]
fn every_corner_has_finite_outputs() {
    for lambda in [0.0, 1e-150, 1e6] {
        for sigma in [-6.0 + 1e-9, 1e6] {
            for r_inf in [1.001, 1e6] {
                for p in [-1e6, 1e6] {
                    let mut s = std::ptr::null_mut();
                    let ok = unsafe { wo_solver_new(lambda, sigma, r_inf, 1e-6, &mut s) };
                    assert_eq!(ok, WoStatus::WoOk, "{lambda} {sigma} {r_inf}: {}", last_error());
                    let radii = [1.0, 0.5 * (1.0 + r_inf), r_inf];
                    for t in [0.0, 1e-14, 1e-8, 1e-2, 1.0, 1e6] {
                        let (mut r, mut v, mut u, mut w) =
                            (f64::NAN, f64::NAN, [f64::NAN; 3], [f64::NAN; 3]);
                        unsafe {
                            // Most corners leave the linear model's validity (a warning, the
                            // advance done); the outputs must be finite all the same.
                            let advanced = wo_solver_advance(s, t, p);
                            assert!(
                                matches!(advanced, WoStatus::WoOk | WoStatus::WoOutsideValidity),
                                "{}",
                                last_error()
                            );
                            assert_eq!(wo_solver_wound_radius(s, &mut r), WoStatus::WoOk);
                            assert_eq!(
                                wo_solver_displacement(s, radii.as_ptr(), u.as_mut_ptr(), 3),
                                WoStatus::WoOk
                            );
                            let status = wo_solver_edge_velocity(s, &mut v);
                            // At lambda = 0 the velocity is infinite at the cut: refused, not a number.
                            if status == WoStatus::WoUndefined {
                                assert_eq!((lambda, t), (0.0, 0.0), "{}", last_error());
                                continue;
                            }
                            assert_eq!(status, WoStatus::WoOk, "{}", last_error());
                            assert_eq!(
                                wo_solver_velocity(s, radii.as_ptr(), w.as_mut_ptr(), 3),
                                WoStatus::WoOk
                            );
                        }
                        let all = [r, v, u[0], u[1], u[2], w[0], w[1], w[2]];
                        assert!(
                            all.iter().all(|x| x.is_finite()),
                            "{lambda} {sigma} {r_inf} {p} t = {t}: {all:?}"
                        );
                    }
                    assert_eq!(unsafe { wo_solver_free(s) }, WoStatus::WoOk);
                }
            }
        }
    }
}

#[test]
fn just_outside_each_corner_is_refused_with_the_range() {
    let cases = [
        (1e-300, 1.0, 10.0, "lambda = 1e-300 is outside the accepted range: 0 or [1e-150, 1e6]"),
        (9.9e-151, 1.0, 10.0, "0 or [1e-150, 1e6]"),
        (1.0000001e6, 1.0, 10.0, "0 or [1e-150, 1e6]"),
        (1.0, -6.0, 10.0, "sigma = -6 is outside the accepted range (-6, 1e6]"),
        (1.0, -10.0, 10.0, "R1 = R0 (1 + sigma/6), must be > 0"),
        (1.0, 1.0000001e6, 10.0, "(-6, 1e6]"),
    ];
    for (lambda, sigma, r_inf, message) in cases {
        let mut s = std::ptr::null_mut();
        assert_eq!(
            unsafe { wo_solver_new(lambda, sigma, r_inf, 1e-6, &mut s) },
            WoStatus::WoInvalidArgument
        );
        assert!(s.is_null());
        assert!(last_error().contains(message), "{}", last_error());
    }
}
