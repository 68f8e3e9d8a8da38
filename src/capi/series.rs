//! Whole time series in one call, and profiles at current positions (what PIV measures),
//! in safe Rust. The shims are in [`super::series_c`].
//!
//! ```text
//! series(problem, p, times)            R(t_i), dR/dt(t_i)  for ascending t_i >= 0, p constant
//! series_sensitivities(problem, ...)   the same and dR/dlambda(t_i), dR/dR_inf(t_i), exact on
//!                                      the solver's mesh (crate::solver::radius_sensitivities)
//! profile_series(problem, p, times, r) u and u_t of the material point currently at r_j:
//!                                      X_j solves X + u(X, t_i) = r_j, then u(X_j, t_i), u_t(X_j, t_i)
//! ```
//!
//! The map `X -> X + u(X, t)` is increasing (the tissue does not fold), from the wound edge
//! `1 + u(1, t)` to the outer edge `R_inf + u(R_inf, t)`; a current radius outside that
//! interval is refused, naming the interval. `X` is found in a bracket on `[1, R_inf]`
//! that every step narrows (so it converges whatever `u` looks like), to a few ulps: by
//! Newton's steps on `X + u(X) - r` with the slope `1 + u_r` of the modal scheme's
//! interpolant where they fall inside the bracket (3-4 evaluations per radius on the PIV
//! fits' profiles, where regula falsi alone took up to 32 rounds), else by the Illinois
//! variant of regula falsi; the searches of all radii of one time side by side
//! ([`reference_radii`]).

use super::error::{Failure, WoStatus};
use super::solver_c::zeros;
use crate::solver::{Params, Settings, Solver, check_edge_stress, radius_sensitivities};

/// One problem of a series call: parameters, accuracy target and the constant edge stress.
#[derive(Debug, Clone, Copy)]
pub struct Problem {
    pub params: Params,
    pub tolerance: f64,
    pub edge_stress: f64,
}

pub(crate) fn start(problem: &Problem) -> Result<Solver, Failure> {
    problem.params.validate().map_err(|e| Failure::invalid(e.to_string()))?;
    check_edge_stress(problem.edge_stress).map_err(|e| Failure::invalid(e.to_string()))?;
    Ok(Solver::new(&problem.params, &Settings::for_tolerance(&problem.params, problem.tolerance)?)?)
}

/// Times must be finite, >= 0 and ascending (equal neighbours allowed).
pub fn check_times(times: &[f64]) -> Result<(), Failure> {
    if let Some(i) = times.iter().position(|t| !(t.is_finite() && *t >= 0.0)) {
        return Err(Failure::invalid(format!(
            "times[{i}] = {} is invalid: expected a finite time >= 0",
            times[i]
        )));
    }
    if let Some(i) = times.windows(2).position(|w| w[1] < w[0]) {
        return Err(Failure::invalid(format!(
            "times[{}] = {} is before times[{i}] = {}: expected ascending times",
            i + 1,
            times[i + 1],
            times[i]
        )));
    }
    Ok(())
}

/// Where a run left the model's validity: the first time at which the state is outside it
/// ([`crate::solver::validity`]), as the step API reports it.
#[must_use = "a run that left the validity is reported with the outputs"]
pub(crate) struct Left(Option<String>);

impl Left {
    /// `WO_OUTSIDE_VALIDITY` (a warning: the outputs are written) with the reason, or OK.
    pub(crate) fn status(self) -> Result<(), Failure> {
        match self.0 {
            Some(why) => Err(Failure::new(WoStatus::WoOutsideValidity, why)),
            None => Ok(()),
        }
    }
}

/// Advance `solver` to each time in turn and call `visit(i, solver)` there; the first time
/// at which the state has left the model's validity (checked at each time, O(modes)).
pub(crate) fn walk(
    solver: &mut Solver,
    (p, r_inf): (f64, f64),
    times: &[f64],
    mut visit: impl FnMut(usize, &Solver) -> Result<(), Failure>,
) -> Result<Left, Failure> {
    let mut left = None;
    for (i, &t) in times.iter().enumerate() {
        if t > solver.time() {
            solver.advance(t - solver.time(), p)?;
        }
        if left.is_none() && solver.time() > 0.0 {
            left = solver.validity_violation(r_inf).map(|why| {
                format!("times[{i}] = {t}: the run leaves the model's validity there: {why} (every output is written; later times are outside too or past it)")
            });
        }
        visit(i, solver)?;
    }
    Ok(Left(left))
}

fn undefined(i: usize, t: f64) -> Failure {
    Failure::new(
        WoStatus::WoUndefined,
        format!(
            "the velocity at times[{i}] = {t} is infinite: at lambda = 0 the velocity at the cut (t = 0) is \
             unbounded (it decays like t^(-1/2)); ask for t > 0, or for the radius only"
        ),
    )
}

