//! The modal basis of the semi-discrete system, shared by every `lambda`.
//!
//! With stiffness `A` (SPD) and mass `B = 4 M + lambda^2 A` (SPD), the semi-discrete
//! system `B u_t = -A u + F` is diagonalised by the generalised eigenproblem
//!
//! ```text
//! B x_k = nu_k A x_k,     X^T A X = I,     X^T B X = diag(nu),     nu_k = 1 / (decay rate)
//! ```
//!
//! With `A = L L^T` (Cholesky),
//!
//! ```text
//! L^-1 B L^-T = 4 L^-1 M L^-T + lambda^2 I = Q diag(mu) Q^T + lambda^2 I
//! ```
//!
//! so the mode shapes `X = L^-T Q` do not depend on lambda, and
//! `nu_k(lambda) = mu_k + lambda^2`: one decomposition per mesh and outer radius serves
//! every lambda (and is cached process-wide, [`super::basis`]). `mu_k` are the relaxation
//! times at `lambda = 0`, all `> 0`.
//!
//! `mu` spans up to 17 decades (~1e-5 at the wound edge, ~R_inf^2 far out). The symmetric
//! eigenproblem is solved by the Jacobi method with a relative stopping rule
//! ([`super::jacobi`]), which keeps the small `mu_k` (the fast modes that shape the opening
//! at early times) to relative accuracy; a QR-based eigensolver loses them at large `R_inf`.
//!
//! In modal coordinates `u = X c`, `c = X^T A u`, each mode relaxes independently to
//! `g = X^T F` (no division, no equilibrium solve):
//!
//! ```text
//! nu_k c_k' = g_k - c_k   =>   c_k(t + h) = g_k + exp(-h / nu_k) (c_k(t) - g_k)
//! ```
//!
//! which is exact for any step `h > 0` with `F` (the edge stress `p`) constant over the
//! step: unconditionally stable, monotone, and free of any time-discretisation error.

use super::galerkin::{self, Functions};
use super::jacobi;
use super::mesh::Mesh;
use super::quadrature::LagrangeBasis;
use nalgebra::{DMatrix, DVector};
use std::sync::OnceLock;

/// The lambda-independent modal decomposition of one mesh on `[1, R_inf]`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Basis {
    pub(crate) mesh: Mesh,
    /// Relaxation times at `lambda = 0`, `mu_k > 0` (in T), ascending.
    pub(crate) mu: DVector<f64>,
    /// Mode shapes (columns), nodal values (`X^T A X = I` in the basis they were computed in).
    pub(crate) shapes: DMatrix<f64>,
    /// Row of the mode shapes at the wound edge, `X[0, :]`.
    pub(crate) edge_row: DVector<f64>,
    /// Row of their radial derivative at the wound edge, `dX/dr[0, :]`: the first element
    /// spans `[b0, b1]` with reference coordinate `x = -1` at `r = 1`, so `dv/dr(1) =
    /// (2 / (b1 - b0)) sum_i l_i'(-1) v_i` over its nodes.
    pub(crate) edge_slope_row: DVector<f64>,
    /// Row of the mode shapes at the outer edge (the last node).
    pub(crate) outer_row: DVector<f64>,
    /// Their derivatives with respect to `R_inf`, on first use ([`super::sensitivity`]).
    pub(crate) rates: LazyRates,
    /// The derivatives of the whole mode shapes, on first use ([`super::sensitivity`]).
    pub(crate) shape_rates: LazyShapeRates,
}

/// Why a modal decomposition could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum ModalError {
    /// The stiffness matrix was not numerically positive definite.
    StiffnessNotPositive,
    /// The eigensolver did not converge or met a non-finite value.
    NoConvergence,
    /// A relaxation time came out non-positive or non-finite (index, value).
    BadRelaxationTime(usize, f64),
}

impl std::fmt::Display for ModalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::StiffnessNotPositive => write!(f, "stiffness matrix is not positive definite"),
            Self::NoConvergence => write!(f, "the eigensolver did not converge"),
            Self::BadRelaxationTime(k, v) => write!(f, "relaxation time {k} is {v}"),
        }
    }
}

/// Largest Gershgorin bound on `mu` up to which the QR eigensolver is used (see [`eigen`]).
const QR_UP_TO: f64 = 1e4;

