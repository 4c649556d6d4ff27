"""Initial state of a rotor transient: zero, given, or the static equilibrium at rest under
the constant loads (linear solve, or Newton on the nonlinear elements started from the
robust rolling-bearing statics when every element is a RollingBearing)."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from rotorsim.analyses.rigid_motions import (
    check_equilibrium,
    free_rigid_motions,
    held_dofs,
    solve_restrained,
)
from rotorsim.analyses.statics.nonlinear_static import nominal_tangent, nonlinear_equilibrium
from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats

WHERE = "transient"


def initial_state(system: RotorSystem, initial: str | tuple[ArrayLike, ArrayLike],
             f: FloatArray, profile: BoundSpeed, t0: float,
             start: FloatArray | None = None) -> tuple[FloatArray, FloatArray]:
    n = system.n_free
    if isinstance(initial, str):
        if initial == "zero":
            return np.zeros(n), np.zeros(n)
        if initial != "static":
            raise ModelError(f"initial must be 'static', 'zero' or (q0, v0), got {initial!r}",
                             f"{WHERE}.initial")
        return static_start(system, f, profile, t0, start), np.zeros(n)
    try:
        q_all, v_all = (np.asarray(x, dtype=float).reshape(-1) for x in initial)
    except (TypeError, ValueError):
        raise ModelError("give initial = (q0, v0) on all DOFs", f"{WHERE}.initial") from None
    ndof = system.dof_map.ndof
    if q_all.shape != (ndof,) or v_all.shape != (ndof,):
        raise ModelError(f"q0 and v0 must have {ndof} entries (all DOFs)", f"{WHERE}.initial")
    free = system.dof_map.free
    return q_all[free], v_all[free]


def static_start(system: RotorSystem, f: FloatArray, profile: BoundSpeed,
                  t0: float, start: FloatArray | None = None) -> FloatArray:
    """Static equilibrium under the constant loads (linear solve without nonlinear
    elements, Newton with them from ``start`` or the nominal-tangent solution)."""
    W, phi = profile.speed(t0), profile.angle(t0)
    K = system.matrices(W).K
    if system.nonlinear is None:
        if not np.any(f):
            return np.zeros(system.n_free)
        rigid = free_rigid_motions(system, K, scaled=True)
        if not rigid.fields.shape[1]:
            return np.asarray(factorize(K, where="transient: static start").solve(f))
        # free motions the loads do no work on (axial, torsion) are held, as in rs.static
        try:
            check_equilibrium(rigid, f)
        except ModelError as exc:
            raise ModelError(f"no static start: {str(exc).split(': ', 1)[-1]}; or use "
                             "initial='zero'",
                             f"{WHERE}.initial") from None
        return solve_restrained(K, f, rigid, Stats())[0]
    nominal = nominal_tangent(system)
    held = held_dofs(free_rigid_motions(system, sp.csr_matrix(K + nominal)))
    return nonlinear_equilibrium(system, f, speed=W, phi=phi, q0=start, held=held,
                                 nominal=nominal, stats=Stats()).q
