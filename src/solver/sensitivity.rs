//! Exact derivatives of the wound radius with respect to lambda and the outer radius,
//! through the modal basis (no new decomposition).
//!
//! With mode shapes `X` (`X^T A X = I`, `X^T 4M X = diag(mu)`, [`super::modal`]), edge row
//! `e_k = X[0, k]` and `nu_k = mu_k + lambda^2`, the wound radius under an edge stress `p`
//! held constant from the cut is ([`super::exact_time`]: `c_k(t) = g_k (1 - E_k)`)
//!
//! ```text
//! R(t) = 1 + sigma / 6 + (sigma - p) S(t),   S(t) = sum_k e_k^2 (1 - E_k),   E_k = exp(-t / nu_k)
//! ```
//!
//! Lambda enters only through `nu_k`, so with `dE_k / dnu_k = E_k t / nu_k^2`
//!
//! ```text
//! dS / dlambda = -2 lambda sum_k e_k^2 E_k t / nu_k^2
//! ```
//!
//! The outer radius moves the element breaks ([`super::mesh::Mesh::break_rates`]), hence
//! `A` and `M` ([`super::galerkin::assemble_r_inf_rate`]: `A'`, `M'`), hence `mu_k` and
//! `e_k`. Differentiating `4 M x_k = mu_k A x_k` and `x_k^T A x_k = 1` (simple eigenvalues):
//!
//! ```text
//! mu_k' = x_k^T (4 M' - mu_k A') x_k
//! x_k'  = sum_{j != k} x_j [x_j^T (4 M' - mu_k A') x_k] / (mu_k - mu_j) - (1/2) (x_k^T A' x_k) x_k
//! ```
//!
//! of which only the edge row `e_k'` is kept ([`ModeRates`](super::modal::ModeRates), computed once per basis and
//! kept with it). The load `(sigma - p)` at the wound edge does not depend on `R_inf`, and
//! `nu_k' = mu_k'`, so
//!
//! ```text
//! dS / dR_inf = sum_k [ 2 e_k e_k' (1 - E_k) - e_k^2 E_k t mu_k' / nu_k^2 ]
//! ```
//!
//! Both are the exact derivatives of the discrete solution on a mesh of fixed degree,
//! element count and grading length (the tolerance rule picks these piecewise constant in
//! `R_inf`, [`super::tolerance`]). `A'` and `M'` are assembled in the nodal basis, in which
//! the nodal shapes are `A`-orthonormal whichever basis computed them (the constant-first
//! basis spans the same space; [`super::galerkin::Functions`]).
//!
//! The eigenvalues of this Sturm-Liouville problem are simple; the smallest relative gap
//! `(mu_{k+1} - mu_k) / mu_{k+1}` is recorded ([`ModeRates::smallest_gap`](super::modal::ModeRates::smallest_gap)): on the meshes
//! of the tolerance rule it is 0.024 at the least (tolerance 1e-11, `R_inf = 1e3`; 0.13 at
//! 1e-6, 0.18 at 1e-2; test below), so `1 / (mu_k - mu_j)` amplifies rounding by 40 at most
//! and no special treatment of close pairs is needed (nor done).

use super::{Params, Settings, SolverError, basis, check_lambda, check_r_inf};

/// `dR/dlambda` and `dR/dR_inf` (in R0 per unit) at each time (in T, >= 0, any order).
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusSensitivities {
    pub d_lambda: Vec<f64>,
    pub d_r_inf: Vec<f64>,
}

