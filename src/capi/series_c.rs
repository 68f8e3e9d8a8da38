//! The exported series functions: thin `extern "C"` shims over [`super::series`], with the
//! pointer rules of [`super::solver_c`] (NULL refused unless its count is 0, outputs written
//! only on success), except that an output marked optional may be NULL to skip it.
#![allow(clippy::missing_safety_doc)]

use super::error::{Failure, WoStatus, run};
use super::pairs::pair_displacement;
use super::profile_rates::{ALL_RATES, RATES, point_rates, profile_rates};
use super::series::{self, Problem, ProfileOut, SeriesOut};
use super::solver_c::{input, output};
use crate::solver::Params;

/// One problem of a series call: the parameters (lambda, sigma, R_inf, as in
/// `wo_solver_new`), the accuracy target `tolerance` (which picks the grid, as there) and
/// the edge stress (in G) held constant from the cut on.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct WoProblem {
    pub lambda: f64,
    pub sigma: f64,
    pub r_inf: f64,
    pub tolerance: f64,
    pub edge_stress: f64,
}

impl WoProblem {
    fn problem(self) -> Problem {
        let WoProblem { lambda, sigma, r_inf, tolerance, edge_stress } = self;
        Problem { params: Params { lambda, sigma, r_inf }, tolerance, edge_stress }
    }
}

/// An optional output array: NULL skips it.
fn optional<'a>(p: *mut f64, count: usize, what: &str) -> Result<Option<&'a mut [f64]>, Failure> {
    if p.is_null() { Ok(None) } else { output(p, count, what).map(Some) }
}

/// The wound radius R(t_i) (in R0) and the edge velocity dR/dt(t_i) (in R0 / T) at
/// `times[i]` (in T; finite, >= 0, ascending), `i < count`, of one `problem`. `velocity` may be NULL (radius only); at
/// lambda = 0 a velocity asked for at t = 0 is infinite in the model: `WO_UNDEFINED`, and
/// nothing is written. One solver is built (O(modes) when the basis of this R_inf is
/// cached) and advanced from time to time, exactly. A run that leaves the model's validity
/// is `WO_OUTSIDE_VALIDITY` (a warning, as `wo_solver_advance`): every output is written and
/// the message names the first time outside; the other series functions likewise.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_series(
    problem: WoProblem,
    times: *const f64,
    count: usize,
    radius: *mut f64,
    velocity: *mut f64,
) -> WoStatus {
    run("wo_series", || {
        let t = input(times, count, "times")?;
        let r = output(radius, count, "radius")?;
        series::series(&problem.problem(), &t, r, optional(velocity, count, "velocity")?)
    })
}

/// As `wo_series`, and the derivatives of the wound radius with respect to lambda
/// (`d_radius_d_lambda`, in R0) and to the outer radius R_inf (`d_radius_d_r_inf`, in R0 per
/// R0) at each time: exact derivatives of the solver's own R(t) on the grid the tolerance
/// picks, through its modal basis (no further decomposition; 0 in lambda at lambda = 0).
/// `velocity`, `d_radius_d_lambda` and `d_radius_d_r_inf` may each be NULL (not computed).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_series_sensitivities(
    problem: WoProblem,
    times: *const f64,
    count: usize,
    radius: *mut f64,
    velocity: *mut f64,
    d_radius_d_lambda: *mut f64,
    d_radius_d_r_inf: *mut f64,
) -> WoStatus {
    run("wo_series_sensitivities", || {
        let t = input(times, count, "times")?;
        let r = output(radius, count, "radius")?;
        let out = SeriesOut {
            velocity: optional(velocity, count, "velocity")?,
            d_lambda: optional(d_radius_d_lambda, count, "d_radius_d_lambda")?,
            d_r_inf: optional(d_radius_d_r_inf, count, "d_radius_d_r_inf")?,
        };
        series::series_sensitivities(&problem.problem(), &t, r, out)
    })
}

/// Displacement u and velocity u_t, at each of `times[i]` (`i < n_times`, ascending), of
/// the material points found at the CURRENT radii `radii[j]` (`j < n_radii`, in R0 from the
/// wound centre, as PIV measures them): X_j solves X + u(X, t_i) = radii[j]. Row-major
/// outputs of `n_times * n_radii` values, `u[i * n_radii + j]`; `u` or `v` may be NULL
/// (not computed). A radius inside the wound or beyond the outer edge at some time is
/// `WO_INVALID_ARGUMENT`, naming the span of the tissue then. Other rules as `wo_series`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_profile_series(
    problem: WoProblem,
    times: *const f64,
    n_times: usize,
    radii: *const f64,
    n_radii: usize,
    u: *mut f64,
    v: *mut f64,
) -> WoStatus {
    run("wo_profile_series", || {
        let count = n_times.checked_mul(n_radii).ok_or_else(|| {
            Failure::new(
                WoStatus::WoInvalidArgument,
                format!("n_times * n_radii = {n_times} * {n_radii} overflows"),
            )
        })?;
        let t = input(times, n_times, "times")?;
        let r = input(radii, n_radii, "radii")?;
        let out = ProfileOut {
            displacement: optional(u, count, "u")?,
            velocity: optional(v, count, "v")?,
        };
        series::profile_series(&problem.problem(), &t, &r, out)
    })
}

