//! Work-precision data of every scheme on the benchmark scenario (R_inf = 10, sigma = 1,
//! 1000 steps of 0.1), in-process.
//!
//! Usage: `cargo run --release --example work_precision -- DIR`; reads DIR/reference_{lambda}.csv
//! (t, R exact; written by python/bench) and writes DIR/work_precision.csv.

#[path = "common/bench_util.rs"]
mod bench_util;

use bench_util::*;
use std::io::Write;
use wound_opening::solver::{MeshSpec, Params, Scheme, Settings, explicit_stability_limits};

fn schemes(lambda: f64) -> Vec<(String, Scheme)> {
    let params = Params { lambda, sigma: SIGMA, r_inf: R_INF };
    let mut out = Vec::new();
    for k in 2..=12 {
        let tol = 10f64.powi(-k);
        let settings = Settings::for_tolerance(&params, tol).expect("valid");
        out.push((format!("modal,tol={tol:.0e}"), Scheme::Modal(settings)));
    }
    for elements in [8, 16, 32, 64, 128, 256] {
        let mesh = MeshSpec { degree: 1, elements, edge_scale: 0.1 };
        out.push((format!("modal_linear,E={elements}"), Scheme::Modal(Settings { mesh })));
    }
    let fine = Settings::for_tolerance(&params, 1e-10).expect("valid").mesh;
    for dt in [0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001] {
        out.push((format!("trbdf2,dt={dt}"), Scheme::TrBdf2 { mesh: fine, max_step: dt }));
    }
    for (points, dt) in
        [(51, 0.05), (101, 0.02), (201, 0.01), (401, 0.005), (1001, 0.002), (2001, 0.001)]
    {
        out.push((format!("paper,N={points};dt={dt}"), Scheme::Paper { points, max_step: dt }));
    }
    for points in [11, 21, 41, 81, 161] {
        let (lambda_max, dt_max) = explicit_stability_limits(points, R_INF, lambda);
        if lambda < lambda_max && dt_max > 0.0 {
            let dt = 0.9 * dt_max;
            out.push((
                format!("explicit,N={points};dt={dt:.3e}"),
                Scheme::Explicit { points, max_step: dt },
            ));
        }
    }
    out
}

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: work_precision DIR"));
    let mut csv = std::fs::File::create(dir.join("work_precision.csv")).expect("writable DIR");
    writeln!(csv, "scheme,lambda,resolution,unknowns,error,cpu_seconds").unwrap();
    for lambda in [0.1, 1.0, 10.0] {
        let rows = read_csv(&dir.join(format!("reference_{lambda}.csv")));
        assert_eq!(rows.len(), SCENARIO_STEPS, "reference rows");
        let reference: Vec<f64> = rows.iter().map(|r| r[1]).collect();
        for (label, scheme) in schemes(lambda) {
            let (name, resolution) = label.split_once(',').expect("label");
            let params = Params { lambda, sigma: SIGMA, r_inf: R_INF };
            let unknowns = wound_opening::solver::Solver::with_scheme(&params, &scheme)
                .map_or(0, |s| s.unknowns());
            let (cpu, radius) = best_cpu(|| scenario(lambda, &scheme));
            let err = radius.map_or(f64::INFINITY, |r| error(&r, &reference));
            writeln!(csv, "{name},{lambda},{resolution},{unknowns},{err:.6e},{cpu:.6e}").unwrap();
            println!(
                "lambda {lambda:>4} {name:>12} {resolution:<24} N={unknowns:<5} error {err:9.2e}  cpu {:9.3} ms",
                cpu * 1e3
            );
        }
    }
}
