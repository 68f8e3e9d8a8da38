//! The exported FMI 3.0 functions (co-simulation and Model Exchange; fmi3Functions.h):
//! thin `extern "C"` shims over the same safe [`Instance`] as FMI 2.0, framed by the same
//! [`with_instance`] (handle table, instance lock, panic boundary, state machine,
//! logging). What FMI 3.0 changes is here: one instantiation function per interface,
//! `fmi3EnterInitializationMode` carrying the experiment, `nValues` beside every array,
//! `fmi3DoStep`'s out-arguments, a logger without format string. The functions this FMU
//! does not provide (clocks, configuration mode, scheduled execution, adjoint derivatives,
//! the other variable types) are in [`crate::fmi::fmi3::unsupported`]; the get and set
//! functions of its variable types in [`crate::fmi::fmi3::values`] (re-exported here).
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::boundary::guard;
use crate::fmi::common::instance::{Call, Instance, Interface, Logger, Status};
pub use crate::fmi::fmi3::derivatives::*;
pub use crate::fmi::fmi3::states::*;
use crate::fmi::fmi3::types::*;
pub use crate::fmi::fmi3::values::*;
use crate::fmi::frame::{register, slice, text, unregister, with_instance};
use std::ffi::{CString, c_char};
use std::sync::Arc;

const OK: Result<Status, String> = Ok(Status::Ok);

/// Logger that forwards to the importer's `fmi3LogMessageCallback` (final text; a literal
/// `#` is written `##`, since `#vr#` names a variable in FMI 3.0 messages).
pub struct LogMessage {
    pub callback: fmi3LogMessageCallback,
    pub env: fmi3InstanceEnvironment,
}

// SAFETY: as for the FMI 2.0 logger (frame.rs): the importer's C function and its
// environment pointer, only passed back to it, on the calling thread.
unsafe impl Send for LogMessage {}
unsafe impl Sync for LogMessage {}

impl Logger for LogMessage {
    fn log(&self, status: Status, category: &str, message: &str) {
        if let Some(f) = self.callback {
            let cat = CString::new(category.replace('\0', "\\0")).unwrap_or_default();
            let msg =
                CString::new(message.replace('\0', "\\0").replace('#', "##")).unwrap_or_default();
            // SAFETY: the importer promised a valid callback.
            unsafe { f(self.env, status as fmi3Status, cat.as_ptr(), msg.as_ptr()) };
        }
    }
}

#[unsafe(no_mangle)]
pub extern "C" fn fmi3GetVersion() -> *const c_char {
    c"3.0".as_ptr()
}

