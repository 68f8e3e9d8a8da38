//! What the shared FMI glue knows of a model: its description (identity, variables,
//! dependencies, the XML) and the [`FmuModel`] trait (in model/fmu_model.rs). The glue
//! ([`crate::fmi::common::instance`], [`crate::fmi::fmi2::functions`]) runs the state machine, the clock, logging and
//! FMU states for any model; a model sees plain values only.

mod fmu_model;
pub use fmu_model::FmuModel;

/// Log categories of every model's `modelDescription.xml`, with their descriptions.
pub const LOG_CATEGORIES: [(&str, &str); 4] = [
    ("logStatusError", "Errors: rejected calls and values, with the reason"),
    ("logStatusWarning", "Warnings"),
    ("logStatusDiscard", "Discarded calls: status information this FMU does not provide"),
    ("logCalls", "Every FMI call with its arguments, and solver set-up details"),
];

/// A refused call or value: the reason, for the logger.
pub type Rejected = String;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    Input,
    Output,
    /// A continuous state or its derivative (Model Exchange).
    Local,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Parameter => "parameter",
            Self::Input => "input",
            Self::Output => "output",
            Self::Local => "local",
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

impl Variable {
    /// A fixed Real parameter.
    pub const fn parameter(
        name: &'static str,
        vr: u32,
        start: f64,
        unit: &'static str,
        description: &'static str,
    ) -> Self {
        let (kind, causality, variability, range) =
            (Kind::Real, Causality::Parameter, Variability::Fixed, None);
        Self {
            name,
            value_reference: vr,
            kind,
            causality,
            variability,
            start: Some(start),
            unit,
            range,
            description,
        }
    }

    /// A fixed Integer parameter in `min ..= max`.
    pub const fn integer(
        name: &'static str,
        vr: u32,
        start: i32,
        range: (i32, i32),
        description: &'static str,
    ) -> Self {
        let (kind, causality, variability, unit) =
            (Kind::Integer, Causality::Parameter, Variability::Fixed, "");
        let start = Some(start as f64);
        Self {
            name,
            value_reference: vr,
            kind,
            causality,
            variability,
            start,
            unit,
            range: Some(range),
            description,
        }
    }

    /// A continuous Real output.
    pub const fn output(
        name: &'static str,
        vr: u32,
        unit: &'static str,
        description: &'static str,
    ) -> Self {
        let (kind, causality, variability, range) =
            (Kind::Real, Causality::Output, Variability::Continuous, None);
        Self {
            name,
            value_reference: vr,
            kind,
            causality,
            variability,
            start: None,
            unit,
            range,
            description,
        }
    }

    /// A continuous Real input.
    pub const fn input(
        name: &'static str,
        vr: u32,
        start: f64,
        unit: &'static str,
        description: &'static str,
    ) -> Self {
        let (kind, causality, variability, range) =
            (Kind::Real, Causality::Input, Variability::Continuous, None);
        Self {
            name,
            value_reference: vr,
            kind,
            causality,
            variability,
            start: Some(start),
            unit,
            range,
            description,
        }
    }
}

/// A model's variable table, declared once: each row names its value-reference constant
/// and the [`Variable`] constructor with its arguments but the value reference, which is the
/// row's position. Defines `enum Vr` (the constants, whose discriminants are the value
/// references; `Vr::ALL` in table order, `from_u32`, `var`) and `VARIABLES`, from which the
/// glue, the XML and the documentation all read.
///
/// A row added after an interface was published takes `= N` after its constant: a value
/// reference after every other one (the continuous states and derivatives follow the rows
/// numbered by position, FMI 3.0's `time` and arrays follow them), so that none moves.
/// Such rows come last ([`Description::first_state`]).
///
/// ```text
/// variable_table! {
///     Gain => parameter("gain", 1.0, "1", "What the gain is ..."),
///     Output => output("y", "m", "What y is ..."),
///     Late = 1000 => integer("late", 0, (0, 1), "Added later ..."),
/// }
/// ```
#[macro_export]
macro_rules! variable_table {
    ($($vr:ident $(= $at:literal)? => $ctor:ident($name:literal $(, $arg:expr)* $(,)?)),+ $(,)?) => {
        /// Value references, in the order of the table.
        #[derive(Debug, Clone, Copy, PartialEq, Eq)]
        #[repr(u32)]
        pub enum Vr {
            $($vr $(= $at)?),+
        }

        impl Vr {
            /// Every value reference, in table order.
            pub const ALL: &'static [Vr] = &[$(Vr::$vr),+];

            pub fn from_u32(vr: u32) -> Option<Self> {
                Self::ALL.iter().copied().find(|&v| v as u32 == vr)
            }

            pub fn var(self) -> &'static Variable {
                VARIABLES.iter().find(|v| v.value_reference == self as u32).expect("every constant has its row")
            }
        }

        /// The variables, in table order.
        pub const VARIABLES: &[Variable] = &[$(Variable::$ctor($name, Vr::$vr as u32 $(, $arg)*)),+];
    };
}

/// A unit a model's variables declare (`<UnitDefinitions>`): its name, then `(attribute,
/// value)` of its `<BaseUnit>` (none for "1").
pub type Unit = (&'static str, &'static [(&'static str, &'static str)]);

/// `<DefaultExperiment>`: what a master runs when told nothing, and what the reference
/// results of the archive are computed with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Experiment {
    pub start: f64,
    pub stop: f64,
    pub step: f64,
    pub tolerance: f64,
}

