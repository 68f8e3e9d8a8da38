"""An SSP 1.0 file of WoundOpening coupled to a closure FMU, laid out as the shipped
WoundClosure.ssp (src/package/ssp.rs writes that one; tests/python/test_ssp.py checks that
this writer, given PurseString.fmu and the worked example, says the same):

    SystemStructure.ssd              components wound and closure, two connections, the
                                     parameters as the system's set (OMSimulator), the step
                                     as OMSimulator's and libcosim's annotations
    resources/<component>.ssv        each component's parameter set, FMU names (libcosim,
                                     ecos by the set's name, fmpy's SSD reader)
    resources/WoundOpening.fmu, resources/<closure>.fmu

Parameters are typed by the FMU's modelDescription.xml (Real, Integer, Boolean, String).
Used by `python python/coupling/ssp.py build` (docs/closure.md).
"""

from __future__ import annotations

import math
import zipfile
from pathlib import Path
from xml.sax.saxutils import quoteattr

from fmpy import read_model_description

from .loop import WOUND_EXAMPLE

SET = "worked_example"
_NS = (
    'xmlns:ssc="http://ssp-standard.org/SSP1/SystemStructureCommon" '
    'xmlns:ssv="http://ssp-standard.org/SSP1/SystemStructureParameterValues"'
)
_SSD_NS = (
    'xmlns:ssd="http://ssp-standard.org/SSP1/SystemStructureDescription" '
    'xmlns:oms="https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd" '
    'xmlns:osp="http://opensimulationplatform.com/SSP/OSPAnnotations"'
)
# FMI 2.0 type -> SSP 1.0 type (an Enumeration's value is its Integer)
_TYPES = {
    "Real": "Real",
    "Integer": "Integer",
    "Enumeration": "Integer",
    "Boolean": "Boolean",
    "String": "String",
}


def _number(x: float) -> str:
    """x as src/package/ssp.rs writes it (Rust's `{}`): whole numbers without a fraction."""
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else repr(float(x))


def _typed(md, values: dict | list, who: str) -> list[tuple[str, str, str]]:
    """[(name, SSP type, value text)] of `values` (a dict, or NAME=VALUE strings), checked
    against the FMU's parameters and their types."""
    if not isinstance(values, dict):
        pairs = {}
        for item in values:
            name, sep, text = item.partition("=")
            if not sep:
                raise ValueError(f"{item!r}: expected NAME=VALUE")
            pairs[name.strip()] = text.strip()
        values = pairs
    variables = {v.name: v for v in md.modelVariables if v.causality in ("parameter", "input")}
    out = []
    for name, value in values.items():
        v = variables.get(name)
        if v is None or v.type not in _TYPES:
            have = ", ".join(sorted(variables))
            raise ValueError(
                f"{who} has no parameter {name!r} of a type SSP 1.0 sets; it has: {have}"
            )
        kind = _TYPES[v.type]
        text = str(value).strip()
        try:
            if kind == "Real":
                number = float(text)
                if not math.isfinite(number):
                    raise ValueError
                text = _number(number)
            elif kind == "Integer":
                number = float(text)
                if not number.is_integer():
                    raise ValueError
                text = str(int(number))
            elif kind == "Boolean":
                text = {"true": "true", "false": "false", "1": "true", "0": "false"}[text.lower()]
        except (ValueError, KeyError):
            raise ValueError(
                f"{who}.{name} is a {v.type} parameter: {value!r} is not one"
            ) from None
        out.append((name, kind, text))
    return out


def _parameters(values, prefix: str, indent: str) -> str:
    return "".join(
        f"{indent}<ssv:Parameter name={quoteattr(prefix + name)}>"
        f"<ssv:{kind} value={quoteattr(text)}/></ssv:Parameter>\n"
        for name, kind, text in values
    )


def ssv(values) -> str:
    """A component's .ssv parameter set."""
    return (
        f'<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<ssv:ParameterSet {_NS} version="1.0" name="{SET}">\n'
        f"  <ssv:Parameters>\n{_parameters(values, '', '    ')}  </ssv:Parameters>\n"
        "</ssv:ParameterSet>\n"
    )


def _outputs(md, names, what: str, who: str) -> None:
    have = {v.name: v for v in md.modelVariables}
    for name, causality in names:
        v = have.get(name)
        if v is None or v.causality != causality or v.type != "Real":
            real = sorted(
                n for n, v in have.items() if v.causality == causality and v.type == "Real"
            )
            raise ValueError(
                f"{who} has no Real {causality} {name!r} ({what}); its Real "
                f"{causality}s: {', '.join(real)}"
            )