/// The displacement over a frame pair of the material point at the CURRENT radius
/// `radii[i]` (in R0) at the time `t_a[i]`, followed to `t_b[i]` (times in T, finite,
/// `0 <= t_a[i] <= t_b[i]`), for each `i < count`, into `out[i]` (in R0): with X solving
/// X + u(X, t_a) = r, `out[i] = u(X, t_b) - u(X, t_a)`, what a PIV vector times the frame
/// interval measures at a point (the model's motion is radial). Each point has its own
/// pair: a PIV field of many frame pairs is one call, the solver built once and advanced
/// through the distinct times in order. A radius inside the wound or beyond the outer edge
/// at its `t_a` is `WO_INVALID_ARGUMENT`, naming the tissue's span then; other rules as
/// `wo_series`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_pair_displacement(
    problem: WoProblem,
    t_a: *const f64,
    t_b: *const f64,
    radii: *const f64,
    count: usize,
    out: *mut f64,
) -> WoStatus {
    run("wo_pair_displacement", || {
        let a = input(t_a, count, "t_a")?;
        let b = input(t_b, count, "t_b")?;
        let r = input(radii, count, "radii")?;
        let o = output(out, count, "out")?;
        pair_displacement(&problem.problem(), &a, &b, &r, o)
    })
}

/// At each of `times[i]` (`i < n_times`, ascending, all > 0) of a problem with
/// `edge_stress` 0: the velocity u_t (in R0 / T) of the material point at the CURRENT
/// radius `radii[j]` (`j < n_radii`) and its derivatives with respect to sigma, lambda and
/// the time t (in T) at that fixed current radius, four values per point into
/// `rates[(i * n_radii + j) * 4 + q]` (q: velocity, d/dsigma, d/dlambda, d/dt); the same
/// of the wound edge dR/dt (its material point held) into `edge[i * 8 + q]`, and their
/// limit from the tissue (a current radius coming down to the edge) into
/// `edge[i * 8 + 4 + q]` (`edge` may be NULL). Exact derivatives of the
/// solver's own velocities on the grid the tolerance picks, through its modal basis. A
/// nonzero edge stress or a time 0 is `WO_INVALID_ARGUMENT`; other rules as
/// `wo_profile_series`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_profile_sensitivities(
    problem: WoProblem,
    times: *const f64,
    n_times: usize,
    radii: *const f64,
    n_radii: usize,
    rates: *mut f64,
    edge: *mut f64,
) -> WoStatus {
    let pointers = Pointers { times, n_times, radii, n_radii, rates, edge };
    rates_shim("wo_profile_sensitivities", RATES, problem, pointers)
}

/// `wo_profile_sensitivities` with six values per point, `rates[(i * n_radii + j) * 6 + q]`
/// (q: velocity, d/dsigma, d/dlambda, d/dt, d/dR_inf, d/dr): also the derivatives with
/// respect to the outer radius R_inf and to the current radius r, both at fixed time and
/// the other parameters held; the edge's into `edge[i * 12 + q]` (its own: d/dr = 0) and,
/// from the tissue, `edge[i * 12 + 6 + q]` (`edge` may be NULL). Exact derivatives of the
/// solver's own velocities on the grid the tolerance picks (its degree, element count and
/// grading length held as R_inf moves); other rules as `wo_profile_sensitivities`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_profile_rates(
    problem: WoProblem,
    times: *const f64,
    n_times: usize,
    radii: *const f64,
    n_radii: usize,
    rates: *mut f64,
    edge: *mut f64,
) -> WoStatus {
    let pointers = Pointers { times, n_times, radii, n_radii, rates, edge };
    rates_shim("wo_profile_rates", ALL_RATES, problem, pointers)
}

/// `wo_profile_rates` with a time of its own for each point: into `rates[i * 6 + q]` the
/// velocity u_t of the material point at the CURRENT radius `radii[i]` at `times[i]` (> 0,
/// in any order) and its derivatives (q as `wo_profile_rates`), for each `i < count`: the
/// points of a PIV field's frame pairs in one call, the solver walked once through their
/// distinct times. The edge's rates: `wo_profile_rates` with `n_radii` 0. Other rules as
/// `wo_profile_rates`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wo_point_rates(
    problem: WoProblem,
    times: *const f64,
    radii: *const f64,
    count: usize,
    rates: *mut f64,
) -> WoStatus {
    run("wo_point_rates", || {
        let values = count.checked_mul(ALL_RATES).ok_or_else(|| {
            Failure::new(WoStatus::WoInvalidArgument, format!("count = {count} overflows"))
        })?;
        let t = input(times, count, "times")?;
        let r = input(radii, count, "radii")?;
        let out = output(rates, values, "rates")?;
        point_rates(ALL_RATES, &problem.problem(), &t, &r, out)
    })
}

/// The arguments of the two profile-rate shims.
struct Pointers {
    times: *const f64,
    n_times: usize,
    radii: *const f64,
    n_radii: usize,
    rates: *mut f64,
    edge: *mut f64,
}

/// A profile-rate call of `width` values per point (twice as many per time at the edge).
fn rates_shim(name: &str, width: usize, problem: WoProblem, p: Pointers) -> WoStatus {
    let Pointers { times, n_times, radii, n_radii, rates, edge } = p;
    run(name, || {
        let count =
            n_times.checked_mul(n_radii).and_then(|c| c.checked_mul(width)).ok_or_else(|| {
                Failure::new(
                    WoStatus::WoInvalidArgument,
                    format!("n_times * n_radii = {n_times} * {n_radii} overflows"),
                )
            })?;
        let t = input(times, n_times, "times")?;
        let r = input(radii, n_radii, "radii")?;
        let out = output(rates, count, "rates")?;
        let edge = optional(edge, n_times.saturating_mul(2 * width), "edge")?;
        profile_rates(width, &problem.problem(), &t, &r, out, edge)
    })
}
