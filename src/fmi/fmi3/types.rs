//! The FMI 3.0 C types (fmi3PlatformTypes.h, fmi3FunctionTypes.h) as Rust declarations.
//! `fmi3Boolean` is C `bool` (one byte); it is received as `u8` so that a value other than
//! 0 or 1 from C is not undefined behaviour in Rust (any non-zero is true).
#![allow(non_camel_case_types, non_snake_case)]

use std::ffi::{c_char, c_void};

pub type fmi3Instance = *mut c_void;
pub type fmi3InstanceEnvironment = *mut c_void;
pub type fmi3FMUState = *mut c_void;
pub type fmi3ValueReference = u32;
pub type fmi3Float32 = f32;
pub type fmi3Float64 = f64;
pub type fmi3Int8 = i8;
pub type fmi3UInt8 = u8;
pub type fmi3Int16 = i16;
pub type fmi3UInt16 = u16;
pub type fmi3Int32 = i32;
pub type fmi3UInt32 = u32;
pub type fmi3Int64 = i64;
pub type fmi3UInt64 = u64;
pub type fmi3Boolean = u8;
pub type fmi3Char = c_char;
pub type fmi3String = *const fmi3Char;
pub type fmi3Byte = u8;
pub type fmi3Binary = *const fmi3Byte;
pub type fmi3Clock = u8;
/// `fmi3Status`: fmi3OK, fmi3Warning, fmi3Discard, fmi3Error, fmi3Fatal.
pub type fmi3Status = std::ffi::c_int;
/// `fmi3DependencyKind` and `fmi3IntervalQualifier` (C enums).
pub type fmi3DependencyKind = std::ffi::c_int;
pub type fmi3IntervalQualifier = std::ffi::c_int;

pub const FMI3_TRUE: fmi3Boolean = 1;
pub const FMI3_FALSE: fmi3Boolean = 0;

/// `fmi3LogMessageCallback`: the message is final text (no format string).
pub type fmi3LogMessageCallback =
    Option<unsafe extern "C" fn(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String)>;
pub type fmi3IntermediateUpdateCallback = Option<
    unsafe extern "C" fn(
        fmi3InstanceEnvironment,
        f64,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        *mut fmi3Boolean,
        *mut f64,
    ),
>;
pub type fmi3ClockUpdateCallback = Option<unsafe extern "C" fn(fmi3InstanceEnvironment)>;
pub type fmi3LockPreemptionCallback = Option<unsafe extern "C" fn()>;
pub type fmi3UnlockPreemptionCallback = Option<unsafe extern "C" fn()>;
