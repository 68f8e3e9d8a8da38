//! Logging of an instance: the FMI status, the importer's logger behind a trait, and the
//! log categories of `modelDescription.xml` ([`LOG_CATEGORIES`]) with the ones switched on.

use crate::fmi::common::model::{LOG_CATEGORIES, Rejected};
use std::sync::Arc;

/// `fmi2Status`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    Ok = 0,
    Warning = 1,
    Discard = 2,
    Error = 3,
    Fatal = 4,
}

/// Where log messages go (the importer's callback, or a test's collector). Shared by the
/// instance and the table of live instances (which logs a call refused because another
/// holds the instance), and so usable from any thread.
pub trait Logger: Send + Sync {
    fn log(&self, status: Status, category: &str, message: &str);
}

const ERROR: usize = 0;
const WARNING: usize = 1;
const DISCARD: usize = 2;
const CALLS: usize = 3;

/// An instance's logger and its categories switched on (`logStatusError` always).
pub struct Log {
    logger: Arc<dyn Logger>,
    on: [bool; LOG_CATEGORIES.len()],
}

impl Log {
    /// Errors, warnings and discards on; `logCalls` as `fmi2Instantiate`'s `loggingOn` says.
    pub fn new(logger: Arc<dyn Logger>, logging_on: bool) -> Self {
        Self { logger, on: std::array::from_fn(|i| i != CALLS || logging_on) }
    }

    pub fn logger(&self) -> Arc<dyn Logger> {
        Arc::clone(&self.logger)
    }

    /// Log under `logStatusError` (always on).
    pub fn error(&self, message: &str) {
        self.logger.log(Status::Error, LOG_CATEGORIES[ERROR].0, message);
    }

    /// Log under `logStatusWarning`, if on.
    pub fn warning(&self, message: &str) {
        if self.on[WARNING] {
            self.logger.log(Status::Warning, LOG_CATEGORIES[WARNING].0, message);
        }
    }

    /// Log under `logStatusWarning`, if on, with status OK: what the master should know
    /// about a result that is nonetheless the answer to its call.
    pub fn note(&self, message: &str) {
        if self.on[WARNING] {
            self.logger.log(Status::Ok, LOG_CATEGORIES[WARNING].0, message);
        }
    }

    /// Log under `logStatusDiscard`, if on.
    pub fn discard(&self, message: &str) {
        if self.on[DISCARD] {
            self.logger.log(Status::Discard, LOG_CATEGORIES[DISCARD].0, message);
        }
    }

    pub fn calls_on(&self) -> bool {
        self.on[CALLS]
    }

    /// Log under `logCalls`, if on.
    pub fn call(&self, message: &str) {
        if self.calls_on() {
            self.logger.log(Status::Ok, LOG_CATEGORIES[CALLS].0, message);
        }
    }

    /// `fmi2SetDebugLogging`: switch the listed categories (all when empty); an unknown
    /// name switches none.
    pub fn switch(&mut self, on: bool, names: &[String]) -> Result<(), Rejected> {
        let mut idx = Vec::with_capacity(names.len());
        for n in names {
            let i = LOG_CATEGORIES.iter().position(|(c, _)| c == n);
            idx.push(i.ok_or_else(|| {
                format!("unknown log category \"{n}\"; declared: {}", category_list())
            })?);
        }
        if idx.is_empty() {
            idx = (0..LOG_CATEGORIES.len()).collect();
        }
        idx.into_iter().for_each(|i| self.on[i] = on);
        self.on[ERROR] = true;
        Ok(())
    }
}

fn category_list() -> String {
    LOG_CATEGORIES.iter().map(|(c, _)| *c).collect::<Vec<_>>().join(", ")
}
