"""rotorsim's own CPU time on the automatic transient path, this tree against an older
revision, interleaved in one process.

On a shared machine the CPU time of a run moves by 20-50 % between minutes, so two
separate runs of ``transient_profile.py`` cannot show a 10 % change. This script imports
both trees into one process (the older one as the package ``rotorsim_base``: a copy of its
``rotorsim`` with the imports renamed), then runs the cases of ``transient_profile.py``
alternately with one and the other and prints the shortest and median CPU time of each,
their steps and the largest difference of their probe histories (relative to the motion).

Run: ``git archive <rev> rotorsim benchmarks | tar -x -C /tmp/base`` once, then
``OPENBLAS_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python benchmarks/transient_before_after.py
/tmp/base [--rounds 15]``.
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parents[1]
for _path in (ROOT, ROOT / "benchmarks"):
    if str(_path) not in sys.path:
        sys.path.insert(0, str(_path))

import bench_transient as new_bench  # noqa: E402
import numpy as np  # noqa: E402

CASES = (("issue14", 3e-2), ("issue14", 1e-3), ("bench", 3e-3), ("bench", 1e-4))
"""The cases of ``transient_profile.py`` (the cheapest runs at 1e-3 and 1e-5 of the motion)."""
_NAME = re.compile(r"\brotorsim(?=[.\s])")


def renamed_copy(base: Path, into: Path) -> Any:
    """Copy ``base/rotorsim`` to ``into/rotorsim_base`` and ``base/benchmarks/
    bench_transient.py`` to ``into/bench_base.py`` with the package renamed; import the
    latter."""
    shutil.copytree(base / "rotorsim", into / "rotorsim_base")
    files = [*(into / "rotorsim_base").rglob("*.py")]
    shutil.copy(base / "benchmarks" / "bench_transient.py", into / "bench_base.py")
    for path in [*files, into / "bench_base.py"]:
        path.write_text(_NAME.sub("rotorsim_base", path.read_text()))
    sys.path.insert(0, str(into))
    import bench_base
    return bench_base


def runner(module: Any, name: str, rtol: float) -> tuple[Callable[[], Any], Any]:
    """``rs.transient`` of the benchmark on model ``name`` at ``rtol`` (as in
    ``transient_profile.py``: same start, 41 output times, model objects built once)."""
    bench = module.MODELS[name]
    _, _, _, _, full = module.first_order(bench)
    start, model = (full, np.zeros_like(full)), bench.build()
    times = np.linspace(0.0, bench.t_end, 41)
    return (lambda: module.rotorsim_run(bench, bench.t_end, None, times=times,
                                        initial=start, rtol=rtol, model=model)), bench


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("base", type=Path, help="tree of the older revision")
    parser.add_argument("--rounds", type=int, default=15)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        old_bench = renamed_copy(args.base, Path(tmp))
        for name, rtol in CASES:
            run_old, bench = runner(old_bench, name, rtol)
            run_new, _ = runner(new_bench, name, rtol)
            a, b = run_old(), run_new()
            pa, pb = (r.displacement(bench.probe, "uy") for r in (a, b))
            gap = float(np.max(np.abs(pa - pb)) / np.ptp(pa))
            cpu: dict[str, list[float]] = {"old": [], "new": []}
            for _ in range(args.rounds):
                for key, run in (("old", run_old), ("new", run_new)):
                    begin = time.process_time()
                    run()
                    cpu[key].append(1e3 * (time.process_time() - begin))
            print(f"{name} rtol {rtol:g}: before {min(cpu['old']):.1f} ms "
                  f"(median {np.median(cpu['old']):.1f}), after {min(cpu['new']):.1f} ms "
                  f"(median {np.median(cpu['new']):.1f}); steps "
                  f"{a.stats['steps']:.0f}+{a.stats['rejected_steps']:.0f} / "
                  f"{b.stats['steps']:.0f}+{b.stats['rejected_steps']:.0f}; probe histories "
                  f"{gap:.1e} of the motion apart", flush=True)


if __name__ == "__main__":
    main()
