//! The FMI 3.0 `modelDescription.xml` (fmi3ModelDescription.xsd) of a model, from the same
//! [`Description`] as the FMI 2.0 one, with the pieces both share ([`crate::fmi::common::xml`]): `Float64` and `Int32` variables
//! with the same value references, the states and derivatives as scalars (value
//! references `table + k` and `table + count + k`, as in FMI 2.0), then the independent
//! variable `time` (FMI 3.0 wants exactly one). `ModelStructure` names value references.

use crate::fmi::common::model::{
    Arrays, Causality, ContinuousStates, Description, Kind, Named, Variability, Variable,
};
use crate::fmi::common::xml::{
    GENERATION_TOOL, Structure, escape, number, units_categories_experiment, value_attributes,
};
use std::fmt::Write;

/// Value reference of the independent variable `time`.
pub fn time_reference(d: &Description) -> u32 {
    d.first_state() + 2 * d.state_count() as u32
}

fn kind3(kind: Kind) -> &'static str {
    match kind {
        Kind::Real => "Float64",
        Kind::Integer => "Int32",
    }
}

fn states(d: &Description, s: &ContinuousStates) -> String {
    let table = d.first_state() as usize;
    let mut x = String::new();
    for k in 0..s.count {
        let _ = writeln!(
            x,
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"local\" variability=\"continuous\" initial=\"calculated\" unit=\"{}\"\n      description=\"{}\"/>",
            escape(&d.state_name(Named::State(k))),
            table + k,
            escape(s.unit),
            escape(s.description)
        );
    }
    for k in 0..s.count {
        let _ = writeln!(
            x,
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"local\" variability=\"continuous\" initial=\"calculated\" unit=\"{}\" derivative=\"{}\"\n      description=\"Time derivative of {}\"/>",
            escape(&d.state_name(Named::Derivative(k))),
            table + s.count + k,
            escape(s.derivative_unit),
            table + k,
            escape(&d.state_name(Named::State(k)))
        );
    }
    x
}

fn unknown(element: &str, vr: u32, deps: &[(u32, &str)]) -> String {
    let list: Vec<String> = deps.iter().map(|(k, _)| k.to_string()).collect();
    let kinds: Vec<&str> = deps.iter().map(|(_, kind)| *kind).collect();
    let kinds = if kinds.is_empty() {
        String::new()
    } else {
        format!(" dependenciesKind=\"{}\"", kinds.join(" "))
    };
    format!("    <{element} valueReference=\"{vr}\" dependencies=\"{}\"{kinds}/>\n", list.join(" "))
}

/// Flags of `<ModelExchange>`: what the glue provides, the same for every model.
pub const MODEL_EXCHANGE_FLAGS: [(&str, &str); 5] = [
    ("needsCompletedIntegratorStep", "false"),
    ("canGetAndSetFMUState", "true"),
    ("canSerializeFMUState", "true"),
    ("providesDirectionalDerivatives", "true"),
    ("providesAdjointDerivatives", "true"),
];

/// Flags of `<CoSimulation>`: what the glue provides, the same for every model.
pub const CO_SIMULATION_FLAGS: [(&str, &str); 7] = [
    ("canHandleVariableCommunicationStepSize", "true"),
    ("canGetAndSetFMUState", "true"),
    ("canSerializeFMUState", "true"),
    ("providesDirectionalDerivatives", "true"),
    ("providesAdjointDerivatives", "true"),
    ("hasEventMode", "false"),
    ("providesIntermediateUpdate", "true"),
];

