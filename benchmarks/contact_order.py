"""Observed order of the transient paths on rotors whose ball contacts close and open
(issue 14: "the order drops at contact closing").

Two rotors of ``benchmarks/bench_transient.py`` (``issue14``, the model of the issue, and
``bench``), each also with a 10 um *preload* instead of the 10 um clearance (every ball stays
in contact: no contact ever closes or opens) and ``bench`` also with a *smooth start* (the
speed rises from 0 to 600 rad/s by a C2 smootherstep over 1 ms instead of the unbalance
being switched on at full speed at ``t = 0``). For each case it prints the error of the
probe (mid-span ``uy`` over 41 times, relative to its peak-to-peak motion) against a
reference, and the observed orders between successive runs:

* fixed-step average acceleration, dt = 40 ... 1.25 us (order from the error ratio of
  halved steps);
* the automatic path ``rs.transient(..., rtol=)``, rtol 1e-4 ... 1e-7 (order as error
  against steps, ``log(e1/e2) / log(N2/N1)``);
* on ``issue14`` also the automatic path with every step that closes a contact retried so
  that it ends at the closing instant (the instant located on the step's dense output by
  regula falsi on the ball's contact deflection): an experiment that wraps
  ``Radau.step``, not a library feature.

The reference is ``solve_ivp`` LSODA at rtol 1e-11 (atol 1e-11 times the probe's motion
and velocity scales) on ``y = [q, v]`` built from the same ``SecondOrderProblem`` (its net
force and exact tangents).

Run: ``OPENBLAS_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python benchmarks/contact_order.py``
(about 4 minutes).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
import scipy.linalg as sl
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_transient as bt

import rotorsim as rs
from rotorsim.analyses.transient.equation import rotor_problem
from rotorsim.analyses.transient.start import initial_state
from rotorsim.assembly.system import RotorSystem, assemble
from rotorsim.time_integration import radau
from rotorsim.time_integration.hermite import quintic_hermite

STEPS = (4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6)
RTOLS = (1e-4, 1e-5, 1e-6, 1e-7)
RAMP = 1e-3
"""Duration of the smooth start [s]."""


def smooth_speed(top: float) -> rs.SpeedFunction:
    """``W(t) = top * s(t / RAMP)``, ``s`` the C2 smootherstep ``x^3 (10 - 15 x + 6 x^2)``."""
    def speed(t: float) -> float:
        x = min(max(t / RAMP, 0.0), 1.0)
        return top * x ** 3 * (10.0 - 15.0 * x + 6.0 * x * x)

    def slope(t: float) -> float:
        x = min(max(t / RAMP, 0.0), 1.0)
        return top * 30.0 * x * x * (1.0 - x) ** 2 / RAMP

    return rs.SpeedFunction(speed, derivative=slope)


@dataclasses.dataclass
class Case:
    """A rotor, its speed and the start state on all DOFs."""

    name: str
    bench: bt.BenchModel
    speed: Any
    rotor: rs.Rotor = dataclasses.field(init=False)
    bearings: list[Any] = dataclasses.field(init=False)
    system: RotorSystem = dataclasses.field(init=False)

    def __post_init__(self) -> None:
        self.rotor, self.bearings = self.bench.build()
        self.system = assemble(self.rotor, self.bearings)

    def run(self, **kw: Any) -> Any:
        times = np.linspace(0.0, self.bench.t_end, 41)
        return rs.transient(self.rotor, self.bench.t_end, kw.pop("dt", None),
                            nonlinear=self.bearings, speed=self.speed,
                            unbalance=self.bench.unbalance, nodes=[self.bench.probe],
                            initial=self.start, output=rs.Output(times=times), **kw)

    @property
    def start(self) -> tuple[Any, Any]:
        """The static equilibrium at rest on all DOFs (every run starts from it)."""
        if not hasattr(self, "_start"):
            q0 = self._problem()[2]
            full = np.zeros(self.system.dof_map.ndof)
            full[self.system.dof_map.free] = q0
            self._start = (full, np.zeros_like(full))
        return self._start

    def _problem(self) -> tuple[Any, Any, Any]:
        profile = (rs.ConstantSpeed(self.speed) if isinstance(self.speed, float)
                   else self.speed).bind(0.0, self.bench.t_end, 8192)
        problem, loads = rotor_problem(self.system, profile, 0.0,
                                       rs.Excitation(unbalance=self.bench.unbalance))
        q0, _ = initial_state(self.system, "static", loads.constant, profile, 0.0)
        return problem, profile, q0

    def reference(self) -> tuple[Any, float]:
        """LSODA at rtol 1e-11 on ``y = [q, v]``: the probe at the 41 times, its motion."""
        problem, profile, q0 = self._problem()
        n = self.system.n_free
        dense = (lambda A: A.toarray() if hasattr(A, "toarray") else np.asarray(A))  # noqa: E731
        mass = sl.lu_factor(dense(problem.mass))
        K, C, G = (dense(A) for A in (problem.stiffness, problem.damping, problem.gyroscopic))

        def rhs(t: float, y: Any) -> Any:
            q, v = y[:n], y[n:]
            return np.concatenate([v, -sl.lu_solve(mass, problem.forces(q, v, t).net)])

        def jac(t: float, y: Any) -> Any:
            ev = problem.forces(y[:n], y[n:], t)
            J = np.zeros((2 * n, 2 * n))
            J[:n, n:] = np.eye(n)
            J[n:, :n] = -sl.lu_solve(mass, K + ev.stiffness_tangent.toarray())
            J[n:, n:] = -sl.lu_solve(mass, C + profile.speed(t) * G
                                     + ev.damping_tangent.toarray())
            return J

        probe = self.system.dofs_of(self.bench.probe, ("uy",))[0]
        scout = self.run(dt=2.5e-6)
        motion = float(np.ptp(scout.displacement(self.bench.probe, "uy")))
        velocity = motion * 2.0 * math.pi / 1e-4  # generous: a 10 kHz vibration
        scale = np.concatenate([np.full(n, motion), np.full(n, velocity)])
        times = np.linspace(0.0, self.bench.t_end, 41)
        sol = solve_ivp(rhs, (0.0, self.bench.t_end), np.concatenate([q0, np.zeros(n)]),
                        method="LSODA", jac=jac, rtol=1e-11, atol=1e-11 * scale, t_eval=times)
        ref = sol.y[probe]
        return ref, float(np.ptp(ref))


def contact_deflections(system: RotorSystem, q: Any, phi: Any) -> Any:
    """Contact deflection (S, balls of all bearings) [m] at ``q`` (S, n) and angles ``phi``
    (S,): positive where a ball is loaded."""
    q = np.atleast_2d(q)
    full = np.zeros((q.shape[0], system.dof_map.ndof))
    full[:, system.dof_map.free] = q
    out = []
    assert system.nonlinear is not None
    for element in system.nonlinear.elements:
        el: Any = element  # a RollingBearing (relative DOFs, ball bearing model)
        node = el.nodes[0]
        delta = el.relative(full[:, 6 * node: 6 * node + 6])
        psi = el.bearing.element_angles(np.asarray(phi, dtype=float))
        out.append(el.bearing._contacts(delta, np.cos(psi), np.sin(psi))[3])
    return np.concatenate(out, axis=1)


class LandOnClosings:
    """Wraps ``Radau.step``: a step in which a contact closes is redone so that it ends at
    the closing instant (located on the dense output). ``landed`` counts the redone steps."""

    def __init__(self, system: RotorSystem) -> None:
        self.system, self.landed, self._plain = system, 0, radau.Radau.step

    def __enter__(self) -> LandOnClosings:
        wrapper = self

        def step(method: Any, problem: Any, state: Any) -> Any:
            return wrapper.step(method, problem, state)

        radau.Radau.step = step  # type: ignore[method-assign, assignment]
        return self

    def __exit__(self, *exc: object) -> None:
        radau.Radau.step = self._plain  # type: ignore[method-assign]

    def step(self, method: Any, problem: Any, state: Any) -> Any:
        new = self._plain(method, problem, state)
        angle = problem.restoring.speed.angle
        g0 = contact_deflections(self.system, state.q, [angle(state.t)])[0]
        g1 = contact_deflections(self.system, new.q, [angle(new.t)])[0]
        closing = np.flatnonzero((g0 <= 0.0) & (g1 > 0.0))
        if closing.size == 0:
            return new
        t_star = self._closing(state, new, angle, closing, g0)
        h = new.t - state.t
        if not 1e-3 * h < t_star - state.t < (1.0 - 1e-3) * h:
            return new
        attempt = radau._Attempt(method, state.cache, state, t_star - state.t)
        solution, err, factor = attempt.run(False)
        if solution is None or err > 1.0:
            return new
        self.landed += 1
        return method._accepted(state, solution, attempt, err,
                                min(method.max_growth, factor), attempt.tally)

    def _closing(self, old: Any, new: Any, angle: Any, balls: Any, g0: Any) -> float:
        """The earliest closing instant of ``balls`` on the quintic dense output."""
        dofs = np.arange(old.q.size)
        grid = old.t + (new.t - old.t) * np.linspace(0.0, 1.0, 41)[1:]
        q, _ = quintic_hermite(old, new, grid, dofs)
        g = contact_deflections(self.system, q, [angle(float(t)) for t in grid])[:, balls]
        after = np.argmax(g > 0.0, axis=0)
        j = int(np.argmin(after))
        k = int(after[j])
        ta, ga = (old.t, g0[balls[j]]) if k == 0 else (grid[k - 1], g[k - 1, j])
        tb, gb = grid[k], g[k, j]
        for _ in range(40):  # regula falsi
            tm = ta - ga * (tb - ta) / (gb - ga)
            qm, _ = quintic_hermite(old, new, np.array([tm]), dofs)
            gm = contact_deflections(self.system, qm, [angle(tm)])[0, balls[j]]
            if gm > 0.0:
                tb, gb = tm, gm
            else:
                ta, ga = tm, gm
            if tb - ta < 1e-12 * (new.t - old.t):
                break
        return float(tb)


def orders(errors: list[float], costs: list[float]) -> list[str]:
    """``log(e1/e2) / log(c2/c1)`` between successive runs."""
    pairs = list(zip(errors, costs, strict=True))
    return [f"{math.log(e1 / e2) / math.log(c2 / c1):.2f}"
            for (e1, c1), (e2, c2) in itertools.pairwise(pairs)]


def study(case: Case, land: bool) -> None:
    ref, motion = case.reference()
    probe = case.bench.probe
    error = (lambda r: float(np.max(np.abs(r.displacement(probe, "uy") - ref))) / motion)  # noqa: E731
    fixed = [error(case.run(dt=dt)) for dt in STEPS]
    step_text = " / ".join(f"{dt * 1e6:g}" for dt in STEPS)
    fixed_orders = " / ".join(orders(fixed, [1 / dt for dt in STEPS]))
    print(f"| `{case.name}` | fixed dt {step_text} us | {' / '.join(f'{e:.2e}' for e in fixed)} "
          f"| {fixed_orders} |")
    variants = [("auto", None)] + ([("auto, steps landing on closings", case.system)]
                                   if land else [])
    for label, system in variants:
        errs: list[float] = []
        steps: list[float] = []
        landed = 0
        for rtol in RTOLS:
            if system is None:
                res = case.run(rtol=rtol)
            else:
                with LandOnClosings(system) as lander:
                    res = case.run(rtol=rtol)
                landed += lander.landed
            errs.append(error(res))
            steps.append(float(res.stats["steps"]))
        extra = f" ({landed} steps landed)" if system is not None else ""
        counts = " / ".join(f"{s:.0f}" for s in steps)
        print(f"| | {label}, rtol {' / '.join(f'{r:g}' for r in RTOLS)}{extra} | "
              f"{' / '.join(f'{e:.2e}' for e in errs)} (steps {counts}) | "
              f"{' / '.join(orders(errs, steps))} |", flush=True)


def main() -> None:
    preload = {"diametral_clearance": -10e-6}
    cases = [
        (Case("issue14", bt.MODELS["issue14"], 1000.0), True),
        (Case("issue14, preloaded", dataclasses.replace(
            bt.MODELS["issue14"], ball={**bt.MODELS["issue14"].ball, **preload}), 1000.0),
         False),
        (Case("bench", bt.MODELS["bench"], 600.0), False),
        (Case("bench, preloaded", dataclasses.replace(
            bt.MODELS["bench"], ball={**bt.MODELS["bench"].ball, **preload}), 600.0), False),
        (Case("bench, smooth start", bt.MODELS["bench"], smooth_speed(600.0)), False),
    ]
    print("| model | runs | error (relative to the motion) | observed order |")
    print("|---|---|---|---|")
    for case, land in cases:
        study(case, land)


if __name__ == "__main__":
    with np.errstate(all="ignore"):
        main()