/// Wound radius into `radius` and, when given, edge velocity into `velocity`, at each time.
pub fn series(
    problem: &Problem,
    times: &[f64],
    radius: &mut [f64],
    velocity: Option<&mut [f64]>,
) -> Result<(), Failure> {
    check_times(times)?;
    let mut solver = start(problem)?;
    let p = problem.edge_stress;
    let mut r = zeros(times.len(), "radius")?;
    let mut v = if velocity.is_some() { zeros(times.len(), "velocity")? } else { Vec::new() };
    let want_velocity = velocity.is_some();
    let left = walk(&mut solver, (p, problem.params.r_inf), times, |i, s| {
        r[i] = s.wound_radius();
        if want_velocity {
            if !s.edge_velocity_defined(p) {
                return Err(undefined(i, times[i]));
            }
            v[i] = s.edge_velocity(p);
        }
        Ok(())
    })?;
    radius.copy_from_slice(&r);
    if let Some(out) = velocity {
        out.copy_from_slice(&v);
    }
    left.status()
}

/// Optional outputs of [`series_sensitivities`] (one value per time each).
pub struct SeriesOut<'a> {
    pub velocity: Option<&'a mut [f64]>,
    pub d_lambda: Option<&'a mut [f64]>,
    pub d_r_inf: Option<&'a mut [f64]>,
}

/// [`series`] and the derivatives of the wound radius with respect to lambda and `R_inf`
/// (in R0 per unit), exact for the mesh the tolerance picks (its degree, element count and
/// grading length held fixed: no decomposition beyond the one of `series`). Every output is
/// written only on success (or with the warning of a run that leaves the validity).
pub fn series_sensitivities(
    problem: &Problem,
    times: &[f64],
    radius: &mut [f64],
    out: SeriesOut<'_>,
) -> Result<(), Failure> {
    let mut r = zeros(times.len(), "radius")?;
    let mut v = match out.velocity {
        Some(_) => Some(zeros(times.len(), "velocity")?),
        None => None,
    };
    let left = match series(problem, times, &mut r, v.as_deref_mut()) {
        Err(f) if f.status == WoStatus::WoOutsideValidity => Err(f),
        Err(f) => return Err(f),
        Ok(()) => Ok(()),
    };
    let settings = Settings::for_tolerance(&problem.params, problem.tolerance)?;
    let d = radius_sensitivities(&problem.params, &settings, problem.edge_stress, times)?;
    radius.copy_from_slice(&r);
    for (o, values) in [
        (out.velocity, v.as_deref()),
        (out.d_lambda, Some(&d.d_lambda[..])),
        (out.d_r_inf, Some(&d.d_r_inf[..])),
    ] {
        if let (Some(o), Some(values)) = (o, values) {
            o.copy_from_slice(values);
        }
    }
    left
}

/// The Illinois search of one reference radius: the bracket `[a, b]` of `X` with the gaps
/// `fa`, `fb` of `X + u(X, t) - r` at its ends, the side that moved last, and the root once
/// found.
#[derive(Debug, Clone, Copy)]
struct Search {
    r: f64,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    side: i8,
    root: Option<f64>,
    /// Newton's next point from the last one, where the solver gave the slope there.
    guess: Option<f64>,
}

impl Search {
    fn new(r: f64, r_inf: f64, (lo, hi): (f64, f64)) -> Self {
        let (fa, fb) = (lo - r, hi - r);
        let root = if fa == 0.0 {
            Some(1.0)
        } else if fb == 0.0 {
            Some(r_inf)
        } else {
            None
        };
        Self { r, a: 1.0, fa, b: r_inf, fb, side: 0, root, guess: None }
    }

    /// The next point: Newton's where it lies inside the open bracket, else regula falsi,
    /// or the midpoint when that leaves the open bracket too.
    fn next(&self) -> f64 {
        if let Some(g) = self.guess.filter(|g| *g > self.a && *g < self.b) {
            return g;
        }
        let c = (self.a * self.fb - self.b * self.fa) / (self.fb - self.fa);
        if c > self.a && c < self.b { c } else { 0.5 * (self.a + self.b) }
    }

    /// Narrow the bracket with the gap `fc` at `c`, halving the stale end's gap when the
    /// same side moves twice (Illinois); done at a zero gap or a bracket of a few ulps.
    fn update(&mut self, c: f64, fc: f64) {
        if fc == 0.0 {
            self.root = Some(c);
            return;
        }
        if (fc < 0.0) == (self.fa < 0.0) {
            (self.a, self.fa) = (c, fc);
            if self.side == -1 {
                self.fb *= 0.5;
            }
            self.side = -1;
        } else {
            (self.b, self.fb) = (c, fc);
            if self.side == 1 {
                self.fa *= 0.5;
            }
            self.side = 1;
        }
        if self.b - self.a <= 4.0 * f64::EPSILON * self.b {
            self.root = Some(self.closer_end());
        }
    }

    /// Newton's point from `c` (gap `fc`, already taken by [`Search::update`]) with the
    /// gap's slope `1 + u_r(c)` (> 0 where the tissue does not fold); a correction within
    /// two ulps of `c` ends the search at `c` (Newton's error is then of that order).
    fn aim(&mut self, c: f64, fc: f64, slope: f64) {
        self.guess = None;
        if self.root.is_some() || !(slope > 0.0 && slope.is_finite()) {
            return;
        }
        let g = c - fc / slope;
        if (g - c).abs() <= 2.0 * f64::EPSILON * c {
            self.root = Some(c);
        } else {
            self.guess = Some(g);
        }
    }

