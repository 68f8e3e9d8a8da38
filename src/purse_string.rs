//! A biological closure model to couple with the wound: an actin purse-string.
//!
//! After a delay `t_d` the cells at the wound border assemble an actin cable whose line
//! tension rises with first-order kinetics of time constant `t_a`:
//!
//! ```text
//! T_c(t) = 0                                     t <= t_d
//! T_c(t) = T_max (1 - exp(-(t - t_d) / t_a))     t >  t_d     (t_a = 0: a step to T_max)
//! ```
//!
//! A line tension `T_c` along a circle of radius `R` in a sheet of thickness `h` pulls
//! the edge inwards with the radial stress (Laplace's law for a line)
//!
//! ```text
//! p = T_c / (h R)
//! ```
//!
//! which is the wound component's `edge_stress` input. Units: `T_c` in piconewtons,
//! `h` and `R` in micrometres, so `p` is in pN / um^2 = pascals. Plain safe Rust: the FMU
//! boundary for it lives in `models::purse_string`.
//!
//! The domain ([`MAX_TENSION`], [`THICKNESS`], [`RADIUS`]; the times only finite and
//! >= 0) keeps every output and derivative finite, far from overflow:
//!
//! ```text
//! 0 <= T_c <= T_max <= 1e9 pN
//! 0 <= p = T_c / (h R)        <= 1e9 / (1e-6 * 1e-6) = 1e21 Pa
//! 0 <= -dp/dR = T_c / (h R^2) <= 1e27 Pa/um
//! ```
//!
//! (A thickness or radius of 5e-324 gave p = inf.) 1e9 pN is a millinewton, 1e-6 um a
//! femtometre, 1e9 um a kilometre: far beyond any cell sheet, so no real case is refused.
#![forbid(unsafe_code)]

/// Parameters of the purse-string.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PurseString {
    /// Saturated line tension `T_max` [pN], in [`MAX_TENSION`].
    pub max_tension: f64,
    /// Assembly time constant `t_a` [s], >= 0.
    pub assembly_time: f64,
    /// Delay `t_d` before assembly starts [s], >= 0 (time since the cut).
    pub delay: f64,
    /// Sheet thickness `h` [um], in [`THICKNESS`].
    pub thickness: f64,
}

/// The closed interval of values a quantity may take, with its unit (for messages).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub min: f64,
    pub max: f64,
    pub unit: &'static str,
}

/// Saturated line tension `T_max`.
pub const MAX_TENSION: Bounds = Bounds { min: 0.0, max: 1e9, unit: "pN" };
/// Sheet thickness `h`.
pub const THICKNESS: Bounds = Bounds { min: 1e-6, max: 1e6, unit: "um" };
/// Wound radius `R` (the input).
pub const RADIUS: Bounds = Bounds { min: 1e-6, max: 1e9, unit: "um" };

/// A bound as the descriptions write it: 0, 1e-6, 1e9.
fn bound_text(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:e}") }
}

impl Bounds {
    /// `value`, if within the bounds; else the reason, naming the value and the range.
    pub fn check(&self, name: &str, value: f64) -> Result<f64, String> {
        if (self.min..=self.max).contains(&value) {
            Ok(value)
        } else {
            let (lo, hi) = (bound_text(self.min), bound_text(self.max));
            Err(format!("{name} = {value} is invalid: it must be in [{lo}, {hi}] {}", self.unit))
        }
    }
}

/// Check a time parameter (`t_assembly`, `t_delay`): finite and `>= 0`. Any such value
/// keeps `T_c` within `[0, T_max]`.
pub fn check_time(name: &str, value: f64) -> Result<f64, String> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(format!("{name} = {value} is invalid: it must be finite and >= 0"))
    }
}

/// Check a wound radius input against [`RADIUS`]. A radius at or below zero means the
/// wound has closed, which this linear model does not describe.
pub fn check_radius(radius: f64) -> Result<f64, String> {
    RADIUS.check("wound_radius", radius).map_err(|e| {
        if radius <= 0.0 {
            format!("{e} (the purse-string stress T_c/(h R) needs an open wound)")
        } else {
            e
        }
    })
}

impl PurseString {
    pub fn validate(&self) -> Result<(), String> {
        MAX_TENSION.check("T_max", self.max_tension)?;
        check_time("t_assembly", self.assembly_time)?;
        check_time("t_delay", self.delay)?;
        THICKNESS.check("thickness", self.thickness)?;
        Ok(())
    }

    /// Line tension `T_c(t)` [pN] at time `t` [s] since the cut.
    pub fn tension(&self, t: f64) -> f64 {
        let s = t - self.delay;
        if s <= 0.0 {
            0.0
        } else if self.assembly_time == 0.0 {
            self.max_tension
        } else {
            -self.max_tension * (-s / self.assembly_time).exp_m1()
        }
    }

    /// Edge stress `p = T_c(t) / (h R)` [Pa] on a wound of radius `R` [um].
    pub fn edge_stress(&self, t: f64, radius: f64) -> f64 {
        self.tension(t) / (self.thickness * radius)
    }

    /// `dp/dR = -T_c(t) / (h R^2)`, for Jacobian-based coupling.
    pub fn edge_stress_slope(&self, t: f64, radius: f64) -> f64 {
        -self.edge_stress(t, radius) / radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const P: PurseString =
        PurseString { max_tension: 6500.0, assembly_time: 30.0, delay: 20.0, thickness: 5.0 };

    #[test]
    fn tension_rises_after_the_delay_to_its_maximum() {
        assert_eq!(P.tension(0.0), 0.0);
        assert_eq!(P.tension(20.0), 0.0);
        // One time constant after the delay: 1 - 1/e of the maximum.
        let want = 6500.0 * (1.0 - (-1.0f64).exp());
        assert!((P.tension(50.0) - want).abs() < 1e-9 * want);
        assert!((P.tension(1e4) - 6500.0).abs() < 1e-9);
        let step = PurseString { assembly_time: 0.0, ..P };
        assert_eq!(step.tension(20.0 + 1e-9), 6500.0);
    }

    #[test]
    fn laplace_law_and_its_slope() {
        // 6500 pN / (5 um * 10 um) = 130 Pa once assembled.
        assert!((P.edge_stress(1e4, 10.0) - 130.0).abs() < 1e-9);
        let (r, d) = (10.0, 1e-6);
        let fd = (P.edge_stress(60.0, r + d) - P.edge_stress(60.0, r - d)) / (2.0 * d);
        assert!((P.edge_stress_slope(60.0, r) - fd).abs() < 1e-7 * fd.abs());
    }

    #[test]
    fn rejects_invalid_values_with_their_name() {
        assert!(
            PurseString { thickness: 0.0, ..P }.validate().unwrap_err().contains("thickness = 0")
        );
        assert!(
            PurseString { max_tension: f64::NAN, ..P }
                .validate()
                .unwrap_err()
                .contains("T_max = NaN")
        );
        assert!(check_radius(-0.5).unwrap_err().contains("wound_radius = -0.5"));
        let tiny = PurseString { thickness: 1e-7, ..P }.validate().unwrap_err();
        assert_eq!(tiny, "thickness = 0.0000001 is invalid: it must be in [1e-6, 1e6] um");
        assert!(check_radius(2e9).unwrap_err().ends_with("it must be in [1e-6, 1e9] um"));
        assert!(
            MAX_TENSION.check("T_max", 1.5e9).unwrap_err().ends_with("it must be in [0, 1e9] pN")
        );
    }
}
