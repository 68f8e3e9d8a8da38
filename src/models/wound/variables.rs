//! The wound FMU's variables: the one table that `modelDescription.xml` is generated
//! from ([`crate::fmi::fmi2::xml`]), and that the code uses.

pub use crate::fmi::common::model::{
    ArrayVariable, Arrays, Causality, ContinuousStates, Description, Experiment, Kind,
    LOG_CATEGORIES, Unit, Variability, Variable,
};

/// `modelIdentifier` of the FMU (and the name of its shared object).
pub const MODEL_IDENTIFIER: &str = "WoundOpening";
/// `guid` of `modelDescription.xml`; `fmi2Instantiate` rejects any other.
pub const GUID: &str = "{8c4e1f0a-3b7d-4e52-9a61-2f0d5c7b9e14}";

/// `description` of `modelDescription.xml`.
pub const SUMMARY: &str = "Opening of a circular wound in a thin incompressible Kelvin-Voigt tissue with substrate friction. Lengths scale with R0 (wound radius), stresses with G (shear modulus), time with T = zeta R0^2 / (4 G); with R0 = 1 um, T = 1 s and G = 1 Pa (the defaults) values are dimensionless.";

crate::variable_table! {
    Lambda => parameter("lambda", 1.0, "1", "Viscous length over the cut radius, 2 sqrt(eta/zeta)/R0: 0 or in [1e-150, 1e6]"),
    Sigma => parameter("sigma", 1.0, "1", "Homeostatic tension over shear modulus, in (-6, 1e6] (R1 = R0 (1 + sigma/6) > 0)"),
    RInf => parameter("R_inf", 10.0, "1", "Outer radius of the tissue over the cut radius, in [1.001, 1e6]"),
    EdgeStress => input("edge_stress", 0.0, "Pa", "Radial stress at the wound edge [Pa], held over each step or, when the master gives its time derivative, linear in time (0 = free edge), |edge_stress| <= 1e6 G; the model sees edge_stress / G"),
    WoundRadius => output("wound_radius", "um", "Wound radius R0 (1 + u(1, t)) [um]; R1 = R0 (1 + sigma/6) just after the cut"),
    EdgeVelocity => output("edge_velocity", "um/s", "Edge velocity dR/dt [um/s] under the current edge_stress; where it is infinite (lambda = 0, at the cut and just after a change of edge_stress) the mean over the next 0.01 T, as the log says"),
    Tolerance => parameter("tolerance", 1e-10, "1", "Accuracy target when the master's experiment defines none: max |R - R_exact| for t >= 0.01 relative to the larger of the free and the actual opening, max(|sigma|, |sigma - p|) S R0 (S = R_final - R1 at sigma 1); sets the mesh; below 1e-11 the log (status OK) names the 1e-11 delivered"),
    Method => integer("method", 0, (0, 3), "0: spectral elements, exact in time (mesh from the tolerance); 1: TR-BDF2 on that mesh; 2: the paper's scheme; 3: explicit scheme"),
    GridPoints => integer("grid_points", 101, (3, 100000), "Uniform grid points of methods 2 and 3"),
    InternalStep => parameter("internal_step", 1e-3, "s", "Largest internal time step [s] of methods 1 to 3"),
    LengthScale => parameter("R0", 1.0, "um", "Length scale: the radius of the cut (1e-12 ..= 1e12; 1 keeps lengths dimensionless)"),
    TimeScale => parameter("T", 1.0, "s", "Time scale T = zeta R0^2 / (4 G) (1e-12 ..= 1e12; 1 keeps time dimensionless)"),
    StressScale => parameter("G", 1.0, "Pa", "Stress scale: the shear modulus (1e-12 ..= 1e12; 1 keeps stresses dimensionless)"),
    // Added after the interface was published: after every other value reference (13 rows,
    // 217 states and derivatives at 13 ..= 446, FMI 3.0's time, n_probes and arrays at 447 ..= 451).
    ValidityWarning = 452 => integer("validity_warning", 1, (0, 1), "How a step that leaves the model's validity (wound radius <= 0, a folded ring, an edge strain beyond 1) is reported: 1, status Warning with the reason in the log (category logStatusWarning); 0, the same log message with status OK, for masters that stop on a warning"),
}

/// Continuous states of Model Exchange: the modal coordinates of the spectral-element
/// mesh less their closed-form response to the edge stress held from the cut
/// ([`super::exchange`]). The modes are uncoupled (`c_k' = (g_k(p) - c_k) / nu_k`), so the
/// ODE is the one the co-simulation step integrates exactly, FMU states and their
/// serialization carry over unchanged (they hold the modal coordinates), and the
/// relaxation times `nu_k` state its stiffness. Nodal values would couple every unknown through the
/// mass matrix. FMI 2.0 fixes the count: the mesh of the largest accepted `R_inf` (1e6)
/// at the finest tolerance (1e-11), 27 elements of degree 8; a smaller mesh leaves the
/// last states at 0 with derivative 0.
pub const MODEL_EXCHANGE_STATES: usize = 217;