/// The exact derivatives of the wound radius of the modal solver (`settings`, edge stress
/// `p` held from the cut) with respect to lambda and `R_inf`, the mesh's degree, element
/// count and grading length held fixed. Times are not checked here (the caller does).
pub fn radius_sensitivities(
    params: &Params,
    settings: &Settings,
    p: f64,
    times: &[f64],
) -> Result<RadiusSensitivities, SolverError> {
    check_lambda(params.lambda)?;
    check_r_inf(params.r_inf)?;
    super::exact_time::Operator::check_mesh(settings.mesh)?;
    let basis = basis::basis(settings.mesh, params.r_inf).map_err(SolverError::Modal)?;
    let rates = basis.rates();
    let (l2, load) = (params.lambda * params.lambda, params.sigma - p);
    let nu: Vec<f64> = basis.mu.iter().map(|m| m + l2).collect();
    let mut decays = Decays::new(nu.len());
    let (mut d_lambda, mut d_r_inf) =
        (Vec::with_capacity(times.len()), Vec::with_capacity(times.len()));
    for &t in times {
        let (mut dl, mut dr) = (0.0, 0.0);
        for (k, &decay) in decays.at(t, &nu).iter().enumerate() {
            let (e, nu) = (basis.edge_row[k], nu[k]);
            // 1 - E_k: its absolute error (eps) is what the sum needs (scale e_k e_k').
            let rise = 1.0 - decay;
            // E_k t / nu_k^2, 0 once E_k underflows (t / nu_k^2 may overflow then).
            let w = if decay == 0.0 { 0.0 } else { decay * (t / nu) / nu };
            dl += e * e * w;
            dr += 2.0 * e * rates.edge[k] * rise - e * e * w * rates.mu[k];
        }
        d_lambda.push(-2.0 * params.lambda * load * dl);
        d_r_inf.push(load * dr);
    }
    Ok(RadiusSensitivities { d_lambda, d_r_inf })
}

/// `E_k(t) = exp(-t / nu_k)` at successive times. A step `h` from the previous time equal
/// to the previous step (as frame times are) multiplies by the factors `exp(-h / nu_k)`
/// already computed, instead of `n` new exponentials: the factors are the modal engine's
/// ([`super::exact_time`]), and the product's relative error grows by one rounding per step
/// (1e-14 after 100 frames, far below the solver's finest tolerance of 1e-11).
struct Decays {
    t: f64,
    step: f64,
    values: Vec<f64>,
    factors: Vec<f64>,
}

impl Decays {
    fn new(n: usize) -> Self {
        Self { t: f64::NAN, step: f64::NAN, values: vec![0.0; n], factors: vec![0.0; n] }
    }

