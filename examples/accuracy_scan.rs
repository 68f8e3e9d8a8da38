//! Wound radius and edge velocity of the default scheme over the edges of the accepted
//! domain, for comparison with the exact solution by `python/bench/accuracy_scan.py`.
//!
//! Usage: `cargo run --release --example accuracy_scan -- TOLERANCE > scan.csv`
//! (rows: lambda, R_inf, tolerance, unknowns, build seconds, t, R, dR/dt).
use std::time::Instant;
use wound_opening::solver::{Params, Settings, Solver};

const LAMBDAS: [f64; 9] = [0.0, 1e-3, 1e-2, 0.1, 1.0, 10.0, 1e3, 1e4, 1e6];
const RADII: [f64; 14] =
    [50.0, 100.0, 150.0, 200.0, 1.001, 1.01, 1.1, 2.0, 10.0, 1e3, 1e4, 1e5, 1e6, 3.0];

fn main() {
    let tol: f64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(1e-10);
    println!("lambda,R_inf,tolerance,unknowns,build_s,t,R,v");
    for r_inf in RADII {
        for lambda in LAMBDAS {
            let params = Params { lambda, sigma: 1.0, r_inf };
            let settings = Settings::for_tolerance(&params, tol).expect("valid");
            let start = Instant::now();
            let mut s = Solver::new(&params, &settings).expect("valid");
            let build = start.elapsed().as_secs_f64();
            // Times 0.01 .. 1e16 T, 4 per decade, and the late relaxation in lambda^2 + R_inf^2 units.
            for k in 0..=72 {
                let t = 0.01 * 10f64.powf(k as f64 / 4.0);
                s.advance(t - s.time(), 0.0).expect("step");
                println!(
                    "{lambda},{r_inf},{tol},{},{build},{t},{:.17e},{:.17e}",
                    s.unknowns(),
                    s.wound_radius(),
                    s.edge_velocity(0.0)
                );
            }
        }
    }
}
