//! Velocities at current radii and at the wound edge with their exact derivatives in sigma,
//! lambda and the time, and in the outer and current radii
//! ([`crate::solver::velocity_rates`]), in safe Rust; the shims are
//! [`super::series_c::wo_profile_sensitivities`] (four values per point) and
//! [`super::series_c::wo_profile_rates`] (six).

use super::error::Failure;
use super::pairs::reference_points;
use super::series::{Problem, check_radii, check_times, start, tissue_points, walk};
use super::solver_c::zeros;
use crate::solver::{Settings, VelocityRates, velocity_rates};

/// Values per point of `wo_profile_sensitivities`: velocity, d/dsigma, d/dlambda, d/dt.
pub const RATES: usize = 4;
/// Values per time of its edge output: the edge's own [`RATES`], then those from the tissue.
pub const EDGE_RATES: usize = 2 * RATES;
/// Values per point of `wo_profile_rates`: those of [`RATES`], then d/dR_inf and d/dr.
pub const ALL_RATES: usize = 6;

/// The first `out.len()` values of velocity, d/dsigma, d/dlambda, d/dt, d/dR_inf, d/dr.
fn put(out: &mut [f64], r: &VelocityRates) {
    let all = [r.velocity, r.d_sigma, r.d_lambda, r.d_tau, r.d_r_inf, r.d_r];
    out.copy_from_slice(&all[..out.len()]);
}

/// At each time `times[i] > 0` (ascending) of a problem with no edge stress: into
/// `points[(i * radii.len() + j) * w ..][..w]` (`w = width`, [`RATES`] or [`ALL_RATES`])
/// the velocity `u_t` (in R0 / T) of the material point at the CURRENT radius `radii[j]`
/// and its derivatives with respect to sigma, lambda and the time at that fixed current
/// radius, and with [`ALL_RATES`] also to `R_inf` and to the current radius; into
/// `edge[2 i w ..][..2 w]` the same of the wound edge (`dR/dt`, its material point held), then their limit from the tissue (a
/// current radius coming down to the edge: same velocity, derivatives through the moving
/// material point). Exact for the solver's grid. Written only on success.
pub fn profile_rates(
    width: usize,
    problem: &Problem,
    times: &[f64],
    radii: &[f64],
    points: &mut [f64],
    edge: Option<&mut [f64]>,
) -> Result<(), Failure> {
    check_times(times)?;
    check_radii(radii)?;
    if problem.edge_stress != 0.0 {
        return Err(Failure::invalid(format!(
            "edge_stress = {}: the sensitivities are those of a free edge (0)",
            problem.edge_stress
        )));
    }
    if let Some(i) = times.iter().position(|t| *t <= 0.0) {
        return Err(Failure::invalid(format!(
            "times[{i}] = {}: the sensitivities need times > 0",
            times[i]
        )));
    }
    let mut solver = start(problem)?;
    let settings = Settings::for_tolerance(&problem.params, problem.tolerance)?;
    let (n, r_inf) = (radii.len(), problem.params.r_inf);
    let mut p = zeros(times.len() * n * width, "rates")?;
    let mut e = zeros(times.len() * 2 * width, "edge")?;
    let left = walk(&mut solver, (0.0, r_inf), times, |i, s| {
        let x = tissue_points(s, radii, r_inf, (i, times[i]))?;
        let (rates, at_edge) =
            velocity_rates(&problem.params, &settings, times[i], &x, width > RATES)?;
        for (j, r) in rates.iter().enumerate() {
            put(&mut p[(i * n + j) * width..][..width], r);
        }
        put(&mut e[2 * i * width..][..width], &at_edge[0]);
        put(&mut e[(2 * i + 1) * width..][..width], &at_edge[1]);
        Ok(())
    })?;
    points.copy_from_slice(&p);
    if let Some(o) = edge {
        o.copy_from_slice(&e);
    }
    left.status()
}

