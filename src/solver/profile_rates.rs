//! Exact derivatives of the velocity of the material point at a fixed current radius with
//! respect to sigma, lambda and the time, through the modal basis (no new decomposition).
//!
//! With the edge stress `p = 0` held from the cut, the modal coordinates of
//! `v = u - sigma r / 6` are `c_k = sigma e_k (1 - E_k)`, `E_k = exp(-tau / nu_k)`,
//! `nu_k = mu_k + lambda^2`, `e_k = X[0, k]` ([`super::exact_time`]), so the displacement
//! is linear in sigma, `u = sigma U(X, tau)`, with mode shapes `phi_k`:
//!
//! ```text
//! U        = X / 6 + sum_k phi_k(X) e_k (1 - E_k)
//! U_t      = sum_k phi_k e_k E_k / nu_k
//! U_tt     = -sum_k phi_k e_k E_k / nu_k^2
//! U_lambda = -2 lambda sum_k phi_k e_k E_k tau / nu_k^2          (dE_k/dnu_k = E_k tau / nu_k^2)
//! U_tlambda = 2 lambda sum_k phi_k e_k E_k (tau - nu_k) / nu_k^3  (d(E/nu)/dnu = E (tau - nu) / nu^3)
//! ```
//!
//! and `U_X`, `U_tX` the same sums with `phi_k'` (plus `1 / 6` in `U_X`), from the Lagrange
//! basis of the element holding `X`. The material point at current radius `r` has `X`
//! solving `X + sigma U(X, tau) = r`; implicit differentiation at fixed `r`, with
//! `J = 1 + sigma U_X > 0` (the map does not fold), gives for any parameter `q`
//!
//! ```text
//! dX/dq = -(d(sigma U)/dq)|_X / J:   dX/dsigma = -U / J,  dX/dlambda = -sigma U_lambda / J,
//!                                    dX/dtau = -sigma U_t / J
//! ```
//!
//! and the velocity there, `V(r) = sigma U_t(X, tau)`, has
//!
//! ```text
//! dV/dsigma  = U_t + sigma U_tX dX/dsigma
//! dV/dlambda = sigma (U_tlambda + U_tX dX/dlambda)
//! dV/dtau    = sigma (U_tt + U_tX dX/dtau)
//! ```
//!
//! The outer radius `R_inf` moves `mu_k` and `e_k` ([`super::modal::ModeRates`]), the
//! whole mode shapes at the nodes (`dX/dR_inf = X C`, [`super::modal::ShapeRates`])
//! and the nodes themselves: the element breaks move with `R_inf`
//! ([`super::mesh::Mesh::break_rates`]), so at a fixed reference radius `X` the interpolated
//! sum `S(X) = sum_i s_i l_i(xi(X))` of nodal values `s_i` changes by
//!
//! ```text
//! dS/dR_inf|_X = sum_i (ds_i/dR_inf) l_i(xi) - S_X(X) m(X),   m(X) = b_e' + (xi + 1) / 2 (b_{e+1}' - b_e')
//! ```
//!
//! (`m`: the velocity of the mesh point at `X` in element `[b_e, b_{e+1}]`, 0 at the edge,
//! which stays at 1). With the modal weights `w_k = e_k (1 - E_k)` of `U - X/6` and
//! `e_k E_k / nu_k` of `U_t`, `d(X w)/dR_inf = X (C w + w')`, where
//!
//! ```text
//! w'(U)   = e_k' (1 - E_k) - e_k E_k tau mu_k' / nu_k^2
//! w'(U_t) = e_k' E_k / nu_k + e_k mu_k' E_k (tau - nu_k) / nu_k^3
//! ```
//!
//! give `U_R`, `U_tR`; then as for any parameter `dX/dR_inf = -sigma U_R / J` and
//! `dV/dR_inf = sigma (U_tR + U_tX dX/dR_inf)`. The derivative in the current radius at
//! fixed parameters is `dV/dr = sigma U_tX / J` (0 for the edge held).
//!
//! The edge velocity (`X = 1` held, the material point of the wound edge) drops the `dX`
//! terms; a current radius at the edge seen from the tissue keeps them (the velocity is the
//! same, its derivatives differ by `sigma U_tX dX/dq`). These are the exact derivatives of the discrete solution for times `tau > 0`
//! (at `tau = 0` the velocity is the closed-form instantaneous response instead; refused
//! here), the mesh (degree, elements, grading) held fixed.

