//! Galerkin (weak) form of the wound-opening problem and its matrices.
//!
//! The stress divergence satisfies, with `D f = 2 (2 f' + f / r)` (radial stress) and
//! `Dth f = 2 (2 f / r + f')` (hoop stress),
//!
//! ```text
//! 4 r D2 f = (r D f)' - Dth f.
//! ```
//!
//! Multiplying `u_t = D2 g`, `g = u + lambda^2 u_t`, by `4 r phi` and integrating over
//! `[1, R_inf]` by parts gives, for every test function `phi`,
//!
//! ```text
//! 4 m(u_t, phi) + a(u + lambda^2 u_t, phi) = R_inf sigma phi(R_inf) - p phi(1)
//!
//! m(f, phi) = int r f phi dr
//! a(f, phi) = int ( 4 r f' phi' + 2 f' phi + 2 f phi' + 4 f phi / r ) dr
//! ```
//!
//! Both edge stresses enter as natural boundary terms: there are no boundary rows to
//! approximate, and the discrete traction is exact. `a` is symmetric and positive
//! definite, `a(f, f) = int 4 r [ (f' + f / 2r)^2 + 3 f^2 / 4r^2 ] dr > 0`, so with a
//! nodal basis the semi-discrete system
//!
//! ```text
//! (4 M + lambda^2 A) u_t = -A u + F,     F = R_inf sigma e_last - p e_first
//! ```
//!
//! has a symmetric positive definite mass `4 M + lambda^2 A` for every `lambda >= 0`
//! (no algebraic constraints even at `lambda = 0`) and a symmetric positive definite
//! stiffness `A`. The integrals use Gauss-Legendre quadrature with `p + 4` points per
//! element: exact for the polynomial terms, spectrally accurate for the `1 / r` term.

use super::mesh::Mesh;
use super::quadrature::{LagrangeBasis, gauss_legendre};
use nalgebra::DMatrix;

/// Stiffness `A` and mass `M` of a mesh (dense, symmetric).
pub(crate) struct Matrices {
    pub(crate) stiffness: DMatrix<f64>,
    pub(crate) mass: DMatrix<f64>,
}

/// Which functions span the discrete space (the same space either way).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Functions {
    /// The nodal (Lagrange) basis: coefficients are nodal values.
    Nodal,
    /// The nodal basis with its first function replaced by the constant `1`: coefficients
    /// `c` give nodal values `u_0 = c_0`, `u_i = c_0 + c_i` ([`to_nodal`]).
    ///
    /// On a thin annulus (`R_inf -> 1`) the derivative terms of `a` are `O(1 / (R_inf - 1))`
    /// while the slowest mode (nearly uniform `u`) has energy `O(R_inf - 1)`: in the nodal
    /// basis that energy is a difference of large entries, and the rounding of assembly
    /// (`eps / (R_inf - 1)^2` relative) spoils the late-time solution (5e-10 of the opening
    /// at `R_inf = 1.01`). With the constant as a basis function its derivative is exactly
    /// 0 and nothing cancels (2e-15 at 1.01, 2e-11 at 1.0001). On large annuli the global
    /// constant couples the fine edge elements to the far field and costs accuracy
    /// instead, so [`super::modal::Basis`] uses it only for `R_inf <= 3`.
    ConstantFirst,
}

