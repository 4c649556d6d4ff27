"""When the automatic path integrates by exponential collocation instead of Radau IIA.

The exponential collocation stepper (:mod:`rotorsim.time_integration.exponential`)
integrates the linear rotor exactly and iterates only on the bearing forces, so a step
costs ``O(n k)`` instead of a factorisation-backed solve of size ``n``; its set-up is one
dense eigen-decomposition of size ``2 n``. It applies when

* the speed is constant over the run (the linear part is then time-invariant);
* the loads are constant plus the unbalance (no base excitation, user forces or torque
  drive), checked by comparing the problem's loads with the harmonic form at a few times;
* the nonlinear forces are local and evaluated in batches (rolling bearings), and no
  bearing's linear coefficients depend on speed;
* the model is small enough for the dense eigen-decomposition to pay off:
  :data:`EXPONENTIAL_LIMIT` free DOFs (measured in ``benchmarks/bench_transient.py``).

Otherwise the automatic path keeps Radau IIA (:mod:`~.auto`).
"""

from __future__ import annotations

import numpy as np

from rotorsim.analyses.transient.loads import TransientLoads
from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.elements.base import FloatArray
from rotorsim.time_integration.exponential import Exponential
from rotorsim.time_integration.exponential_modes import HarmonicLoad
from rotorsim.time_integration.problem import SecondOrderProblem

EXPONENTIAL_LIMIT = 400
"""Largest number of unknowns integrated by exponential collocation: the eigen-decomposition
of size ``2 n`` costs about 40 ms at n = 150 and grows as ``n^3`` (about 0.8 s at n = 400),
while a Radau step of a sparse model of that size costs a few ms
(``docs/benchmarks.md``, transients)."""
CHECK_POINTS = 5
"""Times at which the harmonic form of the loads is compared with the problem's."""


def harmonic_load(problem: SecondOrderProblem, loads: TransientLoads, profile: BoundSpeed,
                  span: tuple[float, float], T: FloatArray | None = None
                  ) -> HarmonicLoad | None:
    """The loads as ``constant + Re(u e^{i W t})`` when they are that over ``span`` at a
    constant speed ``W`` (checked at :data:`CHECK_POINTS` times), else None. ``T``: the
    basis of a reduced problem (``q = T x``; the loads are then ``T^T f``)."""
    t0, t_end = span
    if loads.torsion is not None or loads.forces is not None or loads.base is not None or \
            loads.unbalance_ratio is not None:
        return None
    times = np.linspace(t0, t_end, CHECK_POINTS)
    speeds = np.array([profile.speed(float(t)) for t in times])
    W = float(speeds[0])
    if not np.all(speeds == W) or profile.acceleration(t0) != 0.0:
        return None
    if any(problem.spin(float(t)) != W for t in times):
        return None
    amplitude = np.zeros(problem.n, dtype=complex) if loads.unbalance is None else \
        loads.unbalance * W * W * np.exp(1j * (profile.angle(0.0)))
    constant = np.asarray(loads.constant, dtype=float)
    if T is not None:
        constant, amplitude = T.T @ constant, T.T @ amplitude
    load = HarmonicLoad(constant, amplitude, W)
    for t in times:
        f = problem.external(float(t))
        size = np.abs(f)
        # numpy's allclose test (|a - f| <= atol + rtol |f|, NaN failing), without its
        # wrapper's cost (about 20 us a call, ten calls per run)
        if not (np.abs(load(float(t)) - f) <= 1e-12 * max(float(size.max()), 1e-300)
                + 1e-9 * size).all():
            return None
    return load


def exponential_stepper(problem: SecondOrderProblem, loads: TransientLoads,
                        profile: BoundSpeed, span: tuple[float, float], rtol: float,
                        weights: tuple[float, ...] | None, floor: float | None,
                        T: FloatArray | None = None,
                        physical: tuple[float, ...] | None = None) -> Exponential | None:
    """The exponential collocation stepper at ``rtol`` when it applies (module docstring),
    else None; ``T`` as in :func:`harmonic_load`, ``physical`` the weights of the full
    model's DOFs (the error of a reduced run is measured on them)."""
    if problem.n > EXPONENTIAL_LIMIT or problem.speed_terms is not None or \
            getattr(problem.restoring, "batch", None) is None or \
            getattr(problem.restoring, "damping", None) is not None:
        return None
    load = harmonic_load(problem, loads, profile, span, T)
    if load is None:
        return None
    return Exponential(load, rtol=rtol, weights=weights, motion=floor, basis=T,
                       basis_weights=physical)
