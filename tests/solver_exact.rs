//! The solver against the exact results of docs/model.md ("Exact results"), the observed order of
//! convergence under grid refinement, and independence of the step size (exact in time).

use wound_opening::solver::{MeshSpec, Params, Settings, Solver, exact};

fn solver(lambda: f64, r_inf: f64, mesh: Option<MeshSpec>) -> Solver {
    let settings = mesh.map(|mesh| Settings { mesh }).unwrap_or_default();
    Solver::new(&Params { lambda, sigma: 1.0, r_inf }, &settings).expect("valid parameters")
}

fn amplitude(r_inf: f64) -> f64 {
    exact::final_radius(1.0, r_inf) - exact::initial_radius(1.0)
}

/// Exact `(lambda, t, R(t), dR/dt)` for `sigma = 1`, `R_inf = 10`, `p = 0`: the inverse
/// Laplace transform of docs/model.md ("Exact results") by mpmath's fixed Talbot method at 30
/// significant digits (`python/wound_exact.py`, `edge_mp`), rounded to double.
const LAPLACE_REFERENCE: [(f64, f64, f64, f64); 9] = [
    (0.0, 0.01, 1.1948100659958139, 1.4007729175076447),
    (0.0, 1.0, 1.4095355678459203, 0.09279339465714992),
    (0.1, 0.01, 1.186600326648937, 1.6007047059288693),
    (0.1, 1.0, 1.4087625517081417, 0.09321903313985316),
    (1.0, 0.01, 1.1687443502514077, 0.20711539214739486),
    (1.0, 1.0, 1.3230844084841147, 0.11558187443997547),
    (10.0, 0.01, 1.1667150110491786, 0.004834206579713935),
    (10.0, 1.0, 1.1714782420960355, 0.00478855488442124),
    (10.0, 1000.0, 1.673352408463456, 4.3042366807752954e-07),
];

/// Exact `(lambda, R_inf, t, R(t), dR/dt)` at the edges of the accepted domain, by the same
/// 30-digit (here 40-digit) mpmath inversion: a domain 1e6 wound radii wide (relaxation
/// times over 17 decades) and a thin ring (R_inf = 1.001, opening amplitude 333).
const EDGE_REFERENCE: [(f64, f64, f64, f64, f64); 9] = [
    (0.0, 1000000.0, 0.01, 1.1948100659958139, 1.4007729175076447),
    (0.0, 1000000.0, 1.0, 1.4095355678459203, 0.09279339465714992),
    (0.0, 1000000.0, 100.0, 1.6613467402193063, 5.5657532069235316e-05),
    (0.1, 1000000.0, 0.01, 1.186600326648937, 1.6007047059288693),
    (0.1, 1000000.0, 1.0, 1.4087625517081417, 0.09321903313985316),
    (1000.0, 1000000.0, 1000000.0, 1.4827242519314674, 1.839395884534592e-07),
    (0.0, 1.001, 0.01, 3.657407712266635, 248.13387281177523),
    (0.0, 1.001, 1.0, 177.10230765744305, 118.18015157413379),
    (1.0, 1.001, 10.0, 330.2296454577629, 1.9719179778743827),
];

/// The tolerance contract at the edges of the domain, at the default tolerance 1e-10: the
/// radius within 1e-10 of the opening amplitude (measured: at most 3.4e-12 here). These are
/// the places where a QR eigensolver (1e-6 at R_inf = 1e6, t = 0.01) and a basis without the
/// constant first (3e-8 at R_inf = 1.001, late times) lose the contract.
#[test]
fn edges_of_the_domain_match_the_laplace_solution_at_the_default_tolerance() {
    for (lambda, r_inf, t, radius, velocity) in EDGE_REFERENCE {
        let params = Params { lambda, sigma: 1.0, r_inf };
        let mut s =
            Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
        s.advance(t, 0.0).unwrap();
        let err = (s.wound_radius() - radius).abs() / amplitude(r_inf);
        assert!(err < 1e-10, "lambda {lambda}, R_inf {r_inf}, t {t}: R error {err:e}");
        let verr = (s.edge_velocity(0.0) - velocity).abs() / velocity.abs();
        assert!(verr < 1e-7, "lambda {lambda}, R_inf {r_inf}, t {t}: velocity error {verr:e}");
    }
}

