//! The component's variables: the one table that `modelDescription.xml` must match
//! (checked by `tests/model_description.rs`).

/// `modelIdentifier` of the FMU (and the name of its shared object).
pub const MODEL_IDENTIFIER: &str = "WoundOpening";
/// `guid` of `modelDescription.xml`; `fmi2Instantiate` rejects any other.
pub const GUID: &str = "{8c4e1f0a-3b7d-4e52-9a61-2f0d5c7b9e14}";

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    Input,
    Output,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Parameter => "parameter",
            Self::Input => "input",
            Self::Output => "output",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    Fixed,
    Continuous,
}

impl Variability {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Fixed => "fixed",
            Self::Continuous => "continuous",
        }
    }
}

/// The FMI type of a variable.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Real,
    Integer,
}

impl Kind {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Real => "Real",
            Self::Integer => "Integer",
        }
    }
}

/// Value references, in the order of the table (index = value reference).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u32)]
pub enum Vr {
    Lambda = 0,
    Sigma = 1,
    RInf = 2,
    EdgeStress = 3,
    WoundRadius = 4,
    EdgeVelocity = 5,
    Tolerance = 6,
    Method = 7,
    GridPoints = 8,
    InternalStep = 9,
}

impl Vr {
    pub const ALL: [Vr; 10] = [
        Vr::Lambda,
        Vr::Sigma,
        Vr::RInf,
        Vr::EdgeStress,
        Vr::WoundRadius,
        Vr::EdgeVelocity,
        Vr::Tolerance,
        Vr::Method,
        Vr::GridPoints,
        Vr::InternalStep,
    ];

    pub fn from_u32(vr: u32) -> Option<Self> {
        Self::ALL.get(vr as usize).copied()
    }

    pub fn var(self) -> &'static Variable {
        &VARIABLES[self as usize]
    }
}

/// One `ScalarVariable`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variable {
    pub name: &'static str,
    pub value_reference: u32,
    pub kind: Kind,
    pub causality: Causality,
    pub variability: Variability,
    /// `Some` for parameters and inputs (`initial` is then exact or absent).
    pub start: Option<f64>,
    /// Unit of a Real (empty for an Integer).
    pub unit: &'static str,
    /// Declared `min` and `max` (Integers only).
    pub range: Option<(i32, i32)>,
    pub description: &'static str,
}

pub const VARIABLES: [Variable; 10] = [
    Variable {
        name: "lambda",
        value_reference: 0,
        kind: Kind::Real,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(1.0),
        unit: "1",
        range: None,
        description: "Viscous length over wound radius, 2 sqrt(eta/zeta)/R0 (>= 0)",
    },
    Variable {
        name: "sigma",
        value_reference: 1,
        kind: Kind::Real,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(1.0),
        unit: "G",
        range: None,
        description: "Homeostatic tension over shear modulus",
    },
    Variable {
        name: "R_inf",
        value_reference: 2,
        kind: Kind::Real,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(10.0),
        unit: "R0",
        range: None,
        description: "Outer radius of the tissue over wound radius (> 1, <= 1e6)",
    },
    Variable {
        name: "edge_stress",
        value_reference: 3,
        kind: Kind::Real,
        causality: Causality::Input,
        variability: Variability::Continuous,
        start: Some(0.0),
        unit: "G",
        range: None,
        description: "Radial stress applied at the wound edge, held over each step (0 = free edge)",
    },
    Variable {
        name: "wound_radius",
        value_reference: 4,
        kind: Kind::Real,
        causality: Causality::Output,
        variability: Variability::Continuous,
        start: None,
        unit: "R0",
        range: None,
        description: "Wound radius R(t) = 1 + u(1, t)",
    },
    Variable {
        name: "edge_velocity",
        value_reference: 5,
        kind: Kind::Real,
        causality: Causality::Output,
        variability: Variability::Continuous,
        start: None,
        unit: "R0/T",
        range: None,
        description: "Edge velocity dR/dt under the current edge_stress",
    },
    Variable {
        name: "tolerance",
        value_reference: 6,
        kind: Kind::Real,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(1e-10),
        unit: "1",
        range: None,
        description: "Accuracy target when fmi2SetupExperiment defines none: max |R - R_exact| / (R_final - R1) for t >= 0.01; sets the mesh",
    },
    Variable {
        name: "method",
        value_reference: 7,
        kind: Kind::Integer,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(0.0),
        unit: "",
        range: Some((0, 3)),
        description: "0: spectral elements, exact in time (mesh from the tolerance); 1: TR-BDF2 on that mesh; 2: the paper's scheme; 3: explicit scheme",
    },
    Variable {
        name: "grid_points",
        value_reference: 8,
        kind: Kind::Integer,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(101.0),
        unit: "",
        range: Some((3, 100000)),
        description: "Uniform grid points of methods 2 and 3",
    },
    Variable {
        name: "internal_step",
        value_reference: 9,
        kind: Kind::Real,
        causality: Causality::Parameter,
        variability: Variability::Fixed,
        start: Some(1e-3),
        unit: "T",
        range: None,
        description: "Largest internal time step of methods 1 to 3",
    },
];

/// `ModelStructure/Outputs`: each output with the inputs it depends on directly, and
/// the `dependenciesKind` of each (`fixed`: linear with a factor set by fixed parameters).
pub const OUTPUT_DEPENDENCIES: [(Vr, &[(Vr, &str)]); 2] = [
    (Vr::WoundRadius, &[]),
    (Vr::EdgeVelocity, &[(Vr::EdgeStress, "fixed")]),
];

/// `ModelStructure/InitialUnknowns`: the outputs at initialization and the knowns they
/// depend on (`R1 = 1 + sigma/6`; the initial velocity depends on everything).
pub const INITIAL_DEPENDENCIES: [(Vr, &[Vr]); 2] = [
    (Vr::WoundRadius, &[Vr::Sigma]),
    (
        Vr::EdgeVelocity,
        &[Vr::Lambda, Vr::Sigma, Vr::RInf, Vr::EdgeStress, Vr::Tolerance, Vr::Method, Vr::GridPoints, Vr::InternalStep],
    ),
];

/// Log categories declared in `modelDescription.xml`, with their descriptions.
pub const LOG_CATEGORIES: [(&str, &str); 3] = [
    ("logStatusError", "Errors: rejected calls and values, with the reason"),
    ("logStatusWarning", "Warnings"),
    ("logCalls", "Every FMI call with its arguments, and solver set-up details"),
];

/// Capability flags of `<CoSimulation>` that the code relies on.
pub const CAPABILITIES: [(&str, &str); 8] = [
    ("canHandleVariableCommunicationStepSize", "true"),
    ("canGetAndSetFMUstate", "true"),
    ("canSerializeFMUstate", "true"),
    ("providesDirectionalDerivative", "false"),
    ("canInterpolateInputs", "false"),
    ("maxOutputDerivativeOrder", "0"),
    ("canRunAsynchronuously", "false"),
    ("canNotUseMemoryManagementFunctions", "true"),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_references_are_table_indices() {
        for (i, v) in VARIABLES.iter().enumerate() {
            assert_eq!(v.value_reference as usize, i, "{}", v.name);
            assert_eq!(Vr::from_u32(i as u32).map(|vr| vr.var().name), Some(v.name));
        }
        assert_eq!(Vr::from_u32(VARIABLES.len() as u32), None);
    }
}
