//! The FMI calls an instance answers: in which states of the FMI 2.0 state machines each
//! is allowed (co-simulation, section 4.2.4; Model Exchange, section 3.2.3, as the
//! Reference-FMUs' masks in `fmi2Functions.c` read it), for which interface type, and its
//! name for messages.

use crate::fmi::common::machine::{Interface, Machine};

/// The FMI version an instance was made through: its rules where they differ, and the
/// names its importer knows the functions by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Version {
    Fmi2,
    Fmi3,
}

/// The FMI calls, for the state-machine check and the call log.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    SetDebugLogging,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    Get,
    Set,
    GetFmuState,
    SetFmuState,
    FreeFmuState,
    SerializeFmuState,
    DeSerializeFmuState,
    DoStep,
    CancelStep,
    GetStatus,
    GetDirectionalDerivative,
    SetRealInputDerivatives,
    GetRealOutputDerivatives,
    EnterEventMode,
    NewDiscreteStates,
    EnterContinuousTimeMode,
    CompletedIntegratorStep,
    SetTime,
    SetContinuousStates,
    GetDerivatives,
    GetEventIndicators,
    GetContinuousStates,
    GetNominalsOfContinuousStates,
    /// FMI 3.0: `fmi3GetNumberOfContinuousStates`, `fmi3GetNumberOfEventIndicators`.
    GetNumberOf,
    /// FMI 3.0: the second half of an `fmi3DoStep` with intermediate update.
    FinishStep,
    /// FMI 3.0 Configuration Mode (structural parameters).
    EnterConfigurationMode,
    ExitConfigurationMode,
    /// FMI 3.0 functions this FMU does not provide (clocks, configuration, adjoints, ...):
    /// allowed in every state, refused by their body with the reason.
    Unsupported,
}

impl Call {
    /// The interface type the call belongs to (`None`: both).
    pub fn interface(self) -> Option<Interface> {
        use Call::*;
        match self {
            DoStep | FinishStep | CancelStep | GetStatus | SetRealInputDerivatives | GetRealOutputDerivatives => Some(Interface::CoSimulation),
            EnterEventMode | NewDiscreteStates | EnterContinuousTimeMode | CompletedIntegratorStep | SetTime
            | SetContinuousStates | GetDerivatives | GetEventIndicators | GetContinuousStates
            | GetNominalsOfContinuousStates | GetNumberOf => Some(Interface::ModelExchange),
            _ => None,
        }
    }

    /// States in which `version` allows the call: FMI 2.0's table ([`Call::allowed`]), and
    /// where FMI 3.0 differs, its rules.
    pub fn allowed_in(self, m: Machine, version: Version) -> bool {
        match version {
            Version::Fmi2 => self.allowed(m),
            // FMI 3.0, section 2.3.2: fmi3Get* also reads start values in Instantiated and
            // Configuration Mode (the arrays refuse outputs and states there).
            Version::Fmi3 => self.allowed(m) || (self == Call::Get && matches!(m, Machine::Instantiated | Machine::ConfigurationMode)),
        }
    }

    /// The call's name in `version`.
    pub fn name(self, version: Version) -> String {
        match version {
            Version::Fmi2 => self.fmi_name().to_string(),
            Version::Fmi3 => self.fmi3_name(),
        }
    }

    /// States in which FMI 2.0 allows the call (FMI 3.0's extra states included: an FMI 2.0
    /// instance never enters them).
    pub fn allowed(self, m: Machine) -> bool {
        use Machine::*;
        if m == IntermediateUpdate {
            // FMI 3.0, section 4.2.4: the importer sets the required intermediate inputs
            // from inside the callback (getting them is not allowed: we pass
            // intermediateVariableGetAllowed = false); the step then finishes.
            return matches!(self, Call::Set | Call::FinishStep);
        }
        if m == Error {
            // After an internal failure only recovery and inspection remain.
            return matches!(
                self,
                Call::SetDebugLogging | Call::Reset | Call::Get | Call::GetFmuState | Call::SetFmuState | Call::FreeFmuState
                    | Call::SerializeFmuState | Call::DeSerializeFmuState | Call::GetDerivatives | Call::GetEventIndicators
                    | Call::GetContinuousStates | Call::GetNominalsOfContinuousStates
            );
        }
        match self {
            Call::SetupExperiment | Call::EnterInitializationMode => m == Instantiated,
            Call::ExitInitializationMode => m == InitializationMode,
            Call::DoStep => m == StepComplete,
            Call::Terminate => matches!(m, StepComplete | EventMode | ContinuousTimeMode),
            Call::EnterEventMode | Call::SetTime => matches!(m, EventMode | ContinuousTimeMode),
            Call::NewDiscreteStates | Call::EnterContinuousTimeMode => m == EventMode,
            Call::CompletedIntegratorStep | Call::SetContinuousStates => m == ContinuousTimeMode,
            Call::GetEventIndicators | Call::GetContinuousStates => {
                matches!(m, InitializationMode | EventMode | ContinuousTimeMode | Terminated)
            }
            Call::GetDerivatives => matches!(m, EventMode | ContinuousTimeMode | Terminated),
            Call::GetNominalsOfContinuousStates => matches!(m, Instantiated | EventMode | ContinuousTimeMode | Terminated),
            Call::GetNumberOf | Call::Unsupported => true,
            Call::EnterConfigurationMode => m == Instantiated,
            Call::FinishStep => m == IntermediateUpdate,
            Call::ExitConfigurationMode => m == ConfigurationMode,
            Call::SetDebugLogging
            | Call::Reset
            | Call::GetFmuState
            | Call::SetFmuState
            | Call::FreeFmuState
            | Call::SerializeFmuState
            | Call::DeSerializeFmuState => true,
            Call::Get | Call::GetDirectionalDerivative => !matches!(m, Instantiated | IntermediateUpdate),
            Call::Set => m != Terminated,
            Call::SetRealInputDerivatives => matches!(m, Instantiated | InitializationMode | StepComplete),
            Call::GetStatus | Call::GetRealOutputDerivatives => matches!(m, StepComplete | Terminated),
            // Refused by its body: steps are never asynchronous, so there is nothing to cancel.
            Call::CancelStep => true,
        }
    }

