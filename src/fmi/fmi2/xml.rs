//! `modelDescription.xml` generated from a model's [`Description`]: the variable table
//! the code uses is the only source, so the XML cannot drift from it (as rust-fmi's
//! exporter does it). FMI 2.0 (fmi2ModelDescription.xsd): `ScalarVariable`s in table
//! order, then the continuous states and their derivatives ([`ContinuousStates`]), so the 1-based
//! index that `ModelStructure` uses is `value reference + 1` (value reference = position,
//! [`crate::variable_table`]); rows added later (parameters only, never in `ModelStructure`)
//! come after the derivatives. One archive declares both interfaces:
//! `<ModelExchange>` and `<CoSimulation>` with the same `modelIdentifier`.

use crate::fmi::common::model::{Causality, ContinuousStates, Description, Named, Variable};
use crate::fmi::common::xml::{
    GENERATION_TOOL, Structure, escape, units_categories_experiment, value_attributes,
};
use std::fmt::Write;

/// Flags of `<CoSimulation>`: what the glue provides, the same for every model.
pub const CO_SIMULATION_FLAGS: [(&str, &str); 9] = [
    ("canBeInstantiatedOnlyOncePerProcess", "false"),
    ("canHandleVariableCommunicationStepSize", "true"),
    ("canGetAndSetFMUstate", "true"),
    ("canSerializeFMUstate", "true"),
    ("providesDirectionalDerivative", "true"),
    ("canInterpolateInputs", "true"),
    ("maxOutputDerivativeOrder", "0"),
    ("canRunAsynchronuously", "false"),
    ("canNotUseMemoryManagementFunctions", "true"),
];

/// Flags of `<ModelExchange>`: what the glue provides, the same for every model (no
/// events, so `fmi2CompletedIntegratorStep` is not needed; directional derivatives of the
/// outputs and state derivatives with respect to inputs and states).
pub const MODEL_EXCHANGE_FLAGS: [(&str, &str); 6] = [
    ("completedIntegratorStepNotNeeded", "true"),
    ("canBeInstantiatedOnlyOncePerProcess", "false"),
    ("canNotUseMemoryManagementFunctions", "true"),
    ("canGetAndSetFMUstate", "true"),
    ("canSerializeFMUstate", "true"),
    ("providesDirectionalDerivative", "true"),
];

/// `<Unknown index dependencies dependenciesKind/>` of `ModelStructure`.
fn unknown(vr: u32, deps: &[(u32, &str)]) -> String {
    let list: Vec<String> = deps.iter().map(|(k, _)| (k + 1).to_string()).collect();
    let kinds: Vec<&str> = deps.iter().map(|(_, kind)| *kind).collect();
    let kinds = if kinds.is_empty() {
        String::new()
    } else {
        format!(" dependenciesKind=\"{}\"", kinds.join(" "))
    };
    format!("      <Unknown index=\"{}\" dependencies=\"{}\"{kinds}/>\n", vr + 1, list.join(" "))
}

/// The states (local, continuous, calculated: 0 at the cut) and their derivatives.
fn state_variables(d: &Description, s: &ContinuousStates) -> String {
    let table = d.first_state() as usize;
    let mut x = String::new();
    for k in 0..s.count {
        let vr = table + k;
        let _ = write!(
            x,
            "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" causality=\"local\" variability=\"continuous\" initial=\"calculated\"\n      description=\"{}\">\n      <Real unit=\"{}\"/>\n    </ScalarVariable>\n",
            escape(&d.state_name(Named::State(k))),
            escape(s.description),
            escape(s.unit)
        );
    }
    for k in 0..s.count {
        let vr = table + s.count + k;
        let _ = write!(
            x,
            "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" causality=\"local\" variability=\"continuous\" initial=\"calculated\"\n      description=\"Time derivative of {}\">\n      <Real unit=\"{}\" derivative=\"{}\"/>\n    </ScalarVariable>\n",
            escape(&d.state_name(Named::Derivative(k))),
            escape(&d.state_name(Named::State(k))),
            escape(s.derivative_unit),
            table + k + 1
        );
    }
    x
}

/// The interfaces an FMI 2.0 `modelDescription.xml` declares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interfaces {
    Both,
    CoSimulation,
    ModelExchange,
}

