//! Handle tables: what a pointer given to C (`fmi2Component`, `wo_solver *`, ...) stands for.
//!
//! The pointers handed out are never addresses: they are numbers ([`fresh_handle`], shared
//! by every kind of handle, never reused) looked up in a table. So a NULL, forged, stale or
//! already freed handle, or a handle of another kind (a solver passed as an instance, one
//! instance's FMU state passed to another), is found out and refused; nothing is ever read
//! through it.
//!
//! Several copies of the library can live in one process (two FMUs built from this crate,
//! each its own `.so`, each with its own tables). Each copy numbers its handles with its own
//! secret: handle = `mix(k XOR n)` for the copy's `n`-th handle, with `k` a 64-bit key drawn
//! from the operating system's random source when the copy makes its first handle and `mix`
//! a bijection of 64-bit words (the SplitMix64 finalizer). Within a copy the handles are
//! distinct (a bijection of distinct counters); a handle of another copy is a 64-bit word
//! unrelated to this copy's key, so it names one of this copy's `m` live objects with
//! probability `m / 2^64` (about 5e-14 for a million live objects): a foreign instance,
//! FMU state or solver is refused as unknown.
//!
//! Each table is a lock-guarded map from handle to a shared object (`Arc`): the table lock
//! is held only for the lookup (a read lock, so lookups from many threads run in
//! parallel), then the object itself is used. Removing a handle while another thread is
//! inside a call on its object is safe: that call holds its own `Arc`, and the object is
//! dropped when the last call using it returns. When a table becomes empty its storage is
//! released, so a program that frees everything leaves no allocation behind.

use std::collections::BTreeMap;
use std::fmt;
use std::hash::{BuildHasher, RandomState};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, OnceLock, RwLock, RwLockReadGuard, RwLockWriteGuard};

static NEXT_HANDLE: AtomicU64 = AtomicU64::new(1);

/// This copy's secret key (see the module documentation), drawn once.
static KEY: OnceLock<u64> = OnceLock::new();

/// 64 random bits from the operating system: the standard library seeds each `RandomState`
/// from it (each copy of the library links its own standard library, so its own seed).
fn random_key() -> u64 {
    RandomState::new().hash_one(0x776f_756e_645f_6f70_u64)
}

/// The SplitMix64 finalizer: a bijection of 64-bit words (each step, `x ^= x >> s` and the
/// multiplication by an odd constant modulo 2^64, is invertible) that scatters consecutive
/// inputs over the whole range.
const fn mix(mut x: u64) -> u64 {
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// A handle never given out before by this copy of the library (never 0), and unknown to
/// any other copy in the process but with probability 2^-64 per live object. The counter
/// would take 584 years at 10^9 handles a second to wrap.
pub fn fresh_handle() -> u64 {
    let key = *KEY.get_or_init(random_key);
    loop {
        let handle = mix(key ^ NEXT_HANDLE.fetch_add(1, Ordering::Relaxed));
        if handle != 0 {
            return handle;
        }
    }
}

/// A handle that is not in a table: never created, already removed, or of another kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unknown {
    pub kind: &'static str,
    pub handle: u64,
}

impl fmt::Display for Unknown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {:#x} is unknown (never created by this library, or already freed)",
            self.kind, self.handle
        )
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