use super::quadrature::LagrangeBasis;
use super::{Params, Settings, SolverError, basis, check_lambda, check_r_inf};
use nalgebra::DVector;

/// Velocity (per unit of the time T, in R0) and its derivatives with respect to sigma,
/// lambda and the dimensionless time at fixed current radius, at one point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VelocityRates {
    pub velocity: f64,
    pub d_sigma: f64,
    pub d_lambda: f64,
    pub d_tau: f64,
    /// With respect to the outer radius `R_inf` (the current radius held).
    pub d_r_inf: f64,
    /// With respect to the current radius (the parameters held; 0 at the edge held).
    pub d_r: f64,
}

/// [`VelocityRates`] at the reference radii `x` (in `[1, R_inf]`, from the search of the
/// current radii) and of the wound edge, at one time `tau > 0`, edge stress 0 held from
/// the cut. Returns `(points, [edge, edge from the tissue])`: the edge's own (the material
/// point `X = 1` held) and the limit of the points' as the current radius comes down to the
/// edge (`X = 1` moving with the parameters): the one-sided derivatives either side of the
/// switch from tissue velocity to edge velocity. `outer`: also `d_r_inf` (else 0).
pub fn velocity_rates(
    params: &Params,
    settings: &Settings,
    tau: f64,
    x: &[f64],
    outer: bool,
) -> Result<(Vec<VelocityRates>, [VelocityRates; 2]), SolverError> {
    check_lambda(params.lambda)?;
    check_r_inf(params.r_inf)?;
    super::exact_time::Operator::check_mesh(settings.mesh)?;
    if !(tau > 0.0 && tau.is_finite()) {
        return Err(SolverError::Mesh("velocity rates need a finite time > 0"));
    }
    let basis = basis::basis(settings.mesh, params.r_inf).map_err(SolverError::Modal)?;
    let (lambda, sigma, n) = (params.lambda, params.sigma, basis.len());
    // Modal weights of U - X/6, U_t, U_tt, U_lambda, U_tlambda, as functions of
    // (e_k, nu_k, E_k); the lambda terms are 0 once E_k underflows (tau / nu may overflow).
    let weights = |f: &dyn Fn(f64, f64, f64) -> f64| {
        DVector::from_fn(n, |k, _| {
            let (e, nu) = (basis.edge_row[k], basis.mu[k] + lambda * lambda);
            f(e, nu, (-tau / nu).exp())
        })
    };
    let w = [
        weights(&|e, nu, _| -e * (-tau / nu).exp_m1()),
        weights(&|e, nu, d| e * d / nu),
        weights(&|e, nu, d| -e * d / nu / nu),
        weights(&|e, nu, d| if d == 0.0 { 0.0 } else { -2.0 * lambda * e * (d / nu) * (tau / nu) }),
        weights(&|e, nu, d| {
            if d == 0.0 { 0.0 } else { 2.0 * lambda * e * (d / nu) * (tau / nu - 1.0) / nu }
        }),
    ];
    // R_inf moves mu_k and the whole shapes (nodes held): d(X w)/dR_inf = X (C w + w'), with
    // w' the weights' own rates through e_k' and mu_k' (= nu_k').
    // Without `outer` they are not computed (d_r_inf is then 0): the mode shapes' rates cost
    // two dense products once per basis.
    let moved = |c: &DVector<f64>, own: &dyn Fn(f64, f64, f64, f64, f64) -> f64| {
        if !outer {
            return DVector::zeros(basis.shapes.nrows());
        }
        let (modes, coupling) = (basis.rates(), &basis.shape_rates().coupling);
        let w_rate = DVector::from_fn(n, |k, _| {
            let (e, nu) = (basis.edge_row[k], basis.mu[k] + lambda * lambda);
            own(e, nu, (-tau / nu).exp(), modes.edge[k], modes.mu[k])
        });
        &basis.shapes * (coupling * c + w_rate)
    };
    let r_inf_nodal = [
        moved(&w[0], &|e, nu, d, de, dmu| {
            de * -(-tau / nu).exp_m1() - if d == 0.0 { 0.0 } else { e * d * (tau / nu) / nu * dmu }
        }),
        moved(&w[1], &|e, nu, d, de, dmu| {
            de * d / nu + if d == 0.0 { 0.0 } else { e * dmu * d * (tau - nu) / (nu * nu * nu) }
        }),
    ];
    let nodal = w.map(|c| &basis.shapes * c);
    let nodal =
        [&nodal[0], &nodal[1], &nodal[2], &nodal[3], &nodal[4], &r_inf_nodal[0], &r_inf_nodal[1]];
    let mesh = &basis.mesh;
    let break_rates = mesh.break_rates();
    let lagrange = LagrangeBasis::new(&mesh.reference_nodes);
    // Values and X-derivatives of the seven sums at X, and the velocity dX/dR_inf of the
    // mesh point at X (linear between its element's breaks; 0 at the edge, fixed at 1).
    let (mut val, mut der) = (vec![0.0; lagrange.len()], vec![0.0; lagrange.len()]);
    let mut at = |xr: f64| {
        let (e, xi) = mesh.locate(xr.clamp(1.0, params.r_inf));
        lagrange.eval_into(xi, &mut val, &mut der);
        let scale = 2.0 / (mesh.breaks[e + 1] - mesh.breaks[e]);
        let mut out = [(0.0, 0.0); 7];
        for (o, v) in out.iter_mut().zip(nodal) {
            for i in 0..val.len() {
                let node = v[mesh.global(e, i)];
                o.0 += val[i] * node;
                o.1 += scale * der[i] * node;
            }
        }
        (out, break_rates[e] + 0.5 * (xi + 1.0) * (break_rates[e + 1] - break_rates[e]))
    };
    let mut rates = |xr: f64, moving: bool| {
        let ([u, ut, utt, ul, utl, ur, utr], mesh_rate) = at(xr);
        // At fixed X the mesh moves under it: d/dR_inf of an interpolated sum is its nodal
        // rate minus its X-derivative times the mesh point's velocity (X / 6 is not meshed).
        let (u_r, ut_r) = (ur.0 - u.1 * mesh_rate, utr.0 - ut.1 * mesh_rate);
        let (u, u_x) = (xr.clamp(1.0, params.r_inf) / 6.0 + u.0, 1.0 / 6.0 + u.1);
        let j = 1.0 + sigma * u_x;
        // dX/dq at fixed r (0 when X is held at the edge).
        let dx = |d: f64| if moving { -d / j } else { 0.0 };
        VelocityRates {
            velocity: sigma * ut.0,
            d_sigma: ut.0 + sigma * ut.1 * dx(u),
            d_lambda: sigma * (utl.0 + ut.1 * dx(sigma * ul.0)),
            d_tau: sigma * (utt.0 + ut.1 * dx(sigma * ut.0)),
            d_r_inf: sigma * (ut_r + ut.1 * dx(sigma * u_r)),
            d_r: if moving { sigma * ut.1 / j } else { 0.0 },
        }
    };
    let points = x.iter().map(|&xr| rates(xr, true)).collect();
    Ok((points, [rates(1.0, false), rates(1.0, true)]))
}