def build(
    closure_fmu: str,
    out: str,
    *,
    radius: str = "wound_radius",
    edge_stress: str = "edge_stress",
    record=(),
    closure_values=(),
    wound_values=(),
    wound_fmu: str | None = None,
    step: float = 0.5,
    stop: float = 300.0,
    name: str = "closure",
) -> Path:
    """Writes the SSP to `out` and returns its path; ValueError for a name the FMUs do not
    have, a value their types cannot hold, or a step that does not divide the stop time."""
    if wound_fmu is None:
        from ..shipped import fmu_path

        wound_fmu = str(fmu_path("WoundOpening.fmu"))
    n = round(stop / step) if step > 0 else 0
    if not (math.isfinite(stop) and n >= 1 and abs(n * step - stop) <= 1e-9 * stop):
        raise ValueError(f"stop = {stop} is not a whole number of steps of {step}")
    closure_md = read_model_description(closure_fmu)
    if closure_md.fmiVersion != "2.0" or closure_md.coSimulation is None:
        raise ValueError(f"{closure_fmu}: the SSP's readers need an FMI 2.0 co-simulation archive")
    who = Path(closure_fmu).stem
    _outputs(closure_md, [(radius, "input")], "set to the wound radius", who)
    _outputs(
        closure_md,
        [(edge_stress, "output")] + [(r, "output") for r in record],
        "read as the edge stress",
        who,
    )
    wound_md = read_model_description(wound_fmu)
    given = dict(WOUND_EXAMPLE)
    given.update({k: v for k, _, v in (s.partition("=") for s in wound_values)})
    components = [
        (
            "wound",
            Path(wound_fmu).name,
            [("edge_stress", "input"), ("wound_radius", "output"), ("edge_velocity", "output")],
            _typed(wound_md, given, "WoundOpening"),
        ),
        (
            name,
            Path(closure_fmu).name,
            [(radius, "input"), (edge_stress, "output")] + [(r, "output") for r in record],
            _typed(closure_md, closure_values, who),
        ),
    ]
    if components[0][1] == components[1][1]:
        raise ValueError("the closure FMU's file name must differ from WoundOpening's")
    elements, system_values = "", ""
    for comp, archive, connectors, values in components:
        source = quoteattr("resources/" + archive)
        elements += (
            f'      <ssd:Component name="{comp}" type="application/x-fmu-sharedlibrary" '
            f"source={source}>\n        <ssd:Connectors>\n"
        )
        typed = [(c, kind, "Real") for c, kind in connectors]
        typed += [(p, "parameter", kind) for p, kind, _ in values]
        for connector, kind, ssc in typed:
            elements += (
                f"          <ssd:Connector name={quoteattr(connector)} "
                f'kind="{kind}"><ssc:{ssc}/></ssd:Connector>\n'
            )
        elements += (
            "        </ssd:Connectors>\n        <ssd:ParameterBindings>\n"
            f'          <ssd:ParameterBinding source="resources/{comp}.ssv"/>\n'
            "        </ssd:ParameterBindings>\n      </ssd:Component>\n"
        )
        system_values += _parameters(values, comp + ".", "              ")
    connections = (
        '      <ssd:Connection startElement="wound" startConnector="wound_radius" '
        f'endElement="{name}" endConnector={quoteattr(radius)}/>\n'
        f'      <ssd:Connection startElement="{name}" startConnector={quoteattr(edge_stress)} '
        'endElement="wound" endConnector="edge_stress"/>\n'
    )
    description = quoteattr(f"WoundOpening coupled to {who}; communication step {_number(step)} s")
    ssd = f"""<?xml version="1.0" encoding="UTF-8"?>
<ssd:SystemStructureDescription {_NS} {_SSD_NS} version="1.0" name="WoundClosure">
  <ssd:System name="WoundClosure" description={description}>
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
            <oms:FixedStepMaster description="oms-ma" stepSize="{_number(step)}"/>
          </oms:SimulationInformation>
        </oms:Annotations>
      </ssc:Annotation>
    </ssd:Annotations>
  </ssd:System>
  <ssd:DefaultExperiment startTime="0" stopTime="{_number(stop)}">
    <ssd:Annotations>
      <ssc:Annotation type="com.opensimulationplatform">
        <osp:Algorithm>
          <osp:FixedStepAlgorithm baseStepSize="{_number(step)}"/>
        </osp:Algorithm>
      </ssc:Annotation>
    </ssd:Annotations>
  </ssd:DefaultExperiment>
</ssd:SystemStructureDescription>
"""
    path = Path(out)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("SystemStructure.ssd", ssd)
        for comp, archive, _, values in components:
            z.writestr(f"resources/{comp}.ssv", ssv(values))
        for fmu in (wound_fmu, closure_fmu):  # archives already: stored, not deflated again
            z.write(fmu, f"resources/{Path(fmu).name}", compress_type=zipfile.ZIP_STORED)
    return path
