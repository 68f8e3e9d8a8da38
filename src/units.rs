//! Physical units: the scales that map the solver's dimensionless variables to the
//! units of an experiment, and the conversion from material constants.
//!
//! ```text
//! length   r_phys = R0 r            R0 in micrometres (the wound radius)
//! time     t_phys = T t             T  in seconds,  T = zeta R0^2 / (4 G)
//! stress   s_phys = G s             G  in pascals   (the shear modulus)
//! velocity v_phys = (R0 / T) v      micrometres per second
//! ```
//!
//! With all three scales 1 the physical values equal the dimensionless ones, so the
//! defaults keep the dimensionless behaviour. `lambda`, `sigma` and `R_inf` are ratios
//! and do not depend on the scales.
//!
//! From material constants (shear modulus `G` [Pa], viscosity `eta` [Pa s], friction
//! `zeta` [Pa s / um^2], wound radius `R0` [um], homeostatic tension `sigma_t` [Pa]):
//!
//! ```text
//! lambda = 2 sqrt(eta / zeta) / R0      sigma = sigma_t / G
//! T      = zeta R0^2 / (4 G)            tau = eta / G = lambda^2 T  (the viscous relaxation time)
//! ```
#![forbid(unsafe_code)]

use std::fmt;

/// Smallest and largest accepted scale: wide enough for any experiment, narrow enough
/// that no product or ratio of scales and solver values overflows.
pub const SCALE_MIN: f64 = 1e-12;
pub const SCALE_MAX: f64 = 1e12;

/// The three scales (each 1 for dimensionless use).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Wound radius `R0`, micrometres.
    pub length: f64,
    /// Time unit `T = zeta R0^2 / (4 G)`, seconds.
    pub time: f64,
    /// Shear modulus `G`, pascals.
    pub stress: f64,
}

impl Default for Scales {
    fn default() -> Self {
        Self { length: 1.0, time: 1.0, stress: 1.0 }
    }
}

/// A scale outside `[SCALE_MIN, SCALE_MAX]` (or not finite).
#[derive(Debug, Clone, PartialEq)]
pub struct ScaleError {
    pub name: &'static str,
    pub value: f64,
}

impl fmt::Display for ScaleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} = {} is invalid: it must be finite and in [{SCALE_MIN:e}, {SCALE_MAX:e}]",
            self.name, self.value
        )
    }
}

impl std::error::Error for ScaleError {}

/// Check one scale; `name` is used in the message.
pub fn check_scale(name: &'static str, value: f64) -> Result<f64, ScaleError> {
    if value.is_finite() && (SCALE_MIN..=SCALE_MAX).contains(&value) {
        Ok(value)
    } else {
        Err(ScaleError { name, value })
    }
}

impl Scales {
    pub fn validate(&self) -> Result<(), ScaleError> {
        check_scale("R0", self.length)?;
        check_scale("T", self.time)?;
        check_scale("G", self.stress)?;
        Ok(())
    }

    /// Velocity scale `R0 / T`, micrometres per second.
    pub fn velocity(&self) -> f64 {
        self.length / self.time
    }
}

/// Material constants of an experiment, in micrometres, seconds and pascals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Shear modulus `G` [Pa].
    pub shear_modulus: f64,
    /// Viscosity `eta` [Pa s].
    pub viscosity: f64,
    /// Substrate friction `zeta` [Pa s / um^2].
    pub friction: f64,
    /// Wound radius `R0` [um].
    pub wound_radius: f64,
    /// Homeostatic tension `sigma_t` [Pa].
    pub tension: f64,
}

/// What the component takes: the dimensionless `lambda` and `sigma`, and the scales.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dimensionless {
    pub lambda: f64,
    pub sigma: f64,
    pub scales: Scales,
}

impl Material {
    /// `lambda = 2 sqrt(eta / zeta) / R0`, `sigma = sigma_t / G`, `T = zeta R0^2 / (4 G)`.
    /// Needs `G, zeta, R0 > 0` and `eta >= 0`; the scales are then range-checked.
    pub fn to_dimensionless(&self) -> Result<Dimensionless, String> {
        let m = self;
        let positive = [("G", m.shear_modulus), ("zeta", m.friction), ("R0", m.wound_radius)];
        if let Some((name, v)) = positive.iter().find(|(_, v)| !(v.is_finite() && *v > 0.0)) {
            return Err(format!("{name} = {v} is invalid: it must be finite and > 0"));
        }
        if !(m.viscosity.is_finite() && m.viscosity >= 0.0) {
            return Err(format!("eta = {} is invalid: it must be finite and >= 0", m.viscosity));
        }
        let lambda = 2.0 * (m.viscosity / m.friction).sqrt() / m.wound_radius;
        let time = m.friction * m.wound_radius * m.wound_radius / (4.0 * m.shear_modulus);
        let scales = Scales { length: m.wound_radius, time, stress: m.shear_modulus };
        scales.validate().map_err(|e| e.to_string())?;
        Ok(Dimensionless { lambda, sigma: m.tension / m.shear_modulus, scales })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The README's worked example: R0 = 10 um and tau = eta / G = 10 s at lambda = 1.
    #[test]
    fn worked_example() {
        let m = Material {
            shear_modulus: 100.0,
            viscosity: 1000.0,
            friction: 40.0,
            wound_radius: 10.0,
            tension: 100.0,
        };
        let d = m.to_dimensionless().unwrap();
        assert!((d.lambda - 1.0).abs() < 1e-15);
        assert!((d.scales.time - 10.0).abs() < 1e-12);
        assert_eq!(d.sigma, 1.0);
        let tau = m.viscosity / m.shear_modulus;
        assert!((tau - d.lambda * d.lambda * d.scales.time).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_constants_and_scales() {
        let ok = Material {
            shear_modulus: 1.0,
            viscosity: 0.0,
            friction: 1.0,
            wound_radius: 1.0,
            tension: 1.0,
        };
        assert_eq!(ok.to_dimensionless().unwrap().lambda, 0.0);
        assert!(
            Material { friction: 0.0, ..ok }.to_dimensionless().unwrap_err().contains("zeta = 0")
        );
        assert!(
            Material { viscosity: -1.0, ..ok }.to_dimensionless().unwrap_err().contains("eta = -1")
        );
        assert!(
            Material { wound_radius: 1e13, ..ok }
                .to_dimensionless()
                .unwrap_err()
                .contains("R0 = 1")
        );
        assert!(check_scale("T", f64::NAN).is_err());
        assert!(check_scale("T", 0.0).is_err());
    }
}
