//! The generated `modelDescription.xml` of each model ([`wound_opening::fmi::fmi2::xml`]) parsed
//! back and compared with the model's table: the generator writes what the code uses
//! (fmpy's validation of the archives is in tests/python/test_model_description.py).

use quick_xml::Reader;
use quick_xml::events::Event;
use std::collections::BTreeMap;
use wound_opening::fmi::common::model::{Causality, Description, LOG_CATEGORIES};
use wound_opening::fmi::fmi2::xml;
use wound_opening::models::MODELS;

type Elements = Vec<(String, BTreeMap<String, String>)>;

/// Both models' descriptions with their generated FMI 2.0 XML.
fn models() -> Vec<(&'static Description, String)> {
    MODELS.iter().map(|(d, _)| (*d, xml::fmi2(d))).collect()
}

/// Every element of the document as (path, attributes), in document order.
fn elements(xml: &str) -> Elements {
    let mut reader = Reader::from_str(xml);
    let mut path: Vec<String> = Vec::new();
    let mut out = Vec::new();
    loop {
        let event = reader.read_event().expect("well-formed XML");
        let (e, empty) = match &event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                path.pop();
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let name = e.name().into_inner().to_owned();
        path.push(name);
        let attrs = e
            .attributes()
            .map(|a| {
                let a = a.expect("attribute");
                let key = a.key.into_inner().to_owned();
                (
                    key,
                    a.normalized_value(quick_xml::XmlVersion::Implicit1_0)
                        .expect("value")
                        .into_owned(),
                )
            })
            .collect();
        out.push((path.join("/"), attrs));
        if empty {
            path.pop();
        }
    }
    out
}

fn find<'a>(all: &'a Elements, path: &str) -> Vec<&'a BTreeMap<String, String>> {
    all.iter().filter(|(p, _)| p == path).map(|(_, a)| a).collect()
}

#[test]
fn identity_and_capabilities_match_the_code() {
    for (d, xml) in models() {
        let all = elements(&xml);
        let root = find(&all, "fmiModelDescription")[0];
        assert_eq!(root["fmiVersion"], "2.0");
        assert_eq!(root["guid"], d.guid);
        assert_eq!(root["modelName"], d.model_identifier);
        let cs = find(&all, "fmiModelDescription/CoSimulation")[0];
        assert_eq!(cs["modelIdentifier"], d.model_identifier);
        for (flag, value) in xml::CO_SIMULATION_FLAGS {
            assert_eq!(
                cs.get(flag).map(String::as_str),
                Some(value),
                "{}: CoSimulation/@{flag}",
                d.model_identifier
            );
        }
        let me = find(&all, "fmiModelDescription/ModelExchange");
        assert_eq!(me.len(), 1, "both interfaces in one archive");
        assert_eq!(me[0]["modelIdentifier"], d.model_identifier, "one library for both");
        assert_eq!(me[0]["completedIntegratorStepNotNeeded"], "true", "no events");
    }
    let guids: Vec<&str> = MODELS.iter().map(|(d, _)| d.guid).collect();
    assert_ne!(guids[0], guids[1], "the shared object tells the models apart by GUID");
}

#[test]
fn log_categories_match_the_code() {
    for (_, xml) in models() {
        let all = elements(&xml);
        let cats = find(&all, "fmiModelDescription/LogCategories/Category");
        let xml: Vec<(&str, &str)> =
            cats.iter().map(|a| (a["name"].as_str(), a["description"].as_str())).collect();
        assert_eq!(xml, LOG_CATEGORIES.to_vec());
    }
}

