"""The documentation site: its examples run, its reference pages match the code, it builds.

* ``docs/getting_started.md`` is executed in document order in a temporary folder: TOML
  blocks whose first line is ``# <file>.toml`` are written to that file, ``rotorsim ...``
  lines of bash blocks run through the CLI entry point (exit code 0), python blocks run in
  one namespace. ``docs/analyses.md`` python blocks run the same way.
* The values those pages document are what the code prints: a top-level ``print(...)``
  whose line ends in a comment (or is followed by comment lines) must print that comment's
  text, and a ``text`` block whose first line appears in the output of the page's
  ``rotorsim`` commands must be that output, line for line. Words and layout must match
  (whitespace aside); numbers match to one unit of their last printed digit (a printed,
  rounded value may flip at a rounding boundary when the BLAS kernel changes its last
  bits), integers exactly.
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
import contextlib
import dataclasses
import enum
import inspect
import io
import math
import re
import shlex
import subprocess
import sys
import tokenize
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


NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def _shape(text: str) -> str:
    """The words and punctuation of ``text``, numbers replaced by ``#``, no whitespace."""
    return re.sub(r"\s+", "", NUMBER.sub("#", text))


def _unit(number: str) -> float:
    """One unit of the last printed digit of ``number`` (0 for an integer: exact)."""
    mantissa, _, exponent = number.lower().partition("e")
    if "." not in mantissa:
        return 0.0
    decimals = len(mantissa.split(".")[1])
    return 10.0 ** (-decimals) * 10.0 ** int(exponent or 0)


def assert_prints(actual: str, documented: str, where: str, whole: bool = False) -> None:
    """``actual`` output reads as ``documented`` (a prefix of it unless ``whole``): same
    words, numbers within one unit of the documented last digit."""
    got, want = _shape(actual), _shape(documented)
    same = got == want if whole else want.startswith(got)
    assert got and same, f"{where}: prints {actual!r}, the page says {documented!r}"
    for a, d in zip(NUMBER.findall(actual), NUMBER.findall(documented), strict=False):
        assert abs(float(a) - float(d)) <= _unit(d) + 1e-12 * abs(float(d)), \
            f"{where}: prints {a} where the page says {d} ({actual!r})"


def _comments(code: str) -> dict[int, str]:
    """``{line: comment text}`` of the comments of a python block (1-based lines)."""
    tokens = tokenize.generate_tokens(io.StringIO(code).readline)
    return {t.start[0]: t.string[1:].strip() for t in tokens if t.type == tokenize.COMMENT}


def _documented_output(code: str, stmt: ast.stmt) -> str | None:
    """The output a page documents for a top-level ``print(...)``: the comment ending its
    last line, else the comment-only lines right below it; None if there is none."""
    call = stmt.value if isinstance(stmt, ast.Expr) else None
    if not (isinstance(call, ast.Call) and isinstance(call.func, ast.Name)
            and call.func.id == "print"):
        return None
    comments, lines = _comments(code), code.splitlines()
    end = stmt.end_lineno or stmt.lineno
    if end in comments:
        return comments[end]
    below = []
    for number in range(end + 1, len(lines) + 1):
        if not lines[number - 1].lstrip().startswith("#"):
            break
        below.append(comments[number])
    return "\n".join(below) or None


def run_python(code: str, namespace: dict[str, Any], where: str) -> int:
    """Execute a python block statement by statement; check documented prints. Returns
    the number of prints checked."""
    checked = 0
    for stmt in ast.parse(code).body:
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile(ast.Module([stmt], []), where, "exec"), namespace)
        documented = _documented_output(code, stmt)
        if documented is not None:
            assert_prints(out.getvalue().strip(), documented, f"{where} line {stmt.lineno}")
            checked += 1
    return checked


def check_text_block(code: str, output: str, where: str) -> bool:
    """If the first line of a ``text`` block is a line of ``output``, the block must be
    the output from there on, line for line. Returns whether it was compared."""
    doc_lines = [line for line in code.splitlines() if line.strip()]
    out_lines = [line for line in output.splitlines() if line.strip()]
    starts = [i for i, line in enumerate(out_lines) if line.strip() == doc_lines[0].strip()]
    if not starts:
        return False
    got = out_lines[starts[0]: starts[0] + len(doc_lines)]
    assert len(got) == len(doc_lines), f"{where}: the output ends early"
    for a, d in zip(got, doc_lines, strict=True):
        assert_prints(a, d, where, whole=True)
    return True


@dataclasses.dataclass
class PageRun:
    namespace: dict[str, Any]
    prints_checked: int
    outputs_checked: int


def run_page(page: str, workdir: Path) -> PageRun:
    """Execute the TOML, bash (``rotorsim`` lines) and python blocks of a page in order,
    checking the values the page documents (module docstring)."""
    import matplotlib.pyplot as plt

    run = PageRun({"__name__": f"docs_{Path(page).stem}"}, 0, 0)
    cli_output = ""
    for i, (lang, code) in enumerate(fenced_blocks(page)):
        where = f"{page} block {i}"
        if lang == "toml" and code.startswith("# ") and code.split("\n", 1)[0].endswith(".toml"):
            (workdir / code.split("\n", 1)[0][2:].strip()).write_text(code)
        elif lang == "bash":
            for args in cli_lines(code):
                out = io.StringIO()
                with contextlib.redirect_stdout(out):
                    code_ = main(args)
                assert code_ == 0, f"{where}: rotorsim {shlex.join(args)}"
                cli_output += out.getvalue()
        elif lang == "python":
            run.prints_checked += run_python(code, run.namespace, where)
        elif lang == "text" and cli_output:
            run.outputs_checked += check_text_block(code, cli_output, where)
    plt.close("all")
    return run


def test_getting_started_runs(workdir: Path) -> None:
    run = run_page("getting_started.md", workdir)
    ns = run.namespace
    # the documented values are checked, and none of these checks went missing
    assert run.prints_checked >= 12 and run.outputs_checked >= 1
    # the page loads what `rotorsim run first.toml` wrote and saves its own Campbell diagram
    assert (workdir / "results" / "first" / "campbell.h5").is_file()
    assert (workdir / "results" / "first" / "campbell.png").stat().st_size > 5000
    assert (workdir / "first_campbell.png").stat().st_size > 5000
    assert type(ns["saved"]).__name__ == "CampbellResult"


def test_analyses_examples_run(workdir: Path) -> None:
    run = run_page("analyses.md", workdir)
    assert type(run.namespace["stat"]).__name__ == "StaticResult"
    assert run.prints_checked >= 15


def test_cli_examples_run(workdir: Path) -> None:
    commands = [args for lang, code in fenced_blocks("cli.md") if lang == "bash"
                for args in cli_lines(code)]
    assert {args[0] for args in commands if not args[0].startswith("-")} >= {
        "info", "run", "modal", "campbell", "critical-speeds", "map", "unbalance", "static"}
    for args in commands:
        command = next(a for a in args if not a.startswith("-"))
        extra = [] if command == "info" else ["--fast", "--no-plots", "--out", "runs"]
        # --fast caps a periodic branch at 10 points: it honestly ends short of its end
        # (exit 3, results written); every other example must finish with exit 0
        ok = {0, 3} if command.startswith("periodic") else {0}
        assert main([*args, *extra]) in ok, f"rotorsim {shlex.join(args)}"


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
