//! Several threads on ONE instance, which FMI forbids (an instance is used by one call at
//! a time) but a master can do by mistake: each call either runs alone or is refused with
//! `fmi2Error`; nothing is corrupted, and the instance's clock is exactly the sum of the
//! steps it accepted. (Many instances on many threads: tests/capi_threads.rs. The logged
//! reason of a refusal: tests/fmi_reentry.rs.)

mod common;

use common::fmi::*;
use std::sync::{Arc, Barrier};
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::Vr;

const THREADS: usize = 4;
const ROUNDS: usize = 20_000;
/// A step that is exact in binary, so that the sum of accepted steps is exact too.
const H: f64 = 1.0 / 1024.0;

/// An instance handle, movable to other threads (the point of the test is to misuse it).
#[derive(Clone, Copy)]
struct Shared(fmi2Component);
unsafe impl Send for Shared {}

/// What one thread saw: accepted steps, refused calls.
#[derive(Default)]
struct Seen {
    steps: u64,
    refused: u64,
}

/// Each round: read the time, step from it, read the radius. Every status is OK or Error.
fn hammer(c: Shared, start: Arc<Barrier>) -> Seen {
    let mut seen = Seen::default();
    start.wait();
    for _ in 0..ROUNDS {
        let (s, t) = last_successful_time(c.0);
        assert!(s == OK || s == ERROR, "fmi2GetRealStatus returned {s}");
        if s != OK {
            seen.refused += 1;
            continue;
        }
        // Another thread may have stepped since: a stale point is refused like a busy instance.
        match unsafe { fmi2DoStep(c.0, t, H, 0) } {
            OK => seen.steps += 1,
            ERROR => seen.refused += 1,
            s => panic!("fmi2DoStep returned {s}"),
        }
        let (s, r) = get_real(c.0, Vr::WoundRadius as u32);
        assert!(
            s == ERROR || (s == OK && r.is_finite() && r > 1.0),
            "fmi2GetReal returned {s}, {r}"
        );
    }
    seen
}

fn run_threads(c: fmi2Component, extra: impl FnOnce() + Send + 'static) -> Seen {
    let start = Arc::new(Barrier::new(THREADS + 1));
    let workers: Vec<_> = (0..THREADS)
        .map(|_| {
            let (c, start) = (Shared(c), Arc::clone(&start));
            std::thread::spawn(move || hammer(c, start))
        })
        .collect();
    start.wait();
    extra();
    workers.into_iter().map(|w| w.join().expect("a worker panicked")).fold(
        Seen::default(),
        |a, b| Seen { steps: a.steps + b.steps, refused: a.refused + b.refused },
    )
}

/// Guards against a data race on one instance (two `fmi2DoStep` at once corrupted the heap
/// or the clock): the clock equals the sum of the accepted steps, bit for bit.
#[test]
fn concurrent_calls_on_one_instance_run_alone_or_are_refused() {
    let c = initialized(WOUND, 0.0, &[]);
    let seen = run_threads(c, || {});
    assert!(seen.steps > 0, "some steps were accepted");
    let (s, t) = last_successful_time(c);
    assert_eq!(s, OK);
    assert_eq!(
        t,
        seen.steps as f64 * H,
        "{} accepted steps of {H}, {} refused calls",
        seen.steps,
        seen.refused
    );
    // Still a working instance: one more step from where it is.
    assert_eq!(unsafe { fmi2DoStep(c, t, H, 0) }, OK);
    unsafe { fmi2FreeInstance(c) };
}

/// Guards against freeing an instance under a call in progress on another thread (a
/// use-after-free): the calls in flight finish, later ones are refused.
#[test]
fn freeing_an_instance_while_other_threads_call_it() {
    let c = initialized(WOUND, 0.0, &[]);
    let shared = Shared(c);
    run_threads(c, move || {
        std::thread::sleep(std::time::Duration::from_millis(5));
        let c = shared;
        unsafe { fmi2FreeInstance(c.0) };
    });
    assert_eq!(last_successful_time(c).0, ERROR, "freed");
}
