//! FMI 3.0's [`Dialect`]: the names of its functions (FMI 2.0's with `fmi3` for `fmi2`
//! where they are not renamed), free text in its words, and its rules where they differ.

#![forbid(unsafe_code)]

use crate::fmi::common::call::{Call, Dialect};
use crate::fmi::fmi2::names as fmi2;

/// FMI 3.0, section 2.3.2: fmi3Get* also reads start values in Instantiated and
/// Configuration Mode.
pub const FMI3: Dialect =
    Dialect { name, text, get_before_initialization: true, configuration_mode: true, derivative_arguments: ["unknowns", "knowns", "seed"] };

/// The FMI 3.0 name, where it is not the FMI 2.0 one with `fmi3` for `fmi2`.
pub fn name(call: Call) -> String {
    match call {
        Call::SetupExperiment | Call::EnterInitializationMode => "fmi3EnterInitializationMode".into(),
        Call::Get => "fmi3Get*".into(),
        Call::Set => "fmi3Set*".into(),
        Call::GetFmuState => "fmi3GetFMUState".into(),
        Call::SetFmuState => "fmi3SetFMUState".into(),
        Call::FreeFmuState => "fmi3FreeFMUState".into(),
        Call::SerializeFmuState => "fmi3SerializeFMUState".into(),
        Call::DeSerializeFmuState => "fmi3DeserializeFMUState".into(),
        Call::NewDiscreteStates => "fmi3UpdateDiscreteStates".into(),
        Call::GetDerivatives => "fmi3GetContinuousStateDerivatives".into(),
        Call::GetRealOutputDerivatives => "fmi3GetOutputDerivatives".into(),
        other => fmi2::name(other).replacen("fmi2", "fmi3", 1),
    }
}

/// FMI 2.0 names in free text (variable descriptions, log messages) and what an FMI 3.0
/// importer calls instead; the first that matches wins, then any other `fmi2` prefix
/// becomes `fmi3`.
const FMI3_WORDS: [(&str, &str); 12] = [
    ("fmi2SetRealInputDerivatives", "an intermediate update (requiredIntermediateVariables)"),
    ("fmi2GetRealOutputDerivatives", "fmi3GetOutputDerivatives"),
    ("fmi2SetupExperiment", "fmi3EnterInitializationMode"),
    ("fmi2SetReal", "fmi3SetFloat64"),
    ("fmi2GetReal", "fmi3GetFloat64"),
    ("fmi2GetDerivatives", "fmi3GetContinuousStateDerivatives"),
    ("fmi2NewDiscreteStates", "fmi3UpdateDiscreteStates"),
    ("fmi2DeSerializeFMUstate", "fmi3DeserializeFMUState"),
    ("fmi2SerializeFMUstate", "fmi3SerializeFMUState"),
    ("fmi2GetFMUstate", "fmi3GetFMUState"),
    ("fmi2SetFMUstate", "fmi3SetFMUState"),
    ("fmi2FreeFMUstate", "fmi3FreeFMUState"),
];

/// `text` as an FMI 3.0 importer should read it ([`FMI3_WORDS`]).
pub fn text(text: &str) -> String {
    let mut out = text.to_string();
    for (fmi2, fmi3) in FMI3_WORDS {
        out = out.replace(fmi2, fmi3);
    }
    out.replace("fmi2", "fmi3")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::fmi2::names::FMI2;

    /// Calls that exist in FMI 3.0 only are named as FMI 3.0 names them, whatever the
    /// instance's version: there is no `fmi2EnterConfigurationMode` to point a reader to.
    #[test]
    fn fmi3_only_calls_have_no_fmi2_name() {
        for call in [Call::EnterConfigurationMode, Call::ExitConfigurationMode, Call::GetNumberOf, Call::FinishStep] {
            for dialect in [FMI2, FMI3] {
                assert!((dialect.name)(call).starts_with("fmi3"), "{call:?}: {}", (dialect.name)(call));
            }
        }
        assert_eq!((FMI2.name)(Call::GetFmuState), "fmi2GetFMUstate");
        assert_eq!((FMI3.name)(Call::GetFmuState), "fmi3GetFMUState");
    }
}
