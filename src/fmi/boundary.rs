//! The panic boundary and the importer's logger: what every exported function shares.

use super::instance::{Instance, Logger, Rejected, Status};
use super::types::*;
use std::cell::Cell;
use std::ffi::{CStr, CString};
use std::panic::{AssertUnwindSafe, PanicHookInfo, catch_unwind};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Once, OnceLock};

thread_local! {
    /// While this thread runs inside [`guard`]: the message slot on `guard`'s stack, where
    /// the panic hook records the message instead of printing it; null outside.
    ///
    /// A raw pointer, not an owned `String`, so that this thread-local has no destructor:
    /// glibc cannot unload (dlclose) a library that registered thread-local destructors,
    /// and a master that loads and unloads the FMU would then keep it mapped for good.
    static INSIDE: Cell<*mut String> = const { Cell::new(std::ptr::null_mut()) };
}

/// The hook that was installed before ours, called for panics outside exported functions.
/// Kept in a static (not captured by our hook) so that our hook is a zero-sized closure:
/// installing it allocates nothing that a leak checker would report at exit.
static PREVIOUS_HOOK: OnceLock<PanicHook> = OnceLock::new();

type PanicHook = Box<dyn Fn(&PanicHookInfo<'_>) + Sync + Send + 'static>;

/// Panics caught by [`guard`] since the library was loaded (for tests and fuzzing: no
/// input should ever reach one).
static CAUGHT_PANICS: AtomicU64 = AtomicU64::new(0);

fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        if PREVIOUS_HOOK.set(std::panic::take_hook()).is_err() {
            return; // unreachable: only this Once sets it
        }
        std::panic::set_hook(Box::new(|info| {
            let slot = INSIDE.with(Cell::get);
            if !slot.is_null() {
                // SAFETY: non-null only while `guard` (below us on this thread's stack)
                // runs its closure, during which nothing else touches its message.
                unsafe { *slot = info.to_string() };
            } else if let Some(previous) = PREVIOUS_HOOK.get() {
                previous(info);
            }
        }));
    });
}

/// Run `f`, turning a panic into `Err(message)`: no unwinding crosses the C boundary.
pub fn guard<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    install_panic_hook();
    let mut message = String::new();
    let outer = INSIDE.with(|slot| slot.replace(&mut message));
    let result = catch_unwind(AssertUnwindSafe(f));
    INSIDE.with(|slot| slot.set(outer));
    if result.is_err() {
        CAUGHT_PANICS.fetch_add(1, Ordering::Relaxed);
    }
    result.map_err(|_| message)
}

/// Number of panics [`guard`] has caught in this process.
pub fn caught_panics() -> u64 {
    CAUGHT_PANICS.load(Ordering::Relaxed)
}

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