/// The requirement is 1e-6 of the opening amplitude; the default mesh measures below
/// 2e-12. 1e-9 keeps a margin for rounding on other platforms yet fails on any loss of
/// spectral accuracy (a degree-2 mesh of the same size is at 1e-5).
#[test]
fn default_settings_match_the_laplace_solution() {
    for (lambda, t, radius, velocity) in LAPLACE_REFERENCE {
        let mut s = solver(lambda, 10.0, None);
        s.advance(t, 0.0).unwrap();
        let err = (s.wound_radius() - radius).abs() / amplitude(10.0);
        assert!(err < 1e-9, "lambda {lambda}, t {t}: R error {err:e}");
        let verr = (s.edge_velocity(0.0) - velocity).abs() / velocity.abs();
        assert!(verr < 1e-7, "lambda {lambda}, t {t}: velocity error {verr:e}");
    }
}

/// Relaxed state `u = a r + b / r`: measured error ~1e-11 (the `b / r` term is not a
/// polynomial); 1e-9 of the amplitude bounds it with margin.
#[test]
fn relaxes_to_the_exact_final_state() {
    for lambda in [0.0, 0.1, 1.0, 10.0] {
        for r_inf in [2.0, 10.0] {
            let mut s = solver(lambda, r_inf, None);
            s.advance(1e7, 0.0).unwrap();
            let radii = [1.0, 1.05, 1.3, 1.9, 0.5 * (1.0 + r_inf), r_inf];
            for (r, u) in radii.iter().zip(s.displacement(&radii)) {
                let want = exact::final_displacement(1.0, r_inf, *r);
                assert!(
                    (u - want).abs() < 1e-9 * amplitude(r_inf),
                    "lambda {lambda} R_inf {r_inf} r {r}"
                );
            }
            assert!(s.edge_velocity(0.0).abs() < 1e-12, "at rest: {}", s.edge_velocity(0.0));
        }
    }
}

/// Without friction the wound radius is `no_friction_radius(t / lambda^2)`; at finite
/// lambda the friction term `4 M / lambda^2` perturbs the mass by a relative
/// `O((R_inf / lambda)^2)`. The test checks that bound and its second order in 1/lambda.
#[test]
fn approaches_the_no_friction_solution_as_lambda_grows() {
    for r_inf in [2.0, 10.0] {
        let deviation = |lambda: f64| {
            let mut s = solver(lambda, r_inf, None);
            (1..=50)
                .map(|k| {
                    let t_tau = 0.1 * k as f64;
                    s.advance(t_tau * lambda * lambda - s.time(), 0.0).unwrap();
                    (s.wound_radius() - exact::no_friction_radius(1.0, r_inf, t_tau)).abs()
                        / amplitude(r_inf)
                })
                .fold(0.0, f64::max)
        };
        let (d3, d4) = (deviation(1e3), deviation(1e4));
        assert!(d4 < (r_inf / 1e4).powi(2), "R_inf {r_inf}: deviation {d4:e}");
        let order = (d3 / d4).log10();
        assert!((order - 2.0).abs() < 0.05, "R_inf {r_inf}: order {order}");
    }
}

/// `(lambda, R_inf, r, w(r))`: the instantaneous velocity response to a unit edge stress
/// (`lambda^2 D2 w = w`, `lambda^2 D w(1) = 1`, `D w(R_inf) = 0`), from the unscaled Bessel
/// form evaluated by mpmath at 40 digits: an implementation independent of the scaled one
/// in src/solver/exact.rs (which must survive lambda = 1e-3, where I1(1000) overflows).
#[allow(clippy::excessive_precision)] // the digits as mpmath printed them
const RESPONSE_REFERENCE: [(f64, f64, f64, f64); 11] = [
    (0.001, 10.0, 1.0, -249.99990634366224),
    (0.001, 10.0, 1.002, -33.799999718118042),
    (0.01, 1.001, 1.0, -250.81404836825342),
    (0.1, 10.0, 1.0, -2.4914859677133364),
    (0.1, 10.0, 1.3, -0.10793036720495276),
    (1.0, 10.0, 1.0, -0.20842296974142384),
    (1.0, 10.0, 4.0, -0.0043226961804420635),
    (10.0, 10.0, 1.0, -0.0048346699301258179),
    (10.0, 10.0, 10.0, -0.00049702250431519732),
    (1000.0, 1000000.0, 1.0, -4.9999297638344108e-7),
    (10000.0, 2.0, 1.5, -5.2777776341228182e-9),
];

