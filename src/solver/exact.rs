//! Closed-form results of the continuous model (docs/model.md, "Exact results"), used by the
//! tests and the documentation. Nothing here is discretised.

use super::bessel::{ive, kve};

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

/// Instantaneous velocity response `w(r) = d u_t(r) / d p` to the edge stress: the
/// change of the velocity field when the edge stress applied now changes by one unit.
///
/// Two states that differ only in the edge stress applied now have the same `u`, so their
/// velocity difference `w` solves (the PDE `D2 u + lambda^2 D2 u_t = u_t` and the edge
/// condition `D u + lambda^2 D u_t = p`, differenced):
///
/// ```text
/// lambda^2 D2 w = w,      lambda^2 D w(1) = 1,      D w(R_inf) = 0
/// w = A I1(r / lambda) + B K1(r / lambda)
/// D I1(r x) =  2 (2 x I0(r x) - I1(r x) / r),   D K1(r x) = -2 (2 x K0(r x) + K1(r x) / r),   x = 1 / lambda
/// w(r) = (d_K(R) I1(r x) - d_I(R) K1(r x)) / (lambda^2 (d_I(1) d_K(R) - d_K(1) d_I(R)))
/// ```
///
/// With exponentially scaled functions ([`super::bessel`]) the common factor
/// `exp(x (1 - R_inf))` is taken out of numerator and determinant, leaving only factors
/// `exp(-x (...)) <= 1`: nothing overflows, from `lambda = 1e-9` to `1e9`. It is negative
/// (pulling the edge in reduces its velocity) and falls like `-1 / (4 lambda)` as
/// `lambda -> 0`: the response of the edge is infinite at `lambda = 0`.
/// At the cut (uniform tension, which is at rest under `p = sigma`) the velocity field is
/// `(p - sigma) w(r)`: the velocity just after the cut of docs/model.md, "Exact results".
pub fn velocity_response(lambda: f64, r_inf: f64, r: f64) -> f64 {
    let x = 1.0 / lambda;
    let at = |n: u32, y: f64| (ive(n, y), kve(n, y));
    let ((i0a, i1a), (k0a, k1a)) = ((ive(0, x), ive(1, x)), (kve(0, x), kve(1, x)));
    let xb = x * r_inf;
    let ((i0b, k0b), (i1b, k1b)) = (at(0, xb), at(1, xb));
    // Scaled stress operators: d_I ~ exp(+y), d_K ~ exp(-y).
    let d_ia = 2.0 * (2.0 * x * i0a - i1a);
    let d_ka = -2.0 * (2.0 * x * k0a + k1a);
    let d_ib = 2.0 * (2.0 * x * i0b - i1b / r_inf);
    let d_kb = -2.0 * (2.0 * x * k0b + k1b / r_inf);
    // det e^{x - x R}  =  d_ia d_kb e^{2x(1 - R)} - d_ka d_ib
    let det = d_ia * d_kb * (2.0 * x * (1.0 - r_inf)).exp() - d_ka * d_ib;
    let xr = x * r;
    // num e^{x - x R} = d_kb I1~(xr) e^{x (r + 1 - 2R)} - d_ib K1~(xr) e^{x (1 - r)}
    let num = d_kb * ive(1, xr) * (x * (r + 1.0 - 2.0 * r_inf)).exp()
        - d_ib * kve(1, xr) * (x * (1.0 - r)).exp();
    num / (det * lambda * lambda)
}

/// `d u_t(1) / d p`, the response of the edge velocity to the edge stress applied now
/// ([`velocity_response`] at `r = 1`), for `lambda > 0`.
pub fn edge_velocity_slope(lambda: f64, r_inf: f64) -> f64 {
    velocity_response(lambda, r_inf, 1.0)
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
    fn far_outer_edge_gives_the_semi_infinite_form() {
        use puruspe::Kn;
        for lambda in [0.05, 0.25, 1.0] {
            let x = 1.0 / lambda;
            let (k0, k1) = (Kn(0, x), Kn(1, x));
            let semi = -k1 / (2.0 * lambda * lambda * (k1 + 2.0 * x * k0));
            let far = edge_velocity_slope(lambda, 1.0 + 60.0 * lambda);
            assert!((far - semi).abs() < 1e-14 * semi.abs(), "{lambda}: {far} {semi}");
        }
    }

    /// `w = a r + b / r` (D2 w = 0) as lambda -> infinity: `D w = 6 a - 2 b / r^2`,
    /// so `6 a - 2 b = 1 / lambda^2`, `6 a - 2 b / R^2 = 0`, `w(1) = a + b`.
    #[test]
    fn large_lambda_tends_to_the_no_friction_response() {
        let (lambda, r_inf) = (1e4, 3.0);
        let b = 1.0 / (2.0 * lambda * lambda * (1.0 / (r_inf * r_inf) - 1.0));
        let a = b / (3.0 * r_inf * r_inf);
        let got = edge_velocity_slope(lambda, r_inf);
        assert!((got - (a + b)).abs() < 1e-6 * got.abs(), "{got:e} vs {:e}", a + b);
    }

    #[test]
    fn small_lambda_tends_to_minus_one_over_four_lambda() {
        for lambda in [1e-4, 1e-6, 1e-9] {
            let got = edge_velocity_slope(lambda, 10.0) * 4.0 * lambda;
            assert!((got + 1.0).abs() < 2.0 * lambda, "{lambda}: {got}");
        }
    }
}