/// The FMI 3.0 `modelDescription.xml` (Model Exchange and co-simulation, no event mode).
pub fn fmi3(d: &Description) -> String {
    let id = d.model_identifier;
    let mut x = String::new();
    let _ = write!(
        x,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription\n  fmiVersion=\"3.0\"\n  modelName=\"{id}\"\n  \
         instantiationToken=\"{token}\"\n  description=\"{summary}\"\n  generationTool=\"{GENERATION_TOOL}\"\n  \
         variableNamingConvention=\"flat\">\n\n",
        token = escape(d.guid),
        summary = escape(d.summary),
    );
    for (element, flags) in
        [("ModelExchange", &MODEL_EXCHANGE_FLAGS[..]), ("CoSimulation", &CO_SIMULATION_FLAGS[..])]
    {
        let _ = write!(x, "  <{element}\n    modelIdentifier=\"{id}\"");
        for (flag, value) in flags {
            let _ = write!(x, "\n    {flag}=\"{value}\"");
        }
        x.push_str("/>\n\n");
    }
    x.push_str(&units_categories_experiment(d));
    x.push_str("\n  <ModelVariables>\n");
    // The rows added later (value references after every other) come last.
    let first = d.first_state() as usize;
    let scalar = |x: &mut String, v: &Variable| {
        let mut attrs = value_attributes(v);
        if v.causality == Causality::Input && v.variability == Variability::Continuous {
            // Settable in Intermediate Update Mode (the FMI 3.0 way to interpolated inputs).
            attrs.push_str(" intermediateUpdate=\"true\"");
        }
        let _ = writeln!(
            x,
            "    <{} name=\"{}\" valueReference=\"{}\" causality=\"{}\" variability=\"{}\"{attrs}\n      description=\"{}\"/>",
            kind3(v.kind),
            escape(v.name),
            v.value_reference,
            v.causality.as_str(),
            v.variability.as_str(),
            escape(v.description)
        );
    };
    d.variables[..first].iter().for_each(|v| scalar(&mut x, v));
    if let Some(s) = d.states {
        x.push_str(&states(d, &s));
    }
    let _ = writeln!(
        x,
        "    <Float64 name=\"time\" valueReference=\"{}\" causality=\"independent\" variability=\"continuous\"\n      description=\"Master time; the cut is at the startTime of fmi3EnterInitializationMode\"/>",
        time_reference(d)
    );
    if let Some(a) = d.arrays {
        x.push_str(&arrays(d, &a));
    }
    d.later_rows().iter().for_each(|v| scalar(&mut x, v));
    x.push_str("  </ModelVariables>\n\n  <ModelStructure>\n");
    let structure = Structure::of(d);
    for (vr, deps) in &structure.outputs {
        x.push_str(&unknown("Output", *vr, deps));
    }
    // The array outputs, on their inputs and every state.
    let array_outputs = array_outputs(d);
    for (vr, deps) in &array_outputs {
        x.push_str(&unknown("Output", *vr, deps));
    }
    for (vr, deps) in &structure.derivatives {
        x.push_str(&unknown("ContinuousStateDerivative", *vr, deps));
    }
    for (vr, deps) in &structure.initial {
        let list: Vec<String> = deps.iter().map(|k| k.to_string()).collect();
        let _ = writeln!(
            x,
            "    <InitialUnknown valueReference=\"{vr}\" dependencies=\"{}\"/>",
            list.join(" ")
        );
    }
    // Initially the array outputs depend on every known (no `dependencies` attribute).
    for (vr, _) in &array_outputs {
        let _ = writeln!(x, "    <InitialUnknown valueReference=\"{vr}\"/>");
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// The structural parameter, then each array with a `<Dimension>` naming it.
fn arrays(d: &Description, a: &Arrays) -> String {
    let length = time_reference(d) + 1;
    let mut x = String::new();
    let _ = writeln!(
        x,
        "    <UInt64 name=\"{}\" valueReference=\"{length}\" causality=\"structuralParameter\" variability=\"fixed\" start=\"{}\" min=\"1\" max=\"{}\"\n      description=\"{}\"/>",
        escape(a.length_name),
        a.length_start,
        a.length_max,
        escape(a.length_description)
    );
    for (j, v) in a.arrays.iter().enumerate() {
        let (variability, start) = match v.causality {
            Causality::Parameter => {
                let values: Vec<String> = v.start.iter().map(|&s| number(s)).collect();
                ("fixed", format!(" start=\"{}\"", values.join(" ")))
            }
            _ => ("continuous", String::new()),
        };
        let _ = writeln!(
            x,
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"{}\" variability=\"{variability}\" unit=\"{}\"{start}\n      description=\"{}\">\n      <Dimension valueReference=\"{length}\"/>\n    </Float64>",
            escape(v.name),
            length + 1 + j as u32,
            v.causality.as_str(),
            escape(v.unit),
            escape(v.description)
        );
    }
    x
}

/// Each array output's value reference with its dependencies: its inputs, then every state.
fn array_outputs(d: &Description) -> Vec<(u32, Vec<(u32, &'static str)>)> {
    let Some(a) = d.arrays else { return Vec::new() };
    let (length, table) = (time_reference(d) + 1, d.first_state());
    let states: Vec<(u32, &str)> =
        (0..d.state_count() as u32).map(|k| (table + k, "fixed")).collect();
    a.arrays
        .iter()
        .enumerate()
        .filter(|(_, v)| v.causality == Causality::Output)
        .map(|(j, v)| {
            let deps = v.input_dependencies.iter().copied().chain(states.iter().copied()).collect();
            (length + 1 + j as u32, deps)
        })
        .collect()
}
