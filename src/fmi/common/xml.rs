//! What the FMI 2.0 and 3.0 `modelDescription.xml` writers ([`crate::fmi::fmi2::xml`],
//! [`crate::fmi::fmi3::xml`]) share: escaping, numbers that read back exactly, a table
//! variable's value attributes, `<UnitDefinitions>`, `<LogCategories>`,
//! `<DefaultExperiment>`, and the model structure in value references.

use crate::fmi::common::model::{Description, Kind, LOG_CATEGORIES, Variable};
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
            let _ = writeln!(
                out,
                "    <Unit name=\"{}\"><BaseUnit {}/></Unit>",
                escape(name),
                attrs.join(" ")
            );
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
        let _ = writeln!(
            out,
            "    <Category name=\"{name}\" description=\"{}\"/>",
            escape(description)
        );
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
        let table = d.first_state();
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
        let mut initial: Vec<(u32, Vec<u32>)> =
            d.initial_unknowns.iter().map(|(v, deps)| (*v, deps.to_vec())).collect();
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
