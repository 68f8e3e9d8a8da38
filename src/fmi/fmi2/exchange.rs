//! The exported FMI 2.0 Model Exchange functions (chapter 3): thin `extern "C"` shims over
//! [`crate::fmi::common::exchange`], framed like every other function by [`with_instance`].
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::common::instance::{Call, Instance, Status};
use crate::fmi::fmi2::types::*;
use crate::fmi::frame::with_instance;
use crate::fmi::shims;

const OK: Result<Status, String> = Ok(Status::Ok);

fn flag(b: bool) -> fmi2Boolean {
    if b { FMI2_TRUE } else { FMI2_FALSE }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterEventMode(c: fmi2Component) -> fmi2Status {
    with_instance(
        c,
        Call::EnterEventMode,
        || "fmi2EnterEventMode".into(),
        |i| i.enter_event_mode().map(|_| Status::Ok),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2NewDiscreteStates(
    c: fmi2Component,
    fmi2eventInfo: *mut fmi2EventInfo,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::NewDiscreteStates,
            || "fmi2NewDiscreteStates".into(),
            |i| {
                let out = fmi2eventInfo.as_mut().ok_or("fmi2eventInfo is NULL")?;
                let info = i.new_discrete_states()?;
                *out = fmi2EventInfo {
                    newDiscreteStatesNeeded: flag(info.new_discrete_states_needed),
                    terminateSimulation: flag(info.terminate_simulation),
                    nominalsOfContinuousStatesChanged: flag(info.nominals_changed),
                    valuesOfContinuousStatesChanged: flag(info.values_changed),
                    nextEventTimeDefined: flag(info.next_event_time.is_some()),
                    nextEventTime: info.next_event_time.unwrap_or(0.0),
                };
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2EnterContinuousTimeMode(c: fmi2Component) -> fmi2Status {
    shims::transition(
        c,
        Call::EnterContinuousTimeMode,
        "fmi2EnterContinuousTimeMode",
        Instance::enter_continuous_time_mode,
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
    c: fmi2Component,
    _noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
    enterEventMode: *mut fmi2Boolean,
    terminateSimulation: *mut fmi2Boolean,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::CompletedIntegratorStep,
            || "fmi2CompletedIntegratorStep".into(),
            |i| {
                let enter = enterEventMode.as_mut().ok_or("enterEventMode is NULL")?;
                let terminate =
                    terminateSimulation.as_mut().ok_or("terminateSimulation is NULL")?;
                let (e, t) = i.completed_integrator_step()?;
                (*enter, *terminate) = (flag(e), flag(t));
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetTime(c: fmi2Component, time: fmi2Real) -> fmi2Status {
    shims::set_time(c, time, "fmi2SetTime")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2SetContinuousStates(
    c: fmi2Component,
    x: *const fmi2Real,
    nx: usize,
) -> fmi2Status {
    unsafe { shims::set_continuous_states(c, x, nx, "fmi2SetContinuousStates") }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetDerivatives(
    c: fmi2Component,
    derivatives: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    unsafe {
        shims::get_vector(
            c,
            Call::GetDerivatives,
            derivatives,
            nx,
            Instance::get_derivatives,
            "fmi2GetDerivatives",
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetEventIndicators(
    c: fmi2Component,
    _eventIndicators: *mut fmi2Real,
    ni: usize,
) -> fmi2Status {
    shims::get_event_indicators(c, ni, "fmi2GetEventIndicators")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetContinuousStates(
    c: fmi2Component,
    x: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    unsafe {
        shims::get_vector(
            c,
            Call::GetContinuousStates,
            x,
            nx,
            Instance::get_continuous_states,
            "fmi2GetContinuousStates",
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(
    c: fmi2Component,
    x_nominal: *mut fmi2Real,
    nx: usize,
) -> fmi2Status {
    unsafe {
        shims::get_vector(
            c,
            Call::GetNominalsOfContinuousStates,
            x_nominal,
            nx,
            Instance::get_nominals,
            "fmi2GetNominalsOfContinuousStates",
        )
    }
}
