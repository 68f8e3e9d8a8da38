//! The coupled system as an SSP archive (System Structure and Parameterization 1.0):
//!
//! ```text
//! WoundClosure.ssp
//! ├── SystemStructure.ssd        system "WoundClosure": components, connections, parameters
//! ├── resources/wound.ssv, resources/purse.ssv   each component's parameter set
//! └── resources/WoundOpening.fmu, resources/PurseString.fmu   (the FMI 2.0 co-simulation archives)
//! ```
//!
//! The two connections of python/wound_opening/coupling/loop.py:
//! `wound.wound_radius -> purse.wound_radius`, `purse.edge_stress -> wound.edge_stress`;
//! the parameters of its worked example, run from 0 to 300 s with a communication step of
//! 0.5 s. SSP 1.0 leaves where a reader looks for parameters and the step to each reader, so
//! the file says both in each reader's place (docs/fmi.md, "The SSP file"):
//!
//! - each component's `ParameterBinding` with `source="resources/<component>.ssv"`, a
//!   parameter set named `worked_example` with the FMU's own names (libcosim applies the
//!   components' first sets; ecos the set it is told by name; fmpy's SSD reader reads them);
//! - the same values once more as the system's inline parameter set, names
//!   `<component>.<variable>` (OMSimulator; fmpy's `simulate_ssp(parameter_set=)` form);
//! - the step as OMSimulator's system annotation (`oms:FixedStepMaster`, which also makes
//!   the system one OMSimulator can import) and as libcosim's default-experiment annotation
//!   (`osp:FixedStepAlgorithm`). No tolerance is written: OMSimulator then passes none and
//!   WoundOpening keeps its own (docs/model.md).

use std::path::{Path, PathBuf};

type BoxError = Box<dyn std::error::Error>;

pub const FILE: &str = "WoundClosure.ssp";
const STOP: f64 = 300.0;
const STEP: f64 = 0.5;
/// The parameter sets' name (ecos: `--parameterSet worked_example`).
const SET: &str = "worked_example";
const OMS: &str =
    "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd";
const OSP: &str = "http://opensimulationplatform.com/SSP/OSPAnnotations";
const SSC: &str = "http://ssp-standard.org/SSP1/SystemStructureCommon";
const SSV: &str = "http://ssp-standard.org/SSP1/SystemStructureParameterValues";

/// (component, archive, connectors (name, kind), parameters (name, value)).
type Component = (
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
    &'static [(&'static str, f64)],
);

/// The worked example of python/wound_opening/coupling/loop.py (WOUND_EXAMPLE, PURSE_EXAMPLE):
/// tests/python/test_ssp.py checks that they agree.
const COMPONENTS: [Component; 2] = [
    (
        "wound",
        "WoundOpening.fmu",
        &[("edge_stress", "input"), ("wound_radius", "output"), ("edge_velocity", "output")],
        &[
            ("lambda", 1.0),
            ("sigma", 1.0),
            ("R_inf", 10.0),
            ("R0", 10.0),
            ("T", 10.0),
            ("G", 100.0),
        ],
    ),
    (
        "purse",
        "PurseString.fmu",
        &[("wound_radius", "input"), ("edge_stress", "output"), ("line_tension", "output")],
        &[("T_max", 6500.0), ("t_assembly", 30.0), ("t_delay", 20.0), ("thickness", 5.0)],
    ),
];

/// (start element, start connector, end element, end connector).
const CONNECTIONS: [(&str, &str, &str, &str); 2] = [
    ("wound", "wound_radius", "purse", "wound_radius"),
    ("purse", "edge_stress", "wound", "edge_stress"),
];

/// `<ssv:Parameter>` lines of `values`, names prefixed with `prefix`.
fn parameters(prefix: &str, values: &[(&str, f64)], indent: &str) -> String {
    values
        .iter()
        .map(|(name, value)| format!("{indent}<ssv:Parameter name=\"{prefix}{name}\"><ssv:Real value=\"{value}\"/></ssv:Parameter>\n"))
        .collect()
}

/// `resources/<component>.ssv`: the component's parameter set (SSP 1.0's
/// SystemStructureParameterValues.xsd), names as in the FMU.
pub fn ssv(values: &[(&str, f64)]) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<ssv:ParameterSet xmlns:ssc=\"{SSC}\" xmlns:ssv=\"{SSV}\" version=\"1.0\" name=\"{SET}\">\n  <ssv:Parameters>\n{}  </ssv:Parameters>\n</ssv:ParameterSet>\n",
        parameters("", values, "    ")
    )
}

