//! Handle tables: what a `wo_solver *` or `wo_state *` given to C stands for.
//!
//! The pointers handed out are never addresses: they are numbers (`1, 2, 3, ...`, one
//! counter for both kinds, never reused) looked up in a table. So a NULL, forged, stale or
//! already freed handle, or a state passed where a solver is expected, is found out and
//! refused with `WO_UNKNOWN_HANDLE`; nothing is ever read through it.
//!
//! Each table is a mutex-guarded map from handle to a shared object: the table lock is held
//! only for the lookup, then the object itself is used (solvers through their own mutex,
//! so two threads calling on one solver are serialised, and different solvers run in
//! parallel). When a table becomes empty its storage is released, so a program that frees
//! everything leaves no allocation behind.

use super::error::{Failure, WoStatus};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

static NEXT_HANDLE: AtomicU64 = AtomicU64::new(1);

/// A table of objects of one kind, by handle.
pub struct Table<T> {
    /// The kind, for messages ("solver", "state").
    kind: &'static str,
    map: Mutex<BTreeMap<u64, Arc<T>>>,
}

impl<T> Table<T> {
    pub const fn new(kind: &'static str) -> Self {
        Self { kind, map: Mutex::new(BTreeMap::new()) }
    }

    /// The map, also after a panic elsewhere poisoned the lock: no operation below can
    /// leave it half-updated (insert and remove are single map operations).
    fn map(&self) -> MutexGuard<'_, BTreeMap<u64, Arc<T>>> {
        self.map.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Store `value` under a fresh handle.
    pub fn insert(&self, value: T) -> u64 {
        let handle = NEXT_HANDLE.fetch_add(1, Ordering::Relaxed);
        self.map().insert(handle, Arc::new(value));
        handle
    }

    fn unknown(&self, handle: u64) -> Failure {
        Failure::new(
            WoStatus::WoUnknownHandle,
            format!("{} {handle:#x} is unknown (never created by this library, or already freed)", self.kind),
        )
    }

    pub fn get(&self, handle: u64) -> Result<Arc<T>, Failure> {
        self.map().get(&handle).cloned().ok_or_else(|| self.unknown(handle))
    }

    /// Remove `handle` from the table; the object is dropped once no call uses it any more.
    pub fn remove(&self, handle: u64) -> Result<Arc<T>, Failure> {
        let mut map = self.map();
        let value = map.remove(&handle).ok_or_else(|| self.unknown(handle))?;
        if map.is_empty() {
            *map = BTreeMap::new();
        }
        Ok(value)
    }

    /// Number of live objects (for tests: a program that freed everything leaves 0).
    pub fn len(&self) -> usize {
        self.map().len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
