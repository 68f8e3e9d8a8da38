//! `fmi2Get*Status`: what the FMU provides (fmi2LastSuccessfulTime as a Real,
//! fmi2Terminated as a Boolean) is OK; any other kind is `fmi2Discard`, as FMI 2.0.2
//! section 2.1.3 defines ("fmi2Discard is returned also if the slave is not able to return
//! the required status information") and the Reference-FMUs do.

mod common;

use common::fmi::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;

const DO_STEP_STATUS: fmi2StatusKind = 0;
const PENDING_STATUS: fmi2StatusKind = 1;

/// Guards against answering a status the FMU does not provide with `fmi2Error`, which
/// tells the master the instance is broken (it may only be reset or freed) when it is not.
#[test]
fn status_kinds_not_provided_are_discarded_not_errors() {
    for guid in [WOUND, PURSE] {
        let c = initialized(guid, 0.0, &[]);
        assert_eq!(unsafe { fmi2DoStep(c, 0.0, 0.5, 1) }, OK);
        let (mut st, mut r, mut i, mut b, mut s) = (-1, f64::NAN, -1, -1, std::ptr::null());
        unsafe {
            for kind in [DO_STEP_STATUS, PENDING_STATUS, FMI2_LAST_SUCCESSFUL_TIME, FMI2_TERMINATED]
            {
                assert_eq!(fmi2GetStatus(c, kind, &mut st), DISCARD, "fmi2GetStatus({kind})");
                assert_eq!(
                    fmi2GetIntegerStatus(c, kind, &mut i),
                    DISCARD,
                    "fmi2GetIntegerStatus({kind})"
                );
                assert_eq!(
                    fmi2GetStringStatus(c, kind, &mut s),
                    DISCARD,
                    "fmi2GetStringStatus({kind})"
                );
            }
            for kind in [DO_STEP_STATUS, PENDING_STATUS, FMI2_TERMINATED] {
                assert_eq!(
                    fmi2GetRealStatus(c, kind, &mut r),
                    DISCARD,
                    "fmi2GetRealStatus({kind})"
                );
            }
            for kind in [DO_STEP_STATUS, PENDING_STATUS, FMI2_LAST_SUCCESSFUL_TIME] {
                assert_eq!(
                    fmi2GetBooleanStatus(c, kind, &mut b),
                    DISCARD,
                    "fmi2GetBooleanStatus({kind})"
                );
            }
            assert_eq!(
                (st, i, b, s),
                (-1, -1, -1, std::ptr::null()),
                "a discarded call writes nothing"
            );
            // What is provided is still OK, and a value that is no status kind at all is an error.
            assert_eq!(fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut r), OK);
            assert_eq!(r, 0.5);
            assert_eq!(fmi2GetBooleanStatus(c, FMI2_TERMINATED, &mut b), OK);
            assert_eq!(b, FMI2_FALSE);
            assert_eq!(fmi2GetStatus(c, 7, &mut st), ERROR, "7 is not an fmi2StatusKind");
            assert_eq!(fmi2GetRealStatus(c, -1, &mut r), ERROR, "-1 is not an fmi2StatusKind");
            // The instance goes on.
            assert_eq!(fmi2DoStep(c, 0.5, 0.5, 1), OK);
            fmi2FreeInstance(c);
        }
    }
}
