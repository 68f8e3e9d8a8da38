//! The comparison schemes against the exact solution: the paper's scheme reproduces the
//! first-order errors that docs/model.md ("The paper's own scheme") reports; TR-BDF2 converges at second
//! order in time; linear elements with exact time at second order in space.

use wound_opening::solver::{MeshSpec, Params, Scheme, Settings, Solver, exact};

const TIMES: [f64; 9] = [0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0];

/// Exact R(t) at `TIMES` for sigma = 1, R_inf = 10: python/wound_exact.py `edge` (the
/// Laplace-domain solution, agreeing with 30-digit mpmath to 1e-13).
const EXACT: [(f64, [f64; 9]); 3] = [
    (
        0.1,
        [
            1.251622489477179,
            1.348739749146083,
            1.408762551708134,
            1.475858470310715,
            1.5603031799364528,
            1.6079973285298652,
            1.6382917482457229,
            1.6637671078386764,
            1.672211005132005,
        ],
    ),
    (
        1.0,
        [
            1.186868886232186,
            1.256340374316833,
            1.323084408484105,
            1.4130637734354878,
            1.5329251510141442,
            1.5970947064445615,
            1.6352133923769467,
            1.6629223262999737,
            1.6719957182851066,
        ],
    ),
    (
        10.0,
        [
            1.1671499020476213,
            1.1690782187509017,
            1.171478242096027,
            1.1762439236350979,
            1.1902699785885138,
            1.212769056298522,
            1.2546594943044957,
            1.3587469635739131,
            1.477803936561683,
        ],
    ),
];

/// Largest error at `TIMES`, relative to the opening amplitude.
fn max_error(lambda: f64, scheme: &Scheme, reference: &[f64; 9]) -> f64 {
    let mut s = Solver::with_scheme(&Params { lambda, sigma: 1.0, r_inf: 10.0 }, scheme).unwrap();
    let amp = exact::final_radius(1.0, 10.0) - exact::initial_radius(1.0);
    TIMES.iter().zip(reference).fold(0.0f64, |m, (&t, &r)| {
        s.advance(t - s.time(), 0.0).unwrap();
        m.max((s.wound_radius() - r).abs() / amp)
    })
}

/// The paper's scheme is first order: 10-22 % of the opening amplitude with N = 101 points
/// and 1-2 % with N = 1001, whatever dt, at nine times from 0.1 to 100 (docs/model.md,
/// "The paper's own scheme").
#[test]
fn paper_scheme_reproduces_its_known_first_order_error() {
    for (lambda, reference) in EXACT {
        let coarse = max_error(lambda, &Scheme::Paper { points: 101, max_step: 1e-3 }, &reference);
        let fine = max_error(lambda, &Scheme::Paper { points: 1001, max_step: 1e-3 }, &reference);
        let coarser_step =
            max_error(lambda, &Scheme::Paper { points: 1001, max_step: 4e-3 }, &reference);
        assert!((0.10..0.22).contains(&coarse), "lambda {lambda}: N=101 error {coarse}");
        assert!((0.010..0.020).contains(&fine), "lambda {lambda}: N=1001 error {fine}");
        // First order in space: ten times the points, about a tenth of the error.
        let order = (coarse / fine).log10();
        assert!((order - 1.0).abs() < 0.1, "lambda {lambda}: order {order}");
        // "whatever dt": the spatial error dominates (four times the step changes the error
        // by 0.01-0.1 %, measured; a step four times smaller took three quarters of the time).
        assert!(
            (coarser_step / fine - 1.0).abs() < 0.01,
            "lambda {lambda}: {fine} vs {coarser_step}"
        );
    }
}

/// TR-BDF2 on a mesh fine enough (tolerance 1e-10) that the time error dominates:
/// halving the step divides the error by about 4.
#[test]
fn trbdf2_is_second_order_in_time() {
    let (lambda, reference) = EXACT[1];
    let mesh =
        Settings::for_tolerance(&Params { lambda, sigma: 1.0, r_inf: 10.0 }, 1e-10).unwrap().mesh;
    let errors: Vec<f64> = [0.02, 0.01, 0.005]
        .iter()
        .map(|&dt| max_error(lambda, &Scheme::TrBdf2 { mesh, max_step: dt }, &reference))
        .collect();
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((order - 2.0).abs() < 0.2, "order {order} from {errors:?}");
    }
}

/// Linear elements, exact in time: second order in space (the classical method the
/// spectral default is measured against).
#[test]
fn linear_elements_are_second_order_in_space() {
    for (lambda, reference) in EXACT {
        let errors: Vec<f64> = [16, 32, 64]
            .iter()
            .map(|&elements| {
                let mesh = MeshSpec { degree: 1, elements, edge_scale: 0.1 };
                max_error(lambda, &Scheme::Modal(Settings { mesh }), &reference)
            })
            .collect();
        for w in errors.windows(2) {
            let order = (w[0] / w[1]).log2();
            assert!((order - 2.0).abs() < 0.15, "lambda {lambda}: order {order} from {errors:?}");
        }
    }
}

/// Every scheme rejects an invalid resolution instead of building something absurd.
#[test]
fn invalid_resolutions_are_rejected() {
    let params = Params::default();
    let bad = [
        Scheme::Paper { points: 2, max_step: 1e-3 },
        Scheme::Paper { points: 101, max_step: 0.0 },
        Scheme::Explicit { points: 101, max_step: f64::NAN },
        Scheme::TrBdf2 {
            mesh: MeshSpec { degree: 0, elements: 4, edge_scale: 0.1 },
            max_step: 0.01,
        },
        Scheme::Modal(Settings { mesh: MeshSpec { degree: 4, elements: 4, edge_scale: -1.0 } }),
    ];
    for scheme in bad {
        assert!(Solver::with_scheme(&params, &scheme).is_err(), "{scheme:?}");
    }
}
