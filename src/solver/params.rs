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

/// A parameter value the model cannot use; the message names the variable, the value
/// and the accepted range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParamError {
    Lambda(f64),
    Sigma(f64),
    RInf(f64),
    EdgeStress(f64),
}

/// A value as a message shows it: plain (`-1`, `0.5`, `2000000`), but in exponent form far
/// from 1 (`1e-300`, not 300 zeros).
fn shown(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e16).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = match *self {
            Self::Lambda(x) | Self::Sigma(x) | Self::RInf(x) | Self::EdgeStress(x) => shown(x),
        };
        match *self {
            Self::Lambda(_) => {
                write!(
                    f,
                    "lambda = {v} is outside the accepted range: 0 or [{LAMBDA_MIN:e}, {LAMBDA_MAX:e}]"
                )
            }
            Self::Sigma(_) => write!(
                f,
                "sigma = {v} is outside the accepted range ({SIGMA_MIN}, {SIGMA_MAX:e}] \
                 (the wound radius just after the cut, R1 = R0 (1 + sigma/6), must be > 0)"
            ),
            Self::RInf(_) => {
                write!(f, "R_inf = {v} is outside the accepted range [{R_INF_MIN}, {R_INF_MAX:e}]")
            }
            Self::EdgeStress(_) => {
                write!(
                    f,
                    "edge stress {v} (in units of G) is outside the accepted range [-{EDGE_STRESS_MAX:e}, {EDGE_STRESS_MAX:e}]"
                )
            }
        }
    }
}

impl std::error::Error for ParamError {}

/// The accepted domain: every parameter set inside it meets the tolerance contract of
/// [`super::Settings::for_tolerance`], measured against the exact Laplace-domain solution
/// over all of it by `examples/accuracy_scan.rs` and tests/python/test_domain.py.
///
/// - `lambda` up to 1e6 (tau = 1e12 T): the relaxation times `mu_k + lambda^2` keep the
///   friction part `mu_k` to ~1e-4 relative there, far below its effect on R.
/// - `lambda = 0` or at least `LAMBDA_MIN = 1e-150`: the edge's response to stress,
///   [`super::exact::velocity_response`], divides by `lambda^2`, which must be a normal
///   double (`> 2.2e-308`), and the largest output, the initial edge velocity
///   `|sigma - p| / (4 lambda)` in `R0 / T` (`<= 2e6 / 4e-150 * 1e24 = 5e179` um/s with the
///   largest scales `R0 = 1e12`, `T = 1e-12`), stays finite with a margin of 1e128 for
///   every product the glue forms. Below it the model is `lambda = 0` for all `t > 0`.
/// - `R_inf` from 1.001 (a thin ring: the constant-first basis keeps the late state to
///   ~5e-12; at 1.0001 it is 4e-11, above the tolerance floor) to 1e6 (relaxation times over
///   17 decades, resolved by the Jacobi eigensolver; the mesh grows like ln R_inf).
/// - `sigma` above `SIGMA_MIN = -6`: just after the cut the tissue is in uniform tension,
///   `u = sigma r / 6`, so the wound radius is `R1 = 1 + sigma / 6`, which is a radius only
///   while `> 0`. Up to `SIGMA_MAX = 1e6`, and `|p|` (in G) up to 1e6: the model is linear
///   in both, so any finite value is accurate; the bound keeps every output finite with the
///   largest physical scales (`R0 = 1e12`, `T = 1e-12`, `G = 1e12`: stresses up to 1e18 Pa,
///   lengths up to 1e18 um, velocities as above).
pub const LAMBDA_MAX: f64 = 1e6;
pub const LAMBDA_MIN: f64 = 1e-150;
pub const SIGMA_MIN: f64 = -6.0;
pub const R_INF_MIN: f64 = 1.001;
pub const R_INF_MAX: f64 = 1e6;
pub const SIGMA_MAX: f64 = 1e6;
pub const EDGE_STRESS_MAX: f64 = 1e6;

/// `lambda` 0 or in `[LAMBDA_MIN, LAMBDA_MAX]`.
pub fn check_lambda(v: f64) -> Result<f64, ParamError> {
    if v == 0.0 || (LAMBDA_MIN..=LAMBDA_MAX).contains(&v) {
        Ok(v)
    } else {
        Err(ParamError::Lambda(v))
    }
}

/// `sigma` in `(SIGMA_MIN, SIGMA_MAX]`.
pub fn check_sigma(v: f64) -> Result<f64, ParamError> {
    if v > SIGMA_MIN && v <= SIGMA_MAX { Ok(v) } else { Err(ParamError::Sigma(v)) }
}

/// `R_inf` in `[R_INF_MIN, R_INF_MAX]`.
pub fn check_r_inf(v: f64) -> Result<f64, ParamError> {
    if (R_INF_MIN..=R_INF_MAX).contains(&v) { Ok(v) } else { Err(ParamError::RInf(v)) }
}

/// The edge stress `p` (in units of G) in `[-EDGE_STRESS_MAX, EDGE_STRESS_MAX]`.
pub fn check_edge_stress(v: f64) -> Result<f64, ParamError> {
    if (-EDGE_STRESS_MAX..=EDGE_STRESS_MAX).contains(&v) {
        Ok(v)
    } else {
        Err(ParamError::EdgeStress(v))
    }
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
        let bounds = [
            Params { lambda: 1.0000001e6, ..Params::default() },
            Params { sigma: -6.0, ..Params::default() },
            Params { lambda: 1e-300, ..Params::default() },
            Params { lambda: 0.99e-150, ..Params::default() },
            Params { sigma: 1.0000001e6, ..Params::default() },
            Params { r_inf: 1.000999, ..Params::default() },
            Params { r_inf: 1.0000001e6, ..Params::default() },
        ];
        for p in bounds {
            let msg = p.validate().unwrap_err().to_string();
            assert!(msg.contains("outside the accepted range"), "{msg}");
        }
        let edges =
            [(0.0, 1e6, 1.001), (1e6, -5.999, 1e6), (1e-150, -5.999, 1.001), (1e-150, 1e6, 1e6)];
        for (lambda, sigma, r_inf) in edges {
            assert!(Params { lambda, sigma, r_inf }.validate().is_ok());
        }
        for (p, name) in bad.iter().zip(names) {
            let msg = p.validate().unwrap_err().to_string();
            assert!(msg.starts_with(name.trim_end()), "{msg}");
        }
        assert!(Params { lambda: 0.0, sigma: -2.0, r_inf: 1.01 }.validate().is_ok());
    }
}
