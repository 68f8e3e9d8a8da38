//! The architecture, checked: the FMI glue (src/fmi) names no model, none of a model's
//! variables and no unit, so a new model is a folder under src/models and one line in
//! `models::MODELS`; and `unsafe` code lives only in the C boundary (the FMI shims and
//! their frame, the direct API's shims, the panic boundary), which every other module
//! forbids with `#![forbid(unsafe_code)]`; and the version-independent FMI core
//! (src/fmi/common) names no FMI version: each version's function names and its own calls
//! live in its folder (src/fmi/fmi2, src/fmi/fmi3).

use std::path::{Path, PathBuf};
use wound_opening::models::MODELS;

fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            out.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

fn src(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(rel)
}

/// Whole-word occurrences of `word` in `text` (identifier characters delimit words).
fn has_word(text: &str, word: &str) -> bool {
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(word).any(|(i, _)| {
        let before = text[..i].chars().next_back().is_none_or(|c| !is_ident(c));
        let after = text[i + word.len()..].chars().next().is_none_or(|c| !is_ident(c));
        before && after
    })
}

/// Words of the FMI standard that a model's variables may also be called.
const GENERIC: [&str; 3] = ["tolerance", "method", "time"];

#[test]
fn the_glue_names_no_model_no_variable_and_no_unit() {
    let mut words: Vec<String> = Vec::new();
    for (d, _) in &MODELS {
        words.push(d.model_identifier.to_string());
        // Variable names, except the words FMI itself uses (the tolerance of an experiment,
        // a generic parameter `T`).
        words.extend(
            d.variables
                .iter()
                .map(|v| v.name.to_string())
                .filter(|n| n.len() > 2 && !GENERIC.contains(&n.as_str())),
        );
        words.extend(d.units.iter().map(|(u, _)| format!("\"{u}\"")).filter(|u| u != "\"1\""));
    }
    words.extend(["wound".into(), "purse".into(), "purse_string".into(), "models::".into()]);
    let mut found = Vec::new();
    for file in rust_files(&src("fmi")) {
        let text = std::fs::read_to_string(&file).expect("readable");
        for w in &words {
            let hit = if w.starts_with('"') || w.ends_with("::") {
                text.contains(w.as_str())
            } else {
                has_word(&text, w)
            };
            if hit {
                found.push(format!("{}: {w}", file.display()));
            }
        }
    }
    // The model list itself is the one name the glue needs (fmi2Instantiate picks from it).
    found.retain(|f| !(f.ends_with(": models::") && f.contains("src/fmi/mod.rs")));
    assert!(found.is_empty(), "the FMI glue names model specifics:\n{}", found.join("\n"));
    assert!(
        !words.is_empty() && has_word("a lambda here", "lambda") && !has_word("lambdas", "lambda")
    );
}

#[test]
fn unsafe_code_is_confined_to_the_c_boundary() {
    const BOUNDARY: [&str; 5] =
        ["fmi/fmi2/", "fmi/fmi3/", "fmi/frame.rs", "fmi/shims.rs", "boundary/"];
    const SHIMS: [&str; 2] = ["capi/solver_c.rs", "capi/series_c.rs"];
    let root = src("");
    let mut outside = Vec::new();
    for file in rust_files(&root) {
        let rel = file.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
        let text = std::fs::read_to_string(&file).expect("readable");
        let code: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        let allowed = BOUNDARY.iter().any(|b| rel.starts_with(b))
            || SHIMS.contains(&rel.as_str())
            || rel == "main.rs"
            || rel == "lib.rs"
            || rel.starts_with("capi/panic_tests");
        if has_word(&code, "unsafe") && !allowed {
            outside.push(rel);
        }
    }
    assert!(outside.is_empty(), "unsafe code outside the C boundary: {outside:?}");
    for module in
        ["fmi/common/mod.rs", "solver/mod.rs", "models/mod.rs", "units.rs", "purse_string.rs"]
    {
        let text = std::fs::read_to_string(src(module)).expect("readable");
        assert!(text.contains("#![forbid(unsafe_code)]"), "{module} does not forbid unsafe code");
    }
}

/// `text` without its comment lines and the comment tails of code lines (`//` outside a
/// string literal).
fn code_of(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut in_string = false;
        let mut prev = ' ';
        let mut cut = line.len();
        for (i, c) in line.char_indices() {
            if c == '"' && prev != '\\' {
                in_string = !in_string;
            }
            if !in_string && c == '/' && prev == '/' {
                cut = i - 1;
                break;
            }
            prev = c;
        }
        out.push_str(&line[..cut]);
        out.push('\n');
    }
    out
}