    fn at(&mut self, t: f64, nu: &[f64]) -> &[f64] {
        let h = t - self.t;
        if h == self.step {
            self.values.iter_mut().zip(&self.factors).for_each(|(v, f)| *v *= f);
        } else if h > 0.0 {
            self.factors.iter_mut().zip(nu).for_each(|(f, nu)| *f = (-h / nu).exp());
            self.values.iter_mut().zip(&self.factors).for_each(|(v, f)| *v *= f);
        } else {
            self.values.iter_mut().zip(nu).for_each(|(v, nu)| *v = (-t / nu).exp());
        }
        (self.t, self.step) = (t, if h > 0.0 { h } else { f64::NAN });
        &self.values
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::Solver;

    fn radius(params: &Params, settings: &Settings, t: f64) -> f64 {
        let mut s = Solver::new(params, settings).unwrap();
        if t > 0.0 {
            s.advance(t, 0.0).unwrap();
        }
        s.wound_radius()
    }

    /// Against central differences of solves on the same mesh (step 1e-4 relative:
    /// truncation ~1e-8, rounding ~1e-16 / 1e-4), relative to the opening `R_final - R1`
    /// (`R_inf` as `(R_inf - 1) dR/dR_inf`). Measured worst: 6e-10 in lambda, 3e-8 in `R_inf`
    /// at `R_inf = 1.0011` (the differences' truncation there), 8e-11 from 1.01 on.
    #[test]
    fn derivatives_match_central_differences_of_solves() {
        let times = [0.0, 1e-3, 0.05, 1.0, 30.0, 1e3, 1e5];
        for r_inf in [1.0011, 1.01, 1.5, 3.0, 10.0, 150.0, 1e3, 1e5] {
            for lambda in [0.0, 0.05, 1.0, 20.0] {
                let params = Params { lambda, sigma: 0.7, r_inf };
                let settings = Settings::for_tolerance(&params, 1e-11).unwrap();
                let got = radius_sensitivities(&params, &settings, 0.0, &times).unwrap();
                let opening = radius(&params, &settings, 1e12) - radius(&params, &settings, 0.0);
                let (dl, dr) = (1e-4 * lambda.max(0.01), 1e-4 * (r_inf - 1.0));
                for (i, &t) in times.iter().enumerate() {
                    let at =
                        |lambda, r_inf| radius(&Params { lambda, sigma: 0.7, r_inf }, &settings, t);
                    let fd_l =
                        (at(lambda + dl, r_inf) - at((lambda - dl).abs(), r_inf)) / (2.0 * dl);
                    let fd_r = (at(lambda, r_inf + dr) - at(lambda, r_inf - dr)) / (2.0 * dr);
                    let what = format!("R_inf {r_inf} lambda {lambda} t {t}");
                    assert!(
                        (got.d_lambda[i] - fd_l).abs() < 1e-7 * opening,
                        "{what}: {} vs {fd_l}",
                        got.d_lambda[i]
                    );
                    assert!(
                        ((got.d_r_inf[i] - fd_r) * (r_inf - 1.0)).abs() < 1e-7 * opening,
                        "{what}: {} vs {fd_r}",
                        got.d_r_inf[i]
                    );
                }
            }
        }
    }

    #[test]
    fn the_modes_are_well_separated_on_the_tolerance_meshes() {
        for tol in [1e-2, 1e-6, 1e-11] {
            for r_inf in [1.001, 1.01, 2.0, 3.0, 3.01, 10.0, 1e3, 1e6] {
                let params = Params { lambda: 1.0, sigma: 1.0, r_inf };
                let spec = Settings::for_tolerance(&params, tol).unwrap().mesh;
                let gap = basis::basis(spec, r_inf).unwrap().rates().smallest_gap;
                assert!(gap > 0.01, "tol {tol} R_inf {r_inf}: {gap}");
            }
        }
    }

    /// The decays reused along equal steps (frame times) and recomputed otherwise match
    /// `exp(-t / nu)` to 1e-13 relative (and to the rounding of exp's own argument,
    /// `eps t / nu`, where that is larger), on relaxation times from 1e-5 to 1e12 and
    /// times in any order.
    #[test]
    fn decays_along_frames_are_the_exponentials() {
        let nu: Vec<f64> = (-5..=12).map(|k| 10f64.powi(k) * 1.7).collect();
        let frames: Vec<f64> = (1..=400).map(|k| k as f64 * 0.25).collect();
        let rounded: Vec<f64> = (1..=400).map(|k| k as f64 * 0.25 / 1.6).collect();
        let shuffled = [3.0, 0.5, 0.5, 7.0, 0.0, 2.0, 1e3];
        for times in [&frames[..], &rounded[..], &shuffled[..]] {
            let mut decays = Decays::new(nu.len());
            for &t in times {
                for (got, nu) in decays.at(t, &nu).to_vec().iter().zip(&nu) {
                    let want = (-t / nu).exp();
                    // exp's own argument carries a rounding of eps t / nu, either way
                    let tol = 1e-13 * (1.0 + t / nu) * want + 1e-300;
                    assert!((got - want).abs() <= tol, "t {t} nu {nu}: {got} vs {want}");
                }
            }
        }
    }

    #[test]
    fn no_new_stress_no_motion() {
        let params = Params { lambda: 2.0, sigma: 0.4, r_inf: 5.0 };
        let settings = Settings::for_tolerance(&params, 1e-8).unwrap();
        let got = radius_sensitivities(&params, &settings, 0.4, &[0.0, 1.0, 1e300]).unwrap();
        assert!(got.d_lambda.iter().chain(&got.d_r_inf).all(|v| *v == 0.0), "{got:?}");
        let got = radius_sensitivities(&params, &settings, 0.0, &[0.0, 1e300]).unwrap();
        assert!(got.d_lambda.iter().chain(&got.d_r_inf).all(|v| v.is_finite()), "{got:?}");
        assert_eq!((got.d_lambda[0], got.d_r_inf[0]), (0.0, 0.0));
    }
}
