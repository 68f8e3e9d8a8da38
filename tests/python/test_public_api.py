"""What `import wound_opening` offers: the names the README, docs/*.md, the scripts under
python/, the benchmarks and the tests call as `wound_opening.<name>` (or `wo.<name>`),
pinned, so that moving a module cannot drop one. Each resolves (imported lazily on first
use), `dir()` lists it (and not the module's helpers), the module docstring gives it a line
and `help(wound_opening)` shows it."""

from __future__ import annotations

import pydoc
import re
import subprocess
import sys

import wound_opening

PUBLIC = {
    "FitResult",
    "NativeLibraryMissing",
    "Parameters",
    "RadiusSeries",
    "Simulation",
    "SolverError",
    "TissueFitResult",
    "VelocityProfile",
    "Wound",
    "fit",
    "fit_wounds",
    "fmu_path",
    "fmu_start_values",
    "from_material",
    "library_path",
    "read_profile",
    "read_radius",
    "read_wounds",
    "simulate",
    "sweep",
    "to_material",
    "write_report",
}


def test_all_is_the_pinned_public_api():
    assert set(wound_opening.__all__) == PUBLIC


def test_every_public_name_resolves_and_is_listed():
    for name in sorted(PUBLIC):
        value = getattr(wound_opening, name)
        assert getattr(value, "__name__", name) == name, (name, value)
    assert PUBLIC <= set(dir(wound_opening))
    assert isinstance(wound_opening.__version__, str)


def test_dir_lists_the_public_names_and_not_the_helpers():
    names = [n for n in dir(wound_opening) if not n.startswith("__")]
    assert names == sorted(PUBLIC)


def test_the_docstring_and_help_list_every_public_name():
    """Each public name starts a line of the module docstring (its one-line description),
    and help() (pydoc) renders its documentation."""
    listed = set(re.findall(r"^    (\w+)", wound_opening.__doc__, re.M))
    assert PUBLIC <= listed, sorted(PUBLIC - listed)
    assert listed <= PUBLIC, sorted(listed - PUBLIC)
    text = pydoc.plain(pydoc.render_doc(wound_opening))
    for name in PUBLIC:
        assert re.search(rf"^    (class )?{name}\b", text, re.M), name


def test_the_subpackages_do_not_shadow_a_public_function():
    """`wound_opening.fit` stays the function after its subpackage is imported (a
    subpackage named like a public name would replace it on the package)."""
    import wound_opening.fitting.single  # noqa: F401
    import wound_opening.results.result  # noqa: F401

    assert (
        callable(wound_opening.fit)
        and wound_opening.fit.__module__ == "wound_opening.fitting.single"
    )


def test_the_package_imports_no_numerics_until_a_name_is_used():
    """`import wound_opening` (and `wound-opening --help`) load neither numpy nor scipy."""
    code = (
        "import sys, wound_opening; wound_opening.__all__; print(sorted(m for m in ('numpy', "
        "'scipy', 'pandas') if m in sys.modules))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True
    ).stdout
    assert out.strip() == "[]"