/// The core knows no version: no `fmi2` / `fmi3` (nor `Fmi2`, `FMI3`, ...) in its code,
/// comments aside; the names, the text rewriting and the rules of a version are its
/// folder's `Dialect` (src/fmi/fmi2/names.rs, src/fmi/fmi3/names.rs), and the calls only
/// FMI 3.0 has (its arrays, Intermediate Update Mode) are in src/fmi/fmi3.
#[test]
fn the_fmi_core_names_no_version() {
    let mut found = Vec::new();
    for file in rust_files(&src("fmi/common")) {
        let code = code_of(&std::fs::read_to_string(&file).expect("readable")).to_lowercase();
        for token in ["fmi2", "fmi3"] {
            if code.contains(token) {
                found.push(format!("{}: {token}", file.display()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "the version-independent core names a version:\n{}",
        found.join("\n")
    );
    for (folder, file) in [
        ("fmi2", "names.rs"),
        ("fmi3", "names.rs"),
        ("fmi3", "arrays.rs"),
        ("fmi3", "intermediate.rs"),
    ] {
        let text = std::fs::read_to_string(src(&format!("fmi/{folder}/{file}")))
            .expect("the version's own file");
        assert!(
            text.contains("#![forbid(unsafe_code)]"),
            "fmi/{folder}/{file} is safe Rust and says so"
        );
    }
    assert_eq!(code_of("let a = \"fmi2\"; // fmi3 here\n// fmi3\n"), "let a = \"fmi2\"; \n\n");
}

/// No circle among the solver's modules: a module's `use super::name` of another module
/// (outside its tests) is an edge, and the graph has no cycle. (Items the facade
/// `src/solver/mod.rs` re-exports are not counted here.)
#[test]
fn the_solver_modules_make_no_circle() {
    let dir = src("solver");
    let modules: Vec<String> = rust_files(&dir)
        .iter()
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .filter(|m| m != "mod")
        .collect();
    let edges: Vec<(String, String)> = modules
        .iter()
        .flat_map(|m| {
            let text = std::fs::read_to_string(dir.join(format!("{m}.rs"))).expect("readable");
            let code = text.split("#[cfg(test)]").next().unwrap_or("").to_owned();
            let uses: Vec<String> = code
                .lines()
                .filter(|l| l.trim_start().starts_with("use super::"))
                .map(str::to_owned)
                .collect();
            modules
                .iter()
                .filter(|n| *n != m && uses.iter().any(|u| has_word(u, n)))
                .map(|n| (m.clone(), n.clone()))
                .collect::<Vec<_>>()
        })
        .collect();
    // Depth-first search for a back edge.
    fn visit(m: &str, edges: &[(String, String)], path: &mut Vec<String>, done: &mut Vec<String>) {
        if done.iter().any(|d| d == m) {
            return;
        }
        if let Some(i) = path.iter().position(|p| p == m) {
            panic!("a circle among src/solver's modules: {} -> {m}", path[i..].join(" -> "));
        }
        path.push(m.to_owned());
        for (_, to) in edges.iter().filter(|(from, _)| from == m) {
            visit(to, edges, path, done);
        }
        path.pop();
        done.push(m.to_owned());
    }
    let mut done = Vec::new();
    for m in &modules {
        visit(m, &edges, &mut Vec::new(), &mut done);
    }
    assert!(
        edges.iter().any(|(a, b)| a == "sensitivity" && b == "modal") || edges.len() > 5,
        "edges found: {edges:?}"
    );
}

/// Each FMI version writes its own words: no model description names the other version's
/// functions or statuses, and no source rewrites one version's words into the other's.
#[test]
fn each_fmi_version_writes_its_own_words() {
    for (d, _) in MODELS.iter() {
        let (two, three) =
            (wound_opening::fmi::fmi2::xml::fmi2(d), wound_opening::fmi::fmi3::xml::fmi3(d));
        assert!(
            !three.contains("fmi2"),
            "{}: the FMI 3.0 description names FMI 2.0",
            d.model_identifier
        );
        assert!(
            !two.contains("fmi3"),
            "{}: the FMI 2.0 description names FMI 3.0",
            d.model_identifier
        );
    }
    for path in rust_files(&src("")) {
        let text = std::fs::read_to_string(&path).expect("readable");
        let rewrite = ["replace(\"fmi2\"", "replacen(\"fmi2\""];
        assert!(
            !rewrite.iter().any(|r| text.contains(r)),
            "{}: rewrites FMI 2.0 words",
            path.display()
        );
    }
}
