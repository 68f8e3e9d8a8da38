//! The FMI calls an instance answers: in which states of the FMI 2.0 co-simulation state
//! machine each is allowed (section 4.2.4), and its name for messages.

use super::machine::Machine;

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
}

impl Call {
    /// States in which FMI 2.0 (section 4.2.4) allows the call.
    pub fn allowed(self, m: Machine) -> bool {
        use Machine::*;
        if m == Error {
            // After an internal failure only recovery and inspection remain.
            return matches!(
                self,
                Call::SetDebugLogging | Call::Reset | Call::Get | Call::GetFmuState | Call::SetFmuState | Call::FreeFmuState
                    | Call::SerializeFmuState | Call::DeSerializeFmuState
            );
        }
        match self {
            Call::SetupExperiment | Call::EnterInitializationMode => m == Instantiated,
            Call::ExitInitializationMode => m == InitializationMode,
            Call::Terminate | Call::DoStep => m == StepComplete,
            Call::SetDebugLogging
            | Call::Reset
            | Call::GetFmuState
            | Call::SetFmuState
            | Call::FreeFmuState
            | Call::SerializeFmuState
            | Call::DeSerializeFmuState => true,
            Call::Get | Call::GetDirectionalDerivative => m != Instantiated,
            Call::Set | Call::SetRealInputDerivatives => m != Terminated,
            Call::GetStatus | Call::GetRealOutputDerivatives => matches!(m, StepComplete | Terminated),
            Call::CancelStep => false,
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
        }
    }
}
