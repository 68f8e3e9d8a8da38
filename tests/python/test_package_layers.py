"""The Python package reads inputs -> fitting -> results over the simulation side
(docs/layout.md): every import of every module (function-local ones included), read from
the source, goes down the layers, and no chain of imports leads back to where it started.

Layers, highest first: the command line (cli/: its options, commands, lab-file options,
checks and the report's settings); fitting/ (which builds results from inputs); results/
(which knows the inputs' records, not the fit); inputs/; the simulation side (model,
sweeping, material, shipped, _native). The package's __init__ imports nothing but lazily by name.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "python" / "wound_opening"
#: Anything else: 0 (simulation).
LAYERS = {
    "cli": 4,
    "fitting": 3,
    "results": 2,
    "inputs": 1,
}


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports(path: Path) -> set[str]:
    """The package's modules that `path` imports (absolute names, `wound_opening.x.y`)."""
    name = module_name(path)
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if not target.startswith("wound_opening"):
                continue
            for alias in node.names:  # `from . import _native` names a module
                sub = f"{target}.{alias.name}"
                found.add(sub if module_path(sub) else target)
        elif isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("wound_opening")}
    found.discard(name)
    return found


def module_path(name: str) -> Path | None:
    rel = Path(*name.split(".")[1:])
    for p in (PACKAGE / rel.with_suffix(".py"), PACKAGE / rel / "__init__.py"):
        if p.is_file():
            return p
    return None


def layer(name: str) -> int:
    parts = name.split(".")
    return LAYERS.get(parts[1], 0) if len(parts) > 1 else 0


def graph() -> dict[str, set[str]]:
    return {module_name(p): imports(p) for p in sorted(PACKAGE.rglob("*.py"))}


def test_the_graph_is_read():
    g = graph()
    assert len(g) >= 30, sorted(g)
    assert "wound_opening.fitting.objective" in g["wound_opening.fitting.single"]
    assert "wound_opening._native" in g["wound_opening.model"]  # `from . import _native`


def test_every_import_goes_down_the_layers():
    """inputs/ imports nothing of results/, fitting/ or the command line; results/ nothing of
    fitting/; the simulation side none of them. Within a layer any module may import another."""
    up = [
        f"{a} -> {b}"
        for a, targets in graph().items()
        for b in targets
        if b != "wound_opening" and layer(b) > layer(a)
    ]
    assert not up, "imports that climb a layer:\n" + "\n".join(up)


def test_no_import_cycle():
    g = graph()
    state, cycles = {}, []

    def visit(node, stack):
        state[node] = "open"
        for nxt in sorted(g.get(node, ())):
            if state.get(nxt) == "open":
                cycles.append(" -> ".join(stack[stack.index(nxt) :] + [nxt]))
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = "done"

    for node in sorted(g):
        if node not in state:
            visit(node, [node])
    assert not cycles, "import cycles:\n" + "\n".join(cycles)


def test_no_private_name_crosses_a_module():
    """A name with a leading underscore is its module's own: no other module imports it."""
    crossing = []
    for p in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(p.read_text())):
            if isinstance(node, ast.ImportFrom) and (
                node.level or (node.module or "").startswith("wound_opening")
            ):
                crossing += [
                    f"{module_name(p)}: {a.name}"
                    for a in node.names
                    if a.name.startswith("_")
                    and not a.name.startswith("__")
                    and not module_path(f"wound_opening.{a.name}")
                ]
    assert not crossing, "private names imported from another module:\n" + "\n".join(crossing)


class _Optimiser(Exception):
    """Raised when the trace reaches the local fit: the path is walked."""


def test_a_radius_file_goes_down_the_layers_from_the_command_line_to_the_optimiser():
    """`wound-opening fit <radius file>` traced by sys.setprofile up to the first local fit:
    every call between the package's modules goes to the same layer or a lower one, never
    back up (cli -> fitting -> results / inputs -> simulation), and the path enters each of
    cli, inputs/ and fitting/."""
    import sys

    from wound_opening import cli
    from wound_opening.fitting import local

    root = str(PACKAGE) + "/"
    climbs, entered, errors = set(), set(), []

    def name_of(frame):
        path = frame.f_code.co_filename
        return module_name(Path(path)) if path.startswith(root) else None

    def profile(frame, event, arg):
        if event != "call":
            return
        try:  # an error in here would switch the profiler off unseen: recorded instead
            callee = name_of(frame)
            if callee is None:
                return
            reached_fit = (callee, frame.f_code.co_name) == (local.__name__, "local_fit")
            if not reached_fit:
                entered.add(callee)
                caller = name_of(frame.f_back) if frame.f_back is not None else None
                if caller is not None and layer(callee) > layer(caller):
                    back = frame.f_back.f_code.co_name
                    climbs.add(f"{caller}.{back} -> {callee}.{frame.f_code.co_name}")
        except Exception as e:  # noqa: BLE001
            errors.append(repr(e))
            return
        if reached_fit:
            raise _Optimiser

    data = PACKAGE.parents[1] / "examples" / "data" / "ablation_export.csv"
    argv = [
        "fit",
        str(data),
        "--time-col",
        "Time [ms]",
        "--radius-col",
        "Radius [px]",
        "--time-unit",
        "ms",
        "--length-unit",
        "px",
        "--pixel-size-um",
        "0.1625",
        "--cut-time",
        "2350",
        "--outer-radius-um",
        "100",
    ]
    sys.setprofile(profile)
    try:
        cli.main(argv)
    except _Optimiser:
        reached = True
    else:
        reached = False
    finally:
        sys.setprofile(None)
    assert not errors, errors
    assert reached, "the trace did not reach local_fit"
    assert {
        "wound_opening.cli.commands",
        "wound_opening.inputs.lab_files",
        "wound_opening.fitting.single",
    } <= entered
    assert not climbs, "calls back up a layer:\n" + "\n".join(sorted(climbs))


def test_no_module_is_over_500_lines():
    """The package's modules stay small (docs/layout.md): none over 500 lines."""
    long = {
        str(p.relative_to(PACKAGE)): n
        for p in PACKAGE.rglob("*.py")
        if (n := len(p.read_text().splitlines())) > 500
    }
    assert not long, long
