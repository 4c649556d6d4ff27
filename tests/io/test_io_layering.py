"""Imports inside ``rotorsim.io`` point one way: schema -> specs -> builders -> Model ->
runners -> model_file entry points.

The graph holds every import of one ``rotorsim.io`` module by another, at module level
and inside functions (a lazy import hides a cycle from Python, not from this test);
imports under ``if TYPE_CHECKING:`` are left out because they never run.
"""

from __future__ import annotations

import ast
from pathlib import Path

IO = Path(__file__).resolve().parents[2] / "rotorsim" / "io"
PACKAGE = "rotorsim.io"
SPECS = {f"{PACKAGE}.{name}" for name in ("analysis_spec", "linear_specs", "long_specs",
                                          "api_specs", "spec_registry")}
"""The analysis specs: plain data that imports no schema, builder, Model or runner."""


def module_name(path: Path, root: Path = IO) -> str:
    """Dotted name of a file under ``root`` (the folder of ``rotorsim.io``)."""
    parts = path.relative_to(root).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join((PACKAGE, *parts))


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _runtime_imports(tree: ast.AST) -> list[ast.Import | ast.ImportFrom]:
    """Import statements anywhere in ``tree`` except the bodies of ``if TYPE_CHECKING:``."""
    found: list[ast.Import | ast.ImportFrom] = []
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            stack.extend(node.orelse)
            continue
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append(node)
        stack.extend(ast.iter_child_nodes(node))
    return found


def _targets(node: ast.Import | ast.ImportFrom, here: str, is_package: bool,
             modules: set[str]) -> set[str]:
    """The ``rotorsim.io`` modules one import statement loads."""
    if isinstance(node, ast.Import):
        names = [alias.name for alias in node.names]
    else:
        base = node.module or ""
        if node.level:
            anchor = here.split(".")
            anchor = anchor[:len(anchor) - node.level + (1 if is_package else 0)]
            base = ".".join([*anchor, base] if base else anchor)
        # ``from rotorsim.io import model_build`` loads a submodule, not only the package
        names = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base
                 for alias in node.names]
    out = set()
    for name in names:
        while name and name not in modules:  # ``import rotorsim.io.x.y`` loads x too
            name = name.rpartition(".")[0]
        if name.startswith(PACKAGE):
            out.add(name)
    return out


def import_graph(root: Path = IO) -> dict[str, set[str]]:
    """``{module: modules of rotorsim.io it imports at run time}``."""
    files = {module_name(p, root): p for p in sorted(root.rglob("*.py"))}
    modules = set(files)
    graph: dict[str, set[str]] = {}
    for name, path in files.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        edges: set[str] = set()
        for node in _runtime_imports(tree):
            edges |= _targets(node, name, path.name == "__init__.py", modules)
        graph[name] = edges - {name}
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle of ``graph`` as ``[a, b, ..., a]``, or ``None`` when it is acyclic."""
    state: dict[str, int] = {}  # 1: on the current path, 2: done
    path: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return [*path[path.index(nxt):], nxt]
            if nxt not in state and (cycle := visit(nxt)) is not None:
                return cycle
        path.pop()
        state[node] = 2
        return None

    for start in sorted(graph):
        if start not in state and (cycle := visit(start)) is not None:
            return cycle
    return None


def test_checker_finds_a_cycle_and_ignores_type_checking(tmp_path):
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "a.py").write_text("from rotorsim.io.b import x\n")
    (tmp_path / "b.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from rotorsim.io.a import y\n"
        "def f():\n    from rotorsim.io import c\n")
    (tmp_path / "c.py").write_text("def g():\n    from . import a\n")
    graph = import_graph(tmp_path)
    assert graph["rotorsim.io.b"] == {"rotorsim.io.c"}
    assert find_cycle(graph) == ["rotorsim.io.a", "rotorsim.io.b", "rotorsim.io.c",
                                 "rotorsim.io.a"]
    (tmp_path / "c.py").write_text("")
    assert find_cycle(import_graph(tmp_path)) is None


def test_io_imports_are_acyclic():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle in rotorsim.io: " + " -> ".join(cycle or [])


def test_specs_import_only_specs():
    graph = import_graph()
    outside = {name: sorted(graph[name] - SPECS) for name in sorted(SPECS)}
    assert all(not v for v in outside.values()), outside
