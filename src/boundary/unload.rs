//! Release the library's process-wide caches when it is unloaded (`dlclose`) or the process
//! exits.
//!
//! Rust never drops statics. The modal-basis cache ([`crate::solver::basis`]) holds up to
//! 64 decompositions; a master that loads the FMU, runs and unloads it (fmpy's
//! `simulate_fmu` does, once per simulation) would lose them as unreachable memory with
//! every unload. A function in the ELF `.fini_array` runs at `dlclose` and at exit, after
//! the last call into the library has returned, and empties the cache; an instance or
//! solver still alive keeps its own reference to its basis.

#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".fini_array")]
static RELEASE_ON_UNLOAD: extern "C" fn() = release;

#[cfg(target_os = "linux")]
extern "C" fn release() {
    // Nothing may unwind out of a destructor called by the C runtime.
    let _ = std::panic::catch_unwind(crate::solver::basis::clear);
}