/// The closed-form response against the independent reference: measured relative error
/// below 1e-13, asserted at 1e-12.
#[test]
fn velocity_response_matches_the_bessel_solution() {
    for (lambda, r_inf, r, want) in RESPONSE_REFERENCE {
        let got = exact::velocity_response(lambda, r_inf, r);
        assert!(
            (got - want).abs() < 1e-12 * want.abs(),
            "lambda {lambda} R_inf {r_inf} r {r}: {got:e} vs {want:e}"
        );
    }
}

/// Where the mesh resolves the viscous layer (lambda >= 0.1), the mesh's own velocity just
/// after the cut (a step of 1e-12, so the state has not moved) agrees with the closed form
/// that the solver applies to changes of the edge stress: two independent routes to the
/// same number (measured within 5.1e-11 relative; asserted at 1e-9). The mesh's own
/// response is off by 29 % at lambda = 0.01, where it cannot resolve the boundary layer.
#[test]
fn mesh_velocity_agrees_with_the_closed_form_response_where_it_resolves_the_layer() {
    for lambda in [0.1, 1.0, 10.0] {
        for p in [0.0, 0.4, -0.5] {
            let mut s = solver(lambda, 10.0, None);
            let at_cut = s.edge_velocity(p);
            assert_eq!(at_cut, (p - 1.0) * exact::edge_velocity_slope(lambda, 10.0));
            s.advance(1e-12, p).unwrap();
            let mesh = s.edge_velocity(p);
            assert!(
                (mesh - at_cut).abs() < 1e-9 * at_cut.abs(),
                "lambda {lambda} p {p}: mesh {mesh} vs closed form {at_cut}"
            );
        }
    }
}

/// Linear problem: a constant edge stress scales the opening by `1 - p / sigma`; `p = sigma`
/// keeps the tissue at rest. Only rounding separates the two sides.
#[test]
fn constant_edge_stress_superposes() {
    for lambda in [0.0, 1.0] {
        let (mut free, mut loaded, mut held) =
            (solver(lambda, 10.0, None), solver(lambda, 10.0, None), solver(lambda, 10.0, None));
        let r1 = exact::initial_radius(1.0);
        for t in [0.01, 0.1, 1.0, 10.0, 100.0] {
            let h = t - free.time();
            free.advance(h, 0.0).unwrap();
            loaded.advance(h, 0.3).unwrap();
            held.advance(h, 1.0).unwrap();
            let want = r1 + 0.7 * (free.wound_radius() - r1);
            assert!((loaded.wound_radius() - want).abs() < 1e-13, "lambda {lambda} t {t}");
            assert!((held.wound_radius() - r1).abs() < 1e-13, "lambda {lambda} t {t}: moved");
            assert!(held.edge_velocity(1.0).abs() < 1e-12, "lambda {lambda} t {t}: velocity");
        }
    }
}

