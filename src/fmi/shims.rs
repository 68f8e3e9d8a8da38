//! The bodies of the exported functions whose C signatures FMI 2.0 and 3.0 share (an
//! instance handle, FMU-state pointers, reals and counts): the FMU states and the Model
//! Exchange vectors. Each version's shim calls one of these with its own function name,
//! which the call log shows; the instance names the call in refusals in its own version's
//! words ([`Instance::name_of`]). A NULL pointer is refused under the name of the argument
//! as the version's header spells it.
#![allow(clippy::missing_safety_doc)]

use crate::fmi::common::instance::{Call, Instance, Status};
use crate::fmi::frame::{slice, slice_mut, with_instance};
use std::ffi::c_void;

/// What the shims return: an `fmi2Status` / `fmi3Status` (the same numbers).
pub type StatusCode = i32;

const OK: Result<Status, String> = Ok(Status::Ok);

/// A function's name and the name of its FMU-state argument, as a version spells them.
#[derive(Debug, Clone, Copy)]
pub struct Names {
    pub function: &'static str,
    pub state: &'static str,
}

fn handle(state: *mut c_void) -> Option<u64> {
    (!state.is_null()).then_some(state as u64)
}

fn null(what: &str) -> String {
    format!("{what} is NULL")
}

/// `fmi2GetFMUstate` / `fmi3GetFMUState`: save into `*out` if it names one of the
/// instance's states, else into a new one.
pub unsafe fn get_fmu_state(c: *mut c_void, out: *mut *mut c_void, n: Names) -> StatusCode {
    with_instance(
        c,
        Call::GetFmuState,
        || n.function.into(),
        |i| {
            let slot = unsafe { out.as_mut() }.ok_or_else(|| null(n.state))?;
            *slot = i.get_fmu_state(handle(*slot))? as *mut c_void;
            OK
        },
    )
}

pub unsafe fn set_fmu_state(c: *mut c_void, state: *mut c_void, n: Names) -> StatusCode {
    with_instance(
        c,
        Call::SetFmuState,
        || n.function.into(),
        |i| i.set_fmu_state(handle(state).ok_or_else(|| null(n.state))?).map(|_| Status::Ok),
    )
}

/// Frees `*state` and sets it to NULL; freeing a NULL state is a no-op, as for free().
/// `null_slot_ok`: FMI 3.0 also accepts a NULL pointer to the state.
pub unsafe fn free_fmu_state(
    c: *mut c_void,
    state: *mut *mut c_void,
    null_slot_ok: bool,
    n: Names,
) -> StatusCode {
    with_instance(
        c,
        Call::FreeFmuState,
        || n.function.into(),
        |i| {
            let Some(slot) = (unsafe { state.as_mut() }) else {
                return if null_slot_ok { OK } else { Err(null(n.state)) };
            };
            if let Some(h) = handle(*slot) {
                i.free_fmu_state(h)?;
                *slot = std::ptr::null_mut();
            }
            OK
        },
    )
}

pub unsafe fn serialized_fmu_state_size(
    c: *mut c_void,
    state: *mut c_void,
    size: *mut usize,
    n: Names,
) -> StatusCode {
    with_instance(
        c,
        Call::SerializeFmuState,
        || n.function.into(),
        |i| {
            let out = unsafe { size.as_mut() }.ok_or("size is NULL")?;
            *out = i.serialize_fmu_state(handle(state).ok_or_else(|| null(n.state))?)?.len();
            OK
        },
    )
}

pub unsafe fn serialize_fmu_state(
    c: *mut c_void,
    state: *mut c_void,
    bytes_out: *mut u8,
    size: usize,
    n: Names,
) -> StatusCode {
    with_instance(
        c,
        Call::SerializeFmuState,
        || format!("{}(size={size})", n.function),
        |i| {
            let bytes = i.serialize_fmu_state(handle(state).ok_or_else(|| null(n.state))?)?;
            if size < bytes.len() {
                return Err(format!(
                    "buffer of {size} bytes is too small: the state needs {}",
                    bytes.len()
                ));
            }
            unsafe { slice_mut(bytes_out, bytes.len(), "serializedState") }?
                .copy_from_slice(&bytes);
            OK
        },
    )
}

pub unsafe fn deserialize_fmu_state(
    c: *mut c_void,
    bytes: *const u8,
    size: usize,
    out: *mut *mut c_void,
    n: Names,
) -> StatusCode {
    with_instance(
        c,
        Call::DeSerializeFmuState,
        || format!("{}(size={size})", n.function),
        |i| {
            let slot = unsafe { out.as_mut() }.ok_or_else(|| null(n.state))?;
            let bytes = unsafe { slice(bytes, size, "serializedState") }?;
            *slot = i.deserialize_fmu_state(bytes, handle(*slot))? as *mut c_void;
            OK
        },
    )
}

/// A transition without arguments (`fmi2EnterContinuousTimeMode`, ...).
pub fn transition(
    c: *mut c_void,
    call: Call,
    function: &'static str,
    method: fn(&mut Instance) -> Result<(), String>,
) -> StatusCode {
    with_instance(c, call, || function.into(), |i| method(i).map(|_| Status::Ok))
}

pub fn set_time(c: *mut c_void, time: f64, function: &'static str) -> StatusCode {
    with_instance(
        c,
        Call::SetTime,
        || format!("{function}(time={time})"),
        |i| i.set_time(time).map(|_| Status::Ok),
    )
}

pub unsafe fn set_continuous_states(
    c: *mut c_void,
    x: *const f64,
    nx: usize,
    function: &'static str,
) -> StatusCode {
    with_instance(
        c,
        Call::SetContinuousStates,
        || format!("{function}(n={nx})"),
        |i| i.set_continuous_states(unsafe { slice(x, nx, "the states") }?).map(|_| Status::Ok),
    )
}

/// A getter of `n` values into `out` (derivatives, states, nominals).
pub unsafe fn get_vector(
    c: *mut c_void,
    call: Call,
    out: *mut f64,
    n: usize,
    method: fn(&mut Instance, usize) -> Result<Vec<f64>, String>,
    function: &'static str,
) -> StatusCode {
    with_instance(
        c,
        call,
        || format!("{function}(n={n})"),
        |i| {
            let values = method(i, n)?;
            unsafe { slice_mut(out, n, "the output array") }?.copy_from_slice(&values);
            OK
        },
    )
}

pub fn get_event_indicators(c: *mut c_void, ni: usize, function: &'static str) -> StatusCode {
    with_instance(
        c,
        Call::GetEventIndicators,
        || format!("{function}(n={ni})"),
        |i| i.get_event_indicators(ni).map(|_| Status::Ok),
    )
}
