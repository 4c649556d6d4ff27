"""The automatic transient path: the error-controlled Radau IIA stepper set up for a rotor.

``rs.transient(rotor, t_end, rtol=1e-5)`` (or ``method="auto"``) asks for the response to
``rtol`` of the motion. The stepper (:class:`~rotorsim.time_integration.radau.Radau`, order
5) then needs to know what "the motion" is:

* the unknowns are grouped by kind, translations [m] and rotations [rad], each group with
  one scale (:mod:`~rotorsim.time_integration.motion_scale`);
* the scale of a group is the largest motion ``|q - q(t0)|`` reached so far, but never less
  than an a-priori estimate: the amplitude of the linear response to the unbalance at the
  starting speed (or the final one when the run starts at rest), linearised about the start
  state. Without the estimate the scale would start at zero and the first steps would
  resolve the onset of the motion to ``rtol`` of itself.

The estimate is only a floor of the scale: it does not limit the motion, and a response
that grows larger (a resonance in a run-up) raises the scale as it goes.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp

from rotorsim.analyses.transient.loads import TransientLoads
from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.time_integration.radau import Radau

DEFAULT_RTOL = 1e-4
"""Accuracy of ``method="auto"`` when no ``rtol`` is given."""


def dof_weights(system: RotorSystem, n: int) -> tuple[float, ...] | None:
    """Weight of every unknown in the error measure: 1 for translations, the longest shaft
    element [m] for rotations (None for a reduced problem, whose modal coordinates are not
    physical)."""
    free = np.asarray(system.dof_map.free)
    if free.size != n:
        return None
    lengths = np.diff(np.asarray(system.nodes_pos, dtype=float))
    length = float(np.max(lengths, initial=0.0)) or 1.0
    return tuple(float(x) for x in np.where(free % DOFS_PER_NODE >= 3, length, 1.0))


def auto_stepper(system: RotorSystem, problem: SecondOrderProblem, loads: TransientLoads,
                 profile: BoundSpeed, t0: float, t_end: float, q0: FloatArray,
                 rtol: float) -> Radau:
    """The Radau stepper at ``rtol`` with the weights and motion floor of ``system``."""
    if not (isinstance(rtol, int | float) and 1e-10 <= rtol <= 0.1):
        raise ModelError(f"rtol must be a number in [1e-10, 0.1], got {rtol!r}",
                         "transient.rtol")
    weights = dof_weights(system, problem.n)
    floor = None
    if weights is not None:
        amp = unbalance_amplitude(problem, loads, profile, t0, t_end, q0)
        if amp is not None:
            floor = float(np.max(np.asarray(weights) * amp))
    return Radau(rtol=float(rtol), weights=weights, motion=floor)


def unbalance_amplitude(problem: SecondOrderProblem, loads: TransientLoads,
                        profile: BoundSpeed, t0: float, t_end: float, q0: FloatArray
                        ) -> FloatArray | None:
    """Amplitude (n,) of the linear unbalance response about ``q0`` at the starting speed
    (the final one when the run starts at rest); None without unbalance or speed."""
    if loads.unbalance is None:
        return None
    speed = profile.speed(t0) or profile.speed(t_end)
    if speed <= 0.0:
        return None
    n = problem.n
    stiff, damp = _tangents(problem, q0, t0)
    D: Any = problem.damping_at(speed)
    terms = [(1.0, problem.stiffness), (-speed * speed, problem.mass), (1.0, stiff),
             (1j * speed, D), (1j * speed, damp)]
    if any(sp.issparse(A) for _, A in terms if A is not None):
        A = sum((c * sp.csr_matrix(M) for c, M in terms if M is not None),
                sp.csr_matrix((n, n), dtype=complex))
    else:
        A = sum((c * np.asarray(M) for c, M in terms if M is not None),
                np.zeros((n, n), dtype=complex))
    try:
        ratio = 1.0 if loads.unbalance_ratio is None else loads.unbalance_ratio
        x = factorize(A, where="transient: motion estimate").solve(  # each spool's r W
            (ratio * speed) ** 2 * loads.unbalance)
    except ConvergenceError:  # exactly at a resonance of the linearised rotor
        return None
    amp = np.abs(np.asarray(x))
    return amp if np.all(np.isfinite(amp)) else None


def _tangents(problem: SecondOrderProblem, q0: FloatArray, t0: float) -> tuple[Any, Any]:
    """Tangents of the restoring force at the start (None without one)."""
    if problem.restoring is None:
        return None, None
    out = problem.restoring(q0, np.zeros_like(q0), t0)
    if out is None:
        return None, None
    kt, ct = (T.tocsr() if isinstance(T, LocalMatrix) else T for T in out[1:3])
    return kt, ct
