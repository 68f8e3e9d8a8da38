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
//! of which only the edge row `e_k'` is kept ([`ModeRates`], computed once per basis and
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
//! `(mu_{k+1} - mu_k) / mu_{k+1}` is recorded ([`ModeRates::smallest_gap`]): on the meshes
//! of the tolerance rule it is 0.024 at the least (tolerance 1e-11, `R_inf = 1e3`; 0.13 at
//! 1e-6, 0.18 at 1e-2; test below), so `1 / (mu_k - mu_j)` amplifies rounding by 40 at most
//! and no special treatment of close pairs is needed (nor done).

use super::galerkin;
use super::modal::Basis;
use super::{Params, Settings, SolverError, basis, check_lambda, check_r_inf};
use nalgebra::{DMatrix, DVector};
use std::sync::OnceLock;

/// `d mu_k / dR_inf` and `d e_k / dR_inf` of one basis.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ModeRates {
    pub(crate) mu: DVector<f64>,
    pub(crate) edge: DVector<f64>,
    /// The smallest `(mu_{k+1} - mu_k) / mu_{k+1}` (1 with a single mode).
    pub(crate) smallest_gap: f64,
}

impl ModeRates {
    /// With `Y = 4 M' X`, `Z = A' X` (banded: each node couples to the `p` nodes either
    /// side, `O(n^2 p)`) and `W_jk = e_j / (mu_k - mu_j)` (`W_kk = 0`), the sum over `j` of
    /// the formula above is `(X W)_k . (Y_k - mu_k Z_k)`: one dense product in all.
    fn new(basis: &Basis) -> Self {
        let rate = galerkin::assemble_r_inf_rate(&basis.mesh);
        let (x, mu, e) = (&basis.shapes, &basis.mu, &basis.edge_row);
        let (n, band) = (mu.len(), basis.mesh.degree());
        // Y_ic = sum_j m_ij X_jc over the band; m is symmetric, so m_ij = column i of m, and
        // both factors are contiguous (column-major).
        let banded = |m: &DMatrix<f64>, scale: f64| {
            let (ms, xs) = (m.as_slice(), x.as_slice());
            DMatrix::from_fn(n, n, |i, c| {
                let (lo, hi) = (i.saturating_sub(band), (i + band + 1).min(n));
                scale * ms[i * n + lo..i * n + hi].iter().zip(&xs[c * n + lo..c * n + hi]).map(|(a, b)| a * b).sum::<f64>()
            })
        };
        let (y, z) = (banded(&rate.mass, 4.0), banded(&rate.stiffness, 1.0));
        let w = DMatrix::from_fn(n, n, |j, k| if j == k { 0.0 } else { e[j] / (mu[k] - mu[j]) });
        let xw = x * w;
        let (mut mu_rate, mut edge) = (DVector::zeros(n), DVector::zeros(n));
        for k in 0..n {
            let g = y.column(k) - mu[k] * z.column(k);
            mu_rate[k] = x.column(k).dot(&g);
            edge[k] = xw.column(k).dot(&g) - 0.5 * x.column(k).dot(&z.column(k)) * e[k];
        }
        let smallest_gap = mu.as_slice().windows(2).map(|w| (w[1] - w[0]) / w[1]).fold(1.0, f64::min);
        Self { mu: mu_rate, edge, smallest_gap }
    }
}

/// `dX / dR_inf = X C` of the whole mode shapes (nodal values, the nodes held): with
/// `G = Y - Z diag(mu)` (the `g_k` of [`ModeRates`]), `C_jk = (X^T G)_jk / (mu_k - mu_j)` for
/// `j != k` and `C_kk = -(1/2) (X^T Z)_kk`. Only its products with modal weights are needed
/// (`X (C w)`: `O(n^2)` per weight vector); `C` itself costs two dense products, `O(n^3)`,
/// once per basis, and only where velocities inside the tissue are differentiated
/// ([`super::profile_rates`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ShapeRates {
    pub(crate) coupling: DMatrix<f64>,
}

