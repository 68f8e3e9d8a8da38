//! FMI 3.0's [`Dialect`]: the names of its functions, each written out, and its rules where
//! they differ.

#![forbid(unsafe_code)]

use crate::fmi::common::call::{Call, Dialect};

/// FMI 3.0, section 2.3.2: fmi3Get* also reads start values in Instantiated and
/// Configuration Mode.
pub const FMI3: Dialect = Dialect {
    name,
    get_before_initialization: true,
    configuration_mode: true,
    derivative_arguments: ["unknowns", "knowns", "seed"],
};

/// The call's FMI 3.0 name, each written out (no rewriting of FMI 2.0's).
pub fn name(call: Call) -> String {
    let name = match call {
        Call::SetDebugLogging => "fmi3SetDebugLogging",
        Call::SetupExperiment | Call::EnterInitializationMode => "fmi3EnterInitializationMode",
        Call::ExitInitializationMode => "fmi3ExitInitializationMode",
        Call::Terminate => "fmi3Terminate",
        Call::Reset => "fmi3Reset",
        Call::Get => "fmi3Get*",
        Call::Set => "fmi3Set*",
        Call::GetFmuState => "fmi3GetFMUState",
        Call::SetFmuState => "fmi3SetFMUState",
        Call::FreeFmuState => "fmi3FreeFMUState",
        Call::SerializeFmuState => "fmi3SerializeFMUState",
        Call::DeSerializeFmuState => "fmi3DeserializeFMUState",
        Call::DoStep | Call::FinishStep => "fmi3DoStep",
        Call::CancelStep => "fmi3CancelStep",
        Call::GetStatus => "fmi3Get*Status",
        Call::GetDirectionalDerivative => "fmi3GetDirectionalDerivative",
        Call::SetRealInputDerivatives => "fmi3SetRealInputDerivatives",
        Call::GetRealOutputDerivatives => "fmi3GetOutputDerivatives",
        Call::EnterEventMode => "fmi3EnterEventMode",
        Call::NewDiscreteStates => "fmi3UpdateDiscreteStates",
        Call::EnterContinuousTimeMode => "fmi3EnterContinuousTimeMode",
        Call::CompletedIntegratorStep => "fmi3CompletedIntegratorStep",
        Call::SetTime => "fmi3SetTime",
        Call::SetContinuousStates => "fmi3SetContinuousStates",
        Call::GetDerivatives => "fmi3GetContinuousStateDerivatives",
        Call::GetEventIndicators => "fmi3GetEventIndicators",
        Call::GetContinuousStates => "fmi3GetContinuousStates",
        Call::GetNominalsOfContinuousStates => "fmi3GetNominalsOfContinuousStates",
        Call::GetNumberOf => "fmi3GetNumberOf*",
        Call::EnterConfigurationMode => "fmi3EnterConfigurationMode",
        Call::ExitConfigurationMode => "fmi3ExitConfigurationMode",
        Call::Unsupported => "fmi3",
    };
    name.to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::fmi2::names::FMI2;

    /// Calls that exist in FMI 3.0 only are named as FMI 3.0 names them, whatever the
    /// instance's version: there is no `fmi2EnterConfigurationMode` to point a reader to.
    #[test]
    fn fmi3_only_calls_have_no_fmi2_name() {
        for call in [
            Call::EnterConfigurationMode,
            Call::ExitConfigurationMode,
            Call::GetNumberOf,
            Call::FinishStep,
        ] {
            for dialect in [FMI2, FMI3] {
                assert!(
                    (dialect.name)(call).starts_with("fmi3"),
                    "{call:?}: {}",
                    (dialect.name)(call)
                );
            }
        }
        assert_eq!((FMI2.name)(Call::GetFmuState), "fmi2GetFMUstate");
        assert_eq!((FMI3.name)(Call::GetFmuState), "fmi3GetFMUState");
    }
}