/// SystemStructure.ssd (valid against SSP 1.0's SystemStructureDescription.xsd).
pub fn ssd() -> String {
    let mut elements = String::new();
    let mut system_values = String::new();
    for (name, archive, connectors, values) in COMPONENTS {
        elements.push_str(&format!("      <ssd:Component name=\"{name}\" type=\"application/x-fmu-sharedlibrary\" source=\"resources/{archive}\">\n        <ssd:Connectors>\n"));
        for (connector, kind) in connectors {
            elements.push_str(&format!("          <ssd:Connector name=\"{connector}\" kind=\"{kind}\"><ssc:Real/></ssd:Connector>\n"));
        }
        for (parameter, _) in values {
            elements.push_str(&format!("          <ssd:Connector name=\"{parameter}\" kind=\"parameter\"><ssc:Real/></ssd:Connector>\n"));
        }
        elements.push_str(&format!(
            "        </ssd:Connectors>\n        <ssd:ParameterBindings>\n          <ssd:ParameterBinding source=\"resources/{name}.ssv\"/>\n        </ssd:ParameterBindings>\n      </ssd:Component>\n"
        ));
        system_values.push_str(&parameters(&format!("{name}."), values, "              "));
    }
    let connections: String = CONNECTIONS
        .iter()
        .map(|(a, ac, b, bc)| {
            format!("      <ssd:Connection startElement=\"{a}\" startConnector=\"{ac}\" endElement=\"{b}\" endConnector=\"{bc}\"/>\n")
        })
        .collect();
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<ssd:SystemStructureDescription xmlns:ssc="{SSC}" xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" xmlns:ssv="{SSV}" xmlns:oms="{OMS}" xmlns:osp="{OSP}" version="1.0" name="WoundClosure">
  <ssd:System name="WoundClosure" description="A wound of R0 = 10 um opens (WoundOpening) and an actin purse-string closes it (PurseString); communication step {STEP} s">
    <ssd:ParameterBindings>
      <ssd:ParameterBinding>
        <ssd:ParameterValues>
          <ssv:ParameterSet version="1.0" name="{SET}">
            <ssv:Parameters>
{system_values}            </ssv:Parameters>
          </ssv:ParameterSet>
        </ssd:ParameterValues>
      </ssd:ParameterBinding>
    </ssd:ParameterBindings>
    <ssd:Elements>
{elements}    </ssd:Elements>
    <ssd:Connections>
{connections}    </ssd:Connections>
    <ssd:Annotations>
      <ssc:Annotation type="org.openmodelica">
        <oms:Annotations>
          <oms:SimulationInformation>
            <oms:FixedStepMaster description="oms-ma" stepSize="{STEP}"/>
          </oms:SimulationInformation>
        </oms:Annotations>
      </ssc:Annotation>
    </ssd:Annotations>
  </ssd:System>
  <ssd:DefaultExperiment startTime="0" stopTime="{STOP}">
    <ssd:Annotations>
      <ssc:Annotation type="com.opensimulationplatform">
        <osp:Algorithm>
          <osp:FixedStepAlgorithm baseStepSize="{STEP}"/>
        </osp:Algorithm>
      </ssc:Annotation>
    </ssd:Annotations>
  </ssd:DefaultExperiment>
</ssd:SystemStructureDescription>
"#
    )
}

/// Writes `out_dir/WoundClosure.ssp` from the FMI 2.0 archives already in `out_dir`.
pub fn write_ssp(out_dir: &Path) -> Result<PathBuf, BoxError> {
    let mut entries = vec![("SystemStructure.ssd".to_string(), ssd().into_bytes())];
    for (name, archive, _, values) in COMPONENTS {
        let path = out_dir.join(archive);
        let bytes = std::fs::read(&path)
            .map_err(|e| format!("cannot read {} for {FILE}: {e}", path.display()))?;
        entries.push((format!("resources/{name}.ssv"), ssv(values).into_bytes()));
        entries.push((format!("resources/{archive}"), bytes));
    }
    let path = out_dir.join(FILE);
    super::write_zip(&path, &entries)?;
    Ok(path)
}
