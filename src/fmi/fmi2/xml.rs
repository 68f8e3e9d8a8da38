//! `modelDescription.xml` generated from a model's [`Description`]: the variable table
//! the code uses is the only source, so the XML cannot drift from it (as rust-fmi's
//! exporter does it). FMI 2.0 (fmi2ModelDescription.xsd): `ScalarVariable`s in table
//! order, then the continuous states and their derivatives ([`ContinuousStates`]), so the 1-based
//! index that `ModelStructure` uses is `value reference + 1` (the tables have value
//! reference = position, checked by [`fmi2`]). One archive declares both interfaces:
//! `<ModelExchange>` and `<CoSimulation>` with the same `modelIdentifier`.

use crate::fmi::common::model::{Causality, Description, Kind, LOG_CATEGORIES, Named, ContinuousStates, Variable};
use std::fmt::Write;

pub(in crate::fmi) const GENERATION_TOOL: &str = "wound_opening (Rust)";

/// An attribute value with `& < > "` escaped.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A number as `xs:double` text that reads back to the same `f64` (integers without an
/// exponent, others in Rust's shortest round-trip form).
pub fn number(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 { format!("{}", x as i64) } else { format!("{x:e}") }
}

/// `<UnitDefinitions>` of the units the variables use, in the order the model lists them.
fn unit_definitions(d: &Description) -> String {
    let mut out = String::from("  <UnitDefinitions>\n");
    let state_units = d.states.map_or([""; 2], |s| [s.unit, s.derivative_unit]);
    let used = |n: &str| d.variables.iter().any(|v| v.unit == n) || state_units.contains(&n);
    for (name, base) in d.units.iter().filter(|(n, _)| used(n)) {
        if base.is_empty() {
            let _ = writeln!(out, "    <Unit name=\"{}\"/>", escape(name));
        } else {
            let attrs: Vec<String> = base.iter().map(|(k, v)| format!("{k}=\"{v}\"")).collect();
            let _ = writeln!(out, "    <Unit name=\"{}\"><BaseUnit {}/></Unit>", escape(name), attrs.join(" "));
        }
    }
    out.push_str("  </UnitDefinitions>\n");
    out
}

/// `start`, `min`/`max` and `unit` of a table variable, as attributes (the same in FMI 2.0's
/// type element and FMI 3.0's variable element).
pub(in crate::fmi) fn value_attributes(v: &Variable) -> String {
    let mut attrs = String::new();
    if let Some(s) = v.start {
        let _ = write!(attrs, " start=\"{}\"", number(s));
    }
    if let Some((lo, hi)) = v.range {
        let _ = write!(attrs, " min=\"{lo}\" max=\"{hi}\"");
    }
    if v.kind == Kind::Real && !v.unit.is_empty() {
        let _ = write!(attrs, " unit=\"{}\"", escape(v.unit));
    }
    attrs
}

/// `<UnitDefinitions>`, `<LogCategories>` and `<DefaultExperiment>`, in schema order.
pub(in crate::fmi) fn units_categories_experiment(d: &Description) -> String {
    format!("{}\n{}\n{}", unit_definitions(d), log_categories(), default_experiment(d))
}

fn log_categories() -> String {
    let mut out = String::from("  <LogCategories>\n");
    for (name, description) in LOG_CATEGORIES {
        let _ = writeln!(out, "    <Category name=\"{name}\" description=\"{}\"/>", escape(description));
    }
    out.push_str("  </LogCategories>\n");
    out
}

fn default_experiment(d: &Description) -> String {
    let e = d.default_experiment;
    format!(
        "  <DefaultExperiment startTime=\"{}\" stopTime=\"{}\" stepSize=\"{}\" tolerance=\"{}\"/>\n",
        number(e.start),
        number(e.stop),
        number(e.step),
        number(e.tolerance)
    )
}