    pub fn fmi_name(self) -> &'static str {
        match self {
            Call::SetDebugLogging => "fmi2SetDebugLogging",
            Call::SetupExperiment => "fmi2SetupExperiment",
            Call::EnterInitializationMode => "fmi2EnterInitializationMode",
            Call::ExitInitializationMode => "fmi2ExitInitializationMode",
            Call::Terminate => "fmi2Terminate",
            Call::Reset => "fmi2Reset",
            Call::Get => "fmi2Get*",
            Call::Set => "fmi2Set*",
            Call::GetFmuState => "fmi2GetFMUstate",
            Call::SetFmuState => "fmi2SetFMUstate",
            Call::FreeFmuState => "fmi2FreeFMUstate",
            Call::SerializeFmuState => "fmi2SerializeFMUstate",
            Call::DeSerializeFmuState => "fmi2DeSerializeFMUstate",
            Call::DoStep => "fmi2DoStep",
            Call::CancelStep => "fmi2CancelStep",
            Call::GetStatus => "fmi2Get*Status",
            Call::GetDirectionalDerivative => "fmi2GetDirectionalDerivative",
            Call::SetRealInputDerivatives => "fmi2SetRealInputDerivatives",
            Call::GetRealOutputDerivatives => "fmi2GetRealOutputDerivatives",
            Call::EnterEventMode => "fmi2EnterEventMode",
            Call::NewDiscreteStates => "fmi2NewDiscreteStates",
            Call::EnterContinuousTimeMode => "fmi2EnterContinuousTimeMode",
            Call::CompletedIntegratorStep => "fmi2CompletedIntegratorStep",
            Call::SetTime => "fmi2SetTime",
            Call::SetContinuousStates => "fmi2SetContinuousStates",
            Call::GetDerivatives => "fmi2GetDerivatives",
            Call::GetEventIndicators => "fmi2GetEventIndicators",
            Call::GetContinuousStates => "fmi2GetContinuousStates",
            Call::GetNominalsOfContinuousStates => "fmi2GetNominalsOfContinuousStates",
            // Calls that exist in FMI 3.0 only, under their only names.
            Call::GetNumberOf => "fmi3GetNumberOf*",
            Call::EnterConfigurationMode => "fmi3EnterConfigurationMode",
            Call::FinishStep => "fmi3DoStep",
            Call::ExitConfigurationMode => "fmi3ExitConfigurationMode",
            Call::Unsupported => "fmi3",
        }
    }

    /// The FMI 3.0 name, where it is not the FMI 2.0 one with `fmi3` for `fmi2`.
    pub fn fmi3_name(self) -> String {
        match self {
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
            other => other.fmi_name().replacen("fmi2", "fmi3", 1),
        }
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
pub fn fmi3_text(text: &str) -> String {
    let mut out = text.to_string();
    for (fmi2, fmi3) in FMI3_WORDS {
        out = out.replace(fmi2, fmi3);
    }
    out.replace("fmi2", "fmi3")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Calls that exist in FMI 3.0 only are named as FMI 3.0 names them, whatever the
    /// instance's version: there is no `fmi2EnterConfigurationMode` to point a reader to.
    #[test]
    fn fmi3_only_calls_have_no_fmi2_name() {
        for call in [Call::EnterConfigurationMode, Call::ExitConfigurationMode, Call::GetNumberOf, Call::FinishStep] {
            for version in [Version::Fmi2, Version::Fmi3] {
                assert!(call.name(version).starts_with("fmi3"), "{call:?} in {version:?}: {}", call.name(version));
            }
        }
        assert_eq!(Call::GetFmuState.name(Version::Fmi2), "fmi2GetFMUstate");
        assert_eq!(Call::GetFmuState.name(Version::Fmi3), "fmi3GetFMUState");
    }
}