/// Both instantiation functions: the model by its instantiation token, then register.
fn instantiate(
    interface: Interface,
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    loggingOn: fmi3Boolean,
    env: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    refuse: Option<String>,
) -> fmi3Instance {
    let made = guard(|| {
        let sink = LogMessage { callback: logMessage, env };
        let fail = |msg: String| {
            sink.log(Status::Error, "logStatusError", &format!("fmi3Instantiate: {msg}"));
            None
        };
        let Some(name) = (unsafe { text(instanceName) }) else {
            return fail("instanceName is NULL".into());
        };
        if let Some(why) = refuse {
            return fail(why);
        }
        let token = unsafe { text(instantiationToken) };
        let fresh = match crate::fmi::model_for_guid(token.as_deref(), "instantiationToken") {
            Ok(fresh) => fresh,
            Err(msg) => return fail(msg),
        };
        let instance = Instance::of_interface(
            interface,
            crate::fmi::fmi3::names::FMI3,
            fresh,
            &name,
            Arc::new(sink),
            loggingOn != FMI3_FALSE,
        );
        Some(register(instance))
    });
    made.ok().flatten().unwrap_or(std::ptr::null_mut())
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3InstantiateModelExchange(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
) -> fmi3Instance {
    instantiate(
        Interface::ModelExchange,
        instanceName,
        instantiationToken,
        loggingOn,
        instanceEnvironment,
        logMessage,
        None,
    )
}

/// The importer's `intermediateUpdate` callback, asked for the inputs at the end of each
/// step (see [`crate::fmi::fmi3::intermediate`]).
struct IntermediateUpdate {
    callback: unsafe extern "C" fn(
        fmi3InstanceEnvironment,
        f64,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        fmi3Boolean,
        *mut fmi3Boolean,
        *mut f64,
    ),
    env: fmi3InstanceEnvironment,
}

// SAFETY: as for the logger: the importer's C function and its environment pointer, only
// passed back to it, on the thread that called fmi3DoStep.
unsafe impl Send for IntermediateUpdate {}
unsafe impl Sync for IntermediateUpdate {}

impl crate::fmi::common::instance::Requester for IntermediateUpdate {
    fn request_inputs(&self, time: f64) {
        let (mut early, mut early_time) = (FMI3_FALSE, time);
        // SAFETY: the importer promised a valid callback; the out-arguments are ours.
        unsafe {
            (self.callback)(
                self.env,
                time,
                FMI3_TRUE,
                FMI3_FALSE,
                FMI3_FALSE,
                FMI3_FALSE,
                &mut early,
                &mut early_time,
            )
        };
    }
}

/// `eventModeUsed` needs `hasEventMode` (false here) and is refused, as the standard asks.
/// `requiredIntermediateVariables` (continuous inputs, with an `intermediateUpdate`
/// callback) are asked for at the end of every step: the FMI 3.0 way to an input linear in
/// time over the step (FMI 2.0: `fmi2SetRealInputDerivatives`).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3InstantiateCoSimulation(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    _resourcePath: fmi3String,
    _visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    eventModeUsed: fmi3Boolean,
    _earlyReturnAllowed: fmi3Boolean,
    requiredIntermediateVariables: *const fmi3ValueReference,
    nRequiredIntermediateVariables: usize,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    intermediateUpdate: fmi3IntermediateUpdateCallback,
) -> fmi3Instance {
    let refuse = if eventModeUsed != FMI3_FALSE {
        Some(
            "eventModeUsed = true but this FMU has no event mode (hasEventMode = false)"
                .to_string(),
        )
    } else if nRequiredIntermediateVariables > 0 && intermediateUpdate.is_none() {
        Some(format!(
            "{nRequiredIntermediateVariables} requiredIntermediateVariables but intermediateUpdate is NULL"
        ))
    } else {
        None
    };
    let c = instantiate(
        Interface::CoSimulation,
        instanceName,
        instantiationToken,
        loggingOn,
        instanceEnvironment,
        logMessage,
        refuse,
    );
    let (Some(callback), false) = (intermediateUpdate, c.is_null()) else { return c };
    if nRequiredIntermediateVariables == 0 {
        return c;
    }
    let required = with_instance(
        c,
        Call::Unsupported,
        || "fmi3InstantiateCoSimulation(requiredIntermediateVariables)".into(),
        |i| {
            let vrs = unsafe {
                slice(
                    requiredIntermediateVariables,
                    nRequiredIntermediateVariables,
                    "requiredIntermediateVariables",
                )?
            };
            let requester = Arc::new(IntermediateUpdate { callback, env: instanceEnvironment });
            let set = i.set_intermediate_update(requester, vrs);
            set.map(|_| Status::Ok).map_err(|why| {
                format!("fmi3InstantiateCoSimulation: requiredIntermediateVariables: {why}")
            })
        },
    );
    if required == Status::Ok as fmi3Status {
        c
    } else {
        unregister(c);
        std::ptr::null_mut()
    }
}

/// Frees the instance once no call uses it; an unknown or already freed instance is ignored.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3FreeInstance(instance: fmi3Instance) {
    if guard(|| unregister(instance)).is_err() {}
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetDebugLogging(
    instance: fmi3Instance,
    loggingOn: fmi3Boolean,
    nCategories: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::SetDebugLogging,
            || format!("fmi3SetDebugLogging(loggingOn={loggingOn}, nCategories={nCategories})"),
            |i| {
                let names = slice(categories, nCategories, "categories")?;
                let names: Vec<String> =
                    names.iter().map(|&p| text(p).unwrap_or_default()).collect();
                i.set_debug_logging(loggingOn != FMI3_FALSE, &names).map(|_| Status::Ok)
            },
        )
    }
}

