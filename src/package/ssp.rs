//! The coupled system as an SSP archive (System Structure and Parameterization 1.0):
//!
//! ```text
//! WoundClosure.ssp
//! ├── SystemStructure.ssd        system "WoundClosure": components, connections, parameters
//! └── resources/WoundOpening.fmu, resources/PurseString.fmu   (the FMI 2.0 co-simulation archives)
//! ```
//!
//! The two connections of python/wound_opening/coupling/loop.py:
//! `wound.wound_radius -> purse.wound_radius`, `purse.edge_stress -> wound.edge_stress`;
//! the parameters of its worked example (one system-level parameter set, names
//! `<component>.<variable>`), run from 0 to 300 s (the communication step, 0.5 s in the
//! example, is the master's choice: SSP 1.0 has no field for it).

use std::path::{Path, PathBuf};

type BoxError = Box<dyn std::error::Error>;

pub const FILE: &str = "WoundClosure.ssp";
const STOP: f64 = 300.0;

/// (component, archive, connectors (name, kind), parameters (name, value)).
type Component = (&'static str, &'static str, &'static [(&'static str, &'static str)], &'static [(&'static str, f64)]);

/// The worked example of python/wound_opening/coupling/loop.py (WOUND_EXAMPLE, PURSE_EXAMPLE):
/// tests/python/test_ssp.py checks that they agree.
const COMPONENTS: [Component; 2] = [
    (
        "wound",
        "WoundOpening.fmu",
        &[("edge_stress", "input"), ("wound_radius", "output"), ("edge_velocity", "output")],
        &[("lambda", 1.0), ("sigma", 1.0), ("R_inf", 10.0), ("R0", 10.0), ("T", 10.0), ("G", 100.0)],
    ),
    (
        "purse",
        "PurseString.fmu",
        &[("wound_radius", "input"), ("edge_stress", "output"), ("line_tension", "output")],
        &[("T_max", 6500.0), ("t_assembly", 30.0), ("t_delay", 20.0), ("thickness", 5.0)],
    ),
];

/// (start element, start connector, end element, end connector).
const CONNECTIONS: [(&str, &str, &str, &str); 2] =
    [("wound", "wound_radius", "purse", "wound_radius"), ("purse", "edge_stress", "wound", "edge_stress")];

/// SystemStructure.ssd (valid against SSP 1.0's SystemStructureDescription.xsd).
pub fn ssd() -> String {
    let mut elements = String::new();
    let mut parameters = String::new();
    for (name, archive, connectors, values) in COMPONENTS {
        elements.push_str(&format!("      <ssd:Component name=\"{name}\" type=\"application/x-fmu-sharedlibrary\" source=\"resources/{archive}\">\n        <ssd:Connectors>\n"));
        for (connector, kind) in connectors {
            elements.push_str(&format!("          <ssd:Connector name=\"{connector}\" kind=\"{kind}\"><ssc:Real/></ssd:Connector>\n"));
        }
        for (parameter, _) in values {
            elements.push_str(&format!("          <ssd:Connector name=\"{parameter}\" kind=\"parameter\"><ssc:Real/></ssd:Connector>\n"));
        }
        elements.push_str("        </ssd:Connectors>\n      </ssd:Component>\n");
        for (parameter, value) in values {
            parameters.push_str(&format!(
                "              <ssv:Parameter name=\"{name}.{parameter}\"><ssv:Real value=\"{value}\"/></ssv:Parameter>\n"
            ));
        }
    }
    let connections: String = CONNECTIONS
        .iter()
        .map(|(a, ac, b, bc)| {
            format!("      <ssd:Connection startElement=\"{a}\" startConnector=\"{ac}\" endElement=\"{b}\" endConnector=\"{bc}\"/>\n")
        })
        .collect();
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<ssd:SystemStructureDescription xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues" version="1.0" name="WoundClosure">
  <ssd:System name="WoundClosure" description="A wound of R0 = 10 um opens (WoundOpening) and an actin purse-string closes it (PurseString); communication step 0.5 s in python/coupled_example.py">
    <ssd:ParameterBindings>
      <ssd:ParameterBinding>
        <ssd:ParameterValues>
          <ssv:ParameterSet version="1.0" name="worked_example">
            <ssv:Parameters>
{parameters}            </ssv:Parameters>
          </ssv:ParameterSet>
        </ssd:ParameterValues>
      </ssd:ParameterBinding>
    </ssd:ParameterBindings>
    <ssd:Elements>
{elements}    </ssd:Elements>
    <ssd:Connections>
{connections}    </ssd:Connections>
  </ssd:System>
  <ssd:DefaultExperiment startTime="0" stopTime="{STOP}"/>
</ssd:SystemStructureDescription>
"#
    )
}

/// Writes `out_dir/WoundClosure.ssp` from the FMI 2.0 archives already in `out_dir`.
pub fn write_ssp(out_dir: &Path) -> Result<PathBuf, BoxError> {
    let mut entries = vec![("SystemStructure.ssd".to_string(), ssd().into_bytes())];
    for (_, archive, _, _) in COMPONENTS {
        let path = out_dir.join(archive);
        let bytes = std::fs::read(&path).map_err(|e| format!("cannot read {} for {FILE}: {e}", path.display()))?;
        entries.push((format!("resources/{archive}"), bytes));
    }
    let path = out_dir.join(FILE);
    super::write_zip(&path, &entries)?;
    Ok(path)
}
