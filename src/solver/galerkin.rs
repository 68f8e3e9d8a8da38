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

/// One Gauss point of one element `[a, b]`: reference coordinate `x`, weight, and the
/// values and reference derivatives (`d/dx`) of the element's Lagrange functions there.
struct Point<'a> {
    element: usize,
    a: f64,
    b: f64,
    x: f64,
    weight: f64,
    val: &'a [f64],
    der: &'a [f64],
}

/// Visit the `p + 4` Gauss-Legendre points of every element, in a fixed order.
fn for_each_point(mesh: &Mesh, mut visit: impl FnMut(Point<'_>)) {
    let basis = LagrangeBasis::new(&mesh.reference_nodes);
    let rule = gauss_legendre(mesh.degree() + 4);
    let at_points: Vec<_> = rule.iter().map(|&(x, _)| basis.eval(x)).collect();
    for (element, w) in mesh.breaks.windows(2).enumerate() {
        for (&(x, weight), (val, der)) in rule.iter().zip(&at_points) {
            visit(Point { element, a: w[0], b: w[1], x, weight, val, der });
        }
    }
}

pub(crate) fn assemble(mesh: &Mesh, functions: Functions) -> Matrices {
    let n = mesh.len();
    let p = mesh.degree();
    let constant_first = functions == Functions::ConstantFirst;
    let mut stiffness = DMatrix::zeros(n, n);
    let mut mass = DMatrix::zeros(n, n);
    // (global index, value, derivative) of every function alive on an element at one point.
    let mut local: Vec<(usize, f64, f64)> = Vec::with_capacity(p + 2);
    for_each_point(mesh, |Point { element: e, a, b, x, weight, val, der }| {
        let jac = 0.5 * (b - a);
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
                stiffness[(gi, gj)] +=
                    dw * (4.0 * r * di * dj + 2.0 * (di * fj + fi * dj) + 4.0 * fi * fj / r);
                mass[(gi, gj)] += dw * r * fi * fj;
            }
        }
    });
    Matrices { stiffness, mass }
}

/// `dA / dR_inf` and `dM / dR_inf` in the nodal basis, exact for the quadrature above: the
/// elements' ends move with the outer radius ([`Mesh::break_rates`], `a'`, `b'`), the
/// Lagrange functions stay fixed on the reference element. At a Gauss point `x` of `[a, b]`,
///
/// ```text
/// jac = (b - a) / 2,  r = (a + b) / 2 + jac x,  dw = weight jac,  f_i' = l_i'(x) / jac
/// s = jac' / jac = (b' - a') / (b - a),   r' = (a' + b') / 2 + (b' - a') x / 2
/// dw' = s dw,   (d/dR) f_i' = -s f_i'   (the values f_i do not move)
/// ```
///
/// so the derivative of each point's term, with `q = r' - s r`, is
///
/// ```text
/// stiffness  dw (4 r di dj + 2 (di fj + fi dj) + 4 fi fj / r)   ->  4 q dw (di dj - fi fj / r^2)
/// mass       dw r fi fj                                         ->  (r' + s r) dw fi fj
/// ```
///
/// (the cross terms `2 (di fj + fi dj) dw` do not depend on the element's ends).
pub(crate) fn assemble_r_inf_rate(mesh: &Mesh) -> Matrices {
    let n = mesh.len();
    let p = mesh.degree();
    let rates = mesh.break_rates();
    let mut stiffness = DMatrix::zeros(n, n);
    let mut mass = DMatrix::zeros(n, n);
    for_each_point(mesh, |Point { element: e, a, b, x, weight, val, der }| {
        let jac = 0.5 * (b - a);
        let r = 0.5 * (a + b) + jac * x;
        let dw = weight * jac;
        let (da, db) = (rates[e], rates[e + 1]);
        let s = (db - da) / (b - a);
        let dr = 0.5 * (da + db) + 0.5 * (db - da) * x;
        let q = dr - s * r;
        for i in 0..=p {
            let (gi, fi, di) = (mesh.global(e, i), val[i], der[i] / jac);
            for j in 0..=p {
                let (gj, fj, dj) = (mesh.global(e, j), val[j], der[j] / jac);
                stiffness[(gi, gj)] += 4.0 * q * dw * (di * dj - fi * fj / (r * r));
                mass[(gi, gj)] += (dr + s * r) * dw * fi * fj;
            }
        }
    });
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
        let (nodal, constant) =
            (assemble(&mesh, Functions::Nodal), assemble(&mesh, Functions::ConstantFirst));
        let t = to_nodal(Functions::ConstantFirst, DMatrix::identity(mesh.len(), mesh.len()));
        let a = t.transpose() * &nodal.stiffness * &t;
        let m = t.transpose() * &nodal.mass * &t;
        assert!((a - &constant.stiffness).amax() < 1e-12 * constant.stiffness.amax());
        assert!((m - &constant.mass).amax() < 1e-12 * constant.mass.amax());
    }

    /// The rates against central differences of the assembly at fixed `E` and `ell`.
    #[test]
    fn r_inf_rates_are_the_derivatives_of_the_assembly() {
        let spec = MeshSpec { degree: 5, elements: 4, edge_scale: 0.1 };
        for r_inf in [1.3, 7.0, 300.0] {
            let rate = assemble_r_inf_rate(&Mesh::new(spec, r_inf));
            let h = 1e-5 * r_inf;
            let (up, down) = (
                assemble(&Mesh::new(spec, r_inf + h), Functions::Nodal),
                assemble(&Mesh::new(spec, r_inf - h), Functions::Nodal),
            );
            let fd_a = (up.stiffness - down.stiffness) / (2.0 * h);
            let fd_m = (up.mass - down.mass) / (2.0 * h);
            assert!(
                (&fd_a - &rate.stiffness).amax() < 1e-6 * fd_a.amax(),
                "{r_inf}: {}",
                (&fd_a - &rate.stiffness).amax()
            );
            assert!(
                (&fd_m - &rate.mass).amax() < 1e-6 * fd_m.amax(),
                "{r_inf}: {}",
                (&fd_m - &rate.mass).amax()
            );
        }
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
