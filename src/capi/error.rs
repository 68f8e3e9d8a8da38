//! Status codes of the direct C API, the calling thread's last error message, and the
//! frame every exported `wo_*` function runs in: panic boundary, status, message.

use crate::boundary::guard;
use crate::boundary::registry::Unknown;
use crate::solver::SolverError;
use std::cell::RefCell;
use std::ffi::c_char;

/// Result of every `wo_*` call. On anything but `WO_OK`, `wo_last_error()` names what was
/// wrong, with the expected and the actual value.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WoStatus {
    /// Success.
    WoOk = 0,
    /// A pointer argument that must not be NULL was NULL.
    WoNullPointer = 1,
    /// A value out of range: NaN or infinite, lambda < 0, R_inf <= 1, a tolerance <= 0, a
    /// grid out of range, a time before the solver's, a radius outside [1, R_inf], or an
    /// array length other than the one required.
    WoInvalidArgument = 2,
    /// A solver or state handle that was never created here, or was already freed.
    WoUnknownHandle = 3,
    /// A saved state of another problem (other lambda, sigma, R_inf or grid).
    WoIncompatibleState = 4,
    /// The discretisation could not be built (the modal decomposition failed).
    WoSolverFailed = 5,
    /// An internal error (a caught panic). The solver involved refuses further use until a
    /// saved state is restored into it, or it is freed.
    WoInternalError = 6,
    /// The value asked for is infinite in the model: the velocity at lambda = 0 at the cut,
    /// before the first advance (it decays like t^(-1/2) afterwards). Nothing is written.
    WoUndefined = 7,
    /// A warning, not an error: `wo_solver_advance` did advance (the solver is at `t_end`),
    /// but there the state left the linear model's validity (the wound radius <= 0, the ring
    /// folded, or a strain at the wound edge beyond 1); `wo_last_error()` gives the reason and
    /// the time. Returned once, by the advance that leaves it.
    WoOutsideValidity = 8,
}

/// A refused call: its status and the reason.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    pub status: WoStatus,
    pub message: String,
}

impl Failure {
    pub fn new(status: WoStatus, message: impl Into<String>) -> Self {
        Self { status, message: message.into() }
    }

    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(WoStatus::WoInvalidArgument, message)
    }

    /// A required pointer argument was NULL.
    pub fn null(what: &str) -> Self {
        Self::new(WoStatus::WoNullPointer, format!("{what} is NULL (expected a valid pointer)"))
    }
}

impl From<Unknown> for Failure {
    fn from(e: Unknown) -> Self {
        Self::new(WoStatus::WoUnknownHandle, e.to_string())
    }
}

impl From<SolverError> for Failure {
    fn from(e: SolverError) -> Self {
        let status = match e {
            SolverError::Modal(_) => WoStatus::WoSolverFailed,
            SolverError::StateLength(..) | SolverError::StateNotFinite => {
                WoStatus::WoIncompatibleState
            }
            _ => WoStatus::WoInvalidArgument,
        };
        Self::new(status, e.to_string())
    }
}

/// Room for the message, its terminating NUL included; a longer message is cut at a
/// character boundary.
const MESSAGE_CAPACITY: usize = 2048;

thread_local! {
    /// Message of the calling thread's last `wo_*` call ("" after a success), NUL-terminated.
    /// A fixed buffer rather than a heap string: a thread-local without destructor, so a
    /// program that loads the library with `dlopen` can unload it (glibc keeps a library
    /// that registered thread-local destructors mapped until the process exits).
    static LAST_ERROR: RefCell<[u8; MESSAGE_CAPACITY]> = const { RefCell::new([0; MESSAGE_CAPACITY]) };
}

fn set_last_error(message: &str) {
    let text = message.replace('\0', "\\0");
    let mut end = text.len().min(MESSAGE_CAPACITY - 1);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    LAST_ERROR.with(|slot| {
        let mut buffer = slot.borrow_mut();
        buffer[..end].copy_from_slice(&text.as_bytes()[..end]);
        buffer[end] = 0;
    });
}

/// Pointer to the calling thread's last message; valid until this thread's next `wo_*` call.
pub fn last_error_ptr() -> *const c_char {
    LAST_ERROR.with(|slot| slot.as_ptr().cast::<c_char>().cast_const())
}

/// Run the body of the exported function `name`: a panic becomes `WO_INTERNAL_ERROR`, a
/// refusal its status, and the thread's last error is set to `"name: reason"` (or
/// cleared on success).
pub fn run(name: &str, body: impl FnOnce() -> Result<(), Failure>) -> WoStatus {
    let outcome = guard(body).unwrap_or_else(|panic| {
        Err(Failure::new(
            WoStatus::WoInternalError,
            format!("internal error (caught panic: {panic})"),
        ))
    });
    match outcome {
        Ok(()) => {
            set_last_error("");
            WoStatus::WoOk
        }
        Err(f) => {
            set_last_error(&format!("{name}: {}", f.message));
            f.status
        }
    }
}
