//! The exported FMI 3.0 get and set functions of the variable types this FMU has:
//! `fmi3{Get,Set}Float64` (scalars, `time` and whole arrays), `fmi3{Get,Set}UInt64` (the
//! structural parameter) and `fmi3{Get,Set}Int32`. Thin shims over the safe
//! [`crate::fmi::common::instance::Instance`], framed by [`with_instance`]; the other
//! variable types are refused in [`crate::fmi::fmi3::unsupported`].
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::common::instance::{Call, Status};
use crate::fmi::fmi3::types::*;
use crate::fmi::frame::{slice, slice_mut, with_instance};

const OK: Result<Status, String> = Ok(Status::Ok);

/// FMI 3.0 passes `nValues` beside the value references; for scalar variables they agree.
fn scalars(nvr: usize, n_values: usize) -> Result<(), String> {
    if nvr == n_values {
        Ok(())
    } else {
        Err(format!("nValues = {n_values} but {nvr} scalar variables were named"))
    }
}

/// Scalars, `time` and whole arrays (one value reference each, values concatenated).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetFloat64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::Get,
            || format!("fmi3GetFloat64(nValueReferences={nValueReferences}, nValues={nValues})"),
            |i| {
                let vr = slice(valueReferences, nValueReferences, "valueReferences")?;
                let got = i.get_float64(vr, nValues)?;
                slice_mut(values, nValues, "values")?.copy_from_slice(&got);
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetFloat64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Float64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::Set,
            || format!("fmi3SetFloat64(nValueReferences={nValueReferences}, nValues={nValues})"),
            |i| {
                let vr = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.set_float64(vr, slice(values, nValues, "values")?).map(|_| Status::Ok)
            },
        )
    }
}

/// The structural parameter (the number of probes).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetUInt64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3UInt64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::Get,
            || format!("fmi3GetUInt64(nValueReferences={nValueReferences}, nValues={nValues})"),
            |i| {
                scalars(nValueReferences, nValues)?;
                let got =
                    i.get_uint64(slice(valueReferences, nValueReferences, "valueReferences")?)?;
                slice_mut(values, nValues, "values")?.copy_from_slice(&got);
                OK
            },
        )
    }
}

/// In Configuration Mode only.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetUInt64(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3UInt64,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::Set,
            || format!("fmi3SetUInt64(nValueReferences={nValueReferences}, nValues={nValues})"),
            |i| {
                scalars(nValueReferences, nValues)?;
                let vr = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.set_uint64(vr, slice(values, nValues, "values")?).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetInt32(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::Get,
            || format!("fmi3GetInt32(nValueReferences={nValueReferences}, nValues={nValues})"),
            |i| {
                scalars(nValueReferences, nValues)?;
                let vr = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.get_integer(vr, slice_mut(values, nValues, "values")?).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetInt32(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Int32,
    nValues: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::Set,
            || format!("fmi3SetInt32(nValueReferences={nValueReferences}, nValues={nValues})"),
            |i| {
                scalars(nValueReferences, nValues)?;
                let vr = slice(valueReferences, nValueReferences, "valueReferences")?;
                i.set_integer(vr, slice(values, nValues, "values")?).map(|_| Status::Ok)
            },
        )
    }
}
