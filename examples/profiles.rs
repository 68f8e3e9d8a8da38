//! Displacement and velocity profiles for the paper's four panels (docs/model.md, "The paper's figures"):
//! R_inf = 10, sigma = 1, lambda = 0.1, 1, 10, from the default solver.
//!
//! Usage: `cargo run --release --example profiles -- DIR`; writes DIR/profiles.csv with
//! rows `lambda,t,r,u,v`: t = 0 (v is the velocity just after the cut), 60 times spaced
//! logarithmically from 1e-3 to 1e3 (times 1 for lambda = 10: lambda^2 T), and t = inf
//! (the exact relaxed state `a r + b / r`, v = 0); r on 91 points of [1, 10].

use std::io::Write;
use wound_opening::solver::{Params, Settings, Solver, exact};

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: profiles DIR"));
    let mut csv = std::fs::File::create(dir.join("profiles.csv")).expect("writable DIR");
    writeln!(csv, "lambda,t,r,u,v").unwrap();
    let radii: Vec<f64> = (0..=90).map(|k| 1.0 + 0.1 * k as f64).collect();
    for lambda in [0.1, 1.0, 10.0] {
        let params = Params { lambda, sigma: 1.0, r_inf: 10.0 };
        let mut s = Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).expect("valid"))
            .expect("valid");
        let scale = if lambda > 1.0 { lambda * lambda } else { 1.0 };
        let times = std::iter::once(0.0)
            .chain((0..60).map(|k| scale * 10f64.powf(-3.0 + 6.0 * k as f64 / 59.0)));
        for t in times {
            if t > s.time() {
                s.advance(t - s.time(), 0.0).expect("valid step");
            }
            let (u, v) = (s.displacement(&radii), s.velocity(0.0, &radii));
            for ((r, u), v) in radii.iter().zip(u).zip(v) {
                writeln!(csv, "{lambda},{t:e},{r},{u:e},{v:e}").unwrap();
            }
        }
        for r in &radii {
            writeln!(csv, "{lambda},inf,{r},{:e},0", exact::final_displacement(1.0, 10.0, *r))
                .unwrap();
        }
    }
}
