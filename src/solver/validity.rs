//! Where the linear model's answer stops meaning something.
//!
//! The model is linear elasticity (plus viscosity and friction) in the displacement `u(X, t)`
//! of the material point at reference radius `X`, now at `r = X + u(X, t)`. Its exact answer
//! is a radius and a deformation only while
//!
//! - the wound radius `R = 1 + u(1)` is positive,
//! - the map `X -> X + u(X)` is increasing (`1 + du/dX > 0`: the ring does not fold) and the
//!   outer edge `R_inf + u(R_inf)` stays outside the wound edge,
//! - the strains `u / X` (hoop) and `du/dX` (radial) stay within what a linear model can
//!   claim: here [`STRAIN_MAX`] = 1 (100 %). At hoop strain -1 the wound radius is 0 and at
//!   radial strain -1 the ring folds, so the bound contains the first two conditions at the
//!   edge; it is the coarsest that keeps the geometry, not a claim of accuracy at large strain.
//!   The model's defaults (sigma = 1, R_inf = 10) open to a hoop strain of 0.67.
//!
//! The strains are largest at the wound edge: in uniform tension (`t = 0`) they are
//! `sigma / 6` everywhere, and in the final state `u = a X + b / X` both `u / X = a + b / X^2`
//! and `du/dX = a - b / X^2` fall off from the edge like `1 / X^2`. So the check reads three
//! numbers, `u(1)`, `du/dX(1)` and `u(R_inf)`, each a dot product of the modal coordinates
//! with a precomputed row: O(modes) per step, like the wound radius itself.

/// The largest strain (hoop `u / X` or radial `du/dX`, in magnitude) the model answers for.
pub const STRAIN_MAX: f64 = 1.0;

/// The state at the two edges: `u(1)`, `du/dX` at `X = 1`, and `u(R_inf)`, in R0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edges {
    pub edge: f64,
    pub edge_slope: f64,
    pub outer: f64,
}

/// Why the state `edges` (of a tissue of outer radius `r_inf`) is outside the model's
/// validity, or `None` inside it.
pub fn violation(edges: Edges, r_inf: f64) -> Option<String> {
    let Edges { edge, edge_slope, outer } = edges;
    let (radius, outer_radius) = (1.0 + edge, r_inf + outer);
    if radius <= 0.0 {
        return Some(format!(
            "the wound radius is {radius:.6} R0 <= 0: the linear model has no meaning here"
        ));
    }
    if outer_radius <= radius || 1.0 + edge_slope <= 0.0 {
        return Some(format!(
            "the ring folds (outer edge at {outer_radius:.6} R0, wound edge at {radius:.6} R0, 1 + du/dr = {:.6} at \
             the edge): the linear model has no meaning here",
            1.0 + edge_slope
        ));
    }
    if edge.abs() > STRAIN_MAX || edge_slope.abs() > STRAIN_MAX {
        return Some(format!(
            "the strain at the wound edge (hoop u/r = {edge:.6}, radial du/dr = {edge_slope:.6}) exceeds {STRAIN_MAX}, \
             beyond what the linear model can claim"
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_condition_is_named() {
        let at = |edge, edge_slope, outer| violation(Edges { edge, edge_slope, outer }, 10.0);
        assert_eq!(at(0.5, -0.25, 0.1), None);
        assert!(at(-1.2, 0.0, 0.0).unwrap().contains("wound radius is -0.2"));
        assert!(at(0.5, -1.5, 0.0).unwrap().contains("folds"));
        assert!(at(12.0, 0.0, 0.0).unwrap().contains("folds"));
        assert!(at(1.5, 0.2, 0.5).unwrap().contains("strain at the wound edge"));
        assert!(at(0.2, 1.1, 0.5).unwrap().contains("radial du/dr = 1.1"));
    }
}
