//! The paper's three cases as reference results of the WoundOpening archives
//! (FMI-LS-REF), each with the options that made it:
//!
//! ```text
//! extra/org.fmi-standard.fmi-ls-ref/WoundOpening_lambda_<l>_ref.csv   "time","wound_radius","edge_velocity"
//! extra/org.fmi-standard.fmi-ls-ref/WoundOpening_lambda_<l>.opt       fmusim's options, one a line
//! ```
//!
//! lambda = 0.1 (friction dominated), 1, 10 (viscous); sigma = 1, R_inf = 10, edge_stress
//! = 0, t in [0, 500] T with output interval 0.5 T (the dimensionless units: R0 = T = G = 1).
//! The modal step is exact in time for a held input, so the rows are the solver's values
//! at the default tolerance, compared with the exact solution by tests/python/test_reference_cases.py.

use super::reference::{self, Results};
use plotters::prelude::*;
use wound_opening::fmi::common::model::{Description, Experiment, FmuModel};

type BoxError = Box<dyn std::error::Error>;

/// The model whose archives carry the cases.
const MODEL: &str = "WoundOpening";
pub const LAMBDAS: [f64; 3] = [0.1, 1.0, 10.0];
const EXPERIMENT: Experiment = Experiment { start: 0.0, stop: 500.0, step: 0.5, tolerance: 1e-10 };

fn values(lambda: f64) -> [(&'static str, f64); 3] {
    [("lambda", lambda), ("sigma", 1.0), ("R_inf", 10.0)]
}

/// One case: its file stem, results and options.
pub struct Case {
    pub stem: String,
    pub lambda: f64,
    pub results: Results,
}

/// The cases of model `d` (none for a model other than WoundOpening).
pub fn simulate(
    d: &'static Description,
    fresh: fn() -> Box<dyn FmuModel>,
) -> Result<Vec<Case>, String> {
    if d.model_identifier != MODEL {
        return Ok(Vec::new());
    }
    LAMBDAS
        .iter()
        .map(|&lambda| {
            let results = reference::simulate_with(d, fresh, &values(lambda), EXPERIMENT)?;
            Ok(Case { stem: format!("{MODEL}_lambda_{lambda}"), lambda, results })
        })
        .collect()
}

/// fmusim's command-line options that reproduce the case, one a line.
fn options(lambda: f64) -> String {
    let e = EXPERIMENT;
    let mut out = format!(
        "--interface-type cs\n--start-time {}\n--stop-time {}\n--output-interval {}\n--tolerance {:e}\n",
        e.start, e.stop, e.step, e.tolerance
    );
    for (name, value) in values(lambda) {
        out.push_str(&format!("--start-value {name} {value}\n"));
    }
    out
}

/// The archive entries (CSV and options per case) and the manifest's `<Related>` lines.
pub fn entries(cases: &[Case]) -> (Vec<(String, Vec<u8>)>, String) {
    let mut files = Vec::new();
    let mut related = String::new();
    for c in cases {
        let (csv, opt) = (format!("{}_ref.csv", c.stem), format!("{}.opt", c.stem));
        related.push_str(&format!(
            "  <Related type=\"text/csv\" source=\"{csv}\" role=\"result\" description=\"The paper's case lambda = {l}, sigma = 1, R_inf = 10, edge_stress = 0, run with the options of {opt}\"/>\n  <Related type=\"text/plain\" source=\"{opt}\" role=\"experiment\" description=\"fmusim options that made {csv}\"/>\n",
            l = c.lambda
        ));
        files.push((format!("{}/{csv}", reference::FOLDER), c.results.csv().into_bytes()));
        files.push((format!("{}/{opt}", reference::FOLDER), options(c.lambda).into_bytes()));
    }
    (files, related)
}

/// The page's section: the three wound radii over time (log axis), one SVG.
pub fn section_html(cases: &[Case]) -> Result<String, BoxError> {
    if cases.is_empty() {
        return Ok(String::new());
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 420)).into_drawing_area();
        root.fill(&WHITE)?;
        let column = cases[0]
            .results
            .names
            .iter()
            .position(|n| *n == "wound_radius")
            .ok_or("no wound_radius output")?
            + 1;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "wound_radius, the paper's three cases (reference results)",
                ("sans-serif", 20),
            )
            .margin(14)
            .x_label_area_size(56)
            .y_label_area_size(80)
            .build_cartesian_2d((EXPERIMENT.step..EXPERIMENT.stop).log_scale(), 1.15..1.7)?;
        chart
            .configure_mesh()
            .x_desc("time since the cut [T] (logarithmic)")
            .y_desc("wound_radius [R0]")
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 16))
            .x_label_formatter(&|t| format!("{t}"))
            .draw()?;
        // Okabe-Ito colours.
        let colours = [RGBColor(0, 114, 178), RGBColor(213, 94, 0), RGBColor(0, 158, 115)];
        for (c, colour) in cases.iter().zip(colours) {
            let points = c.results.rows.iter().filter(|r| r[0] > 0.0).map(|r| (r[0], r[column]));
            chart
                .draw_series(LineSeries::new(points, colour.stroke_width(3)))?
                .label(format!("lambda = {}", c.lambda))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(3))
                });
        }
        chart
            .configure_series_labels()
            .label_font(("sans-serif", 16))
            .background_style(WHITE)
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerRight)
            .draw()?;
        root.present()?;
    }
    let files: Vec<String> =
        cases.iter().map(|c| format!("<code>{}_ref.csv</code>", c.stem)).collect();
    Ok(format!(
        "<h2>The paper's three cases</h2>\n<p>lambda = 0.1, 1 and 10 with sigma = 1, R_inf = 10, edge_stress = 0, from 0 to {stop} T at an output interval of {step} T: {files} in <code>{folder}/</code>, each with the fmusim options that made it (<code>.opt</code>). They agree with the exact solution (Laplace transform, python/wound_exact.py) within the default tolerance, 1e-10 of the opening R_final - R1 (measured: at most 7.8e-12, at lambda = 0.1).</p>\n{svg}\n",
        stop = EXPERIMENT.stop,
        step = EXPERIMENT.step,
        files = files.join(", "),
        folder = reference::FOLDER,
    ))
}
