//! FMI 2.0's [`Dialect`]: the names of its functions, and its rules where the core's
//! differ (none: the core's table is FMI 2.0's).

#![forbid(unsafe_code)]

use crate::fmi::common::call::{Call, Dialect};
use crate::fmi::common::instance::{Instance, Interface, Logger};
use crate::fmi::common::model::FmuModel;
use std::sync::Arc;

impl Instance {
    /// An FMI 2.0 co-simulation instance of the model that `fresh` makes.
    pub fn new(
        fresh: fn() -> Box<dyn FmuModel>,
        name: &str,
        logger: Arc<dyn Logger>,
        logging_on: bool,
    ) -> Self {
        Self::of_interface(Interface::CoSimulation, FMI2, fresh, name, logger, logging_on)
    }
}

pub const FMI2: Dialect = Dialect {
    name: |c| name(c).to_string(),
    get_before_initialization: false,
    configuration_mode: false,
    derivative_arguments: ["vUnknown_ref", "vKnown_ref", "dvKnown"],
};

/// The call's FMI 2.0 name (calls that exist in FMI 3.0 only under their only names).
pub fn name(call: Call) -> &'static str {
    match call {
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
