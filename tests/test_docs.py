"""The documentation site: its examples run, its reference pages match the code, it builds.

* ``docs/getting_started.md`` is executed in document order in a temporary folder: TOML
  blocks whose first line is ``# <file>.toml`` are written to that file, ``rotorsim ...``
  lines of bash blocks run through the CLI entry point (exit code 0), python blocks run in
  one namespace. ``docs/analyses.md`` python blocks run the same way.
* Every ``rotorsim ...`` command of ``docs/cli.md`` runs (with ``--fast --no-plots`` added,
  so the whole page takes seconds) and exits with 0.
* Every ``usage: rotorsim ...`` block of ``docs/cli.md`` has the words of the current
  ``--help`` output (produced at 90 columns), and every subcommand has one.
* ``docs/api.md`` has exactly one entry per name of ``rotorsim.__all__``, and each signature
  shown has the parameter names, kinds and defaults of the real one.
* ``mkdocs build --strict`` succeeds: no broken link or anchor, no page missing from the nav.
"""

from __future__ import annotations

import argparse
import ast
import dataclasses
import enum
import inspect
import math
import re
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import rotorsim as rs
from rotorsim.cli.main import build_parser, main

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```[ \t]*$", re.S | re.M)
HELP_COLUMNS = "90"
"""Terminal width at which the help texts in docs/cli.md were produced."""


def fenced_blocks(page: str) -> list[tuple[str, str]]:
    """``(language, code)`` of every top-level fenced block of ``docs/<page>``, in order."""
    return [(m.group(1), m.group(2)) for m in FENCE.finditer((DOCS / page).read_text())]


def cli_lines(code: str) -> list[list[str]]:
    """The ``rotorsim ...`` command lines of a bash block, split like a shell would."""
    commands = []
    for line in code.splitlines():
        words = shlex.split(line, comments=True)
        if words and words[0] == "rotorsim":
            commands.append(words[1:])
    return commands


@pytest.fixture
def workdir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A temporary working folder with ``models/`` available, as in the repository root."""
    (tmp_path / "models").symlink_to(ROOT / "models", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run_page(page: str, workdir: Path) -> dict[str, Any]:
    """Execute the TOML, bash (``rotorsim`` lines) and python blocks of a page in order."""
    import matplotlib.pyplot as plt

    namespace: dict[str, Any] = {"__name__": f"docs_{Path(page).stem}"}
    for i, (lang, code) in enumerate(fenced_blocks(page)):
        if lang == "toml" and code.startswith("# ") and code.split("\n", 1)[0].endswith(".toml"):
            (workdir / code.split("\n", 1)[0][2:].strip()).write_text(code)
        elif lang == "bash":
            for args in cli_lines(code):
                assert main(args) == 0, f"{page} block {i}: rotorsim {shlex.join(args)}"
        elif lang == "python":
            exec(compile(code, f"{page} block {i}", "exec"), namespace)
    plt.close("all")
    return namespace


def test_getting_started_runs(workdir: Path) -> None:
    ns = run_page("getting_started.md", workdir)
    # the page loads what `rotorsim run first.toml` wrote and saves its own Campbell diagram
    assert (workdir / "results" / "first" / "campbell.h5").is_file()
    assert (workdir / "results" / "first" / "campbell.png").stat().st_size > 5000
    assert (workdir / "first_campbell.png").stat().st_size > 5000
    assert type(ns["saved"]).__name__ == "CampbellResult"


def test_analyses_examples_run(workdir: Path) -> None:
    ns = run_page("analyses.md", workdir)
    assert type(ns["stat"]).__name__ == "StaticResult"


def test_cli_examples_run(workdir: Path) -> None:
    commands = [args for lang, code in fenced_blocks("cli.md") if lang == "bash"
                for args in cli_lines(code)]
    assert {args[0] for args in commands if not args[0].startswith("-")} >= {
        "info", "run", "modal", "campbell", "critical-speeds", "map", "unbalance", "static"}
    for args in commands:
        command = next(a for a in args if not a.startswith("-"))
        extra = [] if command == "info" else ["--fast", "--no-plots", "--out", "runs"]
        assert main([*args, *extra]) == 0, f"rotorsim {shlex.join(args)}"


def _subcommands() -> list[str]:
    parser = build_parser()
    [action] = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return list(action.choices)


def test_cli_help_blocks_match_the_parser(monkeypatch: pytest.MonkeyPatch,
                                          capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.setenv("COLUMNS", HELP_COLUMNS)
    documented: dict[str, str] = {}
    for lang, code in fenced_blocks("cli.md"):
        if lang == "text" and code.startswith("usage: rotorsim"):
            word = code.split()[2]
            documented[word if not word.startswith("[") else ""] = code
    assert set(documented) == {"", *_subcommands()}, "every subcommand needs its help block"
    for command, text in documented.items():
        with pytest.raises(SystemExit):
            main([command, "--help"] if command else ["--help"])
        actual = capsys.readouterr().out
        # compared word by word: line wrapping may differ between Python versions
        assert actual.split() == text.split(), f"docs/cli.md: help of '{command}' is stale"


def api_entries() -> dict[str, str]:
    """``{name: first code block}`` of every ``### `name` `` section of docs/api.md."""
    text = (DOCS / "api.md").read_text()
    entries: dict[str, str] = {}
    for m in re.finditer(r"^### `(\w+)`\n\n```python\n(.*?)^```", text, re.S | re.M):
        assert m.group(1) not in entries, f"api.md lists {m.group(1)} twice"
        entries[m.group(1)] = m.group(2)
    return entries


def test_api_page_lists_every_public_name() -> None:
    entries = api_entries()
    assert sorted(entries) == sorted(rs.__all__)


def _real_signature(obj: Any) -> inspect.Signature | None:
    if (isinstance(obj, type) and issubclass(obj, enum.Enum)) or not callable(obj):
        return None
    try:
        return inspect.signature(obj)
    except ValueError:  # e.g. an exception class without its own __init__
        return None


def _documented_parameters(params: str) -> list[tuple[str, str, str | None]]:
    """``(name, kind, default source)`` of a parameter list written as in Python."""
    args = ast.parse(f"def _f({params}): pass").body[0].args  # type: ignore[attr-defined]
    out: list[tuple[str, str, str | None]] = []
    positional = args.posonlyargs + args.args
    defaults = [None] * (len(positional) - len(args.defaults)) + list(args.defaults)
    out += [(a.arg, "positional", d and ast.unparse(d)) for a, d in zip(positional, defaults,
                                                                      strict=True)]
    if args.vararg:
        out.append((args.vararg.arg, "*", None))
    out += [(a.arg, "keyword", d and ast.unparse(d)) for a, d in zip(args.kwonlyargs,
                                                                   args.kw_defaults, strict=True)]
    if args.kwarg:
        out.append((args.kwarg.arg, "**", None))
    return out


_KINDS = {
    inspect.Parameter.POSITIONAL_ONLY: "positional",
    inspect.Parameter.POSITIONAL_OR_KEYWORD: "positional",
    inspect.Parameter.VAR_POSITIONAL: "*",
    inspect.Parameter.KEYWORD_ONLY: "keyword",
    inspect.Parameter.VAR_KEYWORD: "**",
}


def _same_default(obj: Any, name: str, actual: Any, documented: str) -> bool:
    from rotorsim.elements.rolling import StraightProfile
    from rotorsim.io.analysis_spec import Loads

    value = eval(documented, {"nan": math.nan, "inf": math.inf, "Status": rs.Status,
                              "Loads": Loads, "StraightProfile": StraightProfile,
                              "Newmark": rs.Newmark})
    if repr(actual) == "<factory>":  # a dataclass field with default_factory
        [field] = [f for f in dataclasses.fields(obj) if f.name == name]
        actual = field.default_factory()  # type: ignore[operator]
    if isinstance(value, float) and isinstance(actual, float) and math.isnan(value):
        return math.isnan(actual)
    return bool(type(value) is type(actual) and value == actual) or (
        isinstance(value, int | float) and isinstance(actual, int | float) and value == actual)


@pytest.mark.parametrize("name", sorted(rs.__all__))
def test_api_signatures_match_the_code(name: str) -> None:
    code = api_entries()[name]
    obj = getattr(rs, name)
    real = _real_signature(obj)
    m = re.match(rf"rs\.{name}\((.*)\)(\s*->[^\n]*)?\s*$", code, re.S)
    if real is None:
        assert m is None and f"rs.{name}" in code
        return
    assert m is not None, f"api.md: no signature rs.{name}(...)"
    documented = _documented_parameters(m.group(1))
    params = [p for p in real.parameters.values() if p.name != "self"]
    assert [(n, k) for n, k, _ in documented] == [(p.name, _KINDS[p.kind]) for p in params]
    for (pname, _, default), p in zip(documented, params, strict=True):
        if p.default is inspect.Parameter.empty:
            assert default is None, f"{name}: {pname} has no default in the code"
        else:
            assert default is not None, f"{name}: {pname} needs its default {p.default!r}"
            assert _same_default(obj, pname, p.default, default), \
                f"{name}: default of {pname} is {p.default!r}, api.md says {default}"


def test_nav_lists_every_page() -> None:
    nav = re.findall(r"^\s+- [^:]+: (\S+\.md)\s*$", (ROOT / "mkdocs.yml").read_text(), re.M)
    pages = sorted(p.relative_to(DOCS).as_posix() for p in DOCS.rglob("*.md"))
    assert sorted(nav) == pages


def test_site_builds_strict(tmp_path: Path) -> None:
    pytest.importorskip("mkdocs")
    done = subprocess.run(
        # no --quiet: it hides the warnings from the strict-mode counter (mkdocs 1.6)
        [sys.executable, "-m", "mkdocs", "build", "--strict",
         "--config-file", str(ROOT / "mkdocs.yml"), "--site-dir", str(tmp_path / "site")],
        cwd=ROOT, capture_output=True, text=True, timeout=120, check=False)
    assert done.returncode == 0, done.stdout + done.stderr
    assert (tmp_path / "site" / "getting_started.html").is_file()
