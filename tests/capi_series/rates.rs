//! wo_series_sensitivities and wo_profile_rates: the values of wo_series and
//! wo_profile_series to the bit, optional outputs skipped by NULL, and nothing written on
//! a refusal.

use super::*;

/// wo_series_sensitivities: the radius and velocity of wo_series to the bit, optional
/// outputs skipped by NULL, the radius required, and nothing written on a refusal (its
/// derivatives are checked in src/solver/sensitivity.rs and tests/python/test_sensitivities.py).
#[test]
fn sensitivities_give_the_series_values_and_follow_the_pointer_rules() {
    let times = [0.0, 0.5, 3.0, 40.0];
    let problem = pb(0.7, 1.0, 10.0, TOL, 0.2);
    let (mut r, mut v) = ([0.0; 4], [0.0; 4]);
    let (mut r2, mut v2, mut dl, mut dr) = ([0.0; 4], [0.0; 4], [0.0; 4], [0.0; 4]);
    unsafe {
        assert_eq!(
            wo_series(problem, times.as_ptr(), 4, r.as_mut_ptr(), v.as_mut_ptr()),
            WoStatus::WoOk
        );
        let status = wo_series_sensitivities(
            problem,
            times.as_ptr(),
            4,
            r2.as_mut_ptr(),
            v2.as_mut_ptr(),
            dl.as_mut_ptr(),
            dr.as_mut_ptr(),
        );
        assert_eq!(status, WoStatus::WoOk, "{}", last_error());
        assert_eq!((r, v), (r2, v2));
        assert!(
            dl[1..].iter().all(|d| *d < 0.0) && dr[1..].iter().all(|d| *d < 0.0),
            "{dl:?} {dr:?}"
        );
        let mut only = [0.0; 4];
        let status = wo_series_sensitivities(
            problem,
            times.as_ptr(),
            4,
            r2.as_mut_ptr(),
            null_mut(),
            null_mut(),
            only.as_mut_ptr(),
        );
        assert_eq!(status, WoStatus::WoOk);
        assert_eq!(only, dr);
        let status = wo_series_sensitivities(
            problem,
            times.as_ptr(),
            4,
            null_mut(),
            null_mut(),
            dl.as_mut_ptr(),
            null_mut(),
        );
        assert_eq!(status, WoStatus::WoNullPointer);
        assert!(
            last_error().contains("wo_series_sensitivities: radius (with count = 4) is NULL"),
            "{}",
            last_error()
        );
        let mut untouched = [9.0; 2];
        let status = wo_series_sensitivities(
            problem,
            [1.0, 0.5].as_ptr(),
            2,
            r2.as_mut_ptr(),
            null_mut(),
            untouched.as_mut_ptr(),
            null_mut(),
        );
        assert_eq!(status, WoStatus::WoInvalidArgument);
        assert!(last_error().contains("expected ascending times"), "{}", last_error());
        assert_eq!(untouched, [9.0; 2]);
    }
}

/// wo_profile_rates and wo_profile_sensitivities: the velocity of wo_profile_series (to
/// 1e-13 of the largest: the same modal sums in another order), the first four of the six values per point equal to the four of the other, the edge
/// output optional, the rates required, a count that overflows refused, and nothing written
/// on a refusal (their derivatives are checked in src/capi/profile_rates.rs and
/// tests/python/test_piv_jacobian.py).
#[test]
fn profile_rates_give_the_profile_velocities_and_follow_the_pointer_rules() {
    let times = [0.5, 3.0];
    let radii = [1.5, 2.5, 6.0];
    let problem = pb(0.7, 0.8, 10.0, TOL, 0.0);
    let mut v = [0.0; 6];
    let (mut six, mut edge6) = ([0.0; 36], [0.0; 24]);
    let (mut four, mut edge4) = ([0.0; 24], [0.0; 16]);
    unsafe {
        let status = wo_profile_series(
            problem,
            times.as_ptr(),
            2,
            radii.as_ptr(),
            3,
            null_mut(),
            v.as_mut_ptr(),
        );
        assert_eq!(status, WoStatus::WoOk, "{}", last_error());
        let status = wo_profile_rates(
            problem,
            times.as_ptr(),
            2,
            radii.as_ptr(),
            3,
            six.as_mut_ptr(),
            edge6.as_mut_ptr(),
        );
        assert_eq!(status, WoStatus::WoOk, "{}", last_error());
        let status = wo_profile_sensitivities(
            problem,
            times.as_ptr(),
            2,
            radii.as_ptr(),
            3,
            four.as_mut_ptr(),
            edge4.as_mut_ptr(),
        );
        assert_eq!(status, WoStatus::WoOk, "{}", last_error());
        let largest = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (k, (a, b)) in six.chunks(6).zip(four.chunks(4)).enumerate() {
            assert!((a[0] - v[k]).abs() <= 1e-13 * largest, "point {k}: {} against {}", a[0], v[k]);
            assert_eq!(&a[..4], b, "point {k}");
            assert!(a[4].is_finite() && a[5].is_finite() && a[5] != 0.0, "point {k}: {a:?}");
        }
        for (a, b) in edge6.chunks(6).zip(edge4.chunks(4)) {
            assert_eq!(&a[..4], b);
        }
        assert_eq!(
            (edge6[5], edge6[17]),
            (0.0, 0.0),
            "the edge's own velocity does not depend on r"
        );
        let mut again = [0.0; 36];
        let status = wo_profile_rates(
            problem,
            times.as_ptr(),
            2,
            radii.as_ptr(),
            3,
            again.as_mut_ptr(),
            null_mut(),
        );
        assert_eq!(status, WoStatus::WoOk);
        assert_eq!(again, six);
        let status = wo_profile_rates(
            problem,
            times.as_ptr(),
            2,
            radii.as_ptr(),
            3,
            null_mut(),
            edge6.as_mut_ptr(),
        );
        assert_eq!(status, WoStatus::WoNullPointer);
        assert!(
            last_error().contains("wo_profile_rates: rates (with count = 36) is NULL"),
            "{}",
            last_error()
        );
        let mut untouched = [9.0; 36];
        let status = wo_profile_rates(
            problem,
            [0.0, 1.0].as_ptr(),
            2,
            radii.as_ptr(),
            3,
            untouched.as_mut_ptr(),
            null_mut(),
        );
        assert_eq!(status, WoStatus::WoInvalidArgument);
        assert!(last_error().contains("the sensitivities need times > 0"), "{}", last_error());
        assert_eq!(untouched, [9.0; 36]);
        let status = wo_profile_rates(
            problem,
            times.as_ptr(),
            usize::MAX,
            radii.as_ptr(),
            3,
            untouched.as_mut_ptr(),
            null_mut(),
        );
        assert_eq!(status, WoStatus::WoInvalidArgument);
        assert!(last_error().contains("overflows"), "{}", last_error());
    }
}
