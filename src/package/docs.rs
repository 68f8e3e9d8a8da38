//! `documentation/index.html` of the FMU: the model, the variables (from the same table
//! the code uses) and an SVG plot of the wound radius computed by the solver itself.

use plotters::prelude::*;
use wound_opening::fmi::model::Variable;
use wound_opening::fmi::{purse, wound::variables::VARIABLES};
use wound_opening::solver::{Params, Settings, Solver, exact};

type BoxError = Box<dyn std::error::Error>;

const LAMBDAS: [f64; 3] = [0.1, 1.0, 10.0];

/// `(log10 t, R(t))` on a logarithmic time grid from 1e-3 to 1e3 T.
fn radius_curve(lambda: f64) -> Result<Vec<(f64, f64)>, BoxError> {
    let params = Params { lambda, sigma: 1.0, r_inf: 10.0 };
    let mut solver = Solver::new(&params, &Settings::default())?;
    let mut points = Vec::new();
    for k in 0..=240 {
        let t = 10f64.powf(-3.0 + k as f64 * 0.025);
        solver.advance(t - solver.time(), 0.0)?;
        points.push((t.log10(), solver.wound_radius()));
    }
    Ok(points)
}

fn plot_svg() -> Result<String, BoxError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (720, 420)).into_drawing_area();
        root.fill(&WHITE)?;
        let (r1, rf) = (exact::initial_radius(1.0), exact::final_radius(1.0, 10.0));
        let mut chart = ChartBuilder::on(&root)
            .caption("Wound radius after the cut (sigma = 1, R_inf = 10)", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(-3.0..3.0, (r1 - 0.02)..(rf + 0.03))?;
        chart
            .configure_mesh()
            .x_desc("log10(t / T)")
            .y_desc("R / R0")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .draw()?;
        for (lambda, color) in LAMBDAS.iter().zip([RED, GREEN, BLUE]) {
            chart
                .draw_series(LineSeries::new(radius_curve(*lambda)?, color.stroke_width(2)))?
                .label(format!("lambda = {lambda}"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
        }
        chart.configure_series_labels().border_style(BLACK).background_style(WHITE).draw()?;
        root.present()?;
    }
    Ok(svg)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// One table row per variable.
fn variable_rows(variables: &[Variable]) -> String {
    variables
        .iter()
        .map(|v| {
            let start = v.start.map_or("".into(), |s| s.to_string());
            format!(
                "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                v.name,
                v.value_reference,
                v.causality.as_str(),
                start,
                escape(v.unit),
                escape(v.description)
            )
        })
        .collect()
}

const STYLE: &str = "body{font-family:sans-serif;max-width:60em;margin:2em auto}td,th{padding:.2em .6em;border-bottom:1px solid #ccc}pre{background:#f4f4f4;padding:.6em}";
const TABLE_HEAD: &str =
    "<tr><th>name</th><th>value reference</th><th>causality</th><th>start</th><th>unit</th><th>description</th></tr>";

/// `documentation/index.html` of WoundOpening.fmu.
pub fn index_html() -> Result<String, BoxError> {
    let rows = variable_rows(&VARIABLES);
    Ok(format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>WoundOpening FMU</title>
<style>{STYLE}</style>
</head><body>
<h1>WoundOpening</h1>
<p>Opening of a circular wound in a thin, incompressible Kelvin-Voigt tissue (shear modulus G,
viscosity eta) on a substrate with friction zeta, stretched by a homeostatic tension sigma before
the cut. FMI 2.0 co-simulation.</p>
<h2>Model (dimensionless)</h2>
<p>Lengths in R0 (wound radius), stresses in G, time in T = zeta R0<sup>2</sup> / (4 G);
lambda = 2 sqrt(eta / zeta) / R0. Radial displacement u(r, t), 1 &lt; r &lt; R_inf:</p>
<pre>D2 u + lambda^2 D2 u_t - u_t = 0,        D2 f = f'' + f'/r - f/r^2
sigma_rr = D u + lambda^2 D u_t,          D f  = 2 (2 f' + f / r)
sigma_rr(1, t) = edge_stress,  sigma_rr(R_inf, t) = sigma,  u(r, 0) = sigma r / 6
wound_radius = 1 + u(1, t),  edge_velocity = u_t(1, t)</pre>
<p>Solved by spectral elements in r (Galerkin form, edge stresses as natural boundary terms) and
exactly in time, mode by mode, with edge_stress held constant over each communication step.</p>
<h2>Physical units</h2>
<p>The parameters R0 [um], T [s] and G [Pa] (all 1 by default, which keeps every value
dimensionless) scale the master's time (t / T), the edge_stress input (/ G) and the outputs
(wound_radius x R0, edge_velocity x R0 / T). From material constants: lambda = 2 sqrt(eta / zeta) / R0,
sigma = tension / G, T = zeta R0<sup>2</sup> / (4 G); the viscous relaxation time is eta / G = lambda<sup>2</sup> T.</p>
<h2>Variables</h2>
<table>{TABLE_HEAD}
{rows}</table>
<h2>Wound radius (computed by this FMU's solver)</h2>
{svg}
</body></html>
"#,
        svg = plot_svg()?
    ))
}

/// `documentation/index.html` of PurseString.fmu.
pub fn purse_html() -> String {
    let rows = variable_rows(&purse::variables::VARIABLES);
    format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>PurseString FMU</title>
<style>{STYLE}</style>
</head><body>
<h1>PurseString</h1>
<p>An actin purse-string closing a wound, to couple with WoundOpening.fmu (its wound_radius
output to this input, this edge_stress output to its input). FMI 2.0 co-simulation.</p>
<pre>T_c(t) = 0                                              t &lt;= t_delay
T_c(t) = T_max (1 - exp(-(t - t_delay) / t_assembly))   t &gt;  t_delay
edge_stress = T_c / (thickness * wound_radius)           [pN / um^2 = Pa]</pre>
<p>Time is the master's, in seconds since the cut. A wound_radius &lt;= 0 (a closed wound, which
the linear tissue model does not describe) is refused with an error.</p>
<h2>Variables</h2>
<table>{TABLE_HEAD}
{rows}</table>
</body></html>
"#
    )
}