/// Observed order when the elements are halved (degree 1: classical second order;
/// Galerkin nodal superconvergence gives 2p for degree p). Errors against the exact
/// R(1) at lambda = 0 and the exact edge velocity at t = 0.01 at lambda = 1 (the initial
/// velocity itself is exact by construction: see `initial_velocity_is_the_closed_form`).
#[test]
fn converges_at_the_expected_order_under_grid_refinement() {
    let (t, exact_r) = (1.0, LAPLACE_REFERENCE[1].2);
    let (t_v, v_exact) = (LAPLACE_REFERENCE[4].1, LAPLACE_REFERENCE[4].3);
    for (degree, order, sizes) in
        [(1, 2.0, [16, 32, 64]), (2, 4.0, [8, 16, 32]), (3, 6.0, [6, 12, 24])]
    {
        let errors: Vec<(f64, f64)> = sizes
            .iter()
            .map(|&elements| {
                let mesh = MeshSpec { degree, elements, edge_scale: 0.5 };
                let mut s = solver(0.0, 10.0, Some(mesh));
                s.advance(t, 0.0).unwrap();
                let mut viscous = solver(1.0, 10.0, Some(mesh));
                viscous.advance(t_v, 0.0).unwrap();
                ((s.wound_radius() - exact_r).abs(), (viscous.edge_velocity(0.0) - v_exact).abs())
            })
            .collect();
        for w in errors.windows(2) {
            let observed_r = (w[0].0 / w[1].0).log2();
            let observed_v = (w[0].1 / w[1].1).log2();
            // Within 0.3 of the asymptotic order: the coarsest pairs are still pre-asymptotic.
            assert!((observed_r - order).abs() < 0.3, "degree {degree}: R order {observed_r}");
            assert!(
                (observed_v - order).abs() < 0.3,
                "degree {degree}: v(0.01) order {observed_v}"
            );
        }
    }
}

/// Exact in time: one step of 1.0 and 1000 steps of 0.001 give the same state up to
/// rounding, for every regime including the algebraic-edge case lambda = 0.
#[test]
fn result_does_not_depend_on_the_step_size() {
    for lambda in [0.0, 0.1, 10.0] {
        let mut one = solver(lambda, 10.0, None);
        let mut many = solver(lambda, 10.0, None);
        one.advance(1.0, 0.2).unwrap();
        for _ in 0..1000 {
            many.advance(1e-3, 0.2).unwrap();
        }
        assert!((one.wound_radius() - many.wound_radius()).abs() < 1e-13, "lambda {lambda}");
        assert!(
            (one.edge_velocity(0.2) - many.edge_velocity(0.2)).abs() < 1e-11,
            "lambda {lambda}"
        );
    }
}

/// Stable for every lambda and step: from the cut, with p = 0 the exact edge
/// displacement rises monotonically from R1 to R_final. Checked for steps from 1e-9 to
/// 1e6 and lambda from 0 to 1e4.
#[test]
fn stays_bounded_and_monotone_for_any_lambda_and_step() {
    let (r1, rf) = (exact::initial_radius(1.0), exact::final_radius(1.0, 10.0));
    for lambda in [0.0, 1e-3, 0.1, 1.0, 10.0, 1e4] {
        for h in [1e-9, 1e-4, 0.1, 10.0, 1e6] {
            let mut s = solver(lambda, 10.0, None);
            let mut last = s.wound_radius();
            for _ in 0..200 {
                s.advance(h, 0.0).unwrap();
                let r = s.wound_radius();
                assert!(r.is_finite() && r >= last - 1e-14, "lambda {lambda} h {h}: {last} -> {r}");
                assert!(r >= r1 - 1e-14 && r <= rf + 1e-12, "lambda {lambda} h {h}: {r}");
                last = r;
            }
        }
    }
}

#[test]
fn rejects_invalid_steps_and_parameters_without_changing_state() {
    let mut s = solver(1.0, 10.0, None);
    let before = s.state();
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(s.advance(h, 0.0).is_err(), "h = {h}");
    }
    assert!(s.advance(1.0, f64::NAN).is_err());
    assert_eq!(s.state(), before);
    for params in [
        Params { lambda: -1.0, sigma: 1.0, r_inf: 10.0 },
        Params { lambda: 1.0, sigma: f64::NAN, r_inf: 10.0 },
        Params { lambda: 1.0, sigma: 1.0, r_inf: 1.0 },
    ] {
        assert!(Solver::new(&params, &Settings::default()).is_err(), "{params:?}");
    }
}