pub(crate) fn assemble(mesh: &Mesh, functions: Functions) -> Matrices {
    let n = mesh.len();
    let p = mesh.degree();
    let basis = LagrangeBasis::new(&mesh.reference_nodes);
    let rule = gauss_legendre(p + 4);
    let at_points: Vec<_> = rule.iter().map(|&(x, _)| basis.eval(x)).collect();
    let constant_first = functions == Functions::ConstantFirst;
    let mut stiffness = DMatrix::zeros(n, n);
    let mut mass = DMatrix::zeros(n, n);
    // (global index, value, derivative) of every function alive on an element at one point.
    let mut local: Vec<(usize, f64, f64)> = Vec::with_capacity(p + 2);
    for (e, w) in mesh.breaks.windows(2).enumerate() {
        let (a, b) = (w[0], w[1]);
        let jac = 0.5 * (b - a);
        for (&(x, weight), (val, der)) in rule.iter().zip(&at_points) {
            let r = 0.5 * (a + b) + jac * x;
            let dw = weight * jac;
            local.clear();
            local.extend((0..=p).map(|i| (mesh.global(e, i), val[i], der[i] / jac)));
            if constant_first {
                if e == 0 {
                    local[0] = (0, 1.0, 0.0);
                } else {
                    local.push((0, 1.0, 0.0));
                }
            }
            for &(gi, fi, di) in &local {
                for &(gj, fj, dj) in &local {
                    stiffness[(gi, gj)] += dw * (4.0 * r * di * dj + 2.0 * (di * fj + fi * dj) + 4.0 * fi * fj / r);
                    mass[(gi, gj)] += dw * r * fi * fj;
                }
            }
        }
    }
    Matrices { stiffness, mass }
}

/// Nodal values of coefficient vectors (columns of `c`) in the basis `functions`.
pub(crate) fn to_nodal(functions: Functions, mut c: DMatrix<f64>) -> DMatrix<f64> {
    if functions == Functions::ConstantFirst {
        let first = c.row(0).clone_owned();
        for mut row in c.row_iter_mut().skip(1) {
            row += &first;
        }
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::mesh::MeshSpec;

    /// `u = sigma r / 6` is the uniform tension state: `D u = sigma` everywhere, so the
    /// weak form gives `A u = R_inf sigma e_last - sigma e_first` exactly.
    #[test]
    fn uniform_tension_balances_the_edge_tractions() {
        let r_inf = 7.0;
        let mesh = Mesh::new(MeshSpec { degree: 3, elements: 5, edge_scale: 0.2 }, r_inf);
        let m = assemble(&mesh, Functions::Nodal);
        let u = nalgebra::DVector::from_iterator(mesh.len(), mesh.nodes.iter().map(|r| r / 6.0));
        let force = &m.stiffness * u;
        let last = mesh.len() - 1;
        assert!((force[0] + 1.0).abs() < 1e-12, "{}", force[0]);
        assert!((force[last] - r_inf).abs() < 1e-12, "{}", force[last]);
        assert!(force.rows(1, last - 1).amax() < 1e-12);
    }

    /// The same space in two bases: `A_c = T^T A T`, `M_c = T^T M T` with `T = to_nodal`.
    #[test]
    fn constant_first_is_a_change_of_basis() {
        let mesh = Mesh::new(MeshSpec { degree: 4, elements: 3, edge_scale: 0.2 }, 2.5);
        let (nodal, constant) = (assemble(&mesh, Functions::Nodal), assemble(&mesh, Functions::ConstantFirst));
        let t = to_nodal(Functions::ConstantFirst, DMatrix::identity(mesh.len(), mesh.len()));
        let a = t.transpose() * &nodal.stiffness * &t;
        let m = t.transpose() * &nodal.mass * &t;
        assert!((a - &constant.stiffness).amax() < 1e-12 * constant.stiffness.amax());
        assert!((m - &constant.mass).amax() < 1e-12 * constant.mass.amax());
    }

    #[test]
    fn mass_integrates_r_over_the_annulus() {
        let mesh = Mesh::new(MeshSpec { degree: 2, elements: 4, edge_scale: 1.0 }, 3.0);
        let m = assemble(&mesh, Functions::Nodal);
        // sum_ij M_ij = int r dr = (9 - 1) / 2
        assert!((m.mass.sum() - 4.0).abs() < 1e-13);
        assert!((&m.stiffness - m.stiffness.transpose()).amax() < 1e-12);
    }
}
