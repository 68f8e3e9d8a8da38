//! Physical parameters of the dimensionless model and their validation.

/// The model's parameters, in the component's units (lengths in R0, stresses in G).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// `lambda = 2 sqrt(eta / zeta) / R0`: viscous length over wound radius, `>= 0`.
    pub lambda: f64,
    /// Homeostatic tension over shear modulus, finite (any sign).
    pub sigma: f64,
    /// Outer radius over wound radius, finite and `> 1`.
    pub r_inf: f64,
}

impl Default for Params {
    fn default() -> Self {
        Self { lambda: 1.0, sigma: 1.0, r_inf: 10.0 }
    }
}

/// A parameter value the model cannot use; the message names the variable and value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParamError {
    Lambda(f64),
    Sigma(f64),
    RInf(f64),
    EdgeStress(f64),
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Self::Lambda(v) => write!(f, "lambda = {v} is invalid: it must be finite and >= 0"),
            Self::Sigma(v) => write!(f, "sigma = {v} is invalid: it must be finite"),
            Self::RInf(v) => write!(f, "R_inf = {v} is invalid: it must be finite, > 1 and <= {R_INF_MAX:e}"),
            Self::EdgeStress(v) => write!(f, "edge_stress = {v} is invalid: it must be finite"),
        }
    }
}

impl std::error::Error for ParamError {}

/// `lambda` must be finite and non-negative.
pub fn check_lambda(v: f64) -> Result<f64, ParamError> {
    if v.is_finite() && v >= 0.0 { Ok(v) } else { Err(ParamError::Lambda(v)) }
}

/// `sigma` must be finite.
pub fn check_sigma(v: f64) -> Result<f64, ParamError> {
    if v.is_finite() { Ok(v) } else { Err(ParamError::Sigma(v)) }
}

/// Largest accepted `R_inf`: the tolerance rule is verified to 1000 and the modal
/// decomposition stays well conditioned far beyond (tests/solver_exact.rs runs 1e6); above
/// about 1e9 it is not.
pub const R_INF_MAX: f64 = 1e6;

/// `R_inf` must be finite, greater than the wound radius 1, and at most [`R_INF_MAX`].
pub fn check_r_inf(v: f64) -> Result<f64, ParamError> {
    if v.is_finite() && v > 1.0 && v <= R_INF_MAX { Ok(v) } else { Err(ParamError::RInf(v)) }
}

/// The edge stress `p` must be finite.
pub fn check_edge_stress(v: f64) -> Result<f64, ParamError> {
    if v.is_finite() { Ok(v) } else { Err(ParamError::EdgeStress(v)) }
}

impl Params {
    pub fn validate(&self) -> Result<(), ParamError> {
        check_lambda(self.lambda)?;
        check_sigma(self.sigma)?;
        check_r_inf(self.r_inf)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_each_invalid_value_by_name() {
        let bad = [
            Params { lambda: -0.5, ..Params::default() },
            Params { lambda: f64::NAN, ..Params::default() },
            Params { sigma: f64::INFINITY, ..Params::default() },
            Params { r_inf: 1.0, ..Params::default() },
            Params { r_inf: f64::NAN, ..Params::default() },
        ];
        let names = ["lambda = -0.5", "lambda = NaN", "sigma = inf", "R_inf = 1 ", "R_inf = NaN"];
        for (p, name) in bad.iter().zip(names) {
            let msg = p.validate().unwrap_err().to_string();
            assert!(msg.starts_with(name.trim_end()), "{msg}");
        }
        assert!(Params { lambda: 0.0, sigma: -2.0, r_inf: 1.0001 }.validate().is_ok());
    }
}