/// No call may run for minutes or return NaN as a result: a step needing more internal
/// work than `MAX_STEP_WORK` is refused up front, and an explicit step that blows up is
/// refused with the state left as it was.
#[test]
fn runaway_steps_are_refused_and_change_nothing() {
    use wound_opening::solver::{Scheme, SolverError};
    let params = Params { lambda: 1.0, sigma: 1.0, r_inf: 10.0 };
    let mut paper =
        Solver::with_scheme(&params, &Scheme::Paper { points: 101, max_step: 1e-9 }).unwrap();
    assert!(matches!(paper.advance(1.0, 0.0), Err(SolverError::TooManySteps(..))));
    assert_eq!(paper.time(), 0.0);
    // lambda = 1 is far above the explicit limit dr / 2 = 0.045 of a 101-point grid: refused
    // before any step, not after values have grown to 1e171.
    let mut explicit =
        Solver::with_scheme(&params, &Scheme::Explicit { points: 101, max_step: 1e-3 }).unwrap();
    let before = explicit.state();
    let err = explicit.advance(0.1, 0.0).unwrap_err();
    assert!(matches!(err, SolverError::Unstable { .. }), "{err}");
    assert!(err.to_string().contains("unstable for lambda = 1 >= 4.5003e-2"), "{err}");
    assert_eq!(explicit.state(), before);
    // lambda = 0 with an internal step above dt_max = 4.0505e-3 (N = 101, R_inf = 10).
    let still = Params { lambda: 0.0, ..params };
    let (_, dt_max) = wound_opening::solver::explicit_stability_limits(101, 10.0, 0.0);
    for (max_step, refused) in [(1.01 * dt_max, true), (0.99 * dt_max, false)] {
        let mut s =
            Solver::with_scheme(&still, &Scheme::Explicit { points: 101, max_step }).unwrap();
        let got = s.advance(1.0, 0.0);
        assert_eq!(got.is_err(), refused, "max_step {max_step:e}: {got:?}");
        if let Err(e) = got {
            assert!(e.to_string().contains(&format!("dt < {dt_max:.4e}")), "{e}");
            assert_eq!(s.time(), 0.0);
        } else {
            assert!(
                s.wound_radius().is_finite() && s.wound_radius() < exact::final_radius(1.0, 10.0)
            );
        }
    }
}

/// R_inf up to 1e6 is accepted (the mesh grows like ln R_inf: 169 unknowns) and relaxes to
/// the exact final state; beyond, it is refused by name instead of failing slowly.
#[test]
fn very_large_domains_work_up_to_the_limit_and_are_refused_beyond() {
    let mut s = solver(
        1.0,
        1e6,
        Some(
            Settings::for_tolerance(&Params { lambda: 1.0, sigma: 1.0, r_inf: 1e6 }, 1e-10)
                .unwrap()
                .mesh,
        ),
    );
    s.advance(1e15, 0.0).unwrap();
    assert!((s.wound_radius() - exact::final_radius(1.0, 1e6)).abs() < 1e-10 * amplitude(1e6));
    let err = Solver::new(&Params { lambda: 1.0, sigma: 1.0, r_inf: 1e7 }, &Settings::default())
        .unwrap_err();
    assert!(
        err.to_string().starts_with("R_inf = 10000000 is outside the accepted range [1.001, 1e6]"),
        "{err}"
    );
}

/// The process-wide basis cache returns exactly what a fresh build gives, on both
/// eigensolver paths (QR at R_inf = 10, Jacobi at 1e4), so a cache hit cannot change an
/// answer; and solvers of different lambda at one R_inf share it.
#[test]
fn a_cached_basis_is_bit_identical_to_a_fresh_one() {
    use wound_opening::solver::basis;
    for r_inf in [10.0, 1e4] {
        let params = Params { lambda: 0.3, sigma: 1.0, r_inf };
        let spec = Settings::for_tolerance(&params, 1e-10).unwrap().mesh;
        let _warm = Solver::new(&params, &Settings { mesh: spec }).unwrap();
        assert!(basis::fresh_basis_equals_cached(spec, r_inf), "R_inf {r_inf}");
    }
}
