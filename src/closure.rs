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
//! boundary for it lives in `fmi::purse`.

/// Parameters of the purse-string.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PurseString {
    /// Saturated line tension `T_max` [pN], >= 0.
    pub max_tension: f64,
    /// Assembly time constant `t_a` [s], >= 0.
    pub assembly_time: f64,
    /// Delay `t_d` before assembly starts [s], >= 0 (time since the cut).
    pub delay: f64,
    /// Sheet thickness `h` [um], > 0.
    pub thickness: f64,
}

/// Check a parameter that must be finite and `>= 0` (or `> 0` when `strict`).
pub fn check_nonnegative(name: &str, value: f64, strict: bool) -> Result<f64, String> {
    let ok = value.is_finite() && if strict { value > 0.0 } else { value >= 0.0 };
    if ok { Ok(value) } else { Err(format!("{name} = {value} is invalid: it must be finite and {}", if strict { "> 0" } else { ">= 0" })) }
}

/// Check a wound radius input: the stress `T_c / (h R)` needs `R > 0`. A radius at or
/// below zero means the wound has closed, which this linear model does not describe.
pub fn check_radius(radius: f64) -> Result<f64, String> {
    if radius.is_finite() && radius > 0.0 {
        Ok(radius)
    } else {
        Err(format!("wound_radius = {radius} is invalid: it must be finite and > 0 (the purse-string stress T_c/(h R) needs an open wound)"))
    }
}

impl PurseString {
    pub fn validate(&self) -> Result<(), String> {
        check_nonnegative("T_max", self.max_tension, false)?;
        check_nonnegative("t_assembly", self.assembly_time, false)?;
        check_nonnegative("t_delay", self.delay, false)?;
        check_nonnegative("thickness", self.thickness, true)?;
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

    const P: PurseString = PurseString { max_tension: 6500.0, assembly_time: 30.0, delay: 20.0, thickness: 5.0 };

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
        assert!(PurseString { thickness: 0.0, ..P }.validate().unwrap_err().contains("thickness = 0"));
        assert!(PurseString { max_tension: f64::NAN, ..P }.validate().unwrap_err().contains("T_max = NaN"));
        assert!(check_radius(-0.5).unwrap_err().contains("wound_radius = -0.5"));
    }
}
