//! The exported FMI 2.0 functions: thin `extern "C"` shims that convert pointers and hand
//! over to the safe [`Instance`]. Each is framed by [`with_instance`] (lookup of the
//! instance handle, its lock, panic boundary, state machine, logging) or, without an
//! instance, by [`guard`]. The `fmi2Get*Status` functions are in
//! [`crate::fmi::fmi2::status`] (re-exported here).
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::boundary::guard;
use crate::fmi::common::instance::{Call, Instance, Interface, Status};
pub use crate::fmi::fmi2::status::*;
use crate::fmi::fmi2::types::*;
use crate::fmi::frame::{
    CallbackLogger, register, slice, slice_mut, text, unregister, with_instance,
};
use crate::fmi::shims::{self, Names};
use std::ffi::{CString, c_char};
use std::sync::Arc;

const OK: Result<Status, String> = Ok(Status::Ok);

fn no_variables(kind: &str, vr: &[fmi2ValueReference]) -> Result<Status, String> {
    match vr.first() {
        None => OK,
        Some(v) => Err(format!(
            "no {kind} variable has value reference {v} (this FMU has Real and Integer variables only)"
        )),
    }
}

fn not_supported(what: &str) -> Result<Status, String> {
    Err(format!(
        "{what} is not supported by this FMU (see the capability flags of modelDescription.xml)"
    ))
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Instantiate(
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    _fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component {
    let made = guard(|| {
        let f = unsafe { functions.as_ref() }?;
        let (logger, env) = (f.logger, f.componentEnvironment);
        let name = unsafe { text(instanceName) };
        let shown = name.clone().unwrap_or_else(|| "?".into());
        let fail = |msg: String| {
            CallbackLogger::log_once(logger, env, &shown, &format!("fmi2Instantiate: {msg}"));
            None
        };
        let Some(name) = name else { return fail("instanceName is NULL".into()) };
        let interface = match fmuType {
            FMI2_CO_SIMULATION => Interface::CoSimulation,
            FMI2_MODEL_EXCHANGE => Interface::ModelExchange,
            other => {
                return fail(format!(
                    "fmuType = {other}: this FMU supports Model Exchange (0) and co-simulation (1)"
                ));
            }
        };
        let guid = unsafe { text(fmuGUID) };
        let fresh = match crate::fmi::model_for_guid(guid.as_deref(), "GUID") {
            Ok(fresh) => fresh,
            Err(msg) => return fail(msg),
        };
        let sink =
            CallbackLogger { logger, env, name: CString::new(name.as_str()).unwrap_or_default() };
        Some(register(Instance::of_interface(
            interface,
            crate::fmi::fmi2::names::FMI2,
            fresh,
            &name,
            Arc::new(sink),
            loggingOn != FMI2_FALSE,
        )))
    });
    made.ok().flatten().unwrap_or(std::ptr::null_mut())
}

/// Frees the instance once no call uses it; an unknown or already freed `c` is ignored.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
    if guard(|| unregister(c)).is_err() {}
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetDebugLogging(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::SetDebugLogging,
            || format!("fmi2SetDebugLogging(loggingOn={loggingOn}, nCategories={nCategories})"),
            |i| {
                let names = slice(categories, nCategories, "categories")?;
                let names: Vec<String> =
                    names.iter().map(|&p| text(p).unwrap_or_default()).collect();
                i.set_debug_logging(loggingOn != FMI2_FALSE, &names).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetupExperiment(
    c: fmi2Component,
    toleranceDefined: fmi2Boolean,
    tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status {
    let tol = (toleranceDefined != FMI2_FALSE).then_some(tolerance);
    let stop = (stopTimeDefined != FMI2_FALSE).then_some(stopTime);
    with_instance(
        c,
        Call::SetupExperiment,
        || {
            format!(
                "fmi2SetupExperiment(tolerance={tol:?}, startTime={startTime}, stopTime={stop:?})"
            )
        },
        |i| i.setup_experiment(tol, startTime, stop).map(|_| Status::Ok),
    )
}

/// A call without arguments that only moves the state machine: `fmi2EnterInitializationMode`,
/// `fmi2ExitInitializationMode`, `fmi2Terminate`, `fmi2Reset`. (Written out below, one
/// function each rather than by a macro, so that cbindgen sees every exported function.)
fn transition(
    c: fmi2Component,
    call: Call,
    method: fn(&mut Instance) -> Result<(), String>,
) -> fmi2Status {
    with_instance(
        c,
        call,
        || crate::fmi::fmi2::names::name(call).to_string(),
        |i| method(i).map(|_| Status::Ok),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
    transition(c, Call::EnterInitializationMode, Instance::enter_initialization_mode)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
    transition(c, Call::ExitInitializationMode, Instance::exit_initialization_mode)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
    transition(c, Call::Terminate, Instance::terminate)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
    transition(c, Call::Reset, Instance::reset)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::Get,
            || format!("fmi2GetReal(nvr={nvr})"),
            |i| {
                let vr = slice(vr, nvr, "vr")?;
                let out = slice_mut(value, nvr, "value")?;
                i.get_real(vr, out).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetReal(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::Set,
            || format!("fmi2SetReal(nvr={nvr})"),
            |i| {
                let vr = slice(vr, nvr, "vr")?;
                let values = slice(value, nvr, "value")?;
                i.set_real(vr, values).map(|_| Status::Ok)
            },
        )
    }
}

/// `fmi2{Get,Set}{Boolean,String}`: this FMU has Real and Integer variables only, so any value
/// reference is an error (and an empty list is fine).
///
/// # Safety
/// `vr` is NULL or points to `nvr` value references.
unsafe fn no_such_variables(
    c: fmi2Component,
    call: Call,
    fname: &str,
    kind: &str,
    vr: *const fmi2ValueReference,
    nvr: usize,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            call,
            || format!("{fname}(nvr={nvr})"),
            |_| no_variables(kind, slice(vr, nvr, "vr")?),
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::Get,
            || format!("fmi2GetInteger(nvr={nvr})"),
            |i| {
                let vr = slice(vr, nvr, "vr")?;
                let out = slice_mut(value, nvr, "value")?;
                i.get_integer(vr, out).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2Boolean,
) -> fmi2Status {
    unsafe { no_such_variables(c, Call::Get, "fmi2GetBoolean", "Boolean", vr, nvr) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *mut fmi2String,
) -> fmi2Status {
    unsafe { no_such_variables(c, Call::Get, "fmi2GetString", "String", vr, nvr) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetInteger(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::Set,
            || format!("fmi2SetInteger(nvr={nvr})"),
            |i| {
                let vr = slice(vr, nvr, "vr")?;
                let values = slice(value, nvr, "value")?;
                i.set_integer(vr, values).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetBoolean(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2Boolean,
) -> fmi2Status {
    unsafe { no_such_variables(c, Call::Set, "fmi2SetBoolean", "Boolean", vr, nvr) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetString(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    _value: *const fmi2String,
) -> fmi2Status {
    unsafe { no_such_variables(c, Call::Set, "fmi2SetString", "String", vr, nvr) }
}

fn names(function: &'static str) -> Names {
    Names { function, state: "FMUstate" }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe { shims::get_fmu_state(c, FMUstate, names("fmi2GetFMUstate")) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status {
    unsafe { shims::set_fmu_state(c, FMUstate, names("fmi2SetFMUstate")) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2FreeFMUstate(
    c: fmi2Component,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe { shims::free_fmu_state(c, FMUstate, false, names("fmi2FreeFMUstate")) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    unsafe {
        shims::serialized_fmu_state_size(c, FMUstate, size, names("fmi2SerializedFMUstateSize"))
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SerializeFMUstate(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    unsafe {
        shims::serialize_fmu_state(
            c,
            FMUstate,
            serializedState as *mut u8,
            size,
            names("fmi2SerializeFMUstate"),
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status {
    unsafe {
        shims::deserialize_fmu_state(
            c,
            serializedState as *const u8,
            size,
            FMUstate,
            names("fmi2DeSerializeFMUstate"),
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
    c: fmi2Component,
    vUnknown_ref: *const fmi2ValueReference,
    nUnknown: usize,
    vKnown_ref: *const fmi2ValueReference,
    nKnown: usize,
    dvKnown: *const fmi2Real,
    dvUnknown: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::GetDirectionalDerivative,
            || format!("fmi2GetDirectionalDerivative(nUnknown={nUnknown}, nKnown={nKnown})"),
            |i| {
                let unknowns = slice(vUnknown_ref, nUnknown, "vUnknown_ref")?;
                let knowns = slice(vKnown_ref, nKnown, "vKnown_ref")?;
                let seed = slice(dvKnown, nKnown, "dvKnown")?;
                let out = slice_mut(dvUnknown, nUnknown, "dvUnknown")?;
                let got = i.directional_derivative(unknowns, knowns, seed)?;
                out.copy_from_slice(&got);
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::SetRealInputDerivatives,
            || format!("fmi2SetRealInputDerivatives(nvr={nvr})"),
            |i| {
                let vr = slice(vr, nvr, "vr")?;
                let order = slice(order, nvr, "order")?;
                let value = slice(value, nvr, "value")?;
                i.set_real_input_derivatives(vr, order, value).map(|_| Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
    c: fmi2Component,
    _vr: *const fmi2ValueReference,
    _nvr: usize,
    _order: *const fmi2Integer,
    _value: *mut fmi2Real,
) -> fmi2Status {
    with_instance(
        c,
        Call::GetRealOutputDerivatives,
        || "fmi2GetRealOutputDerivatives".into(),
        |_| not_supported("fmi2GetRealOutputDerivatives (maxOutputDerivativeOrder = 0)"),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2DoStep(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status {
    with_instance(
        c,
        Call::DoStep,
        || {
            format!(
                "fmi2DoStep(currentCommunicationPoint={currentCommunicationPoint}, communicationStepSize={communicationStepSize})"
            )
        },
        |i| i.do_step(currentCommunicationPoint, communicationStepSize).map(|_| Status::Ok),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
    with_instance(
        c,
        Call::CancelStep,
        || "fmi2CancelStep".into(),
        |_| not_supported("fmi2CancelStep"),
    )
}
