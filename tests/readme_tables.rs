//! The variable tables of docs/fmi.md against the Rust tables the code and the generated
//! modelDescription.xml use, so that the documented tables cannot drift from the code: every
//! row names a variable of its model with
//! the table's value reference, causality, start value and unit, and every parameter, input
//! and output of the model has a row. Model Exchange states (causality local) and the FMI 3.0
//! arrays are described in prose, not in these tables.

use wound_opening::fmi::common::model::{Causality, Description};
use wound_opening::models::{purse_string as purse, wound};

/// Rows of the markdown table whose header starts with `header`, as trimmed cells.
fn table(readme: &str, header: &str) -> Vec<Vec<String>> {
    let mut lines = readme.lines().skip_while(|l| !l.starts_with(header));
    assert!(lines.next().is_some(), "README has no table with header {header:?}");
    lines
        .skip(1) // |---|
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let inner = l.trim().trim_start_matches('|').trim_end_matches('|');
            // Escaped pipes (\|) belong to a cell.
            inner
                .replace("\\|", "\u{1}")
                .split('|')
                .map(|c| c.trim().replace('\u{1}', "|"))
                .collect()
        })
        .collect()
}

/// Check `rows` (columns: name, value reference, causality, then `start` and `unit` at the
/// given columns) against `description`.
fn check(description: &Description, rows: &[Vec<String>], start_col: usize, unit_col: usize) {
    let model = description.model_identifier;
    for row in rows {
        let name = row[0].trim_matches('`');
        let var = description.variables.iter().find(|v| v.name == name);
        let var = var.unwrap_or_else(|| {
            panic!("{model}: README lists {name}, which the model does not have")
        });
        assert_eq!(row[1], var.value_reference.to_string(), "{model}.{name}: value reference");
        assert!(
            row[2].starts_with(var.causality.as_str()),
            "{model}.{name}: causality {} vs {:?}",
            row[2],
            var.causality
        );
        match var.start {
            Some(start) => {
                let shown: f64 = row[start_col]
                    .parse()
                    .unwrap_or_else(|_| panic!("{model}.{name}: start {:?}", row[start_col]));
                assert_eq!(shown, start, "{model}.{name}: start value");
            }
            None => assert!(
                row[start_col].is_empty(),
                "{model}.{name}: README shows a start value for an output"
            ),
        }
        assert_eq!(row[unit_col], var.unit, "{model}.{name}: unit");
    }
    for var in description.variables.iter().filter(|v| v.causality != Causality::Local) {
        let listed = rows.iter().any(|r| r[0].trim_matches('`') == var.name);
        assert!(listed, "{model}.{}: missing from the README's table", var.name);
    }
}

#[test]
fn readme_variable_tables_match_the_models() {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/fmi.md"))
        .expect("docs/fmi.md");
    let wound_rows =
        table(&readme, "| name | value ref. | causality | variability | start | unit | meaning |");
    check(&wound::variables::DESCRIPTION, &wound_rows, 4, 5);
    let purse_rows = table(&readme, "| name | value ref. | causality | start | unit |");
    check(&purse::variables::DESCRIPTION, &purse_rows, 3, 4);
}
