//! The FMI calls an instance answers: in which states of the FMI 2.0 state machines each
//! is allowed (co-simulation, section 4.2.4; Model Exchange, section 3.2.3, as the
//! Reference-FMUs' masks in `fmi2Functions.c` read it) and for which interface type; what
//! differs between versions (the calls' names, a rule or two) is a [`Dialect`] that each
//! version's folder defines (`src/fmi/fmi2/names.rs`, `src/fmi/fmi3/names.rs`).

use crate::fmi::common::machine::{Interface, Machine};

/// What differs between the FMI versions an instance can be made through: the names its
/// importer knows the functions by and the rules where they differ. Each version's folder
/// defines its own; the core names none.
#[derive(Debug, Clone, Copy)]
pub struct Dialect {
    /// A call's name, for messages.
    pub name: fn(Call) -> String,
    /// The Get calls also read start values in Instantiated and Configuration Mode
    /// (the arrays refuse outputs and states there).
    pub get_before_initialization: bool,
    /// Configuration Mode exists: an FMU state saved there can be restored.
    pub configuration_mode: bool,
    /// The arguments of the directional derivative as this version names them: the
    /// unknowns, the knowns and the seed.
    pub derivative_arguments: [&'static str; 3],
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
            DoStep
            | FinishStep
            | CancelStep
            | GetStatus
            | SetRealInputDerivatives
            | GetRealOutputDerivatives => Some(Interface::CoSimulation),
            EnterEventMode
            | NewDiscreteStates
            | EnterContinuousTimeMode
            | CompletedIntegratorStep
            | SetTime
            | SetContinuousStates
            | GetDerivatives
            | GetEventIndicators
            | GetContinuousStates
            | GetNominalsOfContinuousStates
            | GetNumberOf => Some(Interface::ModelExchange),
            _ => None,
        }
    }

    /// States in which `dialect` allows the call: FMI 2.0's table ([`Call::allowed`]), and
    /// where the dialect differs, its rules.
    pub fn allowed_in(self, m: Machine, dialect: &Dialect) -> bool {
        self.allowed(m)
            || (dialect.get_before_initialization
                && self == Call::Get
                && matches!(m, Machine::Instantiated | Machine::ConfigurationMode))
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
                Call::SetDebugLogging
                    | Call::Reset
                    | Call::Get
                    | Call::GetFmuState
                    | Call::SetFmuState
                    | Call::FreeFmuState
                    | Call::SerializeFmuState
                    | Call::DeSerializeFmuState
                    | Call::GetDerivatives
                    | Call::GetEventIndicators
                    | Call::GetContinuousStates
                    | Call::GetNominalsOfContinuousStates
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
            Call::GetNominalsOfContinuousStates => {
                matches!(m, Instantiated | EventMode | ContinuousTimeMode | Terminated)
            }
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
            Call::Get | Call::GetDirectionalDerivative => {
                !matches!(m, Instantiated | IntermediateUpdate)
            }
            Call::Set => m != Terminated,
            Call::SetRealInputDerivatives => {
                matches!(m, Instantiated | InitializationMode | StepComplete)
            }
            Call::GetStatus | Call::GetRealOutputDerivatives => {
                matches!(m, StepComplete | Terminated)
            }
            // Refused by its body: steps are never asynchronous, so there is nothing to cancel.
            Call::CancelStep => true,
        }
    }
}
