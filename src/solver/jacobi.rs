//! Cyclic Jacobi eigensolver for symmetric positive definite matrices, with the relative
//! stopping rule of Demmel and Veselic ("Jacobi's method is more accurate than QR", SIAM
//! J. Matrix Anal. Appl. 13, 1992).
//!
//! Why not Householder tridiagonalisation + QR (LAPACK, nalgebra's `symmetric_eigen`): those
//! are backward stable in the norm, so every eigenvalue carries an absolute error of about
//! `eps * max|mu|`. The relaxation times of the wound problem span 17 decades at
//! `R_inf = 1e6` (from ~1e-5 T at the wound edge to ~1e12 T), so the fast modes that shape
//! the opening at `t ~ 0.01` came out with relative errors of 1e-2 and the wound radius with
//! errors of 1e-5 of the opening.
//!
//! A plane rotation annihilates `h_pq` when
//!
//! ```text
//! |h_pq| > tol * sqrt(h_pp h_qq)          (relative, not |h_pq| > tol * ||H||)
//! theta = (h_qq - h_pp) / (2 h_pq),  t = sign(theta) / (|theta| + sqrt(1 + theta^2)),
//! c = 1 / sqrt(1 + t^2),  s = t c,   h_pp -= t h_pq,  h_qq += t h_pq
//! ```
//!
//! For a matrix that is `D S D` with `S` well conditioned (a graded matrix, as the reduced
//! mass matrix of a geometrically graded mesh is), this rule gives every eigenvalue to a
//! relative accuracy of about `eps * cond(S)`, small ones included. Measured on the
//! shipped meshes: wound-radius errors of ~1e-12 of the opening at `R_inf = 1e6`, the same
//! as at `R_inf = 10` (tests/solver_exact.rs). The method is deterministic: the same matrix
//! gives bit-identical results on every call (what the cache of [`super::basis`] relies on).

use nalgebra::{DMatrix, DVector};

/// Relative threshold below which an off-diagonal entry counts as zero.
const THRESHOLD: f64 = f64::EPSILON;
/// Sweeps after which the iteration stops whatever the off-diagonal mass (quadratic
/// convergence reaches the threshold in 6 to 12 sweeps for the shipped meshes).
const MAX_SWEEPS: usize = 60;

/// Eigenvalues (ascending) and orthonormal eigenvectors (columns, in the same order) of a
/// symmetric matrix `h`; `None` if the iteration did not converge in [`MAX_SWEEPS`] sweeps
/// or met a non-finite value.
pub(crate) fn symmetric_eigen(h: &DMatrix<f64>) -> Option<(DVector<f64>, DMatrix<f64>)> {
    let n = h.nrows();
    // Row-major copy: rows p and q are contiguous; the matrix is kept symmetric.
    let mut a: Vec<f64> =
        (0..n * n).map(|k| 0.5 * (h[(k / n, k % n)] + h[(k % n, k / n)])).collect();
    let mut v = vec![0.0; n * n];
    (0..n).for_each(|i| v[i * n + i] = 1.0);
    let mut converged = false;
    for _ in 0..MAX_SWEEPS {
        let mut rotations = 0;
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                let (app, aqq) = (a[p * n + p], a[q * n + q]);
                // Not above the threshold, NaN included.
                if apq.abs().partial_cmp(&(THRESHOLD * (app * aqq).abs().sqrt()))
                    != Some(std::cmp::Ordering::Greater)
                {
                    continue;
                }
                rotations += 1;
                let theta = (aqq - app) / (2.0 * apq);
                let t = if theta == 0.0 {
                    1.0
                } else {
                    theta.signum() / (theta.abs() + theta.hypot(1.0))
                };
                let c = 1.0 / t.hypot(1.0);
                let s = t * c;
                rotate(&mut a, n, p, q, c, s);
                a[p * n + p] = app - t * apq;
                a[q * n + q] = aqq + t * apq;
                a[p * n + q] = 0.0;
                a[q * n + p] = 0.0;
                // Eigenvectors are accumulated as rows of `v` (v = V^T), contiguous too.
                rotate_rows(&mut v, n, p, q, c, s);
            }
        }
        if a.iter().any(|x| !x.is_finite()) {
            return None;
        }
        if rotations == 0 {
            converged = true;
            break;
        }
    }
    if !converged {
        return None;
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| a[i * n + i].total_cmp(&a[j * n + j]));
    let values = DVector::from_iterator(n, order.iter().map(|&i| a[i * n + i]));
    let vectors = DMatrix::from_fn(n, n, |row, col| v[order[col] * n + row]);
    Some((values, vectors))
}

/// Rows `p`, `q` of `m` (row-major, `n x n`) replaced by `c r_p - s r_q`, `s r_p + c r_q`.
fn rotate_rows(m: &mut [f64], n: usize, p: usize, q: usize, c: f64, s: f64) {
    let (head, tail) = m.split_at_mut(q * n);
    let (rp, rq) = (&mut head[p * n..p * n + n], &mut tail[..n]);
    for (x, y) in rp.iter_mut().zip(rq.iter_mut()) {
        let (xp, xq) = (*x, *y);
        *x = c * xp - s * xq;
        *y = s * xp + c * xq;
    }
}

/// `A <- J^T A J` for the rotation in the `(p, q)` plane (off the two diagonal entries,
/// which the caller sets from the closed form): rows first, then the columns mirrored.
fn rotate(a: &mut [f64], n: usize, p: usize, q: usize, c: f64, s: f64) {
    rotate_rows(a, n, p, q, c, s);
    for k in 0..n {
        a[k * n + p] = a[p * n + k];
        a[k * n + q] = a[q * n + k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A graded matrix `D S D` (entries over 24 decades) whose eigenvalues are known to
    /// full relative accuracy: `S` = [[2, 1], [1, 2]] blocks scaled by `d`.
    #[test]
    fn small_eigenvalues_of_a_graded_matrix_keep_their_relative_accuracy() {
        let d = [1e-6, 1e-6, 1e6, 1e6];
        let s = DMatrix::from_row_slice(
            4,
            4,
            &[2., 1., 0., 0., 1., 2., 0., 0., 0., 0., 2., 1., 0., 0., 1., 2.],
        );
        let h = DMatrix::from_fn(4, 4, |i, j| d[i] * s[(i, j)] * d[j]);
        let (mu, x) = symmetric_eigen(&h).unwrap();
        let want = [1e-12, 3e-12, 1e12, 3e12];
        for (got, want) in mu.iter().zip(want) {
            assert!((got - want).abs() < 4.0 * f64::EPSILON * want, "{got:e} vs {want:e}");
        }
        let residual = &h * &x - &x * DMatrix::from_diagonal(&mu);
        for k in 0..4 {
            assert!(residual.column(k).norm() < 1e-14 * mu[k], "mode {k}");
        }
        assert!((x.transpose() * &x - DMatrix::identity(4, 4)).amax() < 1e-15);
    }

    #[test]
    fn deterministic_and_sorted() {
        let h = DMatrix::from_fn(30, 30, |i, j| 1.0 / (1.0 + i as f64 + j as f64));
        let (a, va) = symmetric_eigen(&h).unwrap();
        let (b, vb) = symmetric_eigen(&h).unwrap();
        assert_eq!(a, b);
        assert_eq!(va, vb);
        assert!(a.as_slice().windows(2).all(|w| w[0] <= w[1]));
    }

    #[test]
    fn refuses_non_finite_input() {
        let h = DMatrix::from_row_slice(2, 2, &[1.0, f64::NAN, f64::NAN, 1.0]);
        assert!(symmetric_eigen(&h).is_none());
    }
}
