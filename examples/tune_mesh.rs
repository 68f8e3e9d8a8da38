//! Scan of mesh settings against exact reference tables, used to derive and check the
//! tolerance rule of `Settings::for_tolerance` (src/solver/tolerance.rs).
//!
//! Reference tables: `python python/reference_tables.py DIR` (CSV rows t, R, dR/dt).
//! Usage: `tune_mesh DIR DEGREE ELEMENTS EDGE_SCALE` (one mesh, every case), or
//!        `tune_mesh DIR tol` (the rule, for tolerances 1e-2 .. 1e-12).
use wound_opening::solver::*;

const LAMBDAS: [&str; 11] =
    ["0", "0.001", "0.01", "0.03", "0.1", "0.3", "1", "3", "10", "100", "1000"];
const RADII: [&str; 5] = ["1.5", "2", "10", "100", "1000"];

/// Largest error relative to the opening amplitude over the table's times (t >= 0.01).
fn error(dir: &str, lam: &str, r: &str, settings: impl Fn(&Params) -> Settings) -> (f64, usize) {
    let text =
        std::fs::read_to_string(format!("{dir}/ref_{lam}_{r}.csv")).expect("reference table");
    let params = Params { lambda: lam.parse().unwrap(), sigma: 1.0, r_inf: r.parse().unwrap() };
    let mut s = Solver::new(&params, &settings(&params)).unwrap();
    let amp = exact::final_radius(1.0, params.r_inf) - exact::initial_radius(1.0);
    let mut err = 0.0f64;
    for row in text.lines() {
        let v: Vec<f64> = row.split(',').map(|x| x.parse().unwrap()).collect();
        s.advance(v[0] - s.time(), 0.0).unwrap();
        err = err.max((s.wound_radius() - v[1]).abs() / amp);
    }
    (err, s.unknowns())
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let dir = &a[1];
    if a[2] == "tol" {
        for k in 2..=12 {
            let tol = 10f64.powi(-k);
            let (mut worst, mut sizes) = (0.0f64, Vec::new());
            for lam in LAMBDAS {
                for r in RADII {
                    let (e, n) = error(dir, lam, r, |p| Settings::for_tolerance(p, tol).unwrap());
                    worst = worst.max(e);
                    if lam == "0" {
                        sizes.push(n);
                    }
                }
            }
            let ok = if worst <= tol.max(FINEST_TOLERANCE) { "ok" } else { "FAIL" };
            println!(
                "tol {tol:.0e}: worst {worst:.1e} {ok}; unknowns for R_inf {RADII:?}: {sizes:?}"
            );
        }
        return;
    }
    let spec = MeshSpec {
        degree: a[2].parse().unwrap(),
        elements: a[3].parse().unwrap(),
        edge_scale: a[4].parse().unwrap(),
    };
    for lam in LAMBDAS {
        let row: Vec<String> = RADII
            .iter()
            .map(|r| format!("{:8.1e}", error(dir, lam, r, |_| Settings { mesh: spec }).0))
            .collect();
        println!("lam {lam:>6}: {}", row.join(" "));
    }
}
