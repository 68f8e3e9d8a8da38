//! Closed-form results of the continuous model (docs/model.md, section 3), used by the
//! tests and the documentation. Nothing here is discretised.

use puruspe::{In, Kn};

/// Coefficient `k = R_inf^2 / (R_inf^2 - 1)` of the finite-annulus corrections.
fn annulus_factor(r_inf: f64) -> f64 {
    r_inf * r_inf / (r_inf * r_inf - 1.0)
}

/// Relaxed displacement `u_inf(r) = a r + b / r`, `a = sigma k / 6`, `b = sigma k / 2`
/// (free wound edge, `p = 0`).
pub fn final_displacement(sigma: f64, r_inf: f64, r: f64) -> f64 {
    let k = annulus_factor(r_inf);
    sigma * k / 6.0 * r + sigma * k / 2.0 / r
}

/// `R_final = 1 + (2 sigma / 3) k`.
pub fn final_radius(sigma: f64, r_inf: f64) -> f64 {
    1.0 + final_displacement(sigma, r_inf, 1.0)
}

/// `R1 = 1 + sigma / 6`: the wound radius at the moment of the cut.
pub fn initial_radius(sigma: f64) -> f64 {
    1.0 + sigma / 6.0
}

/// Wound radius without friction (`zeta = 0`), at `t_tau = t / tau`:
///
/// ```text
/// R = 1 + a + b,  a = (sigma/6) k (1 - exp(-t_tau) / R_inf^2),  b = (sigma/2) k (1 - exp(-t_tau))
/// ```
pub fn no_friction_radius(sigma: f64, r_inf: f64, t_tau: f64) -> f64 {
    let k = annulus_factor(r_inf);
    let decay = (-t_tau).exp();
    1.0 + sigma / 6.0 * k * (1.0 - decay / (r_inf * r_inf)) + sigma / 2.0 * k * (1.0 - decay)
}

/// Edge velocity `u_t(1, 0+)` just after the cut, for `lambda > 0`.
///
/// `D2 u = 0` at `t = 0+`, so `w = u_t(r, 0+)` solves `lambda^2 D2 w = w` with
/// `lambda^2 D w(1) = p - sigma` and `D w(R_inf) = 0`:
///
/// ```text
/// w = A I1(r / lambda) + B K1(r / lambda)
/// D I1(r/lambda) =  2 (2 I0 / lambda - I1 / r),   D K1(r/lambda) = -2 (2 K0 / lambda + K1 / r)
/// ```
///
/// When `(R_inf - 1) / lambda > 40` the `I` terms are below `exp(-80)` relative and the
/// semi-infinite form is used:
/// `w(1) = (sigma - p) K1 / (2 lambda^2 [K1 + (2 / lambda) K0])`, Bessel functions at `1/lambda`.
/// Valid for `lambda >= 0.002` (the Bessel functions of `1/lambda` underflow below).
pub fn initial_edge_velocity(lambda: f64, sigma: f64, r_inf: f64, p: f64) -> f64 {
    let x = 1.0 / lambda;
    let (k0, k1) = (Kn(0, x), Kn(1, x));
    if (r_inf - 1.0) / lambda > 40.0 {
        return (sigma - p) * k1 / (2.0 * lambda * lambda * (k1 + 2.0 * x * k0));
    }
    let (i0, i1) = (In(0, x), In(1, x));
    let xr = r_inf / lambda;
    let (i0r, i1r, k0r, k1r) = (In(0, xr), In(1, xr), Kn(0, xr), Kn(1, xr));
    let d_i1 = 2.0 * (2.0 * x * i0 - i1);
    let d_k1 = -2.0 * (2.0 * x * k0 + k1);
    let d_ir = 2.0 * (2.0 * x * i0r - i1r / r_inf);
    let d_kr = -2.0 * (2.0 * x * k0r + k1r / r_inf);
    let rhs = (p - sigma) / (lambda * lambda);
    let det = d_i1 * d_kr - d_k1 * d_ir;
    (rhs * d_kr * i1 - rhs * d_ir * k1) / det
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn final_state_is_traction_free_at_the_wound_and_sigma_outside() {
        // D u = 2 (2 u' + u / r) with u = a r + b / r gives 6 a - 2 b / r^2.
        let (sigma, r_inf) = (0.7, 4.0);
        let k = annulus_factor(r_inf);
        let (a, b) = (sigma * k / 6.0, sigma * k / 2.0);
        let d = |r: f64| 6.0 * a - 2.0 * b / (r * r);
        assert!(d(1.0).abs() < 1e-15);
        assert!((d(r_inf) - sigma).abs() < 1e-15);
        assert!((final_displacement(sigma, r_inf, 1.0) - (a + b)).abs() < 1e-15);
    }

    #[test]
    fn no_friction_radius_runs_from_r1_to_r_final() {
        assert!((no_friction_radius(1.0, 10.0, 0.0) - initial_radius(1.0)).abs() < 1e-15);
        assert!((no_friction_radius(1.0, 10.0, 800.0) - final_radius(1.0, 10.0)).abs() < 1e-15);
    }

    #[test]
    fn finite_and_semi_infinite_initial_velocities_agree_when_the_outer_edge_is_far() {
        // (R_inf - 1) / lambda = 39 uses the finite form, 41 the semi-infinite one.
        let lambda = 0.25;
        let near = initial_edge_velocity(lambda, 1.0, 1.0 + 39.0 * lambda, 0.0);
        let far = initial_edge_velocity(lambda, 1.0, 1.0 + 41.0 * lambda, 0.0);
        assert!((near - far).abs() < 1e-14 * far.abs(), "{near} {far}");
    }
}