/// `ModelStructure` in value references, the same for FMI 2.0 (which writes indices,
/// `value reference + 1`) and FMI 3.0.
pub(in crate::fmi) struct Structure {
    /// Each output on its inputs, then (Model Exchange) on every state.
    pub outputs: Vec<(u32, Vec<(u32, &'static str)>)>,
    /// Each derivative on the model's inputs and its own state (the modes are uncoupled).
    pub derivatives: Vec<(u32, Vec<(u32, &'static str)>)>,
    /// The table's initial unknowns, the states (0 at the cut whatever the parameters: no
    /// dependencies) and the derivatives.
    pub initial: Vec<(u32, Vec<u32>)>,
}

impl Structure {
    pub(in crate::fmi) fn of(d: &Description) -> Self {
        let table = d.variables.len() as u32;
        let states: Vec<u32> = (0..d.state_count() as u32).map(|k| table + k).collect();
        let outputs = d
            .outputs
            .iter()
            .map(|(vr, deps)| {
                let mut all: Vec<(u32, &str)> = deps.to_vec();
                all.extend(states.iter().map(|&s| (s, "fixed")));
                (*vr, all)
            })
            .collect();
        let mut initial: Vec<(u32, Vec<u32>)> = d.initial_unknowns.iter().map(|(v, deps)| (*v, deps.to_vec())).collect();
        let mut derivatives = Vec::new();
        if let Some(s) = d.states {
            let n = s.count as u32;
            for &state in &states {
                let mut deps: Vec<(u32, &str)> = s.input_dependencies.to_vec();
                deps.push((state, "fixed"));
                derivatives.push((state + n, deps));
            }
            initial.extend(states.iter().map(|&v| (v, Vec::new())));
            initial.extend(states.iter().map(|&v| (v + n, s.initial_dependencies.to_vec())));
        }
        Self { outputs, derivatives, initial }
    }
}

/// Flags of `<ModelExchange>`: no events, so `fmi2CompletedIntegratorStep` is not needed;
/// FMU states as in co-simulation; no directional derivatives of the derivatives.
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

/// Flags of `<ModelExchange>`: what the glue provides, the same for every model.
pub const MODEL_EXCHANGE_FLAGS: [(&str, &str); 6] = [
    ("completedIntegratorStepNotNeeded", "true"),
    ("canBeInstantiatedOnlyOncePerProcess", "false"),
    ("canNotUseMemoryManagementFunctions", "true"),
    ("canGetAndSetFMUstate", "true"),
    ("canSerializeFMUstate", "true"),
    ("providesDirectionalDerivative", "false"),
];

/// `<Unknown index dependencies dependenciesKind/>` of `ModelStructure`.
fn unknown(vr: u32, deps: &[(u32, &str)]) -> String {
    let list: Vec<String> = deps.iter().map(|(k, _)| (k + 1).to_string()).collect();
    let kinds: Vec<&str> = deps.iter().map(|(_, kind)| *kind).collect();
    let kinds = if kinds.is_empty() { String::new() } else { format!(" dependenciesKind=\"{}\"", kinds.join(" ")) };
    format!("      <Unknown index=\"{}\" dependencies=\"{}\"{kinds}/>\n", vr + 1, list.join(" "))
}

/// The states (local, continuous, calculated: 0 at the cut) and their derivatives.
fn state_variables(d: &Description, s: &ContinuousStates) -> String {
    let table = d.variables.len();
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
        let _ = write!(x, "  <ModelExchange\n    modelIdentifier=\"{}\"\n    needsExecutionTool=\"false\"\n", d.model_identifier);
        for (flag, value) in MODEL_EXCHANGE_FLAGS {
            let _ = writeln!(x, "    {flag}=\"{value}\"");
        }
        x.truncate(x.len() - 1);
        x.push_str("/>\n\n");
    }
    if which != Interfaces::ModelExchange {
        let _ = write!(x, "  <CoSimulation\n    modelIdentifier=\"{}\"\n    needsExecutionTool=\"false\"\n", d.model_identifier);
        for (flag, value) in CO_SIMULATION_FLAGS {
            let _ = writeln!(x, "    {flag}=\"{value}\"");
        }
        x.truncate(x.len() - 1);
        x.push_str("/>\n\n");
    }
    x.push_str(&units_categories_experiment(d));
    x.push_str("\n  <ModelVariables>\n");
    for v in d.variables {
        let _ = write!(
            x,
            "    <!-- index {} -->\n    <ScalarVariable name=\"{}\" valueReference=\"{}\" causality=\"{}\" variability=\"{}\"\n      description=\"{}\">\n",
            index(v.value_reference),
            escape(v.name),
            v.value_reference,
            v.causality.as_str(),
            v.variability.as_str(),
            escape(v.description)
        );
        let attrs = value_attributes(v);
        let _ = write!(x, "      <{}{attrs}/>\n    </ScalarVariable>\n", v.kind.as_str());
    }
    if let Some(s) = d.states {
        x.push_str(&state_variables(d, &s));
    }
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
        let _ = writeln!(x, "      <Unknown index=\"{}\" dependencies=\"{}\"/>", index(vr), list.join(" "));
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    debug_assert!(d.variables.iter().filter(|v| v.causality == Causality::Output).count() == d.outputs.len());
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly() {
        for x in [0.0, 1.0, -1.0, 6500.0, 1e-10, 1e-3, 0.01, 1e6, 1e21, -2.5e-7, 0.1] {
            assert_eq!(number(x).parse::<f64>().unwrap(), x, "{}", number(x));
        }
        assert_eq!(number(100.0), "100");
        assert_eq!(number(1e-10), "1e-10");
    }

    #[test]
    fn escapes_markup() {
        assert_eq!(escape(r#"a < b & "c" > d"#), "a &lt; b &amp; &quot;c&quot; &gt; d");
    }
}