    fn closer_end(&self) -> f64 {
        if self.fa.abs() < self.fb.abs() { self.a } else { self.b }
    }
}

/// The reference radii `X` in `[1, R_inf]` of the material points at current radii `radii`,
/// each within `[lo, hi] = [1 + u(1), R_inf + u(R_inf)]` (checked by the caller).
///
/// Each radius has its own search (Newton inside the bracket where the solver gives the
/// slope, else Illinois; at most 200 steps); the searches advance in
/// rounds, one step each, so that a round evaluates `u` at all their points in one call
/// (the mode shapes are summed into nodal values once per call, `O(modes^2)`, then
/// `O(degree)` per point). Every search takes exactly the steps it takes alone, and each
/// `u(X)` is the same double in a call of many points as of one: the result is that of
/// the one-radius search, bit for bit.
pub fn reference_radii(s: &Solver, radii: &[f64], r_inf: f64, ends: (f64, f64)) -> Vec<f64> {
    let mut searches: Vec<Search> = radii.iter().map(|&r| Search::new(r, r_inf, ends)).collect();
    for _ in 0..200 {
        let open: Vec<usize> =
            (0..searches.len()).filter(|&j| searches[j].root.is_none()).collect();
        if open.is_empty() {
            break;
        }
        let points: Vec<f64> = open.iter().map(|&j| searches[j].next()).collect();
        match s.displacement_slope(&points) {
            Some(us) => {
                for ((&j, &c), (u, u_r)) in open.iter().zip(&points).zip(us) {
                    let search = &mut searches[j];
                    let fc = c + u - search.r;
                    search.update(c, fc);
                    search.aim(c, fc, 1.0 + u_r);
                }
            }
            None => {
                for ((&j, &c), u) in open.iter().zip(&points).zip(s.displacement(&points)) {
                    let search = &mut searches[j];
                    search.update(c, c + u - search.r);
                }
            }
        }
    }
    searches.iter().map(|search| search.root.unwrap_or_else(|| search.closer_end())).collect()
}

pub(crate) fn check_radii(radii: &[f64]) -> Result<(), Failure> {
    match radii.iter().position(|r| !r.is_finite()) {
        Some(j) => Err(Failure::invalid(format!(
            "radii[{j}] = {} is invalid: expected a finite radius",
            radii[j]
        ))),
        None => Ok(()),
    }
}

/// The reference radii of the current radii `radii` at the solver's time (`times[i] = t`),
/// refusing a radius inside the wound or beyond the outer edge then.
pub(crate) fn tissue_points(
    s: &Solver,
    radii: &[f64],
    r_inf: f64,
    (i, t): (usize, f64),
) -> Result<Vec<f64>, Failure> {
    let ends = s.displacement(&[1.0, r_inf]);
    let (lo, hi) = (1.0 + ends[0], r_inf + ends[1]);
    if let Some(j) = radii.iter().position(|r| !(lo..=hi).contains(r)) {
        let place = if radii[j] < lo { "inside the wound" } else { "outside the tissue" };
        return Err(Failure::invalid(format!(
            "radii[{j}] = {} is {place} at times[{i}] = {}: the tissue spans current radii [{lo}, {hi}] then",
            radii[j], t
        )));
    }
    Ok(reference_radii(s, radii, r_inf, (lo, hi)))
}

/// Row-major `(times, radii)` outputs of [`profile_series`]; either may be absent.
pub struct ProfileOut<'a> {
    pub displacement: Option<&'a mut [f64]>,
    pub velocity: Option<&'a mut [f64]>,
}

/// Displacement and velocity, at each time, of the material points at the current radii
/// `radii` (each strictly inside neither the wound nor beyond the outer edge at that time).
pub fn profile_series(
    problem: &Problem,
    times: &[f64],
    radii: &[f64],
    out: ProfileOut<'_>,
) -> Result<(), Failure> {
    check_times(times)?;
    check_radii(radii)?;
    let mut solver = start(problem)?;
    let (p, r_inf) = (problem.edge_stress, problem.params.r_inf);
    let n = radii.len();
    let mut u = zeros(times.len() * n, "u")?;
    let mut v = if out.velocity.is_some() { zeros(times.len() * n, "v")? } else { Vec::new() };
    let want_velocity = out.velocity.is_some();
    let left = walk(&mut solver, (p, r_inf), times, |i, s| {
        let x = tissue_points(s, radii, r_inf, (i, times[i]))?;
        if want_velocity && !s.edge_velocity_defined(p) {
            return Err(undefined(i, times[i]));
        }
        u[i * n..(i + 1) * n].copy_from_slice(&s.displacement(&x));
        if want_velocity {
            v[i * n..(i + 1) * n].copy_from_slice(&s.velocity(p, &x));
        }
        Ok(())
    })?;
    if let Some(o) = out.displacement {
        o.copy_from_slice(&u);
    }
    if let Some(o) = out.velocity {
        o.copy_from_slice(&v);
    }
    left.status()
}
