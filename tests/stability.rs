//! Stability where methods fail: the explicit scheme's limits, measured, against
//! its von Neumann theory (src/solver/explicit.rs); and the shipped scheme, bounded and
//! monotone over the whole map of lambda and step size.

use wound_opening::solver::stability::{self, RunStatus as Status};
use wound_opening::solver::{Params, Scheme, Settings, explicit_stability_limits};

const R_INF: f64 = 10.0;

/// The stability status of `steps` steps of `dt` from the cut, sigma = 1, R_inf = 10.
fn classify(lambda: f64, scheme: &Scheme, dt: f64, steps: usize) -> Status {
    stability::classify(&Params { lambda, sigma: 1.0, r_inf: R_INF }, scheme, dt, steps)
}

/// 4000 steps: near the limit the unstable mode grows slowly, so the verdict needs many steps.
const LONG: usize = 4000;

/// The measured limits (examples/stability_map.rs, run unchecked) lie within 3 % above the
/// theory for N = 21 .. 201; the test brackets the theory by -5 % / +10 %.
#[test]
fn explicit_scheme_fails_exactly_where_its_theory_says() {
    for points in [21, 51] {
        let (lambda_max, _) = explicit_stability_limits(points, R_INF, 0.0);
        for frac in [0.0, 0.5] {
            let lambda = frac * lambda_max;
            let (_, dt_max) = explicit_stability_limits(points, R_INF, lambda);
            let below = Scheme::Explicit { points, max_step: 0.95 * dt_max };
            let above = Scheme::Explicit { points, max_step: 1.10 * dt_max };
            assert_ne!(
                classify(lambda, &below, 0.95 * dt_max, LONG),
                Status::Unbounded,
                "N {points} lambda {lambda}"
            );
            assert_eq!(
                classify(lambda, &above, 1.10 * dt_max, LONG),
                Status::Unbounded,
                "N {points} lambda {lambda}"
            );
        }
        // The lagged viscous term alone: unstable beyond lambda_max whatever the step.
        let dt = 1e-3 * explicit_stability_limits(points, R_INF, 0.0).1;
        let scheme = Scheme::Explicit { points, max_step: dt };
        assert_ne!(classify(0.95 * lambda_max, &scheme, dt, LONG), Status::Unbounded, "N {points}");
        assert_eq!(classify(1.10 * lambda_max, &scheme, dt, LONG), Status::Unbounded, "N {points}");
    }
}

/// The theory: lambda_max = 1 / sqrt(kappa_max) ~ dr / 2 and dt_max = 2 / kappa_max - 2 lambda^2
/// ~ dr^2 / 2 at lambda = 0, checked against the grid spacing (not against the formula).
#[test]
fn explicit_limits_follow_the_grid_spacing() {
    for points in [21, 51, 101, 201] {
        let dr = (R_INF - 1.0) / (points - 1) as f64;
        let (lambda_max, dt_max) = explicit_stability_limits(points, R_INF, 0.0);
        assert!(
            (lambda_max / (dr / 2.0) - 1.0).abs() < 0.01,
            "N {points}: {lambda_max} vs {}",
            dr / 2.0
        );
        assert!((dt_max / (dr * dr / 2.0) - 1.0).abs() < 0.02, "N {points}: {dt_max}");
    }
}

/// The solver refuses, before taking it, every explicit step the theory calls unstable,
/// and takes those just inside: a step beyond them would grow without bound (to 1e171 in 1000
/// steps) while the status said OK.
#[test]
fn solver_refuses_explicit_steps_beyond_the_limits_before_taking_them() {
    use wound_opening::solver::{Solver, SolverError};
    for points in [21, 101] {
        let (lambda_max, dt0) = explicit_stability_limits(points, R_INF, 0.0);
        for (lambda, dt, refused) in [
            (0.0, 1.02 * dt0, true),
            (0.0, 0.98 * dt0, false),
            (1.02 * lambda_max, 1e-3 * dt0, true),
        ] {
            let params = Params { lambda, sigma: 1.0, r_inf: R_INF };
            let mut s =
                Solver::with_scheme(&params, &Scheme::Explicit { points, max_step: dt }).unwrap();
            let got = s.advance(10.0 * dt, 0.0);
            assert_eq!(
                matches!(got, Err(SolverError::Unstable { .. })),
                refused,
                "N {points} lambda {lambda} dt {dt}: {got:?}"
            );
            assert_eq!(s.time() == 0.0, refused);
        }
    }
}

/// The default scheme over the map of examples/stability_map.rs: lambda from 0 to 1e4,
/// steps from 1e-6 to 1e4, 200 steps each: never unbounded, never decreasing.
#[test]
fn shipped_scheme_is_bounded_and_monotone_over_the_whole_map() {
    for lambda in [0.0, 1e-3, 1e-2, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0, 1e3, 1e4] {
        let params = Params { lambda, sigma: 1.0, r_inf: R_INF };
        let scheme = Scheme::Modal(Settings::for_tolerance(&params, 1e-10).unwrap());
        for k in -12..=8 {
            let dt = 10f64.powf(k as f64 / 2.0);
            assert_eq!(
                classify(lambda, &scheme, dt, 200),
                Status::Bounded,
                "lambda {lambda} dt {dt}"
            );
        }
    }
}
