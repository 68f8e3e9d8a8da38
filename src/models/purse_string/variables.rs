//! The purse-string FMU's variables: the one table that `modelDescription.xml` is
//! generated from ([`crate::fmi::fmi2::xml`]), and that the code uses.

pub use crate::fmi::common::model::{Description, Experiment, Unit, Variable};

/// `modelIdentifier` of the FMU (and the name of its shared object).
pub const MODEL_IDENTIFIER: &str = "PurseString";
/// `guid` of its `modelDescription.xml`.
pub const GUID: &str = "{3f9b2d71-6c4a-4e8f-b5d0-91a7e2c4f6b3}";

/// `description` of `modelDescription.xml`.
pub const SUMMARY: &str = "Actin purse-string closing a wound: line tension T_c(t) = T_max (1 - exp(-(t - t_delay) / t_assembly)) after a delay, giving the edge stress p = T_c / (h R) on a wound of radius R. Couples to WoundOpening (wound_radius to wound_radius, edge_stress to edge_stress).";

crate::variable_table! {
    MaxTension => parameter("T_max", 6500.0, "pN", "Saturated line tension of the actin cable (0 ..= 1e9)"),
    AssemblyTime => parameter("t_assembly", 30.0, "s", "Assembly time constant t_a of the line tension (>= 0; 0 = a step)"),
    Delay => parameter("t_delay", 20.0, "s", "Delay after the cut (the master's startTime) before assembly starts (>= 0)"),
    Thickness => parameter("thickness", 5.0, "um", "Thickness h of the cell sheet (1e-6 ..= 1e6)"),
    WoundRadius => input("wound_radius", 10.0, "um", "Wound radius R received from the tissue model (1e-6 ..= 1e9)"),
    EdgeStress => output("edge_stress", "Pa", "Edge stress p = T_c / (h R) pulling the wound edge inwards"),
    LineTension => output("line_tension", "pN", "Line tension T_c(t) = T_max (1 - exp(-(t - t_delay) / t_assembly)) after the delay"),
}

/// The units of the variables (SI base units for `<UnitDefinitions>`).
pub const UNITS: [Unit; 4] = [
    ("Pa", &[("kg", "1"), ("m", "-1"), ("s", "-2")]),
    ("pN", &[("kg", "1"), ("m", "1"), ("s", "-2"), ("factor", "1e-12")]),
    ("s", &[("s", "1")]),
    ("um", &[("m", "1"), ("factor", "1e-6")]),
];

/// The table in the form the shared glue reads.
pub static DESCRIPTION: Description = Description {
    model_identifier: MODEL_IDENTIFIER,
    guid: GUID,
    summary: SUMMARY,
    about: include_str!("about.html"),
    variables: VARIABLES,
    // p = T_c / (h R) is nonlinear in R (`dependent`); T_c depends on time only.
    outputs: &[
        (Vr::EdgeStress as u32, &[(Vr::WoundRadius as u32, "dependent")]),
        (Vr::LineTension as u32, &[]),
    ],
    initial_unknowns: &[
        (
            Vr::EdgeStress as u32,
            &[
                Vr::MaxTension as u32,
                Vr::AssemblyTime as u32,
                Vr::Delay as u32,
                Vr::Thickness as u32,
                Vr::WoundRadius as u32,
            ],
        ),
        (
            Vr::LineTension as u32,
            &[Vr::MaxTension as u32, Vr::AssemblyTime as u32, Vr::Delay as u32],
        ),
    ],
    units: &UNITS,
    default_experiment: Experiment { start: 0.0, stop: 300.0, step: 0.5, tolerance: 1e-10 },
    // A closed form in time: nothing to integrate.
    states: None,
    arrays: None,
};
