"""The automatic reduction's truncation estimate and the stepper's error estimate, checked on
the whole rotor (issue 14, seventh pass).

Two checks on the models of ``bench_transient.py`` (``bench``, ``issue14``), from the static
start, 41 output times, every node's ``ux``, ``uy`` and ``rx``, ``ry`` times the element
length (as the stepper weighs the motion):

* ``truncation``: for each mode count, the estimate of
  :func:`~rotorsim.analyses.transient.exponential_reduction.exponential_reduction`
  (``ringing``, ``drift``, ``estimate``, relative to the a-priori motion) against the
  truncation error found: the model reduced to that count and the full model, both at
  rtol 1e-8; relative to the a-priori motion and to the stepper's motion scale (the larger
  of the a-priori motion and the motion reached);
* ``steps MODEL RTOL``: the automatic run's accepted steps of exponential collocation, each
  with its error estimate and its local error found by integrating the same step in 16
  fixed sub-steps, both in units of the local tolerance; and the run's whole-rotor error
  against the full model at rtol 1e-8, in units of ``rtol``.

Run: ``OPENBLAS_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python benchmarks/reduction_check.py
truncation`` (about a minute) or ``... reduction_check.py steps issue14 0.1 [bench]``
(``bench``: start from the benchmark's equilibrium, :func:`steps`).
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
for _path in (ROOT, ROOT / "benchmarks"):
    if str(_path) not in sys.path:
        sys.path.insert(0, str(_path))

import numpy as np  # noqa: E402
from bench_transient import MODELS, BenchModel, first_order  # noqa: E402

import rotorsim as rs  # noqa: E402
import rotorsim.analyses.transient.exponential_reduction as er  # noqa: E402
import rotorsim.time_integration.exponential as ex  # noqa: E402
from rotorsim.analyses.transient.auto import dof_weights, motion_floor  # noqa: E402
from rotorsim.analyses.transient.equation import rotor_problem  # noqa: E402
from rotorsim.analyses.transient.speed_profile import ConstantSpeed  # noqa: E402
from rotorsim.analyses.transient.start import initial_state  # noqa: E402
from rotorsim.analyses.transient.transient import transient  # noqa: E402
from rotorsim.assembly.system import assemble  # noqa: E402

COUNTS = {"bench": (8, 16, 24, 32, 48), "issue14": (8, 16, 24, 32, 48)}


def whole_rotor(bench: BenchModel, model: Any, rtol: float,
                reduction: int | bool | None, initial: Any = "static"
                ) -> tuple[np.ndarray, Any]:
    """Weighted displacements (4 per node, 41 times) of one run, and the result."""
    rotor, bearings = model
    nodes = list(range(bench.elements + 1))
    res = transient(rotor, bench.t_end, nonlinear=bearings, speed=bench.speed,
                    unbalance=bench.unbalance, nodes=nodes, rtol=rtol, reduction=reduction,
                    initial=initial,
                    output=rs.Output(times=np.linspace(0.0, bench.t_end, 41)))
    L = bench.element_length
    return np.array([res.displacement(n, d) * (1.0 if d[0] == "u" else L)
                     for n in nodes for d in ("ux", "uy", "rx", "ry")]), res


def truncation(name: str) -> None:
    bench = MODELS[name]
    model = bench.build()
    system = assemble(*model)
    profile = ConstantSpeed(bench.speed).bind(0.0, bench.t_end)
    problem, loads = rotor_problem(system, profile, 0.0,
                                   rs.Excitation(unbalance=bench.unbalance))
    q0, _ = initial_state(system, "static", loads.constant, profile, 0.0)
    weights = dof_weights(system, problem.n)
    assert weights is not None and problem.restoring is not None
    floor = motion_floor(problem, loads, profile, 0.0, bench.t_end, q0, weights)
    assert floor is not None
    out = problem.restoring(q0, np.zeros_like(q0), 0.0)
    assert out is not None
    tangent = out[1]
    ref, _ = whole_rotor(bench, model, 1e-8, False)
    reached = float(np.max(np.abs(ref - ref[:, :1])))
    scale = max(reached, floor)
    print(f"\n{name}: a-priori motion {floor * 1e6:.2f} um, reached {reached * 1e6:.2f} um")
    print("| modes | ringing | drift | estimate | error / a-priori motion | error / motion "
          "scale | / estimate | / ringing |\n|---|---|---|---|---|---|---|---|")
    counts = er.MODE_COUNTS
    try:
        for count in COUNTS[name]:
            # the count first, a larger one after it: room for the count's cluster
            er.MODE_COUNTS = (count, max(counts) + 16)  # type: ignore[assignment]
            _, _, decision = er.exponential_reduction(
                system, problem, loads, bench.speed, 1e9, floor, weights, tangent=tangent,
                phase=profile.angle(0.0), duration=bench.t_end)
            rec = decision["tried"][0]
            err = float(np.max(np.abs(whole_rotor(bench, model, 1e-8, rec["modes"])[0] - ref)))
            print(f"| {rec['modes']} | {rec['ringing']:.1e} | {rec['drift']:.1e} | "
                  f"{rec['estimate']:.1e} | {err / floor:.1e} | {err / scale:.1e} | "
                  f"{err / scale / rec['estimate']:.2f} | {err / scale / rec['ringing']:.1f} |",
                  flush=True)
    finally:
        er.MODE_COUNTS = counts


def steps(name: str, rtol: float, start: str = "static") -> None:
    """``start``: ``static`` (the model's static start) or ``bench`` (the equilibrium that
    ``bench_transient.py`` gives every run: on ``issue14`` the static start's eigenbasis is
    refused below rtol 1e-2 and the run falls back to Radau IIA, the benchmark's is not)."""
    bench = MODELS[name]
    model = bench.build()
    initial: Any = "static"
    if start == "bench":
        full = first_order(bench)[4]
        initial = (full, np.zeros_like(full))
    rows: list[tuple[float, float, float, float]] = []
    step = ex.Exponential.step

    def checked(self: ex.Exponential, problem: Any, state: Any) -> Any:
        new = step(self, problem, state)
        if self.fixed:
            return new
        h = new.history_dt
        fine, sub = dataclasses.replace(self, fixed=True), dataclasses.replace(state, dt=h / 16)
        for _ in range(16):
            sub = dataclasses.replace(step(fine, problem, sub), dt=h / 16)
        cache = new.cache
        d = np.abs(new.q - sub.q if cache.basis is None else cache.basis @ (new.q - sub.q))
        true = float((cache.scales.weights * d).max()) / (
            self.local_tol * cache.scales.scale(new.peak))
        rows.append((state.t, h, float(new.error), true))
        return new

    ref, _ = whole_rotor(bench, model, 1e-8, False, initial)
    ex.Exponential.step = checked  # type: ignore[method-assign]
    try:
        run, res = whole_rotor(bench, model, rtol, None, initial)
    finally:
        ex.Exponential.step = step  # type: ignore[method-assign]
    motion = max(float(np.max(np.abs(ref - ref[:, :1]))), 0.0)
    size = (res.options.get("reduction") or {}).get("size")
    print(f"{name} rtol {rtol:g}: {size or 'full'} unknowns, {res.options['method']}, "
          f"whole-rotor error "
          f"{np.max(np.abs(run - ref)) / motion / rtol:.2f} rtol (of the motion reached)")
    print("  t [us]  h [us]  estimate  local error (16 sub-steps)")
    for t, h, est, true in rows:
        print(f"  {t * 1e6:6.0f}  {h * 1e6:6.0f}  {est:8.2f}  {true:8.2f}"
              + ("  <-" if true > 1.0 else ""))


if __name__ == "__main__":
    if sys.argv[1:2] == ["steps"]:
        steps(sys.argv[2], float(sys.argv[3]), *sys.argv[4:5])
    else:
        for model_name in ("bench", "issue14"):
            truncation(model_name)
