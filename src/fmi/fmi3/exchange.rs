//! The exported FMI 3.0 Model Exchange functions. Where the C signature is FMI 2.0's (an
//! instance handle, reals and counts), the body is the one both versions share
//! ([`crate::fmi::shims`]) under FMI 3.0's name; the others (booleans are one byte in FMI
//! 3.0, `fmi3UpdateDiscreteStates` has out-arguments instead of `fmi2EventInfo`, the
//! counts) are written here.
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::common::exchange::EventInfo;
use crate::fmi::common::instance::{Call, Instance, Status};
use crate::fmi::fmi3::types::*;
use crate::fmi::frame::with_instance;
use crate::fmi::shims;

fn flag(b: bool) -> fmi3Boolean {
    if b { FMI3_TRUE } else { FMI3_FALSE }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3EnterContinuousTimeMode(instance: fmi3Instance) -> fmi3Status {
    shims::transition(
        instance,
        Call::EnterContinuousTimeMode,
        "fmi3EnterContinuousTimeMode",
        Instance::enter_continuous_time_mode,
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetTime(instance: fmi3Instance, time: fmi3Float64) -> fmi3Status {
    shims::set_time(instance, time, "fmi3SetTime")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3SetContinuousStates(
    instance: fmi3Instance,
    continuousStates: *const fmi3Float64,
    nContinuousStates: usize,
) -> fmi3Status {
    unsafe {
        shims::set_continuous_states(
            instance,
            continuousStates,
            nContinuousStates,
            "fmi3SetContinuousStates",
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetContinuousStateDerivatives(
    instance: fmi3Instance,
    derivatives: *mut fmi3Float64,
    nContinuousStates: usize,
) -> fmi3Status {
    unsafe {
        shims::get_vector(
            instance,
            Call::GetDerivatives,
            derivatives,
            nContinuousStates,
            Instance::get_derivatives,
            "fmi3GetContinuousStateDerivatives",
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetEventIndicators(
    instance: fmi3Instance,
    _eventIndicators: *mut fmi3Float64,
    nEventIndicators: usize,
) -> fmi3Status {
    shims::get_event_indicators(instance, nEventIndicators, "fmi3GetEventIndicators")
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetContinuousStates(
    instance: fmi3Instance,
    continuousStates: *mut fmi3Float64,
    nContinuousStates: usize,
) -> fmi3Status {
    unsafe {
        shims::get_vector(
            instance,
            Call::GetContinuousStates,
            continuousStates,
            nContinuousStates,
            Instance::get_continuous_states,
            "fmi3GetContinuousStates",
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetNominalsOfContinuousStates(
    instance: fmi3Instance,
    nominals: *mut fmi3Float64,
    nContinuousStates: usize,
) -> fmi3Status {
    unsafe {
        shims::get_vector(
            instance,
            Call::GetNominalsOfContinuousStates,
            nominals,
            nContinuousStates,
            Instance::get_nominals,
            "fmi3GetNominalsOfContinuousStates",
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3CompletedIntegratorStep(
    instance: fmi3Instance,
    _noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    enterEventMode: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::CompletedIntegratorStep,
            || "fmi3CompletedIntegratorStep".into(),
            |i| {
                let enter = enterEventMode.as_mut().ok_or("enterEventMode is NULL")?;
                let terminate =
                    terminateSimulation.as_mut().ok_or("terminateSimulation is NULL")?;
                let (e, t) = i.completed_integrator_step()?;
                (*enter, *terminate) = (flag(e), flag(t));
                Ok(Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3UpdateDiscreteStates(
    instance: fmi3Instance,
    discreteStatesNeedUpdate: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    nominalsOfContinuousStatesChanged: *mut fmi3Boolean,
    valuesOfContinuousStatesChanged: *mut fmi3Boolean,
    nextEventTimeDefined: *mut fmi3Boolean,
    nextEventTime: *mut fmi3Float64,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::NewDiscreteStates,
            || "fmi3UpdateDiscreteStates".into(),
            |i| {
                let outs = [
                    discreteStatesNeedUpdate,
                    terminateSimulation,
                    nominalsOfContinuousStatesChanged,
                    valuesOfContinuousStatesChanged,
                    nextEventTimeDefined,
                ];
                if outs.iter().any(|p| p.is_null()) || nextEventTime.is_null() {
                    return Err("an out-argument is NULL".into());
                }
                let EventInfo {
                    new_discrete_states_needed,
                    terminate_simulation,
                    nominals_changed,
                    values_changed,
                    next_event_time,
                } = i.new_discrete_states()?;
                let flags = [
                    new_discrete_states_needed,
                    terminate_simulation,
                    nominals_changed,
                    values_changed,
                    next_event_time.is_some(),
                ];
                outs.iter().zip(flags).for_each(|(p, f)| **p = flag(f));
                *nextEventTime = next_event_time.unwrap_or(0.0);
                Ok(Status::Ok)
            },
        )
    }
}

/// `fmi3GetNumberOfContinuousStates` and `fmi3GetNumberOfEventIndicators` (0).
unsafe fn number_of(
    instance: fmi3Instance,
    out: *mut usize,
    name: &'static str,
    states: bool,
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::GetNumberOf,
            || name.into(),
            |i| {
                *out.as_mut().ok_or("the out-argument is NULL")? =
                    if states { i.description().state_count() } else { 0 };
                Ok(Status::Ok)
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetNumberOfContinuousStates(
    instance: fmi3Instance,
    nContinuousStates: *mut usize,
) -> fmi3Status {
    unsafe { number_of(instance, nContinuousStates, "fmi3GetNumberOfContinuousStates", true) }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetNumberOfEventIndicators(
    instance: fmi3Instance,
    nEventIndicators: *mut usize,
) -> fmi3Status {
    unsafe { number_of(instance, nEventIndicators, "fmi3GetNumberOfEventIndicators", false) }
}