/// What the initial edge velocity (and the initial derivatives) depend on.
const INITIAL_RATE_DEPENDENCIES: [u32; 11] = [
    Vr::Lambda as u32,
    Vr::Sigma as u32,
    Vr::RInf as u32,
    Vr::EdgeStress as u32,
    Vr::Tolerance as u32,
    Vr::Method as u32,
    Vr::GridPoints as u32,
    Vr::InternalStep as u32,
    Vr::LengthScale as u32,
    Vr::TimeScale as u32,
    Vr::StressScale as u32,
];

/// The units of the variables (SI base units for `<UnitDefinitions>`).
pub const UNITS: [Unit; 6] = [
    ("1", &[]),
    ("1/s", &[("s", "-1")]),
    ("Pa", &[("kg", "1"), ("m", "-1"), ("s", "-2")]),
    ("s", &[("s", "1")]),
    ("um", &[("m", "1"), ("factor", "1e-6")]),
    ("um/s", &[("m", "1"), ("s", "-1"), ("factor", "1e-6")]),
];

/// The table in the form the shared glue reads.
pub static DESCRIPTION: Description = Description {
    model_identifier: MODEL_IDENTIFIER,
    guid: GUID,
    summary: SUMMARY,
    about: include_str!("about.html"),
    variables: VARIABLES,
    // The edge velocity is linear in the edge stress with a factor set by fixed
    // parameters (`fixed`); the radius has no direct dependence on it.
    outputs: &[
        (Vr::WoundRadius as u32, &[]),
        (Vr::EdgeVelocity as u32, &[(Vr::EdgeStress as u32, "fixed")]),
    ],
    // R1 = R0 (1 + sigma / 6); the initial velocity depends on everything but the outputs.
    initial_unknowns: &[
        (Vr::WoundRadius as u32, &[Vr::Sigma as u32, Vr::LengthScale as u32]),
        (Vr::EdgeVelocity as u32, &INITIAL_RATE_DEPENDENCIES),
    ],
    units: &UNITS,
    default_experiment: Experiment { start: 0.0, stop: 100.0, step: 0.01, tolerance: 1e-10 },
    states: Some(ContinuousStates {
        count: MODEL_EXCHANGE_STATES,
        name: "modal_coordinate",
        unit: "1",
        description: "Modal coordinate of the departure u - sigma r / 6 from the uniform tension (in R0), less its exact response to the edge stress held since initialization: 0 at the cut and while the edge stress stays; inert (derivative 0) on modes the mesh does not use",
        derivative_unit: "1/s",
        initial_dependencies: &INITIAL_RATE_DEPENDENCIES,
        input_dependencies: &[(Vr::EdgeStress as u32, "fixed")],
    }),
    arrays: Some(Arrays {
        length_name: "n_probes",
        length_description: "Number of probe radii (structural parameter: set in Configuration Mode), 1 ..= 1000",
        length_start: PROBE_RADII.len() as u64,
        length_max: 1000,
        arrays: &PROBE_ARRAYS,
    }),
};

/// Default probe radii, in um with R0 = 1 um (so in R0): the edge, the viscous boundary
/// layer at lambda = 0.1 to 1, the bulk, and the outer edge of the default R_inf.
pub const PROBE_RADII: [f64; 6] = [1.0, 1.5, 2.0, 3.0, 5.0, 10.0];

/// FMI 3.0 arrays: the radii and the displacement field and velocity there.
pub const PROBE_ARRAYS: [ArrayVariable; 3] = [
    ArrayVariable {
        name: "probe_radii",
        causality: Causality::Parameter,
        unit: "um",
        start: &PROBE_RADII,
        description: "Reference (undeformed) radii X of the probed material points [um], each in [R0, R0 R_inf] (checked when displacement or velocity is read); the point is now at X + displacement, where PIV sees it. Until set, they follow the tissue: R0 (1 + f (R_inf - 1)) for f = 0, 1/18, 1/9, 2/9, 4/9, 1 (the start values at R0 = 1 um, R_inf = 10)",
        input_dependencies: &[],
    },
    ArrayVariable {
        name: "displacement",
        causality: Causality::Output,
        unit: "um",
        start: &[],
        description: "Radial displacement u(X, t) of the material point at each reference radius X of probe_radii [um] (sigma X / 6 at the cut)",
        input_dependencies: &[],
    },
    ArrayVariable {
        name: "velocity",
        causality: Causality::Output,
        unit: "um/s",
        start: &[],
        description: "Radial velocity u_t(X, t) of the material point at each reference radius X of probe_radii [um/s] under the current edge_stress",
        input_dependencies: &[(Vr::EdgeStress as u32, "fixed")],
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_references_are_table_indices_then_after_every_other() {
        let first = DESCRIPTION.first_state() as usize;
        assert_eq!(first, 13, "the published rows");
        for (i, v) in VARIABLES.iter().enumerate() {
            assert_eq!(Vr::from_u32(v.value_reference).map(|vr| vr.var().name), Some(v.name));
            if i < first {
                assert_eq!(v.value_reference as usize, i, "{}", v.name);
            } else {
                // After the states, derivatives, FMI 3.0 time, n_probes and arrays.
                let last = first + 2 * MODEL_EXCHANGE_STATES + 1 + PROBE_ARRAYS.len();
                assert!(v.value_reference as usize > last, "{}", v.name);
            }
        }
        assert_eq!(Vr::from_u32(VARIABLES.len() as u32), None);
    }
}
