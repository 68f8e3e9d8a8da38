//! Exact-in-time integration of the semi-discrete system by its modes.
//!
//! With stiffness `A` (SPD) and mass `B = 4 M + lambda^2 A` (SPD), the semi-discrete
//! system `B u_t = -A u + F` is diagonalised by the generalised eigenproblem
//!
//! ```text
//! B x_k = nu_k A x_k,     X^T A X = I,     X^T B X = diag(nu),     nu_k = 1 / (decay rate)
//! ```
//!
//! computed as `A = L L^T` (Cholesky), `L^-1 B L^-T = Q diag(nu) Q^T` (symmetric
//! eigenproblem), `X = L^-T Q`. The pencil is taken this way round (`nu` = relaxation
//! times, not rates) because a symmetric eigensolver has absolute accuracy
//! `eps max(nu)`: the slow modes, which carry the late-time solution, then get full
//! relative accuracy, and the fast ones (which decay within a few sub-microsecond
//! relaxation times) only lose accuracy that no output can see. Every `nu_k > 0`.
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

use nalgebra::{DMatrix, DVector};

/// The modal decomposition of one discretised problem (fixed `lambda`, mesh, `R_inf`).
#[derive(Debug, Clone)]
pub(crate) struct Modes {
    /// Relaxation times `nu_k > 0` (in T).
    pub(crate) nu: DVector<f64>,
    /// Mode shapes `X` (columns), nodal values.
    pub(crate) shapes: DMatrix<f64>,
}

/// Why a modal decomposition could not be built.
#[derive(Debug, Clone, PartialEq)]
pub enum ModalError {
    /// The stiffness matrix was not numerically positive definite.
    StiffnessNotPositive,
    /// A relaxation time came out non-positive or non-finite (index, value).
    BadRelaxationTime(usize, f64),
}

impl std::fmt::Display for ModalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::StiffnessNotPositive => write!(f, "stiffness matrix is not positive definite"),
            Self::BadRelaxationTime(k, v) => write!(f, "relaxation time {k} is {v}"),
        }
    }
}

impl Modes {
    pub(crate) fn new(stiffness: &DMatrix<f64>, mass: &DMatrix<f64>) -> Result<Self, ModalError> {
        let chol = stiffness.clone().cholesky().ok_or(ModalError::StiffnessNotPositive)?;
        let l = chol.l();
        // C = L^-1 B L^-T, through Y = L^-1 B and C = L^-1 Y^T (B symmetric).
        let y = l.solve_lower_triangular(mass).ok_or(ModalError::StiffnessNotPositive)?;
        let mut c = l.solve_lower_triangular(&y.transpose()).ok_or(ModalError::StiffnessNotPositive)?;
        c = 0.5 * (&c + c.transpose());
        let eig = c.symmetric_eigen();
        let shapes = l.tr_solve_lower_triangular(&eig.eigenvectors).ok_or(ModalError::StiffnessNotPositive)?;
        if let Some((k, &v)) = eig.eigenvalues.iter().enumerate().find(|(_, v)| !(**v > 0.0 && v.is_finite())) {
            return Err(ModalError::BadRelaxationTime(k, v));
        }
        Ok(Self { nu: eig.eigenvalues, shapes })
    }

    pub(crate) fn len(&self) -> usize {
        self.nu.len()
    }
}
