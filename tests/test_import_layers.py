"""core's modules import one way: no cycle among them, counting every import statement wherever it
is (module level, inside a function, under TYPE_CHECKING) and the registry's loading of every
calculator module by name (issue 34 item 7: core/model <-> registry <-> declarations <-> fields <->
units went round, held apart only by imports inside functions and TYPE_CHECKING).

The layers (core/model.py's docstring): errors, units, fields at the bottom; declarations; the
calculators and their scenes (core/sim); the registry, which loads the calculators; model (solve);
sweep, tolerance, presets, export on top. A lazy import (pint, numpy, scipy at first use) is fine:
it is an edge like any other here, and only a cycle fails.
"""

from __future__ import annotations

import ast
import pathlib

CORE = pathlib.Path(__file__).resolve().parents[1] / "core"

# Edges known to close a cycle and left for later (none now); an entry must still exist
# (test_pending_edges_still_exist), so the set cannot outlive its reason.
PENDING: set[tuple[str, str]] = set()


def _modules(core: pathlib.Path) -> dict[str, pathlib.Path]:
    out = {}
    for path in core.rglob("*.py"):
        parts = list(path.relative_to(core.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _targets(module: str, is_package: bool, node: ast.Import | ast.ImportFrom, known) -> set[str]:
    """The core modules one import statement loads (a package and the submodules it names)."""
    names: list[str] = []
    if isinstance(node, ast.Import):
        names = [a.name for a in node.names]
    else:
        if node.level:
            base = module.split(".") if is_package else module.split(".")[:-1]
            base = base[: len(base) - (node.level - 1)]
            prefix = ".".join(base + ([node.module] if node.module else []))
        else:
            prefix = node.module or ""
        names = [prefix] + [f"{prefix}.{a.name}" for a in node.names]
    names = [n.removeprefix("gearhead.") for n in names]
    found = set()
    for n in names:
        parts = n.split(".")
        for i in range(1, len(parts) + 1):  # `import a.b.c` loads a, a.b and a.b.c
            if ".".join(parts[:i]) in known:
                found.add(".".join(parts[:i]))
    # A module's own packages are loaded before it runs, so loading a sibling through them is no
    # edge to them (a package's __init__ may name its parts: core.workbook); reading a name their
    # __init__ defines (`from . import NAME`, NAME no module) still is.
    ancestors = {".".join(module.split(".")[:i]) for i in range(1, len(module.split(".")))}
    if isinstance(node, ast.ImportFrom):
        read = {prefix} if any(f"{prefix}.{a.name}" not in known for a in node.names) else set()
    else:
        read = {n.removeprefix("gearhead.") for n in (a.name for a in node.names)}
    return {m for m in found if m not in ancestors or m in read}


def package_graph(root: pathlib.Path) -> dict[str, set[str]]:
    """{module: the modules of the same package it imports}, every import statement counted."""
    modules = _modules(root)
    graph: dict[str, set[str]] = {}
    for module, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        edges: set[str] = set()
        for node in ast.walk(tree):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                edges |= _targets(module, path.name == "__init__.py", node, modules)
        edges.discard(module)
        graph[module] = edges
    return graph


def import_graph(core: pathlib.Path = CORE) -> dict[str, set[str]]:
    """{module: the core modules it imports}, every import statement counted, plus the registry's
    importlib loading of each calculator module."""
    modules = _modules(core)
    graph = package_graph(core)
    registry = modules["core.registry"].read_text(encoding="utf-8")
    assert "importlib.import_module" in registry, "the registry no longer loads by name: update this test"
    graph["core.registry"] |= {m for m in modules if m.startswith("core.calculators.")}
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle as [a, b, ..., a], or None."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return path[path.index(nxt) :] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        path.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_core_modules_import_one_way():
    graph = import_graph()
    for a, b in PENDING:
        graph[a].discard(b)
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle among core modules: " + " -> ".join(cycle)


def test_tui_modules_import_one_way():
    """tui/ too (issue 42 item 4: cli <-> workbook_cli went round through cli's private helpers,
    imported inside a function). A package's __init__ importing its submodules is no cycle here:
    tui's are empty."""
    graph = package_graph(CORE.parent / "tui")
    graph.pop("tui", None)
    for edges in graph.values():
        edges.discard("tui")
        edges.discard("tui.components")
    cycle = find_cycle(graph)
    assert cycle is None, "import cycle among tui modules: " + " -> ".join(cycle)


def test_pending_edges_still_exist():
    graph = import_graph()
    gone = sorted(f"{a} -> {b}" for a, b in PENDING if b not in graph[a])
    assert not gone, f"no longer imported, remove from PENDING: {', '.join(gone)}"


def test_the_checker_sees_a_cycle_through_a_function_level_import(tmp_path):
    """The graph counts an import inside a function and one under TYPE_CHECKING (both hid the old
    circle), and the registry's loading of calculators by name."""
    core = tmp_path / "core"
    (core / "calculators").mkdir(parents=True)
    (core / "__init__.py").write_text("")
    (core / "calculators" / "__init__.py").write_text("")
    (core / "registry.py").write_text("import importlib\n# importlib.import_module by name\n")
    (core / "a.py").write_text("def f():\n    from .b import x\n")
    (core / "b.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from . import a\n")
    assert find_cycle(import_graph(core)) == ["core.a", "core.b", "core.a"]
    (core / "b.py").write_text("")
    assert find_cycle(import_graph(core)) is None
    (core / "calculators" / "c.py").write_text("from ..registry import importlib\n")
    assert find_cycle(import_graph(core)) == ["core.calculators.c", "core.registry", "core.calculators.c"]


def test_a_package_naming_its_parts_is_no_cycle_but_reading_its_names_back_is(tmp_path):
    """A package whose __init__ re-exports its modules (core.workbook) is no cycle: a module loads
    its siblings through the package, which is already loading. A module that reads a name the
    __init__ defines (the __init__ importing that module) is one."""
    core = tmp_path / "core"
    (core / "calculators").mkdir(parents=True)
    (core / "pkg").mkdir()
    (core / "__init__.py").write_text("")
    (core / "calculators" / "__init__.py").write_text("")
    (core / "registry.py").write_text("import importlib\n# importlib.import_module by name\n")
    (core / "units.py").write_text("")
    (core / "pkg" / "__init__.py").write_text("from .a import x\nfrom .b import y\n")
    (core / "pkg" / "a.py").write_text("from .. import units\nx = 1\n")
    (core / "pkg" / "b.py").write_text("from .a import x\nfrom ..units import *\ny = x\n")
    assert find_cycle(import_graph(core)) is None
    (core / "pkg" / "b.py").write_text("from . import x\ny = x\n")  # x from the __init__
    assert find_cycle(import_graph(core)) == ["core.pkg", "core.pkg.b", "core.pkg"]