/// [`profile_rates`] with a time of its own for each point: into
/// `points[i * width..][..width]` the rates of the material point at the CURRENT radius
/// `radii[i]` at `times[i]` (> 0, any order; a PIV field's ring points, each at its frame
/// pair's time). The solver is built once and walked through the distinct times in
/// ascending order; at each, the points of that time are found and differentiated side by
/// side. A radius inside the wound or beyond the outer edge at its time is refused, naming
/// the tissue's span then. The edge's rates come from [`profile_rates`] with no radii.
pub fn point_rates(
    width: usize,
    problem: &Problem,
    times: &[f64],
    radii: &[f64],
    points: &mut [f64],
) -> Result<(), Failure> {
    check_radii(radii)?;
    if problem.edge_stress != 0.0 {
        return Err(Failure::invalid(format!(
            "edge_stress = {}: the sensitivities are those of a free edge (0)",
            problem.edge_stress
        )));
    }
    if let Some(i) = times.iter().position(|t| !(t.is_finite() && *t > 0.0)) {
        return Err(Failure::invalid(format!(
            "times[{i}] = {}: the sensitivities need finite times > 0",
            times[i]
        )));
    }
    let mut order: Vec<usize> = (0..times.len()).collect();
    order.sort_by(|&a, &b| times[a].total_cmp(&times[b]));
    let mut distinct: Vec<f64> = order.iter().map(|&i| times[i]).collect();
    distinct.dedup();
    let mut solver = start(problem)?;
    let settings = Settings::for_tolerance(&problem.params, problem.tolerance)?;
    let r_inf = problem.params.r_inf;
    let mut p = zeros(radii.len() * width, "rates")?;
    let mut next = 0;
    let left = walk(&mut solver, (0.0, r_inf), &distinct, |k, s| {
        let first = next;
        while next < order.len() && times[order[next]] == distinct[k] {
            next += 1;
        }
        let here = &order[first..next];
        let x = reference_points(s, (radii, here), (times, "times"), r_inf)?;
        let (rates, _) =
            velocity_rates(&problem.params, &settings, distinct[k], &x, width > RATES)?;
        for (&i, rate) in here.iter().zip(&rates) {
            put(&mut p[i * width..][..width], rate);
        }
        Ok(())
    })?;
    points.copy_from_slice(&p);
    left.status()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::capi::series::{ProfileOut, profile_series, series};
    use crate::solver::Params;

    fn problem(sigma: f64, lambda: f64, r_inf: f64) -> Problem {
        Problem { params: Params { lambda, sigma, r_inf }, tolerance: 1e-11, edge_stress: 0.0 }
    }

    /// Velocities at `radii` and at the edge at one time (by `profile_series` and `series`).
    fn velocities(sigma: f64, lambda: f64, r_inf: f64, tau: f64, radii: &[f64]) -> Vec<f64> {
        let pr = problem(sigma, lambda, r_inf);
        let mut v = vec![0.0; radii.len()];
        profile_series(
            &pr,
            &[tau],
            radii,
            ProfileOut { displacement: None, velocity: Some(&mut v) },
        )
        .unwrap();
        let (mut r, mut ve) = ([0.0], [0.0]);
        series(&pr, &[tau], &mut r, Some(&mut ve)).unwrap();
        v.push(ve[0]);
        v
    }

    /// Against central differences of `profile_series` (and of `series` for the edge) at
    /// fixed current radii: relative steps 1e-4 in sigma and lambda, 1e-4 in tau (the grid
    /// does not depend on either), errors relative to the largest velocity of the profile.
    /// Measured worst 4.6e-8 (lambda at tau = 30, the differences' rounding; sigma at tau =
    /// 1e-3, their truncation); most below 1e-8.
    #[test]
    fn rates_match_central_differences_of_profiles() {
        let mut worst: f64 = 0.0;
        for (sigma, lambda, r_inf) in [
            (0.7, 0.3, 10.0),
            (1.5, 2.0, 6.0),
            (0.4, 0.05, 25.0),
            (-0.3, 1.0, 8.0),
            (0.6, 0.0, 6.0),
        ] {
            let sigma: f64 = sigma;
            for tau in [1e-3, 0.05, 1.0, 30.0] {
                let radii: Vec<f64> =
                    [1.3, 2.0, 3.5].iter().map(|f| f * (1.0 + 0.5 * sigma.max(0.0))).collect();
                let mut pts = vec![0.0; radii.len() * RATES];
                let mut edge = [0.0; EDGE_RATES];
                profile_rates(
                    RATES,
                    &problem(sigma, lambda, r_inf),
                    &[tau],
                    &radii,
                    &mut pts,
                    Some(&mut edge),
                )
                .unwrap();
                pts.extend(&edge[..RATES]);
                let at = |sigma, lambda, tau| velocities(sigma, lambda, r_inf, tau, &radii);
                let base = at(sigma, lambda, tau);
                let scale = base.iter().map(|v| v.abs()).fold(1e-300, f64::max);
                let (ds, dl, dt) = (1e-4 * sigma.abs(), 1e-4 * lambda, 1e-4 * tau);
                let diff = |a: Vec<f64>, b: Vec<f64>, h: f64| {
                    a.iter().zip(b).map(|(a, b)| (a - b) / (2.0 * h)).collect::<Vec<_>>()
                };
                let fd_s = diff(at(sigma + ds, lambda, tau), at(sigma - ds, lambda, tau), ds);
                let fd_l = if lambda > 0.0 {
                    diff(at(sigma, lambda + dl, tau), at(sigma, lambda - dl, tau), dl)
                } else {
                    vec![0.0; base.len()]
                };
                let fd_t = diff(at(sigma, lambda, tau + dt), at(sigma, lambda, tau - dt), dt);
                for j in 0..base.len() {
                    let g = &pts[j * RATES..][..RATES];
                    let what = format!(
                        "sigma {sigma} lambda {lambda} R_inf {r_inf} tau {tau} point {j}: {g:?}"
                    );
                    assert!((g[0] - base[j]).abs() <= 1e-13 * scale, "{what} vs {}", base[j]);
                    let errs = [
                        (g[1] - fd_s[j]) * sigma.abs(),
                        (g[2] - fd_l[j]) * lambda.max(1.0),
                        (g[3] - fd_t[j]) * tau,
                    ];
                    for (k, err) in errs.iter().enumerate() {
                        worst = worst.max(err.abs() / scale);
                        assert!(err.abs() < 1e-7 * scale, "{what}: column {k} off by {err}");
                    }
                }
            }
        }
        eprintln!("worst relative difference {worst:e}");
    }

    /// The edge seen from the tissue is the limit of the points at current radii coming
    /// down to the edge (here 1e-9 above it: the rates are smooth in r).
    #[test]
    fn the_edge_from_the_tissue_is_the_limit_of_the_points() {
        for (sigma, lambda, tau) in [(0.7, 0.3, 0.01), (1.2, 2.0, 1.0), (0.5, 0.0, 3.0)] {
            let pr = problem(sigma, lambda, 9.0);
            let (mut r, mut v) = ([0.0], [0.0]);
            series(&pr, &[tau], &mut r, Some(&mut v)).unwrap();
            let (mut pts, mut edge) = ([0.0; RATES], [0.0; EDGE_RATES]);
            profile_rates(RATES, &pr, &[tau], &[r[0] * (1.0 + 1e-9)], &mut pts, Some(&mut edge))
                .unwrap();
            let scale = pts.iter().map(|x| x.abs()).fold(0.0, f64::max);
            for q in 0..RATES {
                assert!(
                    (edge[RATES + q] - pts[q]).abs() < 1e-7 * scale,
                    "{sigma} {lambda} {tau}: {edge:?} vs {pts:?}"
                );
            }
            assert_eq!(edge[0], edge[RATES], "the same velocity");
            assert_ne!(edge[1], edge[RATES + 1], "different derivatives");
        }
    }

    /// The outer-radius and current-radius columns of `profile_rates` against central
    /// differences (relative steps 1e-4 in R_inf, 1e-5 in r, on the same mesh: a case whose
    /// steps changed the element count would fail its first assertion), relative to the
    /// largest velocity. Measured worst 8e-8: the differences' rounding (1e-11 of the
    /// velocity over the step; 1.5e-7 with steps 1e-5).
    #[test]
    fn outer_and_current_radius_rates_match_central_differences() {
        let mut worst: f64 = 0.0;
        for (sigma, lambda, r_inf) in [
            (0.7, 0.3, 10.0),
            (1.5, 2.0, 6.0),
            (0.4, 0.05, 25.0),
            (-0.3, 1.0, 8.0),
            (0.6, 0.0, 2.8),
            (0.5, 3.0, 125.0),
        ] {
            let sigma: f64 = sigma;
            let h = 1e-4 * r_inf;
            let shrink = f64::min(1.0, r_inf / 3.6);
            let mesh = |r: f64| {
                Settings::for_tolerance(&Params { lambda, sigma, r_inf: r }, 1e-11).unwrap().mesh
            };
            assert_eq!(mesh(r_inf - h), mesh(r_inf + h), "a case across an element-count change");
            for tau in [1e-3, 0.05, 1.0, 30.0] {
                let radii: Vec<f64> = [1.3, 2.0, 2.4]
                    .iter()
                    .map(|f| {
                        f64::max(shrink * f, 1.0 + 0.8 * (f - 1.0)) * (1.0 + 0.5 * sigma.max(0.0))
                    })
                    .collect();
                let mut pts = vec![0.0; radii.len() * ALL_RATES];
                let mut edge = [0.0; 2 * ALL_RATES];
                profile_rates(
                    ALL_RATES,
                    &problem(sigma, lambda, r_inf),
                    &[tau],
                    &radii,
                    &mut pts,
                    Some(&mut edge),
                )
                .unwrap();
                let base = velocities(sigma, lambda, r_inf, tau, &radii);
                let scale = base.iter().map(|v| v.abs()).fold(1e-300, f64::max);
                let up = velocities(sigma, lambda, r_inf + h, tau, &radii);
                let down = velocities(sigma, lambda, r_inf - h, tau, &radii);
                let mut rows: Vec<&[f64]> = pts.chunks(ALL_RATES).collect();
                rows.push(&edge[..ALL_RATES]);
                for (j, g) in rows.iter().enumerate() {
                    let what = format!(
                        "sigma {sigma} lambda {lambda} R_inf {r_inf} tau {tau} point {j}: {g:?}"
                    );
                    let fd = (up[j] - down[j]) / (2.0 * h);
                    let err = (g[4] - fd) * r_inf;
                    worst = worst.max(err.abs() / scale);
                    assert!(err.abs() < 1e-6 * scale, "{what}: d/dR_inf {} vs {fd}", g[4]);
                    if j < radii.len() {
                        let dr = 1e-5 * radii[j];
                        let mut near = radii.clone();
                        near[j] += dr;
                        let a = velocities(sigma, lambda, r_inf, tau, &near)[j];
                        near[j] -= 2.0 * dr;
                        let b = velocities(sigma, lambda, r_inf, tau, &near)[j];
                        let err = (g[5] - (a - b) / (2.0 * dr)) * radii[j];
                        worst = worst.max(err.abs() / scale);
                        assert!(
                            err.abs() < 1e-6 * scale,
                            "{what}: d/dr {} vs {}",
                            g[5],
                            (a - b) / (2.0 * dr)
                        );
                    } else {
                        assert_eq!(g[5], 0.0, "the edge's own velocity does not depend on r");
                    }
                }
                let mut four = vec![0.0; radii.len() * RATES];
                profile_rates(
                    RATES,
                    &problem(sigma, lambda, r_inf),
                    &[tau],
                    &radii,
                    &mut four,
                    None,
                )
                .unwrap();
                for (a, b) in four.chunks(RATES).zip(pts.chunks(ALL_RATES)) {
                    assert_eq!(a, &b[..RATES], "the first four values are those of RATES");
                }
            }
        }
        eprintln!("worst relative difference {worst:e}");
    }

    #[test]
    fn an_edge_stress_or_the_cut_is_refused() {
        let mut out = [0.0; RATES];
        let pr = Problem { edge_stress: 0.1, ..problem(0.5, 1.0, 5.0) };
        assert!(profile_rates(RATES, &pr, &[1.0], &[2.0], &mut out, None).is_err());
        assert!(
            profile_rates(RATES, &problem(0.5, 1.0, 5.0), &[0.0], &[2.0], &mut out, None).is_err()
        );
    }
}
