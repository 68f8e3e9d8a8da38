//! `documentation/index.html` of an archive, for any model: its prose
//! ([`Description::about`]), the variables (from the same table the code uses) and an SVG
//! plot of each output in the reference results ([`super::reference`]).

use super::reference::Results;
use plotters::prelude::*;
use wound_opening::fmi::common::model::{Description, Variable};

type BoxError = Box<dyn std::error::Error>;

/// One output over time, on a logarithmic time axis (the opening spans decades of time)
/// from the first positive time: 720 x 400 px with 16 px text at 100 % zoom.
fn plot_svg(results: &Results, column: usize, unit: &str) -> Result<String, BoxError> {
    let points: Vec<(f64, f64)> =
        results.rows.iter().filter(|r| r[0] > 0.0).map(|r| (r[0], r[column + 1])).collect();
    let (t0, t1) = (points[0].0, points[points.len() - 1].0);
    let lo = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let hi = points.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
    let pad = ((hi - lo) * 0.05).max(1e-12 * hi.abs().max(1.0));
    let name = &results.names[column];
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 400)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(format!("{name}, reference results (start values)"), ("sans-serif", 20))
            .margin(14)
            .x_label_area_size(56)
            .y_label_area_size(96)
            .build_cartesian_2d((t0..t1).log_scale(), (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("time since the cut [s] (logarithmic)")
            .y_desc(format!("{name} [{}]", shown_unit(unit)))
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 16))
            .x_label_formatter(&|t| format!("{t}"))
            .draw()?;
        chart.draw_series(LineSeries::new(points, RGBColor(0, 114, 178).stroke_width(3)))?;
        root.present()?;
    }
    Ok(svg)
}

/// How to run this FMU with fmpy, for its outputs.
fn usage(d: &Description, file: &str) -> String {
    let outputs: Vec<String> = d
        .variables
        .iter()
        .filter(|v| v.causality.as_str() == "output")
        .map(|v| format!("'{}'", v.name))
        .collect();
    let e = d.default_experiment;
    format!(
        "<h2>Usage with fmpy</h2>\n<pre>from fmpy import simulate_fmu\n\nresult = simulate_fmu('{file}', stop_time={stop}, output_interval={step},\n                      output=[{outputs}])\nprint(result['time'][-1], result[{first}][-1])</pre>\n",
        stop = e.stop,
        step = e.step,
        outputs = outputs.join(", "),
        first = outputs.first().cloned().unwrap_or_default(),
    )
}

/// A unit as a person reads it: the micro sign for the declared "um" (FMI unit names stay ASCII).
fn shown_unit(unit: &str) -> String {
    unit.replace("um", "µm")
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// One table row per variable.
fn variable_rows(variables: &[Variable]) -> String {
    variables
        .iter()
        .map(|v| {
            let start = v.start.map_or("".into(), |s| if s != 0.0 && s.abs() < 1e-3 { format!("{s:e}") } else { s.to_string() });
            format!(
                "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                v.name,
                v.value_reference,
                v.causality.as_str(),
                start,
                escape(&shown_unit(v.unit)),
                escape(v.description)
            )
        })
        .collect()
}

const STYLE: &str = "body{font-family:sans-serif;font-size:16px;max-width:60em;margin:2em auto}td,th{padding:.2em .6em;border-bottom:1px solid #ccc}pre{background:#f4f4f4;padding:.6em;overflow-x:auto}svg{max-width:100%;height:auto}";
const TABLE_HEAD: &str = "<tr><th>name</th><th>value reference</th><th>causality</th><th>start</th><th>unit</th><th>description</th></tr>";

/// The page of one archive; `interfaces` says which FMI version and interface types it has.
/// `more` is HTML appended after the reference results (the paper's cases, [`super::cases`]).
pub fn index_html(
    d: &Description,
    interfaces: &str,
    file: &str,
    results: &Results,
    more: &str,
) -> Result<String, BoxError> {
    let mut plots = String::new();
    for (i, name) in results.names.iter().enumerate() {
        let unit = d.variables.iter().find(|v| v.name == *name).map_or("", |v| v.unit);
        plots.push_str(&plot_svg(results, i, unit)?);
        plots.push('\n');
    }
    let id = d.model_identifier;
    let e = d.default_experiment;
    Ok(format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{id} FMU</title>
<style>{STYLE}</style>
</head><body>
<h1>{id}</h1>
<p>{interfaces}.</p>
{about}
{usage}<h2>Variables</h2>
<table>{TABLE_HEAD}
{rows}</table>
<h2>Reference results</h2>
<p>The default experiment (start {start} s, stop {stop} s, step {step} s, tolerance {tol:e}) with the start values,
computed by this FMU's own code: <code>extra/org.fmi-standard.fmi-ls-ref/{id}_out.csv</code>
(plotted from the first output time after the start, on a logarithmic time axis).</p>
{plots}{more}</body></html>
"#,
        about = d.about,
        usage = usage(d, file),
        rows = variable_rows(d.variables),
        start = e.start,
        stop = e.stop,
        step = e.step,
        tol = e.tolerance,
    ))
}
