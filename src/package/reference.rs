//! Reference results of an archive (FMI-LS-REF, `extra/org.fmi-standard.fmi-ls-ref/`):
//! the model's outputs over its `<DefaultExperiment>`, computed through the same safe
//! [`Instance`] that every FMI function drives, so any model of the library gets them
//! without code of its own.
//!
//! ```text
//! extra/org.fmi-standard.fmi-ls-ref/fmi-ls-manifest.xml   <fmiReferences> with one <Related role="result">
//! extra/org.fmi-standard.fmi-ls-ref/<Model>_out.csv       "time","output 1",... at the default stepSize (as the Reference-FMUs name it)
//! ```

use std::sync::Arc;
use wound_opening::fmi::common::instance::{Instance, Logger, Status};
use wound_opening::fmi::common::model::{Causality, Description, Experiment, FmuModel};
use wound_opening::fmi::common::xml;

pub const FOLDER: &str = "extra/org.fmi-standard.fmi-ls-ref";

/// At most this many rows (the communication step is the default one; rows are a subset).
const MAX_ROWS: usize = 1000;

struct Silent;
impl Logger for Silent {
    fn log(&self, _: Status, _: &str, _: &str) {}
}

/// Output columns over time: `(names, rows of time then outputs)`.
pub struct Results {
    pub names: Vec<&'static str>,
    pub rows: Vec<Vec<f64>>,
}

/// Run the default experiment with the start values.
pub fn simulate(
    d: &'static Description,
    fresh: fn() -> Box<dyn FmuModel>,
) -> Result<Results, String> {
    simulate_with(d, fresh, &[], d.default_experiment)
}

/// Run experiment `e` with the start values changed by `values` (name, value), set in
/// Initialization Mode as a master does.
pub fn simulate_with(
    d: &'static Description,
    fresh: fn() -> Box<dyn FmuModel>,
    values: &[(&str, f64)],
    e: Experiment,
) -> Result<Results, String> {
    let outputs: Vec<_> = d.variables.iter().filter(|v| v.causality == Causality::Output).collect();
    let vrs: Vec<u32> = outputs.iter().map(|v| v.value_reference).collect();
    let mut inst = Instance::new(fresh, d.model_identifier, Arc::new(Silent), false);
    inst.setup_experiment(Some(e.tolerance), e.start, Some(e.stop))?;
    inst.enter_initialization_mode()?;
    for (name, value) in values {
        let v = d
            .variables
            .iter()
            .find(|v| v.name == *name)
            .ok_or(format!("{} has no variable {name}", d.model_identifier))?;
        inst.set_real(&[v.value_reference], &[*value])?;
    }
    inst.exit_initialization_mode()?;
    let steps = ((e.stop - e.start) / e.step).round() as usize;
    let every = steps.div_ceil(MAX_ROWS).max(1);
    let mut rows = Vec::new();
    let mut values = vec![0.0; vrs.len()];
    for n in 0..=steps {
        let t = e.start + n as f64 * e.step;
        if n > 0 {
            inst.do_step(e.start + (n - 1) as f64 * e.step, e.step)?;
        }
        if n % every == 0 || n == steps {
            inst.get_real(&vrs, &mut values)?;
            rows.push(std::iter::once(t).chain(values.iter().copied()).collect());
        }
    }
    Ok(Results { names: outputs.iter().map(|v| v.name).collect(), rows })
}

impl Results {
    pub fn csv(&self) -> String {
        let head: Vec<String> = std::iter::once("time")
            .chain(self.names.iter().copied())
            .map(|n| format!("\"{n}\""))
            .collect();
        let mut out = head.join(",") + "\n";
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(|&x| xml::number(x)).collect();
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }
}

/// The layered standard's manifest, naming the CSV as the result of the default experiment,
/// then the `<Related>` lines of `more` (the paper's cases, [`super::cases`]).
pub fn manifest(d: &Description, csv_name: &str, more: &str) -> String {
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<fmiReferences xmlns:fmi-ls="http://fmi-standard.org/fmi-ls-manifest" fmi-ls:fmi-ls-name="org.fmi-standard.fmi-ls-ref" fmi-ls:fmi-ls-version="1.0.0-alpha.1" fmi-ls:fmi-ls-description="Reference results of {id}">
  <Related type="text/csv" source="{csv_name}" role="result" description="Outputs of {id} over its DefaultExperiment with the start values, computed by this binary"/>
{more}</fmiReferences>
"#,
        id = d.model_identifier
    )
}