#[test]
fn variables_match_the_table_one_for_one() {
    for (d, xml) in models() {
        let all = elements(&xml);
        let all_svs = find(&all, "fmiModelDescription/ModelVariables/ScalarVariable");
        let nx = d.state_count();
        assert_eq!(
            all_svs.len(),
            d.variables.len() + 2 * nx,
            "the table, the states and their derivatives"
        );
        // The type element of each ScalarVariable, in document order.
        let all_typed: Vec<(&str, &BTreeMap<String, String>)> = all
            .iter()
            .filter_map(|(p, a)| {
                p.strip_prefix("fmiModelDescription/ModelVariables/ScalarVariable/").map(|k| (k, a))
            })
            .collect();
        assert_eq!(all_typed.len(), all_svs.len(), "one type element per variable");
        // The rows numbered by position, the states and derivatives, then the rows added later.
        let (first, later) = (d.first_state() as usize, d.later_rows().len());
        let n = all_svs.len();
        let svs = [&all_svs[..first], &all_svs[n - later..]].concat();
        let typed = [&all_typed[..first], &all_typed[n - later..]].concat();
        let (states, state_types) = (&all_svs[first..n - later], &all_typed[first..n - later]);
        for (k, (sv, (kind, ty))) in states.iter().zip(state_types).enumerate() {
            let vr = first + k;
            assert_eq!((sv["valueReference"].as_str(), *kind), (vr.to_string().as_str(), "Real"));
            assert_eq!((sv["causality"].as_str(), sv["initial"].as_str()), ("local", "calculated"));
            if k >= nx {
                let state = vr - nx + 1;
                assert_eq!(ty["derivative"], state.to_string(), "derivative of index {state}");
                assert_eq!(sv["name"], format!("der({})", all_svs[state - 1]["name"]));
            }
        }
        let units: Vec<&str> = find(&all, "fmiModelDescription/UnitDefinitions/Unit")
            .iter()
            .map(|a| a["name"].as_str())
            .collect();
        for (i, ((sv, (kind, ty)), var)) in svs.iter().zip(typed).zip(d.variables).enumerate() {
            assert!(
                var.value_reference as usize == i || i >= first,
                "{}: value references are table indices",
                var.name
            );
            assert_eq!(sv["name"], var.name);
            assert_eq!(kind, var.kind.as_str(), "{}", var.name);
            assert_eq!(sv["valueReference"], var.value_reference.to_string(), "{}", var.name);
            assert_eq!(sv["causality"], var.causality.as_str(), "{}", var.name);
            assert_eq!(sv["variability"], var.variability.as_str(), "{}", var.name);
            assert_eq!(sv["description"], var.description, "{}", var.name);
            assert_eq!(
                ty.get("start").map(|s| s.parse::<f64>().unwrap()),
                var.start,
                "{}",
                var.name
            );
            assert_eq!(ty.get("unit").map(String::as_str).unwrap_or(""), var.unit, "{}", var.name);
            if !var.unit.is_empty() {
                assert!(units.contains(&var.unit), "unit {} of {} is declared", var.unit, var.name);
            }
            let range = ty
                .get("min")
                .zip(ty.get("max"))
                .map(|(a, b)| (a.parse().unwrap(), b.parse().unwrap()));
            assert_eq!(range, var.range, "{}", var.name);
            assert!(!sv.contains_key("initial"), "{}: initial is left to its default", var.name);
        }
    }
}

/// The physical units are declared with SI base units, so that masters can convert.
#[test]
fn units_are_defined_in_si_base_units() {
    let want = [
        ("Pa", &[("kg", "1"), ("m", "-1"), ("s", "-2")][..]),
        ("s", &[("s", "1")]),
        ("um", &[("m", "1"), ("factor", "1e-6")]),
        ("um/s", &[("m", "1"), ("s", "-1"), ("factor", "1e-6")]),
        ("pN", &[("kg", "1"), ("m", "1"), ("s", "-2"), ("factor", "1e-12")]),
        ("1/s", &[("s", "-1")]),
    ];
    for (d, xml) in models() {
        let all = elements(&xml);
        let units: Vec<&BTreeMap<String, String>> =
            find(&all, "fmiModelDescription/UnitDefinitions/Unit");
        let bases = find(&all, "fmiModelDescription/UnitDefinitions/Unit/BaseUnit");
        // Base units follow their unit in document order; "1" has none.
        let mut b = bases.iter();
        for u in units {
            let name = u["name"].as_str();
            if name == "1" {
                continue;
            }
            let (_, attrs) = want
                .iter()
                .find(|(n, _)| *n == name)
                .unwrap_or_else(|| panic!("{}: unexpected unit {name}", d.model_identifier));
            let got = b.next().expect("a BaseUnit per unit");
            let got: Vec<(&str, &str)> =
                got.iter().map(|(k, v)| (k.as_str(), v.as_str())).collect();
            let mut want: Vec<(&str, &str)> = attrs.to_vec();
            want.sort();
            assert_eq!(got, want, "{}: unit {name}", d.model_identifier);
        }
    }
}

