"""Where the enhanced Adams method of seed 002 is usable: its step limit on finite-element rotors.

The enhanced fourth-order Adams method (``method="adams"``, seed 002 Appendix F) is not
A-stable: on an undamped mode its one-step amplification is ``rho = 1 + (w h)^6 / 90 + ...``
(``tests/time_integration/test_adams.py``), so every mode grows by ``exp(N (w h)^6 / 90)``
over ``N`` steps, and beyond ``w h`` of about 1 the growth is fast (``rho - 1`` = 0.009 at
``w h = 1``, 0.2 at 2). A finite-element shaft has modes up to the axial and shear
frequencies of its shortest element, so the step must resolve the highest of them, whatever
the motion of interest.

This script measures it on the two small rotors of ``benchmarks/bench_transient.py``
(``bench``, ``issue14``; ball bearings with clearance, gravity, unbalance) and on the same
shaft reduced to a few modes:

* the highest natural frequency ``w_max`` of the model linearised about its static state
  (the bearings' nominal tangent), and the largest step whose undamped growth over the run
  stays below a factor 2, ``h_max = (90 ln 2 / N)^(1/6) / w_max`` with ``N = T / h``
  (solved by fixed point);
* runs of ``method="adams"`` at fixed steps from 20 us down, to ``t_end`` of the benchmark:
  diverged or not, the error of the probe's ``uy`` relative to its motion against the
  automatic path at rtol 1e-8, the CPU time; and the automatic path at rtol 1e-3 for scale;
* the same with ``reduction=8`` (Craig-Bampton, 8 fixed-interface modes), whose highest
  frequency is the reduced model's.

Run: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/adams_fe_models.py [--models bench]``.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

ROOT = Path(__file__).resolve().parents[1]
for _path in (ROOT, ROOT / "benchmarks"):
    if str(_path) not in sys.path:
        sys.path.insert(0, str(_path))

import numpy as np  # noqa: E402
import scipy.linalg as sl  # noqa: E402
import scipy.sparse as sp  # noqa: E402
from bench_transient import MODELS, BenchModel  # noqa: E402

import rotorsim as rs  # noqa: E402
from rotorsim.analyses.statics.nonlinear_static import nominal_tangent  # noqa: E402
from rotorsim.analyses.transient.transient import transient  # noqa: E402
from rotorsim.assembly.system import assemble  # noqa: E402
from rotorsim.errors import ConvergenceError  # noqa: E402

STEPS = (2e-5, 5e-6, 1e-6, 2.5e-7)
"""Fixed steps of the Adams runs [s]."""


def highest_frequency(bench: BenchModel, modes: int | None = None) -> float:
    """Highest natural frequency [rad/s] of the model with the bearings' nominal tangent
    (of its Craig-Bampton reduction with ``modes`` modes when given)."""
    rotor, bearings = bench.build()
    system = assemble(rotor, bearings)
    mats = system.matrices(0.0)
    K = sp.csr_matrix(mats.K) + sp.csr_matrix(nominal_tangent(system))
    M = sp.csr_matrix(mats.M)
    if modes is None:
        lam = sl.eigh(K.toarray(), M.toarray(), eigvals_only=True)
    else:
        from rotorsim.assembly.reduction import craig_bampton

        basis = craig_bampton(system, system.nonlinear.dofs, modes)  # type: ignore[union-attr]
        lam = sl.eigh(basis.reduce(K), basis.reduce(M), eigvals_only=True)
    return float(np.sqrt(lam.max()))


def step_limit(w_max: float, t_end: float, growth: float = 2.0) -> float:
    """Largest ``h`` with ``(T / h) (w_max h)^6 / 90 <= ln(growth)`` [s]."""
    h = 1.0 / w_max
    for _ in range(50):
        h = (90.0 * math.log(growth) * h / t_end) ** (1.0 / 6.0) / w_max
    return h


def runs(bench: BenchModel, modes: int | None) -> list[tuple[str, str, float, float]]:
    """(setting, outcome, error relative to the motion, CPU s) of the Adams runs and the
    automatic path at rtol 1e-3."""
    rotor, bearings = bench.build()
    times = np.linspace(0.0, bench.t_end, 41)
    kw: dict[str, Any] = dict(nonlinear=bearings, speed=bench.speed,
                              unbalance=bench.unbalance, nodes=[bench.probe],
                              output=rs.Output(times=times), reduction=modes)
    ref = transient(rotor, bench.t_end, rtol=1e-8, **kw).displacement(bench.probe, "uy")
    motion = float(np.ptp(ref))
    out = []
    settings: list[tuple[str, dict[str, Any]]] = [
        (f"adams dt={dt:g}", {"dt": dt, "method": "adams"}) for dt in STEPS]
    settings.append(("auto rtol=1e-3", {"rtol": 1e-3}))
    for label, extra in settings:
        clock = time.process_time()
        try:
            res = transient(rotor, bench.t_end, **extra, **kw)
            y = res.displacement(bench.probe, "uy")
            err = float(np.max(np.abs(y - ref))) / motion
            outcome = "ok" if np.isfinite(err) and err < 1.0 else "diverged"
        except ConvergenceError:
            err, outcome = math.inf, "diverged (ConvergenceError)"
        out.append((label, outcome, err, time.process_time() - clock))
    return out


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--models", nargs="+", default=["bench", "issue14"],
                        choices=["bench", "issue14"])
    args = parser.parse_args(argv)
    for name in args.models:
        bench = MODELS[name]
        for modes in (None, 8):
            w_max = highest_frequency(bench, modes)
            h = step_limit(w_max, bench.t_end)
            kind = "full" if modes is None else f"reduction={modes}"
            print(f"\n[{name}, {kind}] w_max = {w_max:.4g} rad/s; Adams step for growth < 2x "
                  f"over {bench.t_end:g} s: {h:.3g} s ({bench.t_end / h:.3g} steps)")
            for label, outcome, err, cpu in runs(bench, modes):
                print(f"  {label:22s} {outcome:30s} error {err:9.3g}  cpu {cpu:8.3f} s")


if __name__ == "__main__":
    main()
