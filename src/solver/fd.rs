//! The paper's finite-difference grid and operators (appendix of the paper), shared by
//! the paper's scheme and the explicit scheme.
//!
//! ```text
//! r_i = 1 + i dr,  i = 0 .. N-1,  dr = (R_inf - 1) / (N - 1)
//! interior (central, second order):
//!   D2 u_i = (u_{i+1} - 2 u_i + u_{i-1}) / dr^2 + (u_{i+1} - u_{i-1}) / (2 dr r_i) - u_i / r_i^2
//! edges (one-sided, FIRST order, as in the paper):
//!   D u_0     = (-4/dr + 2/r_0) u_0 + (4/dr) u_1
//!   D u_{N-1} = (4/dr + 2/r_{N-1}) u_{N-1} - (4/dr) u_{N-2}
//! ```

/// A row of a tridiagonal operator: coefficients of `u_{i-1}`, `u_i`, `u_{i+1}`.
pub(crate) type Row = [f64; 3];

#[derive(Debug, Clone)]
pub(crate) struct Grid {
    pub(crate) r: Vec<f64>,
    /// `D2` rows (interior; the two edge rows are unused zeros).
    pub(crate) d2: Vec<Row>,
    /// `D` rows at the wound edge (`[_, D_00, D_01]`) and the outer edge (`[D_{N-1,N-2}, D_{N-1,N-1}, _]`).
    pub(crate) d_edge: Row,
    pub(crate) d_outer: Row,
}

impl Grid {
    pub(crate) fn new(points: usize, r_inf: f64) -> Self {
        let n = points.max(3);
        let dr = (r_inf - 1.0) / (n - 1) as f64;
        let r: Vec<f64> =
            (0..n).map(|i| if i == n - 1 { r_inf } else { 1.0 + i as f64 * dr }).collect();
        let d2 = (0..n)
            .map(|i| {
                if i == 0 || i == n - 1 {
                    return [0.0; 3];
                }
                let (a, b) = (1.0 / (dr * dr), 1.0 / (2.0 * dr * r[i]));
                [a - b, -2.0 * a - 1.0 / (r[i] * r[i]), a + b]
            })
            .collect();
        let d_edge = [0.0, -4.0 / dr + 2.0 / r[0], 4.0 / dr];
        let d_outer = [-4.0 / dr, 4.0 / dr + 2.0 / r[n - 1], 0.0];
        Self { r, d2, d_edge, d_outer }
    }

    pub(crate) fn len(&self) -> usize {
        self.r.len()
    }

    /// `row . (u_{i-1}, u_i, u_{i+1})`, with missing neighbours taken as 0.
    pub(crate) fn apply(row: &Row, u: &[f64], i: usize) -> f64 {
        let left = if i > 0 { row[0] * u[i - 1] } else { 0.0 };
        let right = if i + 1 < u.len() { row[2] * u[i + 1] } else { 0.0 };
        left + row[1] * u[i] + right
    }

    /// `D2 u` at the interior points, zero at the edges.
    pub(crate) fn d2_of(&self, u: &[f64]) -> Vec<f64> {
        (0..u.len()).map(|i| Self::apply(&self.d2[i], u, i)).collect()
    }
}

/// A tridiagonal system factorised once (Thomas algorithm, no pivoting) and solved many times.
#[derive(Debug, Clone)]
pub(crate) struct Tridiagonal {
    /// Sub-diagonal, modified diagonal pivots and super-diagonal.
    sub: Vec<f64>,
    pivot: Vec<f64>,
    sup: Vec<f64>,
}

impl Tridiagonal {
    pub(crate) fn factor(rows: &[Row]) -> Self {
        let n = rows.len();
        let sub: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        let sup: Vec<f64> = rows.iter().map(|r| r[2]).collect();
        let mut pivot = vec![0.0; n];
        pivot[0] = rows[0][1];
        for i in 1..n {
            pivot[i] = rows[i][1] - sub[i] * sup[i - 1] / pivot[i - 1];
        }
        Self { sub, pivot, sup }
    }

    pub(crate) fn solve(&self, rhs: &mut [f64]) {
        let n = rhs.len();
        for i in 1..n {
            rhs[i] -= self.sub[i] / self.pivot[i - 1] * rhs[i - 1];
        }
        rhs[n - 1] /= self.pivot[n - 1];
        for i in (0..n - 1).rev() {
            rhs[i] = (rhs[i] - self.sup[i] * rhs[i + 1]) / self.pivot[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d2_is_exact_on_r_and_one_over_r() {
        // D2 r = 0 and D2 (1/r) = 0 exactly; the central rows are exact on r, and on 1/r to O(dr^2).
        let g = Grid::new(41, 5.0);
        let lin: Vec<f64> = g.r.clone();
        assert!(g.d2_of(&lin).iter().all(|v| v.abs() < 1e-10));
        let inv: Vec<f64> = g.r.iter().map(|r| 1.0 / r).collect();
        let err = g.d2_of(&inv).iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(err < 0.05, "{err}");
    }

    #[test]
    fn thomas_solves_a_tridiagonal_system() {
        let rows = vec![[0.0, 4.0, 1.0], [1.0, 4.0, 1.0], [1.0, 4.0, 1.0], [1.0, 4.0, 0.0]];
        let x = [1.0, -2.0, 3.0, 0.5];
        let mut b: Vec<f64> = (0..4).map(|i| Grid::apply(&rows[i], &x, i)).collect();
        Tridiagonal::factor(&rows).solve(&mut b);
        for (a, e) in b.iter().zip(x) {
            assert!((a - e).abs() < 1e-14);
        }
    }
}