/// Eigenvalues (ascending) and eigenvectors of the reduced mass `C = L^-1 4 M L^-T`.
///
/// The QR eigensolver (nalgebra) has an absolute error of about `eps max(mu)`; the
/// wound-radius error it causes grows like `max(mu)` (measured: 3e-16 of the opening per
/// unit of `max(mu)`, so 2.3e-10 at `R_inf = 1e4`, where `max(mu) = 2e7`). While a
/// Gershgorin bound on `mu` stays below [`QR_UP_TO`] (`R_inf` up to ~150) that is below
/// 1e-12 and QR, five times faster than Jacobi, is used; beyond, the relatively accurate
/// Jacobi method ([`super::jacobi`]). Either choice is a deterministic function of `C`.
fn eigen(c: DMatrix<f64>) -> Result<(DVector<f64>, DMatrix<f64>), ModalError> {
    let bound =
        c.row_iter().map(|row| row.iter().map(|x| x.abs()).sum::<f64>()).fold(0.0, f64::max);
    // Beyond the bound, NaN included.
    if bound.partial_cmp(&QR_UP_TO).is_none_or(|o| o == std::cmp::Ordering::Greater) {
        return jacobi::symmetric_eigen(&c).ok_or(ModalError::NoConvergence);
    }
    let c = 0.5 * (&c + c.transpose());
    let eig = c.symmetric_eigen();
    let mut order: Vec<usize> = (0..eig.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let values = DVector::from_iterator(order.len(), order.iter().map(|&i| eig.eigenvalues[i]));
    let vectors =
        DMatrix::from_fn(order.len(), order.len(), |r, k| eig.eigenvectors[(r, order[k])]);
    Ok((values, vectors))
}

impl Basis {
    /// Largest outer radius at which the constant-first basis is used (see
    /// [`Functions::ConstantFirst`]; both are accurate between 1.5 and 5).
    pub(crate) const CONSTANT_FIRST_UP_TO: f64 = 3.0;

    pub(crate) fn new(mesh: Mesh) -> Result<Self, ModalError> {
        let r_inf = *mesh.nodes.last().expect("a mesh has nodes");
        let functions = if r_inf <= Self::CONSTANT_FIRST_UP_TO {
            Functions::ConstantFirst
        } else {
            Functions::Nodal
        };
        let m = galerkin::assemble(&mesh, functions);
        let chol = m.stiffness.cholesky().ok_or(ModalError::StiffnessNotPositive)?;
        let l = chol.l();
        // C = L^-1 (4 M) L^-T, through Y = L^-1 (4 M) and C = L^-1 Y^T (M symmetric).
        let y =
            l.solve_lower_triangular(&(4.0 * &m.mass)).ok_or(ModalError::StiffnessNotPositive)?;
        let c = l.solve_lower_triangular(&y.transpose()).ok_or(ModalError::StiffnessNotPositive)?;
        let (mu, q) = eigen(c)?;
        if let Some((k, &v)) = mu.iter().enumerate().find(|(_, v)| !(**v > 0.0 && v.is_finite())) {
            return Err(ModalError::BadRelaxationTime(k, v));
        }
        let coefficients =
            l.tr_solve_lower_triangular(&q).ok_or(ModalError::StiffnessNotPositive)?;
        // Nodal shapes; the edge row is the same in both bases (only the first function
        // is nonzero at r = 1), so the load (sigma - p) e_first keeps its modal form.
        let shapes = galerkin::to_nodal(functions, coefficients);
        let edge_row = shapes.row(0).transpose();
        let (_, der) = LagrangeBasis::new(&mesh.reference_nodes).eval(-1.0);
        let scale = 2.0 / (mesh.breaks[1] - mesh.breaks[0]);
        let mut edge_slope_row = DVector::zeros(shapes.ncols());
        for (i, d) in der.iter().enumerate() {
            edge_slope_row += (scale * d) * shapes.row(mesh.global(0, i)).transpose();
        }
        let outer_row = shapes.row(shapes.nrows() - 1).transpose();
        Ok(Self {
            mesh,
            mu,
            shapes,
            edge_row,
            edge_slope_row,
            outer_row,
            rates: LazyRates::default(),
            shape_rates: LazyShapeRates::default(),
        })
    }

    pub(crate) fn len(&self) -> usize {
        self.mu.len()
    }

    /// Relaxation times `nu_k = mu_k + lambda^2`.
    pub(crate) fn relaxation_times(&self, lambda: f64) -> DVector<f64> {
        let l2 = lambda * lambda;
        self.mu.map(|m| m + l2)
    }
}

// The derivatives of a basis with respect to R_inf, kept with the basis that owns them
// (the mathematics: `super::sensitivity`, which uses them).

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
                scale
                    * ms[i * n + lo..i * n + hi]
                        .iter()
                        .zip(&xs[c * n + lo..c * n + hi])
                        .map(|(a, b)| a * b)
                        .sum::<f64>()
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
        let smallest_gap =
            mu.as_slice().windows(2).map(|w| (w[1] - w[0]) / w[1]).fold(1.0, f64::min);
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
            if j == k {
                -0.5 * xz[(k, k)]
            } else {
                (xy[(j, k)] - mu[k] * xz[(j, k)]) / (mu[k] - mu[j])
            }
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
