//! Displacements over frame pairs: what a PIV vector measures, in safe Rust. The shim is
//! `wo_pair_displacement` in [`super::series_c`].
//!
//! A PIV program reports the shift of the texture in its interrogation window between two
//! frames at `t_a < t_b`: the displacement of the same material points over `[t_a, t_b]`,
//! not a velocity at one instant. The model's motion is radial and a material point keeps
//! its reference radius `X`, so for the point at CURRENT radius `r` at `t_a`
//!
//! ```text
//! X + u(X, t_a) = r                  (X found as by wo_profile_series, at t_a)
//! d = u(X, t_b) - u(X, t_a)          (the displacement over the pair, exactly)
//! ```
//!
//! Every point has its own pair of times; the solver is built once and advanced through
//! the distinct times in ascending order (exact in time, as the series functions), so a
//! whole PIV field of many frame pairs is one call: at each distinct time the reference
//! radii of the points whose pair starts there are found side by side
//! ([`super::series::reference_radii`]) and the displacements of the points whose pair
//! starts or ends there are evaluated in one sum of the modes.

use super::error::Failure;
use super::series::{Problem, check_radii, reference_radii, start, walk};
use super::solver_c::zeros;
use crate::solver::Solver;

/// One end of a point's pair: the point's index, and whether it is the pair's end `t_b`.
#[derive(Debug, Clone, Copy)]
struct End {
    time: f64,
    point: usize,
    last: bool,
}

/// `t_a[i]` finite and >= 0, `t_b[i]` finite and >= `t_a[i]`.
fn check_pairs(t_a: &[f64], t_b: &[f64]) -> Result<(), Failure> {
    for (i, (&a, &b)) in t_a.iter().zip(t_b).enumerate() {
        if !(a.is_finite() && a >= 0.0) {
            return Err(Failure::invalid(format!(
                "t_a[{i}] = {a} is invalid: expected a finite time >= 0"
            )));
        }
        if !(b.is_finite() && b >= a) {
            return Err(Failure::invalid(format!(
                "t_b[{i}] = {b} is invalid: expected a finite time >= t_a[{i}] = {a}"
            )));
        }
    }
    Ok(())
}

/// The displacement `u(X_i, t_b[i]) - u(X_i, t_a[i])` of the material point at current
/// radius `radii[i]` at `t_a[i]` (module docstring) into `out[i]`, for every point `i`.
/// A radius inside the wound or beyond the outer edge at its `t_a` is refused, naming the
/// tissue's span then; a run that leaves the model's validity is reported as by the series
/// functions, every output written.
pub fn pair_displacement(
    problem: &Problem,
    t_a: &[f64],
    t_b: &[f64],
    radii: &[f64],
    out: &mut [f64],
) -> Result<(), Failure> {
    check_pairs(t_a, t_b)?;
    check_radii(radii)?;
    let n = radii.len();
    let mut ends = Vec::new();
    ends.try_reserve_exact(2 * n).map_err(|_| super::solver_c::too_large("radii", n))?;
    for i in 0..n {
        ends.push(End { time: t_a[i], point: i, last: false });
        ends.push(End { time: t_b[i], point: i, last: true });
    }
    // Ascending times, a pair's start before its end where the two coincide.
    ends.sort_by(|p, q| p.time.total_cmp(&q.time).then(p.last.cmp(&q.last)));
    let mut times: Vec<f64> = ends.iter().map(|e| e.time).collect();
    times.dedup();
    let mut solver = start(problem)?;
    let r_inf = problem.params.r_inf;
    let mut reference = zeros(n, "reference radii")?;
    let mut d = zeros(n, "displacement")?;
    let mut next = 0;
    let left = walk(&mut solver, (problem.edge_stress, r_inf), &times, |_, s| {
        let first = next;
        while next < ends.len() && ends[next].time == s.time() {
            next += 1;
        }
        let here = &ends[first..next];
        let starting: Vec<usize> = here.iter().filter(|e| !e.last).map(|e| e.point).collect();
        if !starting.is_empty() {
            let x = reference_points(s, (radii, &starting), (t_a, "t_a"), r_inf)?;
            for (&i, &xi) in starting.iter().zip(&x) {
                reference[i] = xi;
            }
        }
        let points: Vec<f64> = here.iter().map(|e| reference[e.point]).collect();
        for (e, u) in here.iter().zip(s.displacement(&points)) {
            if e.last { d[e.point] += u } else { d[e.point] -= u }
        }
        Ok(())
    })?;
    out.copy_from_slice(&d);
    left.status()
}

/// The reference radii of the points `which` (current radii `radii[i]` at the solver's time,
/// `times[i]`, an array the messages call `name`), refusing one inside the wound or beyond
/// the outer edge then.
pub(super) fn reference_points(
    s: &Solver,
    (radii, which): (&[f64], &[usize]),
    (times, name): (&[f64], &str),
    r_inf: f64,
) -> Result<Vec<f64>, Failure> {
    let ends = s.displacement(&[1.0, r_inf]);
    let (lo, hi) = (1.0 + ends[0], r_inf + ends[1]);
    if let Some(&i) = which.iter().find(|&&i| !(lo..=hi).contains(&radii[i])) {
        let place = if radii[i] < lo { "inside the wound" } else { "outside the tissue" };
        return Err(Failure::invalid(format!(
            "radii[{i}] = {} is {place} at {name}[{i}] = {}: the tissue spans current radii \
             [{lo}, {hi}] then",
            radii[i], times[i]
        )));
    }
    let r: Vec<f64> = which.iter().map(|&i| radii[i]).collect();
    Ok(reference_radii(s, &r, r_inf, (lo, hi)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::Params;

    fn problem(lambda: f64) -> Problem {
        Problem {
            params: Params { lambda, sigma: 1.0, r_inf: 10.0 },
            tolerance: 1e-10,
            edge_stress: 0.0,
        }
    }

    /// One point alone gives the same double as among many, whatever the order of pairs.
    #[test]
    fn a_point_among_many_is_the_point_alone() {
        let (a, b, r) = (vec![0.5, 0.1, 0.5], vec![1.0, 0.6, 0.5], vec![3.0, 2.0, 5.0]);
        let mut all = vec![0.0; 3];
        pair_displacement(&problem(1.0), &a, &b, &r, &mut all).unwrap();
        for i in 0..3 {
            let mut one = [0.0];
            pair_displacement(&problem(1.0), &a[i..=i], &b[i..=i], &r[i..=i], &mut one).unwrap();
            assert_eq!(one[0], all[i], "point {i}");
        }
        assert_eq!(all[2], 0.0, "an empty pair moves nothing");
    }

    #[test]
    fn refusals_name_the_point() {
        let mut out = [0.0];
        let e = pair_displacement(&problem(1.0), &[0.5], &[0.4], &[3.0], &mut out).unwrap_err();
        assert!(e.message.contains("t_b[0] = 0.4"), "{}", e.message);
        let e = pair_displacement(&problem(1.0), &[0.5], &[1.0], &[1.01], &mut out).unwrap_err();
        assert!(e.message.contains("inside the wound at t_a[0] = 0.5"), "{}", e.message);
        let e = pair_displacement(&problem(1.0), &[-1.0], &[1.0], &[3.0], &mut out).unwrap_err();
        assert!(e.message.contains("t_a[0] = -1"), "{}", e.message);
    }
}
