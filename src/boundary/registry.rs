//! Handle tables: what a pointer given to C (`fmi2Component`, `wo_solver *`, ...) stands for.
//!
//! The pointers handed out are never addresses: they are numbers from one process-wide
//! counter ([`fresh_handle`]: `1, 2, 3, ...`, shared by every kind of handle, never reused)
//! looked up in a table. So a NULL, forged, stale or already freed handle, or a handle of
//! another kind (a solver passed as an instance, one instance's FMU state passed to
//! another), is found out and refused; nothing is ever read through it.
//!
//! Each table is a lock-guarded map from handle to a shared object (`Arc`): the table lock
//! is held only for the lookup (a read lock, so lookups from many threads run in
//! parallel), then the object itself is used. Removing a handle while another thread is
//! inside a call on its object is safe: that call holds its own `Arc`, and the object is
//! dropped when the last call using it returns. When a table becomes empty its storage is
//! released, so a program that frees everything leaves no allocation behind.

use std::collections::BTreeMap;
use std::fmt;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, RwLock, RwLockReadGuard, RwLockWriteGuard};

static NEXT_HANDLE: AtomicU64 = AtomicU64::new(1);

/// A handle never given out before in this process (never 0). The counter would take
/// 584 years at 10^9 handles a second to wrap.
pub fn fresh_handle() -> u64 {
    NEXT_HANDLE.fetch_add(1, Ordering::Relaxed)
}

/// A handle that is not in a table: never created, already removed, or of another kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unknown {
    pub kind: &'static str,
    pub handle: u64,
}

impl fmt::Display for Unknown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {:#x} is unknown (never created by this library, or already freed)", self.kind, self.handle)
    }
}

/// A table of objects of one kind, by handle.
pub struct Table<T> {
    /// The kind, for messages ("solver", "state", "instance").
    kind: &'static str,
    map: RwLock<BTreeMap<u64, Arc<T>>>,
}

impl<T> Table<T> {
    pub const fn new(kind: &'static str) -> Self {
        Self { kind, map: RwLock::new(BTreeMap::new()) }
    }

    /// The map, also after a panic elsewhere poisoned the lock: no operation below can
    /// leave it half-updated (insert and remove are single map operations).
    fn read(&self) -> RwLockReadGuard<'_, BTreeMap<u64, Arc<T>>> {
        self.map.read().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    fn write(&self) -> RwLockWriteGuard<'_, BTreeMap<u64, Arc<T>>> {
        self.map.write().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Store `value` under a fresh handle.
    pub fn insert(&self, value: T) -> u64 {
        let handle = fresh_handle();
        self.write().insert(handle, Arc::new(value));
        handle
    }

    fn unknown(&self, handle: u64) -> Unknown {
        Unknown { kind: self.kind, handle }
    }

    pub fn get(&self, handle: u64) -> Result<Arc<T>, Unknown> {
        self.read().get(&handle).cloned().ok_or_else(|| self.unknown(handle))
    }

    /// Remove `handle` from the table; the object is dropped once no call uses it any more.
    pub fn remove(&self, handle: u64) -> Result<Arc<T>, Unknown> {
        let mut map = self.write();
        let value = map.remove(&handle).ok_or_else(|| self.unknown(handle))?;
        if map.is_empty() {
            *map = BTreeMap::new();
        }
        Ok(value)
    }

    /// Number of live objects (for tests: a program that freed everything leaves 0).
    pub fn len(&self) -> usize {
        self.read().len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
