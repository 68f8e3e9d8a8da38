//! Why a solver could not be built or advanced.

use super::{ModalError, ParamError};

/// Why a solver could not be built or advanced.
#[derive(Debug, Clone, PartialEq)]
pub enum SolverError {
    Param(ParamError),
    Modal(ModalError),
    /// A step size that is not finite and positive.
    Step(f64),
    /// A state of the wrong length (expected, actual).
    StateLength(usize, usize),
    /// A state with a non-finite time or coefficient.
    StateNotFinite,
    /// Mesh settings out of range, with the reason.
    Mesh(&'static str),
    /// A tolerance that is not finite and positive.
    Tolerance(f64),
    /// A sigma so small that the rounding of the wound radius misses the tolerance
    /// ([`tolerance::sigma_floor`]).
    Unresolved {
        sigma: f64,
        tolerance: f64,
        floor: f64,
    },
    /// A communication step that would need more internal work than allowed
    /// (its work, the limit).
    TooManySteps(f64, f64),
    /// The explicit scheme blew up in this step (state left as before the step).
    Diverged,
    /// A step of the explicit scheme beyond its von Neumann limits, refused before it is taken.
    Unstable {
        lambda: f64,
        lambda_max: f64,
        dt: f64,
        dt_max: f64,
    },
    /// An edge stress varying within a step asked of a scheme that holds it constant.
    NotLinearInTime,
}

impl std::fmt::Display for SolverError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Param(e) => e.fmt(f),
            Self::Modal(e) => write!(f, "modal decomposition failed: {e}"),
            Self::Step(h) => write!(f, "step size {h} is invalid: it must be finite and > 0"),
            Self::StateLength(want, got) => {
                write!(f, "state has {got} modal coefficients but the solver has {want}")
            }
            Self::StateNotFinite => write!(f, "state holds a non-finite value"),
            Self::Mesh(why) => write!(f, "mesh settings invalid: {why}"),
            Self::Tolerance(t) => {
                write!(f, "tolerance = {t} is invalid: it must be finite and > 0")
            }
            Self::Unresolved { sigma, tolerance, floor } => write!(
                f,
                "sigma = {sigma:e} is too small for tolerance {tolerance:e}: accepted: sigma = 0 or |sigma| >= {floor:.2e} \
                 (6 eps / tolerance; and sigma in (-6, 1e6]). The wound radius R0 (1 + u) is a double near R0, rounded to \
                 2.2e-16 R0, and the opening is about |sigma| R0 / 2: at this sigma no double meets the tolerance. \
                 A tolerance >= {:.2e} accepts this sigma",
                6.0 * f64::EPSILON / sigma.abs()
            ),
            Self::TooManySteps(work, max) => write!(
                f,
                "this step would need {work:.1e} updates of the unknowns (at most {max:.0e} are allowed in one step): take shorter communication steps or a larger internal_step"
            ),
            Self::Unstable { lambda, lambda_max, dt, dt_max } => {
                if lambda >= lambda_max {
                    write!(
                        f,
                        "the explicit scheme is unstable for lambda = {lambda} >= {lambda_max:.4e} (about dr/2 on this grid), whatever the step: use method 0"
                    )
                } else {
                    write!(
                        f,
                        "the explicit scheme's internal step {dt:.4e} breaks its stability limit dt < {dt_max:.4e} (2/kappa_max - 2 lambda^2): lower internal_step or take shorter communication steps"
                    )
                }
            }
            Self::Diverged => write!(
                f,
                "the explicit scheme blew up in this step (internal step above its stability limit, or lambda > dr/2); the state is left as before the step"
            ),
            Self::NotLinearInTime => write!(
                f,
                "an edge stress that varies within a step (an input derivative) needs method 0 (exact in time); methods 1 to 3 hold it constant over a step"
            ),
        }
    }
}

impl std::error::Error for SolverError {}

impl From<ParamError> for SolverError {
    fn from(e: ParamError) -> Self {
        Self::Param(e)
    }
}
