//! FMI 3.0's FMU-state functions: the same bodies as FMI 2.0's (same handles, same checks,
//! [`crate::fmi::shims`]), under FMI 3.0's names; `fmi3FreeFMUState` also accepts a NULL
//! pointer.
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::fmi3::types::*;
use crate::fmi::shims::{self, Names};

fn names(function: &'static str) -> Names {
    Names { function, state: "FMUState" }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetFMUState(
    instance: fmi3Instance,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    unsafe { shims::get_fmu_state(instance, FMUState, names("fmi3GetFMUState")) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetFMUState(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
) -> fmi3Status {
    unsafe { shims::set_fmu_state(instance, FMUState, names("fmi3SetFMUState")) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3FreeFMUState(
    instance: fmi3Instance,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    unsafe { shims::free_fmu_state(instance, FMUState, true, names("fmi3FreeFMUState")) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SerializedFMUStateSize(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    size: *mut usize,
) -> fmi3Status {
    unsafe {
        shims::serialized_fmu_state_size(
            instance,
            FMUState,
            size,
            names("fmi3SerializedFMUStateSize"),
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SerializeFMUState(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    serializedState: *mut fmi3Byte,
    size: usize,
) -> fmi3Status {
    unsafe {
        shims::serialize_fmu_state(
            instance,
            FMUState,
            serializedState,
            size,
            names("fmi3SerializeFMUState"),
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3DeserializeFMUState(
    instance: fmi3Instance,
    serializedState: *const fmi3Byte,
    size: usize,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status {
    unsafe {
        shims::deserialize_fmu_state(
            instance,
            serializedState,
            size,
            FMUState,
            names("fmi3DeserializeFMUState"),
        )
    }
}
