//! The state machine of an instance ([`Machine`]) and the master's clock ([`Clock`], with
//! the tolerance on communication points, [`time_slack`]): what the glue keeps for every
//! model besides the model itself. Which call is allowed in which state is [`crate::fmi::common::call`].

/// The interface type an instance was made for (`fmi2Instantiate`'s `fmuType`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface {
    ModelExchange,
    CoSimulation,
}

/// The FMI 2.0 state machine's states: co-simulation (synchronous, section 4.2.4) and
/// Model Exchange (section 3.2.3) share all but `StepComplete` (co-simulation) and
/// `EventMode`, `ContinuousTimeMode` (Model Exchange).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Machine {
    Instantiated,
    InitializationMode,
    StepComplete,
    Terminated,
    /// After an internal failure: only reset, restore or inspection are allowed.
    Error,
    EventMode,
    ContinuousTimeMode,
    /// FMI 3.0: structural parameters may be set (entered from `Instantiated`).
    ConfigurationMode,
    /// FMI 3.0 co-simulation: inside `fmi3DoStep`, while the importer's `intermediateUpdate`
    /// runs; only the required intermediate inputs may be set.
    IntermediateUpdate,
}

impl Machine {
    pub fn code(self) -> u8 {
        self as u8
    }

    pub fn from_code(c: u8) -> Option<Self> {
        [
            Self::Instantiated,
            Self::InitializationMode,
            Self::StepComplete,
            Self::Terminated,
            Self::Error,
            Self::EventMode,
            Self::ContinuousTimeMode,
            Self::ConfigurationMode,
            Self::IntermediateUpdate,
        ]
        .get(c as usize)
        .copied()
    }

    /// Whether an instance of `interface` can be in this state.
    pub fn belongs_to(self, interface: Interface) -> bool {
        match self {
            Self::StepComplete | Self::IntermediateUpdate => interface == Interface::CoSimulation,
            Self::EventMode | Self::ContinuousTimeMode => interface == Interface::ModelExchange,
            _ => true,
        }
    }
}

/// The master's clock of one instance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clock {
    /// `startTime` of `fmi2SetupExperiment`: the cut, time 0 of every model.
    pub start: f64,
    pub stop: Option<f64>,
    /// Master time of the last communication point.
    pub time: f64,
}

impl Clock {
    /// The time a model sees: since `startTime`, so that every model puts the cut at the
    /// same instant whatever the master's time origin.
    pub fn since_start(&self) -> f64 {
        self.time - self.start
    }
}

/// How far apart the master's time and the instance's may be and still be the same
/// instant, for a step `h` at time `t`:
///
/// ```text
/// |currentCommunicationPoint - time| <= 1e-6 h + 4 eps |t|        (eps = f64::EPSILON)
/// ```
///
/// 4 eps |t| is a few roundings of a time near t, whatever the step (a master that sums
/// its steps, or computes t_n = n h, differs from t + h by that much); 1e-6 h lets a master
/// whose clock is coarser than that still through, while a point a millionth of a step
/// away from the instance's time is refused. The same slack bounds how far a step may end
/// past `stopTime`.
pub fn time_slack(h: f64, t: f64) -> f64 {
    1e-6 * h + 4.0 * f64::EPSILON * t.abs()
}
