//! The exported FMI 2.0 status functions (`fmi2Get*Status`, co-simulation, section 4.2.3):
//! `fmi2LastSuccessfulTime` and `fmi2Terminated` are answered, every other kind is
//! `fmi2Discard` with the reason logged. Thin shims framed by [`with_instance`].
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::common::instance::{Call, Instance, Status};
use crate::fmi::fmi2::types::*;
use crate::fmi::frame::with_instance;

const OK: Result<Status, String> = Ok(Status::Ok);

/// `fmi2Get*Status` asked for a kind this FMU does not provide: `fmi2Discard`, with the
/// reason logged. FMI 2.0.2, section 2.1.3: "For co-simulation: fmi2Discard is returned
/// also if the slave is not able to return the required status information"; section 4.2.3
/// (fmi2GetXXXStatus): "If a status is required which cannot be retrieved by the slave it
/// returns fmi2Discard". The Reference-FMUs (src/fmi2Functions.c, `getStatus`) do the same.
/// A value that is no `fmi2StatusKind` at all is an invalid argument: `fmi2Error`.
fn status_not_provided(
    i: &Instance,
    function: &str,
    kind: fmi2StatusKind,
) -> Result<Status, String> {
    const KINDS: [&str; 4] =
        ["fmi2DoStepStatus", "fmi2PendingStatus", "fmi2LastSuccessfulTime", "fmi2Terminated"];
    let name = usize::try_from(kind).ok().and_then(|k| KINDS.get(k));
    let name =
        name.ok_or_else(|| format!("status kind {kind} is not an fmi2StatusKind (0 to 3)"))?;
    Ok(i.discard(&format!(
        "{function}: {name} is not provided by this FMU (it provides fmi2LastSuccessfulTime through \
         fmi2GetRealStatus and fmi2Terminated through fmi2GetBooleanStatus; its fmi2DoStep is \
         synchronous, never pending)"
    )))
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    _value: *mut fmi2Status,
) -> fmi2Status {
    with_instance(
        c,
        Call::GetStatus,
        || format!("fmi2GetStatus({s})"),
        |i| status_not_provided(i, "fmi2GetStatus", s),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetRealStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Real,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::GetStatus,
            || format!("fmi2GetRealStatus({s})"),
            |i| {
                if s != FMI2_LAST_SUCCESSFUL_TIME {
                    return status_not_provided(i, "fmi2GetRealStatus", s);
                }
                *value.as_mut().ok_or("value is NULL")? = i.last_successful_time();
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetIntegerStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    _value: *mut fmi2Integer,
) -> fmi2Status {
    with_instance(
        c,
        Call::GetStatus,
        || format!("fmi2GetIntegerStatus({s})"),
        |i| status_not_provided(i, "fmi2GetIntegerStatus", s),
    )
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    unsafe {
        with_instance(
            c,
            Call::GetStatus,
            || format!("fmi2GetBooleanStatus({s})"),
            |i| {
                if s != FMI2_TERMINATED {
                    return status_not_provided(i, "fmi2GetBooleanStatus", s);
                }
                *value.as_mut().ok_or("value is NULL")? =
                    if i.wants_to_terminate() { FMI2_TRUE } else { FMI2_FALSE };
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi2GetStringStatus(
    c: fmi2Component,
    s: fmi2StatusKind,
    _value: *mut fmi2String,
) -> fmi2Status {
    with_instance(
        c,
        Call::GetStatus,
        || format!("fmi2GetStringStatus({s})"),
        |i| status_not_provided(i, "fmi2GetStringStatus", s),
    )
}
