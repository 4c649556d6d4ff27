"""Import rules of the package layout (DESIGN sections 1, 2 and 12; docs/architecture.md).

The rules are data (:data:`RULES`): which modules may not import which. The checker parses
every module with ``ast`` and counts module-level and function-level (lazy) imports alike;
imports under ``if TYPE_CHECKING:`` never run and are left out. Each rule is also run on a
small fake package with a planted violation (:data:`PLANTED`), so the checker itself stays
tested. Besides the rules: no import cycle among the modules of ``rotorsim.io``, every
subpackage has an ``__init__.py`` with a docstring, no catch-all modules, and ``import
rotorsim`` loads no heavy optional or slow-to-import module.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "rotorsim"
ROLLING = "rotorsim.elements.rolling"
NUMERICS = ("rotorsim.solvers", "rotorsim.time_integration", "rotorsim.harmonic_balance",
            "rotorsim.hb")
FAMILIES = tuple(f"rotorsim.analyses.{f}"
                 for f in ("linear", "statics", "transient", "periodic", "sweep", "standards",
                           "quasiperiodic"))
ROLLING_SHARED = tuple(f"{ROLLING}.{m}"
                       for m in ("geometry", "state", "element_equilibrium", "condensation"))
NOT_AT_IMPORT = (
    # slow SciPy submodules (0.05-0.4 s each), imported where they are used
    "scipy.stats", "scipy.optimize", "scipy.interpolate", "scipy.integrate", "scipy.spatial",
    "scipy.special", "scipy.signal", "scipy.fft", "scipy.ndimage", "xml.etree.ElementTree",
    # optional dependencies, at the edges only (STYLE practice 13)
    "matplotlib", "h5py", "meshio", "skfem", "tqdm", "dask",
)
"""Modules that ``import rotorsim`` must not load."""


@dataclass(frozen=True)
class Rule:
    """Modules in ``owners`` (and below; not those in ``exempt``) import nothing in
    ``forbidden`` (and below), except what is in ``allowed`` (and below)."""

    name: str
    text: str
    owners: tuple[str, ...]
    forbidden: tuple[str, ...]
    allowed: tuple[str, ...] = ()
    exempt: tuple[str, ...] = ()


RULES = (
    Rule("physics-never-calls-analyses",
         "elements, model and assembly never import the analyses (an element returns its "
         "force, tangent and linearisation at a given state; equilibria are analyses)",
         ("rotorsim.elements", "rotorsim.model", "rotorsim.assembly"), ("rotorsim.analyses",)),
    Rule("numerics-are-rotor-agnostic",
         "solvers, time_integration, harmonic_balance and the public hb layer work on small "
         "problem protocols and never import model, elements, assembly or analyses",
         NUMERICS,
         ("rotorsim.model", "rotorsim.elements", "rotorsim.assembly", "rotorsim.analyses")),
    Rule("results-do-not-plot",
         "results never import analyses, plotting or matplotlib",
         ("rotorsim.results",), ("rotorsim.analyses", "rotorsim.plotting", "matplotlib")),
    Rule("analyses-linear", "the linear family imports no other analysis family",
         (FAMILIES[0],), FAMILIES[1:]),
    Rule("analyses-statics", "statics imports only the linear family",
         (FAMILIES[1],), FAMILIES[2:]),
    Rule("analyses-transient", "transient imports only statics and linear",
         (FAMILIES[2],), FAMILIES[3:]),
    Rule("analyses-periodic", "periodic imports only statics, linear and quasiperiodic (to "
         "which it hands unbalance with incommensurate varying compliance)",
         (FAMILIES[3],), (FAMILIES[2], FAMILIES[4])),
    Rule("analyses-quasiperiodic", "quasiperiodic imports only statics, linear and "
         "transient (whose runs find what the motion is where a torus loses stability)",
         (FAMILIES[6],), FAMILIES[3:6]),
    Rule("analyses-standards", "standards (the API checks) imports only linear and statics",
         (FAMILIES[5],), (*FAMILIES[2:5], FAMILIES[6])),
    Rule("analyses-no-front-ends", "no analysis imports the command line or the figures",
         ("rotorsim.analyses",), ("rotorsim.cli", "rotorsim.plotting", "matplotlib")),
    Rule("analyses-shared", "the shared top-level analyses modules (system_input, "
         "keyword_check, rigid_motions) import no analysis family",
         ("rotorsim.analyses",), FAMILIES, exempt=FAMILIES),
    Rule("rolling-contact", "rolling.contact imports nothing else of rolling",
         (f"{ROLLING}.contact",), (ROLLING,), allowed=(f"{ROLLING}.contact",)),
    *(Rule(f"rolling-{model}",
           f"rolling.{model} imports only itself, rolling.contact and the shared rolling "
           f"modules{extra_text}: not the other bearing models nor the wrappers (element, "
           "centrifugal, reversed, large_rotation, lubrication, the rolling package)",
           (f"{ROLLING}.{model}",), (ROLLING,),
           allowed=(f"{ROLLING}.{model}", f"{ROLLING}.contact", *ROLLING_SHARED, *extra))
      for model, extra, extra_text in (
          ("ball", (), ""), ("roller", (), ""),
          ("flexible_ring", (f"{ROLLING}.roller.profile",), " and roller.profile"))),
    Rule("rolling-shared", "the shared rolling modules (geometry, state, "
         "element_equilibrium, condensation) import only each other",
         ROLLING_SHARED, (ROLLING,), allowed=ROLLING_SHARED),
)
"""The import rules; docs/architecture.md states them in words."""


# ------------------------------------------------------------------------------ checker
@dataclass(frozen=True)
class Import:
    """One import statement: ``module`` (dotted) imports ``target`` at ``path:line``."""

    module: str
    target: str
    path: str
    line: int
    lazy: bool  # inside a function

    def describe(self) -> str:
        where = "function-level" if self.lazy else "module-level"
        return f"{self.path}:{self.line} ({where}) imports {self.target}"


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


class _ImportCollector(ast.NodeVisitor):
    def __init__(self, module: str, is_package: bool, root: Path, path: str) -> None:
        self.module, self.is_package, self.root, self.path = module, is_package, root, path
        self.depth = 0
        self.found: list[Import] = []

    def _add(self, targets: list[str], node: ast.stmt) -> None:
        for target in dict.fromkeys(targets):  # each module once per statement
            self.found.append(Import(self.module, target, self.path, node.lineno,
                                     self.depth > 0))

    def _function(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> None:
        self.depth += 1
        self.generic_visit(node)
        self.depth -= 1

    visit_FunctionDef = visit_AsyncFunctionDef = _function

    def visit_If(self, node: ast.If) -> None:
        if _is_type_checking(node.test):  # never runs: only the else branch counts
            for child in node.orelse:
                self.visit(child)
        else:
            self.generic_visit(node)

    def visit_Import(self, node: ast.Import) -> None:
        self._add([alias.name for alias in node.names], node)

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        base = node.module or ""
        if node.level:  # relative: resolved against this module's package
            parts = self.module.split(".")[: len(self.module.split(".")) - node.level
                                            + self.is_package]
            base = ".".join([*parts, base] if base else parts)
        targets = []
        for alias in node.names:  # `from pkg import sub` imports the module pkg.sub
            sub = self.root.joinpath(*f"{base}.{alias.name}".split("."))
            is_module = sub.with_suffix(".py").exists() or (sub / "__init__.py").exists()
            targets.append(f"{base}.{alias.name}" if is_module else base)
        self._add(targets, node)


def collect_imports(package_dir: Path) -> list[Import]:
    """Every import of every module under ``package_dir`` (a package named after it)."""
    root = package_dir.parent
    found: list[Import] = []
    for path in sorted(package_dir.rglob("*.py")):
        rel = path.relative_to(root).with_suffix("")
        is_package = rel.name == "__init__"
        module = ".".join(rel.parts[:-1] if is_package else rel.parts)
        collector = _ImportCollector(module, is_package, root, str(path.relative_to(root)))
        collector.visit(ast.parse(path.read_text(), filename=str(path)))
        found.extend(collector.found)
    return found


def _within(name: str, prefixes: tuple[str, ...]) -> bool:
    return any(name == p or name.startswith(p + ".") for p in prefixes)


def violations(imports: list[Import], rule: Rule) -> list[str]:
    """Messages naming each offending module, line and import of ``rule``."""
    return [f"{imp.describe()}: breaks '{rule.name}' ({rule.text})" for imp in imports
            if _within(imp.module, rule.owners) and not _within(imp.module, rule.exempt)
            and _within(imp.target, rule.forbidden) and not _within(imp.target, rule.allowed)]


def import_cycles(imports: list[Import], package: str) -> list[str]:
    """The import cycles among the modules of ``package`` (module- and function-level
    imports alike), each as the modules of one strongly connected component and its edges."""
    edges: dict[str, dict[str, Import]] = {}
    for imp in imports:
        if _within(imp.module, (package,)) and _within(imp.target, (package,)):
            edges.setdefault(imp.module, {}).setdefault(imp.target, imp)
    cycles = []
    for component in _strongly_connected(edges):
        inner = [imp for m in sorted(component) for t, imp in sorted(edges.get(m, {}).items())
                 if t in component]
        if len(component) > 1 or inner:
            cycles.append(f"cycle among {sorted(component)}: "
                          + "; ".join(imp.describe() for imp in inner))
    return cycles


def _strongly_connected(edges: dict[str, dict[str, Import]]) -> list[set[str]]:
    """Tarjan's strongly connected components of the graph ``edges``."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    components: list[set[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        for nxt in edges.get(node, {}):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = set()
            while True:
                member = stack.pop()
                component.add(member)
                if member == node:
                    break
            components.append(component)

    for node in sorted(edges):
        if node not in index:
            visit(node)
    return components


