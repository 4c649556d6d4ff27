"""Wall time of ``import rotorsim`` in fresh processes, and where it goes.

Runs ``python -c "import rotorsim"`` ``--repeat`` times, each in a new interpreter, and prints
the median wall time (with the bare interpreter start, ``python -c pass``, for reference),
then one ``python -X importtime`` run: the time by top-level package and the modules with the
largest cumulative import time.

The public names of ``rotorsim`` load on first use, so the script also times what a script
pays on its first use of a layer (:data:`FIRST_USES`: the model, a linear analysis, a model
file, a transient, a periodic branch, every public name, and the command line's ``--help``).

Bytecode: as after a normal install, the compiled ``.pyc`` files are used. They go to a
temporary ``PYTHONPYCACHEPREFIX`` written by one warm-up run (``PYTHONDONTWRITEBYTECODE`` is
dropped for the child processes), so the source tree stays clean. ``--no-bytecode-cache``
measures the other case, every module compiled on each import.

Usage::

    .venv/bin/python benchmarks/import_time.py [--repeat 15] [--top 15] [--module rotorsim]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FIRST_USES = {
    "rs.Rotor (model and elements)": "import rotorsim as rs; rs.Rotor",
    "rs.modal (linear analyses)": "import rotorsim as rs; rs.modal",
    "rs.load_model (model files)": "import rotorsim as rs; rs.load_model",
    "rs.transient (time integration)": "import rotorsim as rs; rs.transient",
    "rs.periodic (harmonic balance)": "import rotorsim as rs; rs.periodic",
    "every public name": "import rotorsim as rs; [getattr(rs, n) for n in rs.__all__]",
    "rotorsim --help (command line)":
        "import sys; sys.argv = ['rotorsim', '--help']; import runpy; "
        "runpy.run_module('rotorsim', run_name='__main__')",
}
"""What a script pays on first use of a layer: label -> code run in a fresh process."""


def child_env(pycache: str | None) -> dict[str, str]:
    """The environment of the measured processes: bytecode written to and read from
    ``pycache`` (None: not written, every module compiled from source)."""
    env = dict(os.environ)
    if pycache is None:
        env["PYTHONDONTWRITEBYTECODE"] = "1"
        env.pop("PYTHONPYCACHEPREFIX", None)
    else:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = pycache
    return env


def wall_times(code: str, repeat: int, env: dict[str, str]) -> list[float]:
    """Wall time [s] of ``python -c code`` in ``repeat`` fresh processes (run from the
    repository root, so its ``rotorsim`` is the one imported)."""
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, check=True,
                       stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
    return times


def import_profile(module: str, env: dict[str, str]) -> list[tuple[str, int, int, int]]:
    """``(name, depth, self_us, cumulative_us)`` of every module imported by ``import
    module``, from one ``-X importtime`` run, in the order Python reports them."""
    done = subprocess.run([sys.executable, "-X", "importtime", "-c", f"import {module}"],
                          cwd=ROOT, env=env, check=True, capture_output=True, text=True)
    rows = []
    for line in done.stderr.splitlines():
        if not line.startswith("import time:") or "self [us]" in line:
            continue
        self_us, cumulative_us, name = line[len("import time:"):].split("|")
        depth = (len(name) - len(name.lstrip(" ")) - 1) // 2
        rows.append((name.strip(), depth, int(self_us), int(cumulative_us)))
    return rows


def print_profile(rows: list[tuple[str, int, int, int]], top: int) -> None:
    """Self time by top-level package, and the ``top`` largest cumulative times."""
    by_package: Counter[str] = Counter()
    for name, _, self_us, _ in rows:
        by_package[name.split(".")[0]] += self_us
    total = sum(by_package.values())
    print(f"\n-X importtime: {len(rows)} modules, {total / 1e3:.0f} ms in all "
          "(importtime itself adds some)")
    print("self time by package: " + ", ".join(
        f"{name} {us / 1e3:.0f} ms" for name, us in by_package.most_common(6)))
    print(f"\ntop {top} modules by cumulative import time:")
    print(f"{'cumulative':>11} {'self':>8}  module (indent = import depth)")
    for name, depth, self_us, cumulative_us in sorted(rows, key=lambda r: -r[3])[:top]:
        print(f"{cumulative_us / 1e3:8.1f} ms {self_us / 1e3:5.1f} ms  {'  ' * depth}{name}")


def main(argv: list[str] | None = None) -> dict[str, float]:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=15, help="fresh processes per timing")
    parser.add_argument("--top", type=int, default=15, help="modules listed")
    parser.add_argument("--module", default="rotorsim", help="module to import")
    parser.add_argument("--no-bytecode-cache", action="store_true",
                        help="compile every module on each import (no .pyc files)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="import-time-pyc-") as cache:
        env = child_env(None if args.no_bytecode_cache else cache)
        for code in (f"import {args.module}", *FIRST_USES.values()):
            wall_times(code, 1, env)  # warm-up: writes the bytecode
        bare = statistics.median(wall_times("pass", args.repeat, env))
        times = wall_times(f"import {args.module}", args.repeat, env)
        rows = import_profile(args.module, env)
        uses = {} if args.module != "rotorsim" else {
            label: statistics.median(wall_times(code, args.repeat, env))
            for label, code in FIRST_USES.items()}
    median = statistics.median(times)
    print(f"command: {sys.executable} -c 'import {args.module}'  (from {ROOT}, "
          f"{'no .pyc' if args.no_bytecode_cache else 'with .pyc'}, {args.repeat} processes)")
    print(f"import {args.module}: median {median:.3f} s wall (min {min(times):.3f}, "
          f"max {max(times):.3f}); bare interpreter start {bare:.3f} s; "
          f"load average {os.getloadavg()[0]:.2f}")
    print_profile(rows, args.top)
    if uses:
        print(f"\nfirst use after `import rotorsim as rs` (median of {args.repeat} fresh "
              "processes, import included):")
        for label, seconds in uses.items():
            print(f"{seconds:8.3f} s  {label}")
    return {"median_s": median, "interpreter_s": bare, **uses}


if __name__ == "__main__":
    main()