/// `fmi3EnterInitializationMode` carries what `fmi2SetupExperiment` did.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterInitializationMode(
    instance: fmi3Instance,
    toleranceDefined: fmi3Boolean,
    tolerance: fmi3Float64,
    startTime: fmi3Float64,
    stopTimeDefined: fmi3Boolean,
    stopTime: fmi3Float64,
) -> fmi3Status {
    let tol = (toleranceDefined != FMI3_FALSE).then_some(tolerance);
    let stop = (stopTimeDefined != FMI3_FALSE).then_some(stopTime);
    with_instance(
        instance,
        Call::EnterInitializationMode,
        || {
            format!(
                "fmi3EnterInitializationMode(tolerance={tol:?}, startTime={startTime}, stopTime={stop:?})"
            )
        },
        |i| {
            i.setup_experiment(tol, startTime, stop)?;
            i.enter_initialization_mode().map(|_| Status::Ok)
        },
    )
}

fn transition(
    instance: fmi3Instance,
    call: Call,
    method: fn(&mut Instance) -> Result<(), String>,
) -> fmi3Status {
    with_instance(
        instance,
        call,
        || crate::fmi::fmi3::names::name(call),
        |i| method(i).map(|_| Status::Ok),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3ExitInitializationMode(instance: fmi3Instance) -> fmi3Status {
    transition(instance, Call::ExitInitializationMode, Instance::exit_initialization_mode)
}

/// Model Exchange only (co-simulation without event mode never enters it).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterEventMode(instance: fmi3Instance) -> fmi3Status {
    transition(instance, Call::EnterEventMode, Instance::enter_event_mode)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3Terminate(instance: fmi3Instance) -> fmi3Status {
    transition(instance, Call::Terminate, Instance::terminate)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3Reset(instance: fmi3Instance) -> fmi3Status {
    transition(instance, Call::Reset, Instance::reset)
}

/// Configuration Mode, for the structural parameter (from Instantiated, back to it).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterConfigurationMode(instance: fmi3Instance) -> fmi3Status {
    transition(instance, Call::EnterConfigurationMode, Instance::enter_configuration_mode)
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3ExitConfigurationMode(instance: fmi3Instance) -> fmi3Status {
    transition(instance, Call::ExitConfigurationMode, Instance::exit_configuration_mode)
}

/// One step; never early, no event handling (no event mode), `lastSuccessfulTime` the end
/// of an accepted step (else the time before it), `terminateSimulation` at the stop time.
/// With required intermediate variables, the importer is asked for them at the end of the
/// step, the instance unlocked meanwhile ([`crate::fmi::fmi3::intermediate`]).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3DoStep(
    instance: fmi3Instance,
    currentCommunicationPoint: fmi3Float64,
    communicationStepSize: fmi3Float64,
    _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    eventHandlingNeeded: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    earlyReturn: *mut fmi3Boolean,
    lastSuccessfulTime: *mut fmi3Float64,
) -> fmi3Status {
    let (t, h) = (currentCommunicationPoint, communicationStepSize);
    let describe =
        || format!("fmi3DoStep(currentCommunicationPoint={t}, communicationStepSize={h})");
    let outs = |i: &Instance| -> Result<(), String> {
        let event = unsafe { eventHandlingNeeded.as_mut() }.ok_or("eventHandlingNeeded is NULL")?;
        let terminate =
            unsafe { terminateSimulation.as_mut() }.ok_or("terminateSimulation is NULL")?;
        let early = unsafe { earlyReturn.as_mut() }.ok_or("earlyReturn is NULL")?;
        let last = unsafe { lastSuccessfulTime.as_mut() }.ok_or("lastSuccessfulTime is NULL")?;
        (*event, *early) = (FMI3_FALSE, FMI3_FALSE);
        *last = i.last_successful_time();
        *terminate = if i.wants_to_terminate() { FMI3_TRUE } else { FMI3_FALSE };
        Ok(())
    };
    let mut asked = None;
    let first = with_instance(instance, Call::DoStep, describe, |i| {
        outs(i)?;
        match i.begin_step(t, h)? {
            Some(ask) => asked = Some(ask),
            None => {
                let stepped = i.do_step(t, h);
                outs(i)?;
                stepped?;
            }
        }
        OK
    });
    let Some((requester, p0)) = asked else { return first };
    // A panic in the importer's callback is caught; the step goes on with the inputs it had.
    let _ = guard(|| requester.request_inputs(t + h));
    with_instance(instance, Call::FinishStep, describe, |i| {
        let stepped = i.finish_step(t, h, &p0);
        outs(i)?;
        stepped.map(|_| Status::Ok)
    })
}
