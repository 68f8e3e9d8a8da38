//! FMI 3.0 probe radii: where the `displacement` and `velocity` arrays are read.
//!
//! A probe is a material point named by its reference radius `X` (the undeformed position,
//! in the configuration where the wound edge is at `R0`); at time `t` it is at the current
//! radius `X + u(X, t)`, which is where a PIV measurement would see it.
//!
//! Until the master sets `probe_radii`, the probes follow the tissue: fractions
//! `f = 0, 1/18, 1/9, 2/9, 4/9, 1` of the ring, `X = R0 (1 + f (R_inf - 1))` (the edge, the
//! viscous boundary layer at lambda = 0.1 to 1, the bulk, the outer edge). At the default
//! `R0 = 1 um`, `R_inf = 10` these are the declared start values 1, 1.5, 2, 3, 5, 10 um; for
//! any accepted `R0` and `R_inf` they lie in the tissue `[R0, R0 R_inf]`, so the defaults
//! work for every accepted parameter set.

/// Default fractions of the ring, as numerators over 18 (exact at `R_inf = 10`).
const NUMERATORS: [f64; 6] = [0.0, 1.0, 2.0, 4.0, 8.0, 18.0];

/// The probes: the defaults that follow the tissue (how many), or radii the master set (um).
#[derive(Debug, Clone, PartialEq)]
pub enum Probes {
    Default(usize),
    Set(Vec<f64>),
}

impl Default for Probes {
    fn default() -> Self {
        Self::Default(NUMERATORS.len())
    }
}

impl Probes {
    pub fn len(&self) -> usize {
        match self {
            Self::Default(n) => *n,
            Self::Set(radii) => radii.len(),
        }
    }

    /// The radii in um for the wound radius `r0` (um) and outer radius `r_inf` (in R0): the
    /// default fractions as far as they go, then the outer edge.
    pub fn radii(&self, r0: f64, r_inf: f64) -> Vec<f64> {
        match self {
            Self::Set(radii) => radii.clone(),
            Self::Default(n) => (0..*n)
                .map(|i| match NUMERATORS.get(i) {
                    Some(&k) if k < 18.0 => r0 * (1.0 + k * (r_inf - 1.0) / 18.0),
                    _ => r0 * r_inf,
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_the_declared_start_values_and_stay_in_any_tissue() {
        assert_eq!(
            Probes::default().radii(1.0, 10.0),
            super::super::variables::PROBE_RADII.to_vec()
        );
        for (r0, r_inf) in [(6.0, 1.001), (1e-12, 1e6), (1e12, 1.001), (1e12, 1e6), (6.0, 3.7)] {
            for r in Probes::Default(9).radii(r0, r_inf) {
                assert!((r0..=r0 * r_inf).contains(&r), "{r} outside [{r0}, {}]", r0 * r_inf);
            }
        }
    }
}
