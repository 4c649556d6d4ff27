"""The static start of the periodic and quasi-periodic analyses: the equilibrium under the
constant loads and the DOFs held at zero (one per free rigid motion that no element
restrains)."""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.rigid_motions import free_rigid_motions, held_dofs
from rotorsim.analyses.statics.nonlinear_static import nominal_tangent, nonlinear_equilibrium
from rotorsim.assembly.system import RotorSystem
from rotorsim.solvers.linear import factorize
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def static_start(system: RotorSystem, K: Any, f: FloatArray, speed: float, phi: float,
                 stats: Stats, x0: FloatArray | None = None) -> tuple[FloatArray, IntArray]:
    """Static equilibrium ``K q + r(q) = f`` (n_free,) and the held free DOFs, one per free
    rigid motion of ``K`` plus the nominal bearing tangent; the nonlinear solve starts from
    ``x0`` (n_free,) when given
    (:func:`~rotorsim.analyses.statics.nonlinear_static.start_point`)."""
    if system.nonlinear is None:
        rigid = free_rigid_motions(system, sp.csr_matrix(K))
        held = np.asarray(held_dofs(rigid), dtype=np.int64)
        keep = np.setdiff1d(np.arange(system.n_free), held)
        q = np.zeros(system.n_free)
        if np.any(f):
            q[keep] = factorize(sp.csr_matrix(K)[keep][:, keep], stats=stats,
                                where="periodic: static start").solve(f[keep])
        return q, held
    nominal = nominal_tangent(system)
    rigid = free_rigid_motions(system, sp.csr_matrix(K + nominal))
    held = np.asarray(held_dofs(rigid), dtype=np.int64)
    eq = nonlinear_equilibrium(system, f, speed=speed, phi=phi, q0=x0, held=held.tolist(),
                               nominal=nominal, stats=stats)
    return eq.q, held