/// The FMI 2.0 `modelDescription.xml` of a model (Model Exchange and co-simulation). A
/// variable's value reference is its position in the table ([`crate::variable_table`]).
pub fn fmi2(d: &Description) -> String {
    fmi2_with(d, Interfaces::Both)
}

/// The FMI 2.0 `modelDescription.xml` declaring `which` interfaces. Co-simulation alone
/// declares no continuous states (they are Model Exchange's): the table's variables keep
/// their value references, so the library serves every archive with one GUID.
pub fn fmi2_with(d: &Description, which: Interfaces) -> String {
    let without_states = Description { states: None, ..*d };
    let d = if which == Interfaces::CoSimulation { &without_states } else { d };
    let index = |vr: u32| (vr + 1).to_string();
    let mut x = String::new();
    let _ = write!(
        x,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription\n  fmiVersion=\"2.0\"\n  modelName=\"{id}\"\n  \
         guid=\"{guid}\"\n  description=\"{summary}\"\n  generationTool=\"{GENERATION_TOOL}\"\n  \
         variableNamingConvention=\"flat\"\n  numberOfEventIndicators=\"0\">\n\n",
        id = d.model_identifier,
        guid = escape(d.guid),
        summary = escape(d.summary),
    );
    if which != Interfaces::CoSimulation {
        let _ = write!(
            x,
            "  <ModelExchange\n    modelIdentifier=\"{}\"\n    needsExecutionTool=\"false\"\n",
            d.model_identifier
        );
        for (flag, value) in MODEL_EXCHANGE_FLAGS {
            let _ = writeln!(x, "    {flag}=\"{value}\"");
        }
        x.truncate(x.len() - 1);
        x.push_str("/>\n\n");
    }
    if which != Interfaces::ModelExchange {
        let _ = write!(
            x,
            "  <CoSimulation\n    modelIdentifier=\"{}\"\n    needsExecutionTool=\"false\"\n",
            d.model_identifier
        );
        for (flag, value) in CO_SIMULATION_FLAGS {
            let _ = writeln!(x, "    {flag}=\"{value}\"");
        }
        x.truncate(x.len() - 1);
        x.push_str("/>\n\n");
    }
    x.push_str(&units_categories_experiment(d));
    x.push_str("\n  <ModelVariables>\n");
    // The rows added later come after the states: every other index stays `vr + 1`.
    let later = d.later_rows();
    let index_of = |v: &Variable| match later.iter().position(|l| l == v) {
        Some(j) => (d.first_state() as usize + 2 * d.state_count() + j + 1).to_string(),
        None => index(v.value_reference),
    };
    let scalar = |x: &mut String, v: &Variable| {
        let _ = write!(
            x,
            "    <!-- index {} -->\n    <ScalarVariable name=\"{}\" valueReference=\"{}\" causality=\"{}\" variability=\"{}\"\n      description=\"{}\">\n",
            index_of(v),
            escape(v.name),
            v.value_reference,
            v.causality.as_str(),
            v.variability.as_str(),
            escape(v.description)
        );
        let attrs = value_attributes(v);
        let _ = write!(x, "      <{}{attrs}/>\n    </ScalarVariable>\n", v.kind.as_str());
    };
    d.variables[..d.first_state() as usize].iter().for_each(|v| scalar(&mut x, v));
    if let Some(s) = d.states {
        x.push_str(&state_variables(d, &s));
    }
    later.iter().for_each(|v| scalar(&mut x, v));
    x.push_str("  </ModelVariables>\n\n  <ModelStructure>\n    <Outputs>\n");
    let structure = Structure::of(d);
    for (vr, deps) in &structure.outputs {
        x.push_str(&unknown(*vr, deps));
    }
    x.push_str("    </Outputs>\n");
    if d.states.is_some() {
        x.push_str("    <Derivatives>\n");
        for (vr, deps) in &structure.derivatives {
            x.push_str(&unknown(*vr, deps));
        }
        x.push_str("    </Derivatives>\n");
    }
    x.push_str("    <InitialUnknowns>\n");
    for (vr, deps) in structure.initial {
        let list: Vec<String> = deps.iter().map(|k| index(*k)).collect();
        let _ = writeln!(
            x,
            "      <Unknown index=\"{}\" dependencies=\"{}\"/>",
            index(vr),
            list.join(" ")
        );
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    debug_assert!(
        d.variables.iter().filter(|v| v.causality == Causality::Output).count() == d.outputs.len()
    );
    x
}