#[test]
fn model_structure_matches_the_declared_dependencies() {
    for (d, xml) in models() {
        let all = elements(&xml);
        // 1-based index of a variable in `ModelVariables`.
        let index = |vr: u32| (vr + 1).to_string();
        let name = |vr: u32| d.variables[vr as usize].name;
        let outputs = find(&all, "fmiModelDescription/ModelStructure/Outputs/Unknown");
        assert_eq!(outputs.len(), d.outputs.len());
        // Each output on its inputs, then on every state (in Model Exchange).
        let (table, nx) = (d.first_state(), d.state_count() as u32);
        let states: Vec<(u32, &str)> = (table..table + nx).map(|v| (v, "fixed")).collect();
        for (xml, (vr, deps)) in outputs.iter().zip(d.outputs) {
            assert_eq!(xml["index"], index(*vr));
            let deps: Vec<(u32, &str)> =
                deps.iter().copied().chain(states.iter().copied()).collect();
            let want: Vec<String> = deps.iter().map(|(v, _)| index(*v)).collect();
            assert_eq!(xml["dependencies"], want.join(" "), "{}", name(*vr));
            let kinds: Vec<&str> = deps.iter().map(|(_, k)| *k).collect();
            assert_eq!(
                xml.get("dependenciesKind").map(String::as_str).unwrap_or(""),
                kinds.join(" ")
            );
        }
        // Each derivative on the inputs of the model's table and its own state.
        let derivatives = find(&all, "fmiModelDescription/ModelStructure/Derivatives/Unknown");
        assert_eq!(derivatives.len(), nx as usize);
        if let Some(s) = d.states {
            for (k, xml) in derivatives.iter().enumerate() {
                let k = k as u32;
                assert_eq!(xml["index"], index(table + nx + k));
                let mut want: Vec<String> =
                    s.input_dependencies.iter().map(|(v, _)| index(*v)).collect();
                want.push(index(table + k));
                assert_eq!(xml["dependencies"], want.join(" "));
            }
        }
        // The table's initial unknowns, then the states, then the derivatives.
        let initial = find(&all, "fmiModelDescription/ModelStructure/InitialUnknowns/Unknown");
        assert_eq!(initial.len(), d.initial_unknowns.len() + 2 * nx as usize);
        for (k, xml) in initial[d.initial_unknowns.len()..].iter().enumerate() {
            assert_eq!(xml["index"], index(table + k as u32));
        }
        for (xml, (vr, deps)) in initial.iter().zip(d.initial_unknowns) {
            assert_eq!(xml["index"], index(*vr));
            let want: Vec<String> = deps.iter().map(|v| index(*v)).collect();
            assert_eq!(xml["dependencies"], want.join(" "), "{}", name(*vr));
        }
        // Every output is listed, and nothing else.
        let outs: Vec<_> =
            d.variables.iter().filter(|v| v.causality == Causality::Output).collect();
        assert_eq!(outs.len(), outputs.len());
    }
}

/// Guards against a `DefaultExperiment` without a tolerance: a master that runs the
/// defaults then picks its own. WoundOpening declares the start value of its `tolerance`
/// parameter (what it uses when fmi2SetupExperiment defines none); PurseString, which
/// has no solver, declares 1e-10 as well.
#[test]
fn default_experiment_declares_the_default_tolerance() {
    for (d, xml) in models() {
        let all = elements(&xml);
        let exp = find(&all, "fmiModelDescription/DefaultExperiment")[0];
        let tol: f64 = exp
            .get("tolerance")
            .unwrap_or_else(|| panic!("{}: no tolerance", d.model_identifier))
            .parse()
            .unwrap();
        let want =
            d.variables.iter().find(|v| v.name == "tolerance").map_or(1e-10, |v| v.start.unwrap());
        assert_eq!(tol, want, "{}: DefaultExperiment/@tolerance", d.model_identifier);
    }
}

/// Guards against descriptions that contradict the declared unit: edge_stress,
/// edge_velocity and internal_step were described "in units of G, R0/T, T" while declared
/// in Pa, um/s and s (what the master actually exchanges since the physical scales).
#[test]
fn descriptions_state_the_declared_unit() {
    for (d, _) in models() {
        for v in d.variables {
            assert!(!v.description.contains("in units of"), "{}: {}", v.name, v.description);
        }
    }
    let wound = MODELS[0].0;
    for name in ["edge_stress", "edge_velocity", "internal_step"] {
        let v = wound.variables.iter().find(|v| v.name == name).unwrap();
        assert!(
            v.description.contains(&format!("[{}]", v.unit)),
            "{name} ({}): {}",
            v.unit,
            v.description
        );
    }
}

/// Each model declares every unit its variables, states and arrays use, once: a unit left
/// out would be missing from `<UnitDefinitions>` while a variable names it.
#[test]
fn every_model_declares_the_units_it_uses() {
    for (d, _) in &MODELS {
        let mut used: Vec<&str> =
            d.variables.iter().map(|v| v.unit).filter(|u| !u.is_empty()).collect();
        if let Some(s) = d.states {
            used.extend([s.unit, s.derivative_unit]);
        }
        if let Some(a) = d.arrays {
            used.extend(a.arrays.iter().map(|v| v.unit));
        }
        let declared: Vec<&str> = d.units.iter().map(|(name, _)| *name).collect();
        for unit in used {
            assert!(
                declared.contains(&unit),
                "{}: unit {unit} is used but not declared",
                d.model_identifier
            );
        }
        let mut unique = declared.clone();
        unique.dedup();
        assert_eq!(unique, declared, "{}: a unit declared twice", d.model_identifier);
    }
}

/// The value reference of every variable is its position in its model's table (what
/// `variable_table!` guarantees, and what the XML's indices assume), but for the rows added
/// later, whose value references come after every other (states, derivatives, FMI 3.0's).
#[test]
fn value_references_are_table_positions() {
    for (d, _) in &MODELS {
        let first = d.first_state() as usize;
        for (i, v) in d.variables.iter().enumerate() {
            let after_all =
                2 + first + 2 * d.state_count() + d.arrays.map_or(0, |a| a.arrays.len());
            assert!(
                v.value_reference as usize == i
                    || (i >= first && v.value_reference as usize >= after_all),
                "{}: {}",
                d.model_identifier,
                v.name
            );
        }
    }
}