def packages_without_docstring(package_dir: Path) -> list[str]:
    """Folders with Python modules whose ``__init__.py`` is missing or has no docstring."""
    problems = []
    for folder in sorted({p.parent for p in package_dir.rglob("*.py")}):
        init = folder / "__init__.py"
        rel = folder.relative_to(package_dir.parent)
        if not init.exists():
            problems.append(f"{rel}: no __init__.py")
        elif not ast.get_docstring(ast.parse(init.read_text())):
            problems.append(f"{rel}/__init__.py: no docstring (say what lives here and what "
                            "it may import)")
    return problems


# ---------------------------------------------------------------------- the real package
IMPORTS = collect_imports(PACKAGE)


@pytest.mark.parametrize("rule", RULES, ids=lambda r: r.name)
def test_import_rule(rule):
    assert not _missing_owners(rule), f"{rule.name}: no such modules {_missing_owners(rule)}"
    offenders = violations(IMPORTS, rule)
    assert not offenders, "\n".join(offenders)


def _missing_owners(rule: Rule) -> list[str]:
    """Owners of ``rule`` that name no module of the package (a rule gone stale)."""
    modules = {imp.module for imp in IMPORTS}
    return [o for o in rule.owners if not any(_within(m, (o,)) for m in modules)]


def test_no_import_cycle_in_io():
    cycles = import_cycles(IMPORTS, "rotorsim.io")
    assert not cycles, "\n".join(cycles)


