//! The reason of a call refused because the instance is busy, as the master's logger
//! receives it: from a second thread, and from inside the logger callback itself. The
//! instances here are put in the table with a Rust logger ([`frame::register`]), since
//! Rust cannot define the variadic C logger that `fmi2Instantiate` takes.

mod common;

use common::fmi::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use wound_opening::fmi::common::instance::{Instance, Logger, Status};
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::fmi::frame::{self, BUSY};
use wound_opening::models::wound::WoundModel;

/// A logger that records every message and, on a `logCalls` message, runs `reenter` on
/// the component (once, or always) from inside the callback.
#[derive(Default)]
#[allow(clippy::type_complexity)]
struct Reentrant {
    log: Mutex<Vec<(Status, String, String)>>,
    component: AtomicUsize,
    reenter: Mutex<Option<fn(fmi2Component) -> fmi2Status>>,
    inside: AtomicBool,
    statuses: Mutex<Vec<fmi2Status>>,
    /// Busy-wait in each logCalls message, to widen the window for another thread.
    linger: AtomicBool,
}

impl Logger for Reentrant {
    fn log(&self, status: Status, category: &str, message: &str) {
        self.log.lock().unwrap().push((status, category.into(), message.into()));
        if category != "logCalls" {
            return;
        }
        if self.linger.load(Ordering::Relaxed) {
            let t0 = std::time::Instant::now();
            while t0.elapsed() < std::time::Duration::from_micros(20) {}
        }
        let reenter = *self.reenter.lock().unwrap();
        if let Some(f) = reenter
            && !self.inside.swap(true, Ordering::SeqCst)
        {
            let c = self.component.load(Ordering::SeqCst) as fmi2Component;
            let s = f(c);
            self.statuses.lock().unwrap().push(s);
            self.inside.store(false, Ordering::SeqCst);
        }
    }
}

impl Reentrant {
    fn busy_refusals(&self) -> Vec<String> {
        let log = self.log.lock().unwrap();
        log.iter()
            .filter(|(s, c, m)| *s == Status::Error && c == "logStatusError" && m.contains(BUSY))
            .map(|(_, _, m)| m.clone())
            .collect()
    }
}

/// A WoundOpening instance in the table with `logger`, logCalls on, initialized at 0.
fn registered(logger: &Arc<Reentrant>) -> fmi2Component {
    let c = frame::register(Instance::new(WoundModel::fresh, "reentry", logger.clone(), true));
    logger.component.store(c as usize, Ordering::SeqCst);
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
    }
    c
}

/// Guards against a call from inside the logger callback re-entering an instance that is
/// in the middle of a call (it aliased the instance being modified): the inner call is
/// refused and the reason logged; the outer call completes.
#[test]
fn a_call_from_inside_the_logger_is_refused_with_the_reason() {
    let logger = Arc::new(Reentrant::default());
    let c = registered(&logger);
    *logger.reenter.lock().unwrap() = Some(|c| unsafe { fmi2DoStep(c, 0.0, 0.5, 0) });
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 0.5, 0) }, OK, "the outer call");
    assert_eq!(*logger.statuses.lock().unwrap(), [ERROR], "the inner call");
    assert_eq!(logger.busy_refusals(), [format!("fmi2DoStep: {BUSY}")]);
    *logger.reenter.lock().unwrap() = None;
    assert_eq!(last_successful_time(c), (OK, 0.5), "one step, not two");
    unsafe { fmi2FreeInstance(c) };
}

/// Guards against freeing an instance from inside its own logger callback (a
/// use-after-free in the call that is logging): the call completes, later ones are refused.
#[test]
fn freeing_the_instance_from_inside_its_logger_is_safe() {
    let logger = Arc::new(Reentrant::default());
    let c = registered(&logger);
    *logger.reenter.lock().unwrap() = Some(|c| {
        unsafe { fmi2FreeInstance(c) };
        OK
    });
    let live = frame::live_instances();
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 0.5, 0) }, OK, "the call in progress completes");
    assert!(frame::live_instances() < live, "freed");
    *logger.reenter.lock().unwrap() = None;
    assert_eq!(last_successful_time(c).0, ERROR);
}

/// Guards against a concurrent call being refused silently: with two threads on one
/// instance, every refused fmi2DoStep logged a reason, either the busy instance or the
/// communication point another thread's step made stale, and at least one was busy.
#[test]
fn a_concurrent_call_is_refused_with_the_reason_logged() {
    let logger = Arc::new(Reentrant::default());
    logger.linger.store(true, Ordering::Relaxed);
    let c = registered(&logger) as usize;
    let refused = AtomicUsize::new(0);
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                let c = c as fmi2Component;
                for _ in 0..2000 {
                    let (st, t) = last_successful_time(c);
                    if st == OK && unsafe { fmi2DoStep(c, t, 1.0 / 1024.0, 0) } == ERROR {
                        refused.fetch_add(1, Ordering::Relaxed);
                    }
                }
            });
        }
    });
    let log = logger.log.lock().unwrap();
    let errors: Vec<&String> =
        log.iter().filter(|(s, _, _)| *s == Status::Error).map(|(_, _, m)| m).collect();
    let steps = errors.iter().filter(|m| m.starts_with("fmi2DoStep: ")).count();
    assert_eq!(steps, refused.load(Ordering::Relaxed), "one logged reason per refused fmi2DoStep");
    assert!(
        errors.iter().all(|m| m.contains(BUSY) || m.contains("Expected currentCommunicationPoint")),
        "{errors:?}"
    );
    assert!(
        errors.iter().any(|m| m.contains(BUSY)),
        "some calls met a busy instance: {} errors",
        errors.len()
    );
    drop(log);
    unsafe { fmi2FreeInstance(c as fmi2Component) };
}
