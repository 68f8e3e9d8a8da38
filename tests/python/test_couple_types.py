"""couple() sets a closure's parameters of every FMI 2.0 type with that type's setter
(docs/closure.md): a closure built here with pythonfmu whose edge stress depends on a Real,
a Boolean and a String parameter couples through couple(), and with a constant edge stress
the coupled radius is the exact solution under that stress (docs/model.md, superposition)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
import wound_exact as we

from wound_opening.coupling.loop import WOUND_EXAMPLE, Closure, couple

HELD = '''
from pythonfmu import Boolean, Fmi2Causality, Fmi2Slave, Fmi2Variability, Real, String


class HeldStress(Fmi2Slave):
    """A constant edge stress: value in `unit` ("Pa" or "kPa") while `on`, else 0."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.value, self.on, self.unit, self.radius = 0.0, False, "Pa", 10.0
        fixed = {"causality": Fmi2Causality.parameter, "variability": Fmi2Variability.tunable}
        self.register_variable(Real("value", **fixed))
        self.register_variable(Boolean("on", **fixed))
        self.register_variable(String("unit", **fixed))
        self.register_variable(Real("radius", causality=Fmi2Causality.input))
        self.register_variable(Real("p", causality=Fmi2Causality.output, getter=self.p))

    def p(self):
        return self.value * {"Pa": 1.0, "kPa": 1000.0}[self.unit] if self.on else 0.0

    def do_step(self, current_time, step_size):
        return True
'''


@pytest.fixture(scope="module")
def held_fmu(tmp_path_factory):
    folder = tmp_path_factory.mktemp("held")
    (folder / "held.py").write_text(HELD)
    done = subprocess.run(
        [sys.executable, "-m", "pythonfmu", "build", "-f", "held.py", "-d", str(folder)],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    return str(folder / "HeldStress.fmu")


def test_real_boolean_and_string_parameters_reach_the_closure(held_fmu, fmu_path):
    w = WOUND_EXAMPLE
    held = Closure(radius="radius", edge_stress="p")
    params = {"value": 0.03, "on": True, "unit": "kPa"}  # 30 Pa = 0.3 sigma G
    run = couple(fmu_path, held_fmu, closure=held, purse_params=params, step=1.0, stop=100.0)
    p = 30.0 / w["G"]
    exact = w["R0"] * we.edge(w["lambda"], w["sigma"], w["R_inf"], run.time[1:] / w["T"], p=p)[0]
    opening = w["R0"] * (we.final_radius(w["sigma"], w["R_inf"]) - we.initial_radius(w["sigma"]))
    assert np.all(run.edge_stress == 30.0)
    assert np.max(np.abs(run.wound_radius[1:] - exact)) <= 1e-10 * opening
    off = couple(
        fmu_path, held_fmu, closure=held, purse_params=params | {"on": False}, step=50.0, stop=100.0
    )
    assert np.all(off.edge_stress == 0.0)
    with pytest.raises(ValueError, match="on is a Boolean parameter: 1 is not one"):
        couple(fmu_path, held_fmu, closure=held, purse_params={"on": 1}, step=1.0, stop=1.0)
    with pytest.raises(ValueError, match="unit is a String parameter"):
        couple(fmu_path, held_fmu, closure=held, purse_params={"unit": 1.0}, step=1.0, stop=1.0)
