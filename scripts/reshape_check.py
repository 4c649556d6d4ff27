"""Check that a refactoring leaves every model's results bit-identical.

``run OUT`` runs every model in ``models/`` with ``rotorsim run`` (no plots) into ``OUT``.
``compare A B`` then compares every HDF5 dataset and attribute of the two output folders
bit for bit, except the ones that record when or how long (``created``, wall times).

Usage::

    python scripts/reshape_check.py run /tmp/before      # on the old commit
    python scripts/reshape_check.py run /tmp/after       # on the new commit
    python scripts/reshape_check.py compare /tmp/before /tmp/after

"Bit-identical" holds only for two runs on the same machine and BLAS (DESIGN section 12).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
VOLATILE = ("created", "wall_time", "elapsed", "seconds", "time_s", "rotorsim_version")


def run_all(out: Path) -> None:
    """Run every model file of ``models/`` into ``out/<model>/``."""
    for model in sorted((ROOT / "models").glob("*.toml")):
        cmd = [sys.executable, "-m", "rotorsim", "run", str(model), "--out", str(out),
               "--no-plots", "--no-progress"]
        done = subprocess.run(cmd, capture_output=True, text=True)
        print(f"{model.name}: exit {done.returncode}", flush=True)
        (out / f"{model.stem}.log").write_text(done.stdout + done.stderr)


def _volatile(name: str) -> bool:
    leaf = name.rsplit("/", 1)[-1].lower()
    return leaf.endswith("_time") or any(word in leaf for word in VOLATILE)


def _comparable(value: object) -> bytes:
    """Bytes that are equal exactly when two stored values are (strings by content, JSON
    attributes without their volatile keys, numbers bit for bit)."""
    array = np.asarray(value)
    if array.dtype.kind in "OSU":
        items = [v.decode() if isinstance(v, bytes) else str(v) for v in array.reshape(-1)]
        if len(items) == 1 and items[0].startswith("{"):
            try:
                record = json.loads(items[0])
            except ValueError:
                pass
            else:
                if isinstance(record, dict):
                    kept = {k: v for k, v in record.items() if not _volatile(k)}
                    items = [json.dumps(kept, sort_keys=True)]
        return repr((array.shape, items)).encode()
    return repr((array.dtype.str, array.shape)).encode() + array.tobytes()


def _entries(path: Path) -> dict[str, bytes]:
    entries: dict[str, bytes] = {}
    with h5py.File(path, "r") as f:
        def visit(name: str, obj: Any) -> None:
            for key, value in obj.attrs.items():
                if not _volatile(key):
                    entries[f"{name}@{key}"] = _comparable(value)
            if isinstance(obj, h5py.Dataset) and not _volatile(name):
                entries[name] = _comparable(obj[()])
        visit("", f)
        f.visititems(visit)
    return entries


def compare(a: Path, b: Path) -> int:
    """Print every difference between two output folders; return the number found."""
    files_a = {p.relative_to(a) for p in a.rglob("*.h5")}
    files_b = {p.relative_to(b) for p in b.rglob("*.h5")}
    problems = [f"only in {a}: {p}" for p in sorted(files_a - files_b)]
    problems += [f"only in {b}: {p}" for p in sorted(files_b - files_a)]
    n_entries = 0
    for rel in sorted(files_a & files_b):
        ea, eb = _entries(a / rel), _entries(b / rel)
        n_entries += len(ea)
        for key in sorted(set(ea) | set(eb)):
            if ea.get(key) != eb.get(key):
                problems.append(f"{rel}: {key} differs")
    for line in problems:
        print(line)
    print(f"{len(files_a & files_b)} files, {n_entries} entries compared, "
          f"{len(problems)} differences")
    return len(problems)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("run").add_argument("out", type=Path)
    cmp = sub.add_parser("compare")
    cmp.add_argument("a", type=Path)
    cmp.add_argument("b", type=Path)
    args = parser.parse_args()
    if args.command == "run":
        run_all(args.out)
        return 0
    return 1 if compare(args.a, args.b) else 0


if __name__ == "__main__":
    sys.exit(main())