def test_every_subpackage_has_a_docstring():
    problems = packages_without_docstring(PACKAGE)
    assert not problems, "\n".join(problems)


def test_no_catch_all_modules():
    assert not [p for p in PACKAGE.rglob("*.py") if p.stem in ("utils", "helpers")]


def test_import_loads_no_slow_or_optional_module():
    """A structural check of import time (timings are flaky): ``import rotorsim`` loads none
    of :data:`NOT_AT_IMPORT` (``benchmarks/import_time.py`` measures the time)."""
    code = (f"import sys, rotorsim; heavy = {NOT_AT_IMPORT!r}; "
            "print(','.join(m for m in heavy if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=PACKAGE.parent)
    assert out.stdout.strip() == "", f"import rotorsim loads {out.stdout.strip()}"


# ------------------------------------------------- the checker on planted violations
PLANTED = {
    # rule name: (importing module, its source, the import reported)
    "physics-never-calls-analyses": (
        "rotorsim.elements.rolling.element",
        "def linearize(load):\n    from rotorsim.analyses.statics.bearing_statics import "
        "bearing_equilibrium\n", "rotorsim.analyses.statics.bearing_statics"),
    "numerics-are-rotor-agnostic": (
        "rotorsim.solvers.newton", "from rotorsim.model.rotor import Rotor\n",
        "rotorsim.model.rotor"),
    "results-do-not-plot": (
        "rotorsim.results.modal", "import matplotlib.pyplot as plt\n", "matplotlib.pyplot"),
    "analyses-linear": (
        "rotorsim.analyses.linear.modal",
        "from rotorsim.analyses.statics.static import static\n",
        "rotorsim.analyses.statics.static"),
    "analyses-statics": (
        "rotorsim.analyses.statics.static", "import rotorsim.analyses.transient.start\n",
        "rotorsim.analyses.transient.start"),
    "analyses-transient": (
        "rotorsim.analyses.transient.start",
        "def f():\n    from rotorsim.analyses.periodic import branch\n",
        "rotorsim.analyses.periodic.branch"),
    "analyses-periodic": (
        "rotorsim.analyses.periodic.branch",
        "from rotorsim.analyses.transient.start import x\n",
        "rotorsim.analyses.transient.start"),
    "analyses-standards": (
        "rotorsim.analyses.standards.api_stability",
        "from rotorsim.analyses.transient.start import x\n",
        "rotorsim.analyses.transient.start"),
    "analyses-quasiperiodic": (
        "rotorsim.analyses.quasiperiodic.problem",
        "from rotorsim.analyses.periodic.excitation import vc_orders\n",
        "rotorsim.analyses.periodic.excitation"),
    "analyses-no-front-ends": (
        "rotorsim.analyses.transient.transient",
        "def run():\n    from rotorsim.plotting import plot\n", "rotorsim.plotting"),
    "analyses-shared": (
        "rotorsim.analyses.system_input",
        "from rotorsim.analyses.linear.modal import modal\n", "rotorsim.analyses.linear.modal"),
    "rolling-contact": (
        f"{ROLLING}.contact.hertz_point", "from ..geometry import cage_ratio\n",
        f"{ROLLING}.geometry"),
    "rolling-ball": (
        f"{ROLLING}.ball.bearing", f"from {ROLLING}.roller.bearing import RollerBearing\n",
        f"{ROLLING}.roller.bearing"),
    "rolling-roller": (
        f"{ROLLING}.roller.bearing", f"from {ROLLING} import BallBearing\n", ROLLING),
    "rolling-flexible_ring": (
        f"{ROLLING}.flexible_ring.bearing",
        f"from {ROLLING}.roller.profile import StraightProfile\n"
        f"from {ROLLING}.centrifugal import CentrifugalBearing\n", f"{ROLLING}.centrifugal"),
    "rolling-shared": (
        f"{ROLLING}.geometry", f"from {ROLLING}.contact.hertz_point import point_contact\n",
        f"{ROLLING}.contact.hertz_point"),
}
"""One planted violation per rule; every other import in the planted source is allowed."""

_FAKE_MODULES = ("rotorsim.analyses.statics.bearing_statics", "rotorsim.analyses.periodic.branch",
                 "rotorsim.analyses.transient.start", f"{ROLLING}.roller.profile",
                 f"{ROLLING}.contact.hertz_point", f"{ROLLING}.geometry")


def _write(root: Path, module: str, source: str = "") -> None:
    path = root.joinpath(*module.split(".")).with_suffix(".py")
    for folder in reversed(path.relative_to(root).parents[:-1]):  # outermost first
        (root / folder).mkdir(exist_ok=True)
        (root / folder / "__init__.py").touch()
    path.write_text(source)


def test_every_rule_has_a_planted_violation():
    assert sorted(PLANTED) == sorted(rule.name for rule in RULES)


@pytest.mark.parametrize("rule", RULES, ids=lambda r: r.name)
def test_checker_reports_a_planted_violation(tmp_path, rule):
    module, source, target = PLANTED[rule.name]
    for name in _FAKE_MODULES:
        _write(tmp_path, name)
    _write(tmp_path, module, source)
    found = violations(collect_imports(tmp_path / "rotorsim"), rule)
    assert len(found) == 1, found
    path = module.replace(".", "/") + ".py"
    assert found[0].startswith(f"{path}:") and f"imports {target}: breaks '{rule.name}'" \
        in found[0], found[0]
    # the same module on its own is clean under every rule
    _write(tmp_path, module, "")
    assert not any(violations(collect_imports(tmp_path / "rotorsim"), r) for r in RULES)


def test_checker_skips_type_checking_imports(tmp_path):
    _write(tmp_path, "rotorsim.elements.shaft",
           "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
           "    from rotorsim.analyses.linear.modal import modal\n"
           "else:\n    import rotorsim.analyses.linear.campbell\n")
    found = violations(collect_imports(tmp_path / "rotorsim"), RULES[0])
    assert [f.split(" (")[0] for f in found] == ["rotorsim/elements/shaft.py:5"], found
    assert "imports rotorsim.analyses.linear.campbell" in found[0]


def test_checker_finds_an_io_cycle_closed_by_a_lazy_import(tmp_path):
    _write(tmp_path, "rotorsim.io.model_file", "from rotorsim.io.analysis_spec import Spec\n")
    _write(tmp_path, "rotorsim.io.analysis_spec",
           "def run():\n    from rotorsim.io import model_file\n")
    _write(tmp_path, "rotorsim.io.hdf5", "from rotorsim.io.analysis_spec import Spec\n")
    [cycle] = import_cycles(collect_imports(tmp_path / "rotorsim"), "rotorsim.io")
    assert "['rotorsim.io.analysis_spec', 'rotorsim.io.model_file']" in cycle
    assert "rotorsim/io/analysis_spec.py:2 (function-level) imports rotorsim.io.model_file" \
        in cycle and "hdf5" not in cycle
    _write(tmp_path, "rotorsim.io.analysis_spec", "")
    assert not import_cycles(collect_imports(tmp_path / "rotorsim"), "rotorsim.io")


def test_checker_finds_a_package_without_docstring(tmp_path):
    _write(tmp_path, "rotorsim.results.modal")
    (tmp_path / "rotorsim" / "__init__.py").write_text('"""The package."""\n')
    (tmp_path / "rotorsim" / "results" / "__init__.py").write_text("# no docstring\n")
    (tmp_path / "rotorsim" / "orphan").mkdir()
    (tmp_path / "rotorsim" / "orphan" / "loose.py").touch()
    assert packages_without_docstring(tmp_path / "rotorsim") == [
        "rotorsim/orphan: no __init__.py",
        "rotorsim/results/__init__.py: no docstring (say what lives here and what it may "
        "import)"]


def test_numerics_leave_files_to_io():
    """Checkpoints go through rotorsim.io.checkpoint_file, resolved when one is written:
    the numerics never import h5py, nor rotorsim.io when they are imported."""
    offenders = [imp.describe() for imp in collect_imports(PACKAGE)
                 if imp.module.startswith(NUMERICS)
                 and (imp.target.startswith("h5py")
                      or (imp.target.startswith("rotorsim.io") and not imp.lazy))]
    assert not offenders, offenders


def _stub_names() -> tuple[set[str], set[str]]:
    """Names imported by ``rotorsim/__init__.pyi`` and the names in its ``__all__``."""
    tree = ast.parse((PACKAGE / "__init__.pyi").read_text())
    imported = {alias.asname or alias.name for node in tree.body
                if isinstance(node, ast.ImportFrom) for alias in node.names}
    listed: set[str] = set()
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(
                isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            listed = set(ast.literal_eval(node.value))
    return imported, listed


def test_public_names_are_listed_once_in_the_stub():
    """The stub's imports (what the lazy loader serves) and its ``__all__`` (what type
    checkers and ``from rotorsim import *`` see) name the same public API."""
    import rotorsim

    imported, listed = _stub_names()
    assert imported == listed, (imported ^ listed)
    assert set(rotorsim.__all__) == listed


def test_import_loads_no_rotorsim_module():
    """``import rotorsim`` only attaches the lazy loader; each public name loads on first
    use (the import-time target of docs/benchmarks.md)."""
    code = ("import sys, rotorsim; print(','.join(sorted(m for m in sys.modules "
            "if m.startswith(('rotorsim.', 'numpy', 'scipy')))))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == ""


def test_every_public_name_loads_eagerly():
    """With ``EAGER_IMPORT=1`` the loader imports every public name at once: a name whose
    module or attribute is missing fails here rather than on a user's first use."""
    code = "import rotorsim as rs; print(len(rs.__all__), all(hasattr(rs, n) for n in rs.__all__))"
    env = {**os.environ, "EAGER_IMPORT": "1"}
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, env=env)
    count, resolved = out.stdout.split()
    assert int(count) > 50 and resolved == "True", out.stdout + out.stderr
