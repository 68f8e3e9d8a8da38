//! A bounded, thread-safe, process-wide cache of modal bases ([`Basis`]), keyed by mesh
//! settings and outer radius.
//!
//! The basis does not depend on lambda (see [`super::modal`]), so a new instance, a reset
//! or a new lambda at an outer radius already seen costs `O(modes)` instead of a
//! decomposition (`O(n^3)`, milliseconds). A hit returns the very basis a fresh build
//! gives: the build is deterministic (assembly, Cholesky and the Jacobi sweeps run in a
//! fixed order), and the key holds the exact bits of every input.
//!
//! At most [`CAPACITY`] bases are kept (least recently used first out); the largest, at
//! `R_inf = 1e6` and the finest tolerance, holds ~220 modes (~0.4 MB). The lock is held
//! only to look up and insert, never while building, so threads building different bases
//! do not wait for each other (two threads that miss on the same key both build it, and
//! get equal bases).

use super::mesh::{Mesh, MeshSpec};
use super::modal::{Basis, ModalError};
use std::sync::{Arc, Mutex};

/// Bases kept at most.
pub const CAPACITY: usize = 64;

/// The exact bits of everything a basis depends on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Key {
    degree: usize,
    elements: usize,
    edge_scale: u64,
    r_inf: u64,
}

impl Key {
    fn new(spec: MeshSpec, r_inf: f64) -> Self {
        Self {
            degree: spec.degree,
            elements: spec.elements,
            edge_scale: spec.edge_scale.to_bits(),
            r_inf: r_inf.to_bits(),
        }
    }
}

/// Entries, most recently used last.
static CACHE: Mutex<Vec<(Key, Arc<Basis>)>> = Mutex::new(Vec::new());

fn entries() -> std::sync::MutexGuard<'static, Vec<(Key, Arc<Basis>)>> {
    // No operation below can leave the list half-updated, so a poisoned lock is usable.
    CACHE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The basis of `spec` on `[1, r_inf]`, from the cache or built (and then cached).
pub(crate) fn basis(spec: MeshSpec, r_inf: f64) -> Result<Arc<Basis>, ModalError> {
    let key = Key::new(spec, r_inf);
    {
        let mut list = entries();
        if let Some(i) = list.iter().position(|(k, _)| *k == key) {
            let hit = list.remove(i);
            let basis = hit.1.clone();
            list.push(hit);
            return Ok(basis);
        }
    }
    let built = Arc::new(Basis::new(Mesh::new(spec, r_inf))?);
    let mut list = entries();
    if let Some((_, other)) = list.iter().find(|(k, _)| *k == key) {
        return Ok(other.clone());
    }
    if list.len() >= CAPACITY {
        list.remove(0);
    }
    list.push((key, built.clone()));
    Ok(built)
}

/// A basis built without the cache (for tests: a hit must equal it bit for bit).
pub fn fresh_basis_equals_cached(spec: MeshSpec, r_inf: f64) -> bool {
    match (Basis::new(Mesh::new(spec, r_inf)), basis(spec, r_inf)) {
        (Ok(fresh), Ok(cached)) => fresh == *cached,
        _ => false,
    }
}

/// Empty the cache (bases in use stay alive with their solvers). Called when the library
/// is unloaded ([`crate::boundary`]).
pub fn clear() {
    *entries() = Vec::new();
}

/// Number of cached bases.
pub fn cached() -> usize {
    entries().len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hit_is_the_same_basis_and_the_cache_stays_bounded() {
        let spec = MeshSpec { degree: 3, elements: 2, edge_scale: 0.1 };
        let a = basis(spec, 3.0).unwrap();
        let b = basis(spec, 3.0).unwrap();
        assert!(Arc::ptr_eq(&a, &b));
        assert!(fresh_basis_equals_cached(spec, 3.0));
        for k in 0..CAPACITY + 5 {
            basis(spec, 4.0 + k as f64).unwrap();
        }
        assert!(cached() <= CAPACITY);
    }
}
