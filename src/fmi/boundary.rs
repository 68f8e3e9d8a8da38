//! What every exported FMI function shares: the frame of a call on an instance (behind
//! the crate's panic boundary, [`crate::boundary::guard`]), the importer's logger, and the
//! conversion of C arguments.

use super::instance::{Instance, Logger, Rejected, Status};
use super::types::*;
use crate::boundary::guard;
use std::ffi::{CStr, CString};

pub fn status_code(s: Status) -> fmi2Status {
    s as fmi2Status
}

/// Frame a call on an instance: null check, panic boundary, state machine, logging.
///
/// # Safety
/// `c` is null or a pointer returned by `fmi2Instantiate` and not yet freed.
pub unsafe fn with_instance(
    c: fmi2Component,
    call: super::instance::Call,
    describe: impl FnOnce() -> String,
    body: impl FnOnce(&mut Instance) -> Result<Status, Rejected>,
) -> fmi2Status {
    let Some(inst) = (unsafe { (c as *mut Instance).as_mut() }) else {
        return status_code(Status::Error);
    };
    let ptr: *mut Instance = inst;
    match guard(|| inst.call(call, describe, body)) {
        Ok(Ok(s)) => status_code(s),
        Ok(Err(s)) => status_code(s),
        Err(panic) => {
            // The closure's borrow ended with the unwind; the instance is still allocated.
            let inst = unsafe { &mut *ptr };
            inst.fail(&format!("{}: internal error (caught panic: {panic})", call.fmi_name()));
            status_code(Status::Error)
        }
    }
}

/// Logger that forwards to the importer's `fmi2CallbackLogger`.
pub struct CallbackLogger {
    pub logger: fmi2CallbackLogger,
    pub env: fmi2ComponentEnvironment,
    pub name: CString,
}

fn c_text(s: &str) -> CString {
    CString::new(s.replace('\0', "\\0")).unwrap_or_default()
}

impl Logger for CallbackLogger {
    fn log(&self, status: Status, category: &str, message: &str) {
        if let Some(f) = self.logger {
            let (cat, msg) = (c_text(category), c_text(message));
            // SAFETY: the importer promised a valid logger; the message goes through "%s".
            unsafe { f(self.env, self.name.as_ptr(), status_code(status), cat.as_ptr(), c"%s".as_ptr(), msg.as_ptr()) };
        }
    }
}

impl CallbackLogger {
    pub fn log_once(logger: fmi2CallbackLogger, env: fmi2ComponentEnvironment, name: &str, message: &str) {
        CallbackLogger { logger, env, name: c_text(name) }.log(Status::Error, "logStatusError", message);
    }
}

/// A C string argument as text (`None` for null).
///
/// # Safety
/// `s` is null or a NUL-terminated string.
pub unsafe fn text(s: fmi2String) -> Option<String> {
    (!s.is_null()).then(|| unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned())
}

/// A C array argument as a slice; `Err` when it is null but `n > 0`.
///
/// # Safety
/// `p` is null or points to `n` valid elements.
pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], Rejected> {
    match (p.is_null(), n) {
        (_, 0) => Ok(&[]),
        (true, _) => Err(format!("{what} is NULL but {n} elements were announced")),
        (false, _) => Ok(unsafe { std::slice::from_raw_parts(p, n) }),
    }
}

/// Mutable counterpart of [`slice`].
///
/// # Safety
/// `p` is null or points to `n` valid elements not aliased elsewhere.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Result<&'a mut [T], Rejected> {
    match (p.is_null(), n) {
        (_, 0) => Ok(&mut []),
        (true, _) => Err(format!("{what} is NULL but {n} elements were announced")),
        (false, _) => Ok(unsafe { std::slice::from_raw_parts_mut(p, n) }),
    }
}
