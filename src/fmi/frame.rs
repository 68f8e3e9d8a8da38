//! The frame of every exported FMI function: the table of live instances, what a call
//! on one goes through, the importer's logger, and the conversion of C arguments.
//!
//! An `fmi2Component` is a handle, never an address: a number from the crate's handle
//! counter, looked up in [`INSTANCES`] ([`crate::boundary::registry`]). A call
//!
//! 1. looks the handle up: NULL, made-up, freed or other kinds of handles are not there,
//!    and the call returns `fmi2Error` (there is no logger to tell; nothing is read
//!    through the pointer);
//! 2. takes the instance's lock with `try_lock`: FMI allows one call at a time on an
//!    instance, so a second, concurrent call (another thread, or a call from inside the
//!    logger callback) is refused with `fmi2Error` and logged through the logger that the
//!    table keeps next to the lock;
//! 3. runs behind the panic boundary ([`crate::boundary::guard`]) through
//!    [`Instance::call`] (state machine, logging).
//!
//! `fmi2FreeInstance` removes the handle; a call in progress on another thread holds its
//! own reference (`Arc`) to the entry, so the instance is dropped when that call returns,
//! never under it. A second `fmi2FreeInstance` of the same handle finds nothing and is
//! ignored.

use crate::boundary::guard;
use crate::boundary::pointers::{self, BadArray};
use crate::boundary::registry::Table;
use crate::fmi::common::instance::{Call, Dialect, Instance, Logger, Rejected, Status};
use crate::fmi::fmi2::types::*;
use std::ffi::CString;
use std::sync::{Arc, Mutex, TryLockError};

/// A live instance as the table holds it: the logger next to the lock, so that a call
/// refused because the instance is busy can still be logged.
pub struct Entry {
    logger: Arc<dyn Logger>,
    /// The instance's FMI version, to name a refused call as its importer knows it.
    dialect: Dialect,
    instance: Mutex<Instance>,
}

/// The live instances of the process, by handle.
static INSTANCES: Table<Entry> = Table::new("instance");

/// Why a concurrent call is refused (FMI 2.0, section 2.1.5: an instance is not
/// thread-safe; the master calls it from one thread at a time).
pub const BUSY: &str =
    "another call on this instance is in progress (FMI forbids concurrent calls on one instance)";

pub fn status_code(s: Status) -> fmi2Status {
    s as fmi2Status
}

fn handle_of(c: fmi2Component) -> u64 {
    c as usize as u64
}

/// Put `instance` in the table of live instances; the handle is what the master holds.
/// (`fmi2Instantiate` does this; tests use it to give an instance a Rust logger.)
pub fn register(instance: Instance) -> fmi2Component {
    let (logger, dialect) = (instance.logger(), instance.dialect());
    INSTANCES.insert(Entry { logger, dialect, instance: Mutex::new(instance) }) as usize
        as fmi2Component
}

/// `fmi2FreeInstance`: forget the handle. An unknown handle (a second free, or one never
/// ours) is ignored: FMI gives this function no status to report it with.
pub fn unregister(c: fmi2Component) {
    if INSTANCES.remove(handle_of(c)).is_err() {}
}

/// Number of live instances (for tests: 0 once everything is freed).
pub fn live_instances() -> usize {
    INSTANCES.len()
}

/// Frame a call on the instance `c`: look it up, lock it, run `body` through
/// [`Instance::call`] behind the panic boundary. Never reads through `c`.
pub fn with_instance(
    c: fmi2Component,
    call: Call,
    describe: impl FnOnce() -> String,
    body: impl FnOnce(&mut Instance) -> Result<Status, Rejected>,
) -> fmi2Status {
    let framed = guard(|| {
        let Ok(entry) = INSTANCES.get(handle_of(c)) else { return Status::Error };
        let mut inst = match entry.instance.try_lock() {
            Ok(inst) => inst,
            Err(TryLockError::WouldBlock) => {
                entry.logger.log(
                    Status::Error,
                    "logStatusError",
                    &format!("{}: {BUSY}", (entry.dialect.name)(call)),
                );
                return Status::Error;
            }
            // A panic escaped an earlier call while it held the lock (only a panicking
            // logger can do that: calls run behind their own guard): its data may be
            // half-updated, as after any internal error.
            Err(TryLockError::Poisoned(poisoned)) => {
                entry.instance.clear_poison();
                let mut inst = poisoned.into_inner();
                inst.fail(&format!(
                    "{}: an earlier call on this instance was interrupted by an internal error",
                    (entry.dialect.name)(call)
                ));
                inst
            }
        };
        match guard(|| inst.call(call, describe, body)) {
            Ok(Ok((s, warning))) => s.max(warning),
            Ok(Err(s)) => s,
            Err(panic) => {
                inst.fail(&format!(
                    "{}: internal error (caught panic: {panic})",
                    (entry.dialect.name)(call)
                ));
                Status::Error
            }
        }
    });
    status_code(framed.unwrap_or(Status::Error))
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

// SAFETY: the fields are the importer's logger (a C function), its environment pointer,
// which is only passed back to it, and an owned string. FMI 2.0 lets an instance be called
// from any thread (one call at a time), and the FMU calls the logger on the calling thread.
// Two threads log at once only if the master calls one instance concurrently (forbidden
// by FMI; the refusal is logged) or calls instances that share an environment.
unsafe impl Send for CallbackLogger {}
unsafe impl Sync for CallbackLogger {}

impl Logger for CallbackLogger {
    fn log(&self, status: Status, category: &str, message: &str) {
        if let Some(f) = self.logger {
            let (cat, msg) = (c_text(category), c_text(message));
            // SAFETY: the importer promised a valid logger; the message goes through "%s".
            unsafe {
                f(
                    self.env,
                    self.name.as_ptr(),
                    status_code(status),
                    cat.as_ptr(),
                    c"%s".as_ptr(),
                    msg.as_ptr(),
                )
            };
        }
    }
}

impl CallbackLogger {
    pub fn log_once(
        logger: fmi2CallbackLogger,
        env: fmi2ComponentEnvironment,
        name: &str,
        message: &str,
    ) {
        CallbackLogger { logger, env, name: c_text(name) }.log(
            Status::Error,
            "logStatusError",
            message,
        );
    }
}

/// A C string argument as text (`None` for null).
///
/// # Safety
/// `s` is null or a NUL-terminated string.
pub unsafe fn text(s: fmi2String) -> Option<String> {
    unsafe { pointers::text(s) }
}

/// A C array argument as a slice; `Err` when it is null but `n > 0`.
///
/// # Safety
/// `p` is null or points to `n` valid elements.
pub unsafe fn slice<'a, T>(p: *const T, n: usize, what: &str) -> Result<&'a [T], Rejected> {
    unsafe { pointers::slice(p, n) }.map_err(|e| null_array(what, e))
}

/// Mutable counterpart of [`slice`].
///
/// # Safety
/// `p` is null or points to `n` valid elements not aliased elsewhere.
pub unsafe fn slice_mut<'a, T>(p: *mut T, n: usize, what: &str) -> Result<&'a mut [T], Rejected> {
    unsafe { pointers::slice_mut(p, n) }.map_err(|e| null_array(what, e))
}

fn null_array(what: &str, e: BadArray) -> Rejected {
    e.reason(what)
}
