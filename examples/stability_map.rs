//! Stability map of every scheme over lambda and step size (and grid size), and the
//! measured limits of the explicit scheme against its von Neumann theory
//! (src/solver/explicit.rs).
//!
//! Usage: `cargo run --release --example stability_map -- DIR`; writes DIR/stability.csv
//! and DIR/explicit_limits.csv.
//!
//! Status of a run of 200 steps of size dt from the cut (p = 0, R_inf = 10): see
//! `wound_opening::solver::stability`.

#[path = "common/bench_util.rs"]
mod bench_util;

use bench_util::*;
use std::io::Write;
use wound_opening::solver::{Params, Scheme, Settings, explicit_stability_limits};

const STEPS: usize = 200;

/// The schemes of the map; the internal step of the stepping schemes is the map's dt.
fn scheme(name: &str, points: usize, lambda: f64, dt: f64) -> Scheme {
    match name {
        "modal" => Scheme::Modal(
            Settings::for_tolerance(&Params { lambda, sigma: SIGMA, r_inf: R_INF }, 1e-10)
                .expect("valid"),
        ),
        "trbdf2" => Scheme::TrBdf2 {
            mesh: Settings::for_tolerance(&Params { lambda, sigma: SIGMA, r_inf: R_INF }, 1e-6)
                .expect("valid")
                .mesh,
            max_step: dt,
        },
        "paper" => Scheme::Paper { points, max_step: dt },
        _ => Scheme::Explicit { points, max_step: dt },
    }
}

/// Smallest value in `[lo, hi]` (log scale) at which `unstable` turns true, by bisection.
fn threshold(mut lo: f64, mut hi: f64, unstable: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..40 {
        let mid = (lo * hi).sqrt();
        if unstable(mid) { hi = mid } else { lo = mid }
    }
    (lo * hi).sqrt()
}

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: stability_map DIR"));
    let mut csv = std::fs::File::create(dir.join("stability.csv")).expect("writable DIR");
    writeln!(csv, "scheme,lambda,dt,points,status").unwrap();
    let lambdas = [0.0, 1e-3, 1e-2, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0, 1e3, 1e4];
    let steps: Vec<f64> = (-12..=8).map(|k| 10f64.powf(k as f64 / 2.0)).collect();
    for (name, grids) in [
        ("modal", vec![0]),
        ("trbdf2", vec![0]),
        ("paper", vec![101, 1001]),
        ("explicit", vec![21, 51, 101]),
    ] {
        for &points in &grids {
            for &lambda in &lambdas {
                for &dt in &steps {
                    let st = classify(lambda, &scheme(name, points, lambda, dt), dt, STEPS);
                    writeln!(
                        csv,
                        "{name},{lambda},{dt:e},{points},{}",
                        format!("{st:?}").to_lowercase()
                    )
                    .unwrap();
                }
            }
            println!("{name} N={points}: done");
        }
    }
    // Explicit limits: dt_max at several lambda below lambda_max, and lambda_max at small dt.
    let mut lim = std::fs::File::create(dir.join("explicit_limits.csv")).expect("writable DIR");
    writeln!(
        lim,
        "points,lambda,dt_max_theory,dt_max_measured,lambda_max_theory,lambda_max_measured"
    )
    .unwrap();
    for points in [21, 51, 101, 201] {
        let (lambda_max, _) = explicit_stability_limits(points, R_INF, 0.0);
        let long = 20 * STEPS;
        let dt_small = 1e-3 * explicit_stability_limits(points, R_INF, 0.0).1;
        let lambda_measured = threshold(1e-3 * lambda_max, 1e3 * lambda_max, |l| {
            classify(l, &Scheme::Explicit { points, max_step: dt_small }, dt_small, long)
                == Status::Unbounded
        });
        for frac in [0.0, 0.25, 0.5, 0.75, 0.9] {
            let lambda = frac * lambda_max;
            let (_, dt_theory) = explicit_stability_limits(points, R_INF, lambda);
            let dt_measured = threshold(1e-4 * dt_theory, 1e2 * dt_theory, |dt| {
                classify(lambda, &Scheme::Explicit { points, max_step: dt }, dt, long)
                    == Status::Unbounded
            });
            writeln!(lim, "{points},{lambda:e},{dt_theory:e},{dt_measured:e},{lambda_max:e},{lambda_measured:e}").unwrap();
            println!(
                "explicit N={points} lambda={lambda:.4}: dt_max theory {dt_theory:.4e} measured {dt_measured:.4e}; lambda_max theory {lambda_max:.4} measured {lambda_measured:.4}"
            );
        }
    }
}
