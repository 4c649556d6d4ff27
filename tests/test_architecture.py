"""Import rules of DESIGN section 1: numerics never depend on the rotor model."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "rotorsim"
NUMERICS = ("solvers", "time_integration", "harmonic_balance")
MODEL_LAYERS = ("rotorsim.model", "rotorsim.elements", "rotorsim.assembly", "rotorsim.analyses")


def _imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(), filename=str(path))
    names: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
    return names


@pytest.mark.parametrize("layer", NUMERICS)
def test_numerics_do_not_import_model_layers(layer):
    folder = PACKAGE / layer
    offenders = []
    for path in folder.rglob("*.py") if folder.exists() else []:
        for name in _imports(path):
            if name.startswith(MODEL_LAYERS):
                offenders.append(f"{path.relative_to(PACKAGE)} imports {name}")
    assert not offenders, offenders


def _module_level_imports(path: Path) -> set[str]:
    names: set[str] = set()
    for node in ast.parse(path.read_text(), filename=str(path)).body:
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
    return names


@pytest.mark.parametrize("layer", NUMERICS)
def test_numerics_leave_files_to_io(layer):
    """Checkpoints go through rotorsim.io.checkpoint_file, resolved when one is written:
    the numerics never import h5py, nor rotorsim.io when they are imported."""
    offenders = []
    for path in (PACKAGE / layer).rglob("*.py"):
        names = _imports(path)
        offenders += [f"{path.relative_to(PACKAGE)} imports h5py" for n in names
                      if n.startswith("h5py")]
        offenders += [f"{path.relative_to(PACKAGE)} imports {n} at module level"
                      for n in _module_level_imports(path) if n.startswith("rotorsim.io")]
    assert not offenders, offenders


def test_results_do_not_import_analyses_or_plotting():
    offenders = [
        f"{path.name} imports {name}"
        for path in (PACKAGE / "results").rglob("*.py")
        for name in _imports(path)
        if name.startswith(("rotorsim.analyses", "rotorsim.plotting", "matplotlib"))
    ]
    assert not offenders, offenders


def test_no_catch_all_modules():
    assert not [p for p in PACKAGE.rglob("*.py") if p.stem in ("utils", "helpers")]


def test_import_has_no_heavy_side_effects():
    code = (
        "import sys, rotorsim; "
        "heavy = [m for m in ('matplotlib', 'h5py', 'meshio', 'skfem', 'tqdm') "
        "if m in sys.modules]; print(','.join(heavy))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
