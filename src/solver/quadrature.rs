//! Reference-element tools: Gauss rules and the Lagrange basis on Gauss-Lobatto-Legendre
//! (GLL) nodes, all on the reference interval `[-1, 1]`.
//!
//! ```text
//! GLL nodes of degree p:   x_0 = -1,  x_p = +1,  x_1..x_{p-1} = roots of P'_p(x)
//!                          (the roots of P'_p are the Gauss-Jacobi nodes with alpha = beta = 1)
//! Lagrange basis:          l_j(x) = prod_{m != j} (x - x_m) / (x_j - x_m)
//! barycentric form:        l_j(x) = (w_j / (x - x_j)) / sum_m w_m / (x - x_m),
//!                          w_j = 1 / prod_{m != j} (x_j - x_m)
//! ```
//!
//! Nodes and weights of the Gauss rules come from the `gauss-quad` crate.

use gauss_quad::{FiniteAboveNegOneF64, GaussJacobi, GaussLegendre};
use std::num::NonZeroUsize;

/// Gauss-Legendre rule with `n >= 1` points: `(node, weight)` pairs on `[-1, 1]`,
/// exact for polynomials of degree `2n - 1`.
pub(crate) fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let n = NonZeroUsize::new(n.max(1)).expect("max(1) is non-zero");
    let mut pairs = GaussLegendre::new(n).as_node_weight_pairs().to_vec();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    pairs
}

/// The `p + 1` Gauss-Lobatto-Legendre nodes of degree `p >= 1`, ascending, on `[-1, 1]`.
pub(crate) fn gauss_lobatto_nodes(p: usize) -> Vec<f64> {
    let mut nodes = vec![-1.0];
    if let Some(interior) = NonZeroUsize::new(p.saturating_sub(1)) {
        let one = FiniteAboveNegOneF64::new(1.0).expect("1 is finite and above -1");
        let mut inner: Vec<f64> = GaussJacobi::new(interior, one, one).nodes().copied().collect();
        inner.sort_by(f64::total_cmp);
        nodes.extend(inner);
    }
    nodes.push(1.0);
    nodes
}

/// Lagrange basis through a fixed set of distinct nodes, evaluated in barycentric form.
#[derive(Debug, Clone)]
pub(crate) struct LagrangeBasis {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl LagrangeBasis {
    pub(crate) fn new(nodes: &[f64]) -> Self {
        let weights = nodes
            .iter()
            .enumerate()
            .map(|(j, &xj)| {
                let prod: f64 = nodes
                    .iter()
                    .enumerate()
                    .filter(|&(m, _)| m != j)
                    .map(|(_, &xm)| xj - xm)
                    .product();
                1.0 / prod
            })
            .collect();
        Self { nodes: nodes.to_vec(), weights }
    }

    pub(crate) fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Values `l_j(x)` and derivatives `l_j'(x)` of every basis function at `x`.
    ///
    /// ```text
    /// between nodes:  l_j'(x)   = l_j(x) sum_{m != j} 1 / (x - x_m)     (logarithmic derivative)
    /// at node x_k:    l_j'(x_k) = (w_j / w_k) / (x_k - x_j)   for j != k,
    ///                 l_k'(x_k) = -sum_{j != k} l_j'(x_k)     (the basis sums to one)
    /// ```
    pub(crate) fn eval(&self, x: f64) -> (Vec<f64>, Vec<f64>) {
        let (mut val, mut der) = (vec![0.0; self.len()], vec![0.0; self.len()]);
        self.eval_into(x, &mut val, &mut der);
        (val, der)
    }

    /// [`LagrangeBasis::eval`] into `val` and `der` (each `len()` long) without allocating,
    /// for the loops over many points; `der` first holds `1 / (x - x_m)`.
    pub(crate) fn eval_into(&self, x: f64, val: &mut [f64], der: &mut [f64]) {
        let n = self.len();
        if let Some(k) = self.nodes.iter().position(|&xk| xk == x) {
            val.fill(0.0);
            val[k] = 1.0;
            der.fill(0.0);
            for j in (0..n).filter(|&j| j != k) {
                der[j] = self.weights[j] / self.weights[k] / (x - self.nodes[j]);
            }
            der[k] = -der.iter().sum::<f64>();
            return;
        }
        for (d, &xm) in der.iter_mut().zip(&self.nodes) {
            *d = 1.0 / (x - xm);
        }
        let total_inv: f64 = der.iter().sum();
        let denom: f64 = self.weights.iter().zip(der.iter()).map(|(w, i)| w * i).sum();
        for j in 0..n {
            let inv = der[j];
            val[j] = self.weights[j] * inv / denom;
            der[j] = val[j] * (total_inv - inv);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_degree_2n_minus_1_exactly() {
        let rule = gauss_legendre(4);
        let integral: f64 = rule.iter().map(|(x, w)| w * x.powi(6)).sum();
        assert!((integral - 2.0 / 7.0).abs() < 1e-15, "integral {integral}");
    }

    #[test]
    fn lobatto_nodes_are_symmetric_and_include_the_ends() {
        let nodes = gauss_lobatto_nodes(4);
        let expected = [-1.0, -(3.0f64 / 7.0).sqrt(), 0.0, (3.0f64 / 7.0).sqrt(), 1.0];
        for (a, b) in nodes.iter().zip(expected) {
            assert!((a - b).abs() < 1e-14, "{nodes:?}");
        }
    }

    #[test]
    fn basis_reproduces_a_polynomial_and_its_derivative() {
        let basis = LagrangeBasis::new(&gauss_lobatto_nodes(5));
        let f = |x: f64| 3.0 * x.powi(5) - x.powi(2) + 0.5;
        let df = |x: f64| 15.0 * x.powi(4) - 2.0 * x;
        let values: Vec<f64> = basis.nodes.iter().map(|&x| f(x)).collect();
        for x in [-1.0, -0.3, 0.0, 0.77, 1.0] {
            let (val, der) = basis.eval(x);
            let fx: f64 = val.iter().zip(&values).map(|(l, v)| l * v).sum();
            let dfx: f64 = der.iter().zip(&values).map(|(l, v)| l * v).sum();
            assert!((fx - f(x)).abs() < 1e-13, "f({x})");
            assert!((dfx - df(x)).abs() < 1e-12, "f'({x})");
        }
    }
}
