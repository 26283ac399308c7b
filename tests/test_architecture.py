"""docs/architecture.md's module map is the code's: every module is in it, in one layer, and
the imports (those inside functions and under TYPE_CHECKING included) run only within a layer
or down to a lower one, never round a circle."""

from __future__ import annotations

import ast
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "src" / "grainclass"
ARCHITECTURE = (ROOT / "docs" / "architecture.md").read_text()


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def _layers() -> dict[str, int]:
    """Each module of the map, by its dotted name, and the number of its layer."""
    section = ARCHITECTURE.split("\n## Module map\n", 1)[1].split("\n## ", 1)[0]
    layer_of: dict[str, int] = {}
    layer = 0
    for line in section.splitlines():
        heading = re.match(r"### (\d+)\. ", line)
        if heading:
            layer = int(heading.group(1))
        row = re.match(r"\| \[`([^`]+)`\]", line)
        if row and row.group(1).endswith(".py"):
            assert layer, f"{row.group(1)} stands in no layer"
            name = _module_name(PACKAGE / row.group(1))
            assert name not in layer_of, f"{row.group(1)} stands in two layers"
            layer_of[name] = layer
    return layer_of


def _imports(name: str, path: Path) -> set[str]:
    """The modules of grainclass that ``name`` imports anywhere in its file. ``from package
    import module`` imports that module (its package's __init__ runs first, as for any module
    of the package, and is not counted as imported)."""
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join([*base, *([node.module] if node.module else [])])
            else:
                module = node.module or ""
            inner = [f"{module}.{alias.name}" for alias in node.names]
            inner = [m for m in inner if m in MODULES]
            found.update(inner if len(inner) == len(node.names) else [module, *inner])
    return {module for module in found if module in MODULES and module != name}


GRAPH = {name: _imports(name, path) for name, path in MODULES.items()}


def test_every_module_is_in_the_map_once():
    layer_of = _layers()
    assert sorted(set(MODULES) - set(layer_of)) == []
    assert sorted(set(layer_of) - set(MODULES)) == []


def test_no_module_imports_one_of_a_higher_layer():
    layer_of = _layers()
    upward = [
        f"{module} (layer {layer_of[module]}) imports {imported} (layer {layer_of[imported]})"
        for module, imported_modules in sorted(GRAPH.items())
        for imported in sorted(imported_modules)
        if layer_of[imported] > layer_of[module]
    ]
    assert upward == []


def test_no_import_circle():
    # Depth-first search for a back edge: a path that comes back to a module on it.
    state: dict[str, str] = {}
    circles: list[list[str]] = []

    def visit(module: str, path: list[str]) -> None:
        state[module] = "open"
        for imported in sorted(GRAPH[module]):
            if state.get(imported) == "open":
                circles.append([*path[path.index(imported) :], imported])
            elif imported not in state:
                visit(imported, [*path, imported])
        state[module] = "done"

    for module in sorted(GRAPH):
        if module not in state:
            visit(module, [module])
    assert circles == []


def test_the_checks_see_imports_inside_functions():
    """The map's checks would pass vacuously if lazy imports went unseen: the commands import
    the library inside their functions."""
    assert "grainclass.datasets" in GRAPH["grainclass.cli.summarize"]
    assert "grainclass.classification" in GRAPH["grainclass.pipeline"]
