//! The FMI 3.0 functions this FMU exports because every FMU must (fmi3Functions.h; importers
//! resolve all of them when loading) but does not provide: the variable types it has none
//! of (a call naming no variable succeeds, any value reference is an error naming the
//! type), clocks and their intervals and shifts, event mode in co-simulation, output
//! derivatives, variable dependencies at run time, and scheduled execution. Each is
//! framed like every other function and refused with the reason under `logStatusError`.
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::common::instance::{Call, Status};
use crate::fmi::fmi3::types::*;
use crate::fmi::frame::{slice, with_instance};

/// A getter or setter of a type this FMU has no variables of.
///
/// # Safety
/// `vr` is NULL or points to `nvr` value references.
unsafe fn no_variables(
    instance: fmi3Instance,
    call: Call,
    name: &'static str,
    kind: &str,
    vr: *const fmi3ValueReference,
    nvr: usize,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            call,
            || format!("{name}(nValueReferences={nvr})"),
            |_| match slice(vr, nvr, "valueReferences")?.first() {
                None => Ok(Status::Ok),
                Some(v) => Err(format!(
                    "{name}: no {kind} variable has value reference {v} (this FMU has Float64, Int32 and UInt64 variables only)"
                )),
            },
        )
    }
}

/// A function this FMU does not provide: refused with the reason.
fn unsupported(instance: fmi3Instance, name: &'static str, why: &'static str) -> fmi3Status {
    with_instance(
        instance,
        Call::Unsupported,
        || name.into(),
        |_| Err(format!("{name} is not supported by this FMU: {why}")),
    )
}

macro_rules! typed_access {
    ($($get:ident, $set:ident, $ty:ty, $kind:literal;)*) => {$(
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $get(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, _values: *mut $ty, _nValues: usize) -> fmi3Status {
            unsafe { no_variables(instance, Call::Get, stringify!($get), $kind, valueReferences, nValueReferences) }
        }
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $set(instance: fmi3Instance, valueReferences: *const fmi3ValueReference, nValueReferences: usize, _values: *const $ty, _nValues: usize) -> fmi3Status {
            unsafe { no_variables(instance, Call::Set, stringify!($set), $kind, valueReferences, nValueReferences) }
        }
    )*};
}

