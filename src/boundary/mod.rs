//! What every exported C function of the crate shares, for the FMI functions
//! ([`crate::fmi`]) and the direct C API ([`crate::capi`]) alike: the panic boundary
//! ([`guard`]: no unwinding ever crosses into C), the handle tables ([`registry`]: what
//! C holds are numbers looked up in a table, never addresses) and the conversion of C
//! arguments ([`pointers`]).

pub mod pointers;
pub mod registry;
mod unload;

use std::cell::Cell;
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
