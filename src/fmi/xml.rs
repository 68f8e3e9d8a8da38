//! `modelDescription.xml` generated from a model's [`Description`]: the variable table
//! the code uses is the only source, so the XML cannot drift from it (as rust-fmi's
//! exporter does it). FMI 2.0 (fmi2ModelDescription.xsd): `ScalarVariable`s in table
//! order, so the 1-based index that `ModelStructure` uses is `value reference + 1` (the
//! tables have value reference = position, checked by [`fmi2`]).

use super::model::{Causality, Description, Kind, LOG_CATEGORIES, UNITS};
use std::fmt::Write;

const GENERATION_TOOL: &str = "wound_opening (Rust)";

/// An attribute value with `& < > "` escaped.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// A number as `xs:double` text that reads back to the same `f64` (integers without an
/// exponent, others in Rust's shortest round-trip form).
pub fn number(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 { format!("{}", x as i64) } else { format!("{x:e}") }
}

/// `<UnitDefinitions>` of the units the variables use, in [`UNITS`] order.
fn unit_definitions(d: &Description) -> String {
    let mut out = String::from("  <UnitDefinitions>\n");
    for (name, base) in UNITS.iter().filter(|(n, _)| d.variables.iter().any(|v| v.unit == *n)) {
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

/// The FMI 2.0 `modelDescription.xml` of a model (co-simulation).
///
/// # Panics
/// If a value reference is not the variable's position in the table (a table error that
/// the unit tests of every model catch).
pub fn fmi2(d: &Description) -> String {
    for (i, v) in d.variables.iter().enumerate() {
        assert_eq!(v.value_reference as usize, i, "{}: value references must be table positions", v.name);
    }
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
    let _ = write!(x, "  <CoSimulation\n    modelIdentifier=\"{}\"\n    needsExecutionTool=\"false\"\n", d.model_identifier);
    x.push_str("    canBeInstantiatedOnlyOncePerProcess=\"false\"\n");
    for (flag, value) in d.capabilities {
        let _ = writeln!(x, "    {flag}=\"{value}\"");
    }
    x.truncate(x.len() - 1);
    x.push_str("/>\n\n");
    x.push_str(&unit_definitions(d));
    x.push('\n');
    x.push_str(&log_categories());
    x.push('\n');
    x.push_str(&default_experiment(d));
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
        let _ = write!(x, "      <{}{attrs}/>\n    </ScalarVariable>\n", v.kind.as_str());
    }
    x.push_str("  </ModelVariables>\n\n  <ModelStructure>\n    <Outputs>\n");
    for (vr, deps) in d.outputs {
        let list: Vec<String> = deps.iter().map(|(k, _)| index(*k)).collect();
        let kinds: Vec<&str> = deps.iter().map(|(_, kind)| *kind).collect();
        let kinds = if kinds.is_empty() { String::new() } else { format!(" dependenciesKind=\"{}\"", kinds.join(" ")) };
        let _ = writeln!(x, "      <Unknown index=\"{}\" dependencies=\"{}\"{kinds}/>", index(*vr), list.join(" "));
    }
    x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for (vr, deps) in d.initial_unknowns {
        let list: Vec<String> = deps.iter().map(|k| index(*k)).collect();
        let _ = writeln!(x, "      <Unknown index=\"{}\" dependencies=\"{}\"/>", index(*vr), list.join(" "));
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