impl ShapeRates {
    fn new(basis: &Basis) -> Self {
        let rate = galerkin::assemble_r_inf_rate(&basis.mesh);
        let (x, mu) = (&basis.shapes, &basis.mu);
        let (y, z) = (4.0 * &rate.mass * x, &rate.stiffness * x);
        let (xy, xz) = (x.transpose() * y, x.transpose() * z);
        let coupling = DMatrix::from_fn(mu.len(), mu.len(), |j, k| {
            if j == k { -0.5 * xz[(k, k)] } else { (xy[(j, k)] - mu[k] * xz[(j, k)]) / (mu[k] - mu[j]) }
        });
        Self { coupling }
    }
}

/// [`ShapeRates`] on first use, kept with the basis (as [`LazyRates`]).
#[derive(Debug, Clone, Default)]
pub(crate) struct LazyShapeRates(OnceLock<ShapeRates>);

impl PartialEq for LazyShapeRates {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The [`ModeRates`] of a basis, computed on first use and kept with it (measured
/// 2026-12-03 on a loaded machine, 65 modes: about 0.2 ms, a quarter of the 0.5 to 0.9 ms of
/// the decomposition; a basis that only ever serves plain series never pays it). Derived from the
/// basis alone, so it takes no part in comparing bases (a cached basis whose rates were
/// asked for equals a fresh one).
#[derive(Debug, Clone, Default)]
pub(crate) struct LazyRates(OnceLock<ModeRates>);

impl PartialEq for LazyRates {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Basis {
    pub(crate) fn rates(&self) -> &ModeRates {
        self.rates.0.get_or_init(|| ModeRates::new(self))
    }

    pub(crate) fn shape_rates(&self) -> &ShapeRates {
        self.shape_rates.0.get_or_init(|| ShapeRates::new(self))
    }
}

/// `dR/dlambda` and `dR/dR_inf` (in R0 per unit) at each time (in T, >= 0, any order).
#[derive(Debug, Clone, PartialEq)]
pub struct RadiusSensitivities {
    pub d_lambda: Vec<f64>,
    pub d_r_inf: Vec<f64>,
}

/// The exact derivatives of the wound radius of the modal solver (`settings`, edge stress
/// `p` held from the cut) with respect to lambda and `R_inf`, the mesh's degree, element
/// count and grading length held fixed. Times are not checked here (the caller does).
pub fn radius_sensitivities(params: &Params, settings: &Settings, p: f64, times: &[f64]) -> Result<RadiusSensitivities, SolverError> {
    check_lambda(params.lambda)?;
    check_r_inf(params.r_inf)?;
    super::exact_time::Operator::check_mesh(settings.mesh)?;
    let basis = basis::basis(settings.mesh, params.r_inf).map_err(SolverError::Modal)?;
    let rates = basis.rates();
    let (l2, load) = (params.lambda * params.lambda, params.sigma - p);
    let nu: Vec<f64> = basis.mu.iter().map(|m| m + l2).collect();
    let mut decays = Decays::new(nu.len());
    let (mut d_lambda, mut d_r_inf) = (Vec::with_capacity(times.len()), Vec::with_capacity(times.len()));
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
                    let at = |lambda, r_inf| radius(&Params { lambda, sigma: 0.7, r_inf }, &settings, t);
                    let fd_l = (at(lambda + dl, r_inf) - at((lambda - dl).abs(), r_inf)) / (2.0 * dl);
                    let fd_r = (at(lambda, r_inf + dr) - at(lambda, r_inf - dr)) / (2.0 * dr);
                    let what = format!("R_inf {r_inf} lambda {lambda} t {t}");
                    assert!((got.d_lambda[i] - fd_l).abs() < 1e-7 * opening, "{what}: {} vs {fd_l}", got.d_lambda[i]);
                    assert!(((got.d_r_inf[i] - fd_r) * (r_inf - 1.0)).abs() < 1e-7 * opening, "{what}: {} vs {fd_r}", got.d_r_inf[i]);
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
