//! `modelDescription/modelDescription.xml` is written by hand; the variable table in
//! `src/fmi/variables.rs` is what the code uses. This test parses the XML and fails on
//! any disagreement between the two.

use quick_xml::Reader;
use quick_xml::events::Event;
use std::collections::BTreeMap;
use wound_opening::fmi::variables::*;

const XML: &str = include_str!("../modelDescription/modelDescription.xml");

/// Every element of the document as (path, attributes), in document order.
fn elements() -> Vec<(String, BTreeMap<String, String>)> {
    let mut reader = Reader::from_str(XML);
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
                (key, a.normalized_value(quick_xml::XmlVersion::Implicit1_0).expect("value").into_owned())
            })
            .collect();
        out.push((path.join("/"), attrs));
        if empty {
            path.pop();
        }
    }
    out
}

fn find<'a>(all: &'a [(String, BTreeMap<String, String>)], path: &str) -> Vec<&'a BTreeMap<String, String>> {
    all.iter().filter(|(p, _)| p == path).map(|(_, a)| a).collect()
}

#[test]
fn identity_and_capabilities_match_the_code() {
    let all = elements();
    let root = find(&all, "fmiModelDescription")[0];
    assert_eq!(root["fmiVersion"], "2.0");
    assert_eq!(root["guid"], GUID);
    let cs = find(&all, "fmiModelDescription/CoSimulation")[0];
    assert_eq!(cs["modelIdentifier"], MODEL_IDENTIFIER);
    for (flag, value) in CAPABILITIES {
        assert_eq!(cs.get(flag).map(String::as_str), Some(value), "CoSimulation/@{flag}");
    }
    assert!(find(&all, "fmiModelDescription/ModelExchange").is_empty(), "co-simulation only");
}

#[test]
fn log_categories_match_the_code() {
    let all = elements();
    let cats = find(&all, "fmiModelDescription/LogCategories/Category");
    let xml: Vec<(&str, &str)> = cats.iter().map(|a| (a["name"].as_str(), a["description"].as_str())).collect();
    assert_eq!(xml, LOG_CATEGORIES.to_vec());
}

#[test]
fn variables_match_the_table_one_for_one() {
    let all = elements();
    let svs = find(&all, "fmiModelDescription/ModelVariables/ScalarVariable");
    assert_eq!(svs.len(), VARIABLES.len(), "number of ScalarVariables");
    // The type element of each ScalarVariable, in document order.
    let typed: Vec<(&str, &BTreeMap<String, String>)> = all
        .iter()
        .filter_map(|(p, a)| p.strip_prefix("fmiModelDescription/ModelVariables/ScalarVariable/").map(|k| (k, a)))
        .collect();
    assert_eq!(typed.len(), VARIABLES.len(), "one type element per variable");
    let units: Vec<&str> =
        find(&all, "fmiModelDescription/UnitDefinitions/Unit").iter().map(|a| a["name"].as_str()).collect();
    for ((sv, (kind, ty)), var) in svs.iter().zip(&typed).zip(&VARIABLES) {
        assert_eq!(sv["name"], var.name);
        assert_eq!(*kind, var.kind.as_str(), "{}", var.name);
        assert_eq!(sv["valueReference"], var.value_reference.to_string(), "{}", var.name);
        assert_eq!(sv["causality"], var.causality.as_str(), "{}", var.name);
        assert_eq!(sv["variability"], var.variability.as_str(), "{}", var.name);
        assert_eq!(sv["description"], var.description, "{}", var.name);
        assert_eq!(ty.get("start").map(|s| s.parse::<f64>().unwrap()), var.start, "{}", var.name);
        assert_eq!(ty.get("unit").map(String::as_str).unwrap_or(""), var.unit, "{}", var.name);
        if !var.unit.is_empty() {
            assert!(units.contains(&var.unit), "unit {} of {} is declared", var.unit, var.name);
        }
        let range = ty.get("min").zip(ty.get("max")).map(|(a, b)| (a.parse().unwrap(), b.parse().unwrap()));
        assert_eq!(range, var.range, "{}", var.name);
        assert!(!sv.contains_key("initial"), "{}: initial is left to its default", var.name);
    }
}

/// 1-based index of a variable in `ModelVariables`.
fn index(vr: Vr) -> String {
    (vr as usize + 1).to_string()
}

#[test]
fn model_structure_matches_the_declared_dependencies() {
    let all = elements();
    let outputs = find(&all, "fmiModelDescription/ModelStructure/Outputs/Unknown");
    assert_eq!(outputs.len(), OUTPUT_DEPENDENCIES.len());
    for (xml, (vr, deps)) in outputs.iter().zip(OUTPUT_DEPENDENCIES) {
        assert_eq!(xml["index"], index(vr));
        let want: Vec<String> = deps.iter().map(|(d, _)| index(*d)).collect();
        assert_eq!(xml["dependencies"], want.join(" "), "{}", vr.var().name);
        let kinds: Vec<&str> = deps.iter().map(|(_, k)| *k).collect();
        assert_eq!(xml.get("dependenciesKind").map(String::as_str).unwrap_or(""), kinds.join(" "));
    }
    let initial = find(&all, "fmiModelDescription/ModelStructure/InitialUnknowns/Unknown");
    assert_eq!(initial.len(), INITIAL_DEPENDENCIES.len());
    for (xml, (vr, deps)) in initial.iter().zip(INITIAL_DEPENDENCIES) {
        assert_eq!(xml["index"], index(vr));
        let want: Vec<String> = deps.iter().map(|d| index(*d)).collect();
        assert_eq!(xml["dependencies"], want.join(" "), "{}", vr.var().name);
    }
    // Every output is listed, and nothing else.
    let outs: Vec<_> = VARIABLES.iter().filter(|v| v.causality == Causality::Output).collect();
    assert_eq!(outs.len(), outputs.len());
}
