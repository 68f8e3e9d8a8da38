//! Fuzzing `fmi2DeSerializeFMUstate` with bytes: genuine serialized states of an instance
//! (and of an instance with other parameters), random bytes, and those states truncated,
//! bit-flipped, overwritten, lengthened or mutated in any field and then re-sealed with a
//! valid CRC-32 so that the decoder's field checks are reached. Time-bounded: see
//! tests/common/fuzz.rs.
//!
//! What must hold: bytes without a valid checksum are never accepted; an accepted state can
//! be restored, stepped from and read; no call reaches the panic boundary.

mod common;

use common::fuzz::{Budget, MESH_FIELDS, NULL_CALLBACKS, Rng, mutated, reseal_crc};
use std::collections::BTreeMap;
use std::ffi::CString;
use wound_opening::boundary::caught_panics;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::GUID;

/// Restore `h` into `c`, step from its time, read the outputs; the statuses, by call.
fn use_state(
    rng: &mut Rng,
    c: fmi2Component,
    h: fmi2FMUstate,
    stats: &mut BTreeMap<&'static str, [u64; 5]>,
) {
    let mut record = |call: &'static str, s: fmi2Status| {
        assert!((0..=4).contains(&s), "{call} returned {s}");
        stats.entry(call).or_default()[s as usize] += 1;
    };
    let mut now = 0.0;
    let mut out = [0.0; 2];
    unsafe {
        record("fmi2SetFMUstate", fmi2SetFMUstate(c, h));
        record("fmi2GetRealStatus", fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut now));
        record("fmi2DoStep", fmi2DoStep(c, now, rng.pick(&[1e-3, 0.1, 10.0]), 0));
        record("fmi2GetReal", fmi2GetReal(c, [4u32, 5].as_ptr(), 2, out.as_mut_ptr()));
    }
}

/// An initialized instance (lambda, sigma = 1, R_inf = 10) and serialized states of it at
/// several points: before initialization, at t = 0, mid-run, with a stop time, terminated.
fn instance_with_states(lambda: f64) -> (fmi2Component, Vec<Vec<u8>>) {
    let name = c"deserialize";
    let guid = CString::new(GUID).unwrap();
    let c = unsafe {
        fmi2Instantiate(name.as_ptr(), 1, guid.as_ptr(), c"".as_ptr(), &NULL_CALLBACKS, 0, 0)
    };
    assert!(!c.is_null());
    let mut blobs = Vec::new();
    let mut save = |c: fmi2Component| {
        let mut st = std::ptr::null_mut();
        let mut size = 0;
        unsafe {
            assert_eq!(fmi2GetFMUstate(c, &mut st), 0);
            assert_eq!(fmi2SerializedFMUstateSize(c, st, &mut size), 0);
            let mut b = vec![0u8; size];
            assert_eq!(fmi2SerializeFMUstate(c, st, b.as_mut_ptr() as *mut fmi2Byte, size), 0);
            assert_eq!(fmi2FreeFMUstate(c, &mut st), 0);
            blobs.push(b);
        }
    };
    unsafe {
        assert_eq!(fmi2SetReal(c, &0, 1, &lambda), 0);
        save(c);
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 1, 50.0), 0);
        assert_eq!(fmi2EnterInitializationMode(c), 0);
        assert_eq!(fmi2ExitInitializationMode(c), 0);
        save(c);
        assert_eq!(fmi2SetReal(c, &3, 1, &0.3), 0);
        assert_eq!(fmi2DoStep(c, 0.0, 1.5, 0), 0);
        save(c);
        assert_eq!(fmi2Terminate(c), 0);
        save(c);
        assert_eq!(fmi2Reset(c), 0);
        assert_eq!(fmi2SetReal(c, &0, 1, &lambda), 0);
        assert_eq!(fmi2EnterInitializationMode(c), 0);
        assert_eq!(fmi2ExitInitializationMode(c), 0);
    }
    (c, blobs)
}

#[test]
fn corrupted_serialized_states_are_refused_and_resealed_ones_are_refused_or_usable() {
    let budget = Budget::from_env(0xDE5E_2024);
    let mut rng = Rng::new(budget.seed);
    let mut stats = BTreeMap::new();
    let (c, mut blobs) = instance_with_states(1.0);
    let (other, foreign) = instance_with_states(0.0);
    blobs.extend(foreign);
    // kind -> (tried, accepted): plain corruptions must never be accepted.
    let mut outcome: BTreeMap<&str, (u64, u64)> = BTreeMap::new();
    let mut iterations = 0u64;
    while budget.left() {
        iterations += 1;
        let (bytes, resealed) = mutated(&mut rng, &blobs);
        let genuine = blobs.contains(&bytes);
        let kind = match (genuine, resealed) {
            (true, _) => "genuine (own or of lambda = 0)",
            (false, true) => "mutated, valid checksum",
            (false, false) => "corrupted or random",
        };
        let mut h = std::ptr::null_mut();
        let s = unsafe {
            fmi2DeSerializeFMUstate(c, bytes.as_ptr() as *const fmi2Byte, bytes.len(), &mut h)
        };
        assert!(s == 0 || s == 3, "fmi2DeSerializeFMUstate returned {s}");
        let entry = outcome.entry(kind).or_default();
        entry.0 += 1;
        if s == 0 {
            entry.1 += 1;
            assert!(
                genuine || resealed,
                "seed {}: iteration {iterations} accepted corrupted bytes {bytes:?}",
                budget.seed
            );
            // An accepted state must be usable: restore it, step from it, read outputs.
            use_state(&mut rng, c, h, &mut stats);
            assert_eq!(unsafe { fmi2FreeFMUstate(c, &mut h) }, 0);
        }
        assert_eq!(
            caught_panics(),
            0,
            "seed {}: iteration {iterations} reached the panic boundary",
            budget.seed
        );
    }
    unsafe {
        fmi2FreeInstance(c);
        fmi2FreeInstance(other);
    }
    println!("deserialization: seed {}, {iterations} inputs", budget.seed);
    for (kind, (tried, accepted)) in &outcome {
        println!("  {kind:32} tried {tried:7}  accepted {accepted:7}");
    }
    for (call, counts) in &stats {
        println!("  then {call:26} ok {:7}  error {:7}", counts[0], counts[3]);
    }
}

/// Found by this harness and fixed in src/fmi (now src/models/wound/fmu_state.rs): the mesh stored in a serialized
/// state was not checked, so bytes re-sealed with another mesh were accepted (and, by an
/// instance without a solver, first built: 1 x 2000 took 12 s).
#[test]
fn a_serialized_state_with_a_forged_mesh_is_refused() {
    let (c, blobs) = instance_with_states(1.0);
    let deserialize = |bytes: &[u8]| {
        let mut h = std::ptr::null_mut();
        unsafe {
            fmi2DeSerializeFMUstate(c, bytes.as_ptr() as *const fmi2Byte, bytes.len(), &mut h)
        }
    };
    assert_eq!(deserialize(&blobs[1]), 0, "control: the genuine state is accepted");
    let mut forged = blobs[1].clone();
    forged[MESH_FIELDS.start..MESH_FIELDS.start + 4].copy_from_slice(&1u32.to_le_bytes());
    forged[MESH_FIELDS.start + 4..MESH_FIELDS.end].copy_from_slice(&40u32.to_le_bytes());
    reseal_crc(&mut forged);
    let s = deserialize(&forged);
    unsafe { fmi2FreeInstance(c) };
    assert_eq!(s, 3, "a state of mesh 1 x 40 was accepted by an instance of another mesh");
}
