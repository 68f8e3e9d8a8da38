//! The radial mesh: spectral elements on `[1, R_inf]`, graded towards the wound edge.
//!
//! The solution has its structure at the wound edge `r = 1`: a boundary layer of width
//! `lambda` just after the cut (viscous length) and a diffusive front of width
//! `~ 2 sqrt(t)` in the friction regime; far from the wound it tends to `a r + b / r`.
//! Element breaks are therefore uniform in the stretched coordinate
//!
//! ```text
//! xi(r) = ln(1 + (r - 1) / ell),      r_j = 1 + ell [ (1 + (R_inf - 1) / ell)^(j / E) - 1 ],
//! ```
//!
//! `j = 0..E`: a geometric progression of element widths starting near `ell` at the
//! wound edge. Each element carries a degree-`p` Lagrange basis on its GLL nodes; the
//! global nodes are shared at element breaks, so there are `E p + 1` unknowns.

use super::quadrature::gauss_lobatto_nodes;

/// How finely the radius is resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSpec {
    /// Polynomial degree `p >= 1` in each element (1 = linear finite elements).
    pub degree: usize,
    /// Number of elements `E >= 1`.
    pub elements: usize,
    /// Grading length `ell > 0` (in R0): the first element is about this wide when `E` is
    /// large; `ell >= R_inf - 1` gives nearly uniform elements.
    pub edge_scale: f64,
}

/// Element breaks and global node positions of a [`MeshSpec`] on `[1, r_inf]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    pub(crate) breaks: Vec<f64>,
    /// Reference GLL nodes of one element, on `[-1, 1]`.
    pub(crate) reference_nodes: Vec<f64>,
    /// Global nodes, ascending: `nodes[0] = 1`, `nodes[last] = r_inf`.
    pub(crate) nodes: Vec<f64>,
    /// The grading length `ell` of its [`MeshSpec`].
    pub(crate) edge_scale: f64,
}

impl Mesh {
    pub fn new(spec: MeshSpec, r_inf: f64) -> Self {
        let e = spec.elements.max(1);
        let ell = spec.edge_scale;
        let stretch = 1.0 + (r_inf - 1.0) / ell;
        let mut breaks: Vec<f64> =
            (0..=e).map(|j| 1.0 + ell * (stretch.powf(j as f64 / e as f64) - 1.0)).collect();
        breaks[e] = r_inf;
        let reference_nodes = gauss_lobatto_nodes(spec.degree.max(1));
        let mut nodes = vec![1.0];
        for w in breaks.windows(2) {
            let (a, b) = (w[0], w[1]);
            nodes.extend(reference_nodes[1..].iter().map(|x| 0.5 * (a + b) + 0.5 * (b - a) * x));
        }
        Self { breaks, reference_nodes, nodes, edge_scale: ell }
    }

    /// `d b_j / d R_inf` of every break at fixed `E` and `ell` (the breaks move smoothly
    /// with the outer radius): with `S = 1 + (R_inf - 1) / ell`,
    ///
    /// ```text
    /// b_j = 1 + ell (S^(j/E) - 1)   =>   d b_j / d R_inf = (j / E) S^(j/E - 1)
    /// ```
    ///
    /// (0 at the wound edge, 1 at the outer edge).
    pub(crate) fn break_rates(&self) -> Vec<f64> {
        let e = self.breaks.len() - 1;
        let r_inf = self.breaks[e];
        let stretch = 1.0 + (r_inf - 1.0) / self.edge_scale;
        let mut rates: Vec<f64> = (0..=e)
            .map(|j| j as f64 / e as f64 * stretch.powf(j as f64 / e as f64 - 1.0))
            .collect();
        rates[e] = 1.0;
        rates
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    pub(crate) fn degree(&self) -> usize {
        self.reference_nodes.len() - 1
    }

    /// Global index of local node `i` of element `e`.
    pub(crate) fn global(&self, e: usize, i: usize) -> usize {
        e * self.degree() + i
    }

    /// The element containing `r` (the last one for `r = r_inf`) and the reference
    /// coordinate of `r` in it.
    pub(crate) fn locate(&self, r: f64) -> (usize, f64) {
        let e = self.breaks[1..].partition_point(|&b| b < r).min(self.breaks.len() - 2);
        let (a, b) = (self.breaks[e], self.breaks[e + 1]);
        (e, ((2.0 * r - a - b) / (b - a)).clamp(-1.0, 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_span_the_domain_and_ascend() {
        let spec = MeshSpec { degree: 4, elements: 6, edge_scale: 0.05 };
        let mesh = Mesh::new(spec, 10.0);
        assert_eq!(mesh.len(), 6 * 4 + 1);
        assert_eq!(mesh.nodes[0], 1.0);
        assert_eq!(*mesh.nodes.last().unwrap(), 10.0);
        assert!(mesh.nodes.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn elements_grow_geometrically_from_the_edge() {
        let spec = MeshSpec { degree: 1, elements: 8, edge_scale: 0.1 };
        let mesh = Mesh::new(spec, 100.0);
        let widths: Vec<f64> = mesh.breaks.windows(2).map(|w| w[1] - w[0]).collect();
        let ratio = widths[1] / widths[0];
        for w in widths.windows(2) {
            assert!((w[1] / w[0] - ratio).abs() < 1e-9 * ratio, "{widths:?}");
        }
    }

    #[test]
    fn locate_finds_the_element_and_reference_coordinate() {
        let mesh = Mesh::new(MeshSpec { degree: 2, elements: 3, edge_scale: 1e3 }, 4.0);
        for &r in &[1.0, 1.7, 2.5, 4.0] {
            let (e, x) = mesh.locate(r);
            let (a, b) = (mesh.breaks[e], mesh.breaks[e + 1]);
            assert!(a <= r && r <= b);
            assert!((0.5 * (a + b) + 0.5 * (b - a) * x - r).abs() < 1e-14);
        }
    }
}
