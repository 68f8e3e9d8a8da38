//! How a scheme behaves over many steps from the cut: the measurement behind the stability
//! map (`examples/stability_map.rs`) and its tests (`tests/stability.rs`).
//!
//! The exact wound radius rises monotonically from R1 = 1 + sigma/6 to R_final, so a run is
//! judged by its radii alone:
//!
//! ```text
//! Unbounded     a radius that is not finite, or further than 10 amplitudes (R_final - R1) from R1,
//!               or a step the scheme refuses
//! Oscillating   a radius below the previous one by more than 1e-9 amplitude
//! Bounded       neither (overshooting R_final is an accuracy matter, not counted here)
//! ```

use super::{Params, Scheme, Solver, exact, explicit::unchecked_trajectory};

/// Stability status of a run from the cut with a free edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunStatus {
    Bounded,
    Oscillating,
    Unbounded,
}

/// Classify `steps` steps of size `dt` of `scheme` on `params` with a free edge. The
/// explicit scheme runs unchecked (the solver refuses its steps beyond the von Neumann
/// limits before taking them; here is where it really fails).
pub fn classify(params: &Params, scheme: &Scheme, dt: f64, steps: usize) -> RunStatus {
    let Params { lambda, sigma, r_inf } = *params;
    let radii: Box<dyn Iterator<Item = Option<f64>>> = match *scheme {
        Scheme::Explicit { points, .. } => Box::new(
            unchecked_trajectory(points, r_inf, lambda, sigma, dt, steps).into_iter().map(Some),
        ),
        _ => {
            let Ok(mut s) = Solver::with_scheme(params, scheme) else {
                return RunStatus::Unbounded;
            };
            Box::new((0..steps).map(move |_| s.advance(dt, 0.0).ok().map(|_| s.wound_radius())))
        }
    };
    let r1 = exact::initial_radius(sigma);
    let amp = (exact::final_radius(sigma, r_inf) - r1).abs();
    let mut last = r1;
    let mut status = RunStatus::Bounded;
    for r in radii {
        let Some(r) = r else { return RunStatus::Unbounded };
        if !r.is_finite() || (r - r1).abs() > 10.0 * amp {
            return RunStatus::Unbounded;
        }
        if r < last - 1e-9 * amp {
            status = RunStatus::Oscillating;
        }
        last = r;
    }
    status
}