/// A model as the glue, the description generator ([`crate::fmi::fmi2::xml`]) and the packaging see
/// it: every `modelDescription.xml` is generated from this table, so the XML and the code
/// cannot disagree.
#[derive(Debug)]
pub struct Description {
    pub model_identifier: &'static str,
    /// `guid` (FMI 2.0) and `instantiationToken` (FMI 3.0).
    pub guid: &'static str,
    /// `fmiModelDescription/@description`.
    pub summary: &'static str,
    /// The model in HTML, for `documentation/index.html`.
    pub about: &'static str,
    /// In table order: indexed by value reference up to [`Description::first_state`],
    /// then the rows added later, with value references after every other.
    pub variables: &'static [Variable],
    /// `ModelStructure/Outputs`: each output's value reference with the inputs it depends
    /// on directly and the `dependenciesKind` of each.
    pub outputs: &'static [(u32, &'static [(u32, &'static str)])],
    /// `ModelStructure/InitialUnknowns`: value references of the unknown and its knowns.
    pub initial_unknowns: &'static [(u32, &'static [u32])],
    pub default_experiment: Experiment,
    /// The units its variables use, in the order of `<UnitDefinitions>`.
    pub units: &'static [Unit],
    /// Continuous states for Model Exchange, if any (see [`ContinuousStates`]).
    pub states: Option<ContinuousStates>,
    /// FMI 3.0 only: array variables sized by a structural parameter (see [`Arrays`]).
    pub arrays: Option<Arrays>,
}

/// FMI 3.0 array variables whose length is one structural parameter (`UInt64`,
/// settable in Configuration Mode), after the independent variable `time`:
///
/// ```text
/// value reference  time + 1        the structural parameter (the length)
///                  time + 2 + j    arrays[j]
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arrays {
    pub length_name: &'static str,
    pub length_description: &'static str,
    /// Start and largest accepted length.
    pub length_start: u64,
    pub length_max: u64,
    pub arrays: &'static [ArrayVariable],
}

/// One array of [`Arrays`]: a fixed parameter (with start values, as many as the start
/// length) or a continuous output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrayVariable {
    pub name: &'static str,
    pub causality: Causality,
    pub unit: &'static str,
    pub start: &'static [f64],
    pub description: &'static str,
    /// Inputs (table value references) an output depends on directly, with their kind.
    pub input_dependencies: &'static [(u32, &'static str)],
}

/// A model's continuous states (Model Exchange): `count` state variables and as many
/// derivatives, after the table's variables. FMI 2.0 fixes the number of states in the
/// XML, so `count` is the most the accepted domain needs; a model using fewer keeps the
/// rest at 0 with derivative 0.
///
/// ```text
/// value reference  table.len() + k            name[k+1]         k = 0 .. count
///                  table.len() + count + k    der(name[k+1])
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContinuousStates {
    pub count: usize,
    pub name: &'static str,
    pub unit: &'static str,
    pub description: &'static str,
    /// Unit of the derivatives.
    pub derivative_unit: &'static str,
    /// Which table variables (inputs and parameters) the derivatives depend on at
    /// initialization, and which inputs during the run (with `dependenciesKind`).
    pub initial_dependencies: &'static [u32],
    pub input_dependencies: &'static [(u32, &'static str)],
}

/// What a value reference names: a row of the table, a state or a derivative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Named {
    Table(&'static Variable),
    State(usize),
    Derivative(usize),
}

impl Description {
    /// The variable of a value reference, which must be of type `kind`.
    pub fn typed(&self, kind: Kind, vr: u32) -> Result<&'static Variable, Rejected> {
        match self.variables.iter().find(|v| v.value_reference == vr) {
            Some(v) if v.kind == kind => Ok(v),
            Some(v) => Err(format!(
                "{} (value reference {vr}) is {}, not {}",
                v.name,
                v.kind.as_str(),
                kind.as_str()
            )),
            None => Err(format!("no {} variable has value reference {vr}", kind.as_str())),
        }
    }

    /// Value reference of the first continuous state: the number of leading rows whose value
    /// reference is their position (the table less the rows added later).
    pub fn first_state(&self) -> u32 {
        self.variables.iter().zip(0..).take_while(|(v, i)| v.value_reference == *i).count() as u32
    }

    /// The rows added later (value references after every other), in table order.
    pub fn later_rows(&self) -> &'static [Variable] {
        &self.variables[self.first_state() as usize..]
    }

    /// Number of continuous states (0 without Model Exchange states).
    pub fn state_count(&self) -> usize {
        self.states.map_or(0, |s| s.count)
    }

    /// What `vr` names, if it is a variable of type `kind` (states are Reals).
    pub fn named(&self, kind: Kind, vr: u32) -> Result<Named, Rejected> {
        let (first, n) = (self.first_state() as usize, self.state_count());
        let k = (vr as usize).wrapping_sub(first);
        match self.typed(kind, vr) {
            Err(_) if k < 2 * n && kind == Kind::Real => {
                Ok(if k < n { Named::State(k) } else { Named::Derivative(k - n) })
            }
            row => row.map(Named::Table),
        }
    }

    /// The name of a state's or derivative's variable.
    pub fn state_name(&self, named: Named) -> String {
        let s = self.states.map_or("x", |s| s.name);
        match named {
            Named::Table(v) => v.name.to_owned(),
            Named::State(k) => format!("{s}[{}]", k + 1),
            Named::Derivative(k) => format!("der({s}[{}])", k + 1),
        }
    }
}