typed_access! {
    fmi3GetFloat32, fmi3SetFloat32, fmi3Float32, "Float32";
    fmi3GetInt8, fmi3SetInt8, fmi3Int8, "Int8";
    fmi3GetUInt8, fmi3SetUInt8, fmi3UInt8, "UInt8";
    fmi3GetInt16, fmi3SetInt16, fmi3Int16, "Int16";
    fmi3GetUInt16, fmi3SetUInt16, fmi3UInt16, "UInt16";
    fmi3GetUInt32, fmi3SetUInt32, fmi3UInt32, "UInt32";
    fmi3GetInt64, fmi3SetInt64, fmi3Int64, "Int64";
    fmi3GetBoolean, fmi3SetBoolean, fmi3Boolean, "Boolean";
    fmi3GetString, fmi3SetString, fmi3String, "String";
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetBinary(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    _valueSizes: *mut usize,
    _values: *mut fmi3Binary,
    _nValues: usize,
) -> fmi3Status {
    unsafe {
        no_variables(
            instance,
            Call::Get,
            "fmi3GetBinary",
            "Binary",
            valueReferences,
            nValueReferences,
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetBinary(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    _valueSizes: *const usize,
    _values: *const fmi3Binary,
    _nValues: usize,
) -> fmi3Status {
    unsafe {
        no_variables(
            instance,
            Call::Set,
            "fmi3SetBinary",
            "Binary",
            valueReferences,
            nValueReferences,
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetClock(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    _values: *mut fmi3Clock,
) -> fmi3Status {
    unsafe {
        no_variables(
            instance,
            Call::Get,
            "fmi3GetClock",
            "Clock",
            valueReferences,
            nValueReferences,
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetClock(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    _values: *const fmi3Clock,
) -> fmi3Status {
    unsafe {
        no_variables(
            instance,
            Call::Set,
            "fmi3SetClock",
            "Clock",
            valueReferences,
            nValueReferences,
        )
    }
}

const NO_CLOCKS: &str = "it has no clocks";

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetIntervalDecimal(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _intervals: *mut f64,
    _qualifiers: *mut fmi3IntervalQualifier,
) -> fmi3Status {
    unsupported(instance, "fmi3GetIntervalDecimal", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetIntervalFraction(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *mut u64,
    _resolutions: *mut u64,
    _qualifiers: *mut fmi3IntervalQualifier,
) -> fmi3Status {
    unsupported(instance, "fmi3GetIntervalFraction", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetShiftDecimal(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _shifts: *mut f64,
) -> fmi3Status {
    unsupported(instance, "fmi3GetShiftDecimal", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetShiftFraction(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *mut u64,
    _resolutions: *mut u64,
) -> fmi3Status {
    unsupported(instance, "fmi3GetShiftFraction", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetIntervalDecimal(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _intervals: *const f64,
) -> fmi3Status {
    unsupported(instance, "fmi3SetIntervalDecimal", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetIntervalFraction(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *const u64,
    _resolutions: *const u64,
) -> fmi3Status {
    unsupported(instance, "fmi3SetIntervalFraction", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetShiftDecimal(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _shifts: *const f64,
) -> fmi3Status {
    unsupported(instance, "fmi3SetShiftDecimal", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetShiftFraction(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _counters: *const u64,
    _resolutions: *const u64,
) -> fmi3Status {
    unsupported(instance, "fmi3SetShiftFraction", NO_CLOCKS)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetNumberOfVariableDependencies(
    instance: fmi3Instance,
    _vr: fmi3ValueReference,
    _n: *mut usize,
) -> fmi3Status {
    unsupported(
        instance,
        "fmi3GetNumberOfVariableDependencies",
        "the dependencies are those of modelDescription.xml",
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetVariableDependencies(
    instance: fmi3Instance,
    _dependent: fmi3ValueReference,
    _elementIndicesOfDependent: *mut usize,
    _independents: *mut fmi3ValueReference,
    _elementIndicesOfIndependents: *mut usize,
    _dependencyKinds: *mut fmi3DependencyKind,
    _nDependencies: usize,
) -> fmi3Status {
    unsupported(
        instance,
        "fmi3GetVariableDependencies",
        "the dependencies are those of modelDescription.xml",
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EvaluateDiscreteStates(instance: fmi3Instance) -> fmi3Status {
    unsupported(instance, "fmi3EvaluateDiscreteStates", "it has no discrete states")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterStepMode(instance: fmi3Instance) -> fmi3Status {
    unsupported(
        instance,
        "fmi3EnterStepMode",
        "it has no event mode in co-simulation (hasEventMode = false)",
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetOutputDerivatives(
    instance: fmi3Instance,
    _vr: *const fmi3ValueReference,
    _n: usize,
    _orders: *const fmi3Int32,
    _values: *mut f64,
    _nValues: usize,
) -> fmi3Status {
    unsupported(instance, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder = 0")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3ActivateModelPartition(
    instance: fmi3Instance,
    _clockReference: fmi3ValueReference,
    _activationTime: f64,
) -> fmi3Status {
    unsupported(instance, "fmi3ActivateModelPartition", "it does not provide scheduled execution")
}

/// Scheduled execution is not provided: NULL, with the reason logged.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3InstantiateScheduledExecution(
    _instanceName: fmi3String,
    _instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    _loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    _clockUpdate: fmi3ClockUpdateCallback,
    _lockPreemption: fmi3LockPreemptionCallback,
    _unlockPreemption: fmi3UnlockPreemptionCallback,
) -> fmi3Instance {
    use crate::fmi::common::instance::Logger;
    let sink =
        crate::fmi::fmi3::functions::LogMessage { callback: logMessage, env: instanceEnvironment };
    // A panic in the importer's logger is caught; the answer is NULL either way.
    let _ = crate::boundary::guard(|| {
        sink.log(
            Status::Error,
            "logStatusError",
            "fmi3InstantiateScheduledExecution: this FMU does not provide scheduled execution",
        )
    });
    std::ptr::null_mut()
}
