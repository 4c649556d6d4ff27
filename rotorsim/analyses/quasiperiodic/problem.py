"""A rotor on rolling bearings with unbalance as a quasi-periodic problem on a 2-torus.

The shaft turns at ``W``; the unbalance forces the shaft frequency ``w1 = W`` (angle
``theta1 = W t``, the shaft angle). The rolling elements move with their cages at
``kappa W``, so a bearing of ``Z`` elements repeats its stiffness at the varying-compliance
(VC) frequency ``w2 = Z kappa W`` (angle ``theta2``; the cage angle is ``theta2 / Z``).
When ``Z kappa`` is irrational the two frequencies are incommensurate and the response is
a 2-torus, which :mod:`rotorsim.harmonic_balance.quasi` computes. Every rolling bearing
must then share one VC order ``Z kappa`` (two orders would make three frequencies).

The problem is posed on the *active* DOFs, as the periodic analysis poses its own (free
rigid motions held at zero), at a fixed speed: gravity and point loads in the mean, the
unbalance ``m e W^2`` in the tone ``(1, 0)``. The bearings' forces are evaluated with the
"shaft angle" ``theta2 / (Z kappa)``, which puts their cages at ``theta2 / Z``;
everything else about them (speed, damping) is as in the periodic analysis.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.analyses.statics.static_start import static_start
from rotorsim.analyses.varying_compliance import vc_orders
from rotorsim.assembly.loads import gravity_load, nodal_load, unbalance_amplitudes
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.assembly.system import RotorSystem
from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi import QuasiProblem, TorusHarmonics
from rotorsim.solvers.stats import Stats

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

WHERE = "quasi_periodic"
SAME_ORDER = 1e-9
"""VC orders of two bearings closer than this (relative) are the same frequency."""


@dataclass(frozen=True, eq=False)
class RotorQuasiProblem:
    """The problem on the active DOFs with the maps back to the rotor.

    Attributes
    ----------
    problem : QuasiProblem
    active : int array
        Free-DOF index of each active DOF.
    static : array (n_free,)
        Static equilibrium at the speed [m, rad] (the start of the mean).
    vc_order : float
        ``Z kappa``: ``w2 = vc_order W``.
    speed : float
        ``W`` [rad/s].
    """

    problem: QuasiProblem
    active: IntArray
    static: FloatArray
    vc_order: float
    speed: float


@dataclass(frozen=True, eq=False)
class TorusBearingForce:
    """The rolling bearings' forces on the active nonlinear DOFs as a function of the torus
    angles (the cage at ``theta2 / Z``)."""

    assembly: NonlinearAssembly
    positions: IntArray
    vc_order: float
    speed: float
    damped: bool

    def __call__(self, q: FloatArray, v: FloatArray, theta1: FloatArray,
                 theta2: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        return self.assembly.evaluate_on(self.positions, q, v, theta2 / self.vc_order,
                                         self.speed, self.damped)


def common_vc_order(system: RotorSystem) -> float:
    """The VC order ``Z kappa`` shared by the rolling bearings whose cages turn.

    Raises
    ------
    ModelError
        No bearing with a turning cage (the response is periodic: use ``rs.periodic``), or
        bearings of different orders (three or more frequencies).
    """
    orders = vc_orders(system.nonlinear.elements) if system.nonlinear is not None else []
    if not orders:
        raise ModelError("no rolling bearing with a turning cage: the unbalance response is "
                         "periodic (use rs.periodic)", WHERE)
    ref = orders[0]
    if any(abs(o - ref) > SAME_ORDER * ref for o in orders):
        raise ModelError(f"rolling bearings of different varying-compliance orders "
                         f"{sorted(set(round(o, 9) for o in orders))} force more than two "
                         "frequencies; the two-frequency harmonic balance needs one order",
                         WHERE)
    return float(ref)


def build_quasi_problem(system: RotorSystem, speed: float, harmonics: TorusHarmonics, *,
                        unbalance: Sequence[tuple[int, float, float]],
                        gravity: float | None, direction: Any,
                        loads: Sequence[tuple[int, str, float]] = (),
                        stats: Stats) -> RotorQuasiProblem:
    """The quasi-periodic problem of ``system`` at ``speed`` [rad/s] (module docstring)."""
    if not (np.isfinite(speed) and speed > 0):
        raise ModelError(f"speed must be positive and finite [rad/s], got {speed!r}",
                         f"{WHERE}.speed")
    order = common_vc_order(system)
    mats = system.matrices(speed)  # speed-dependent linear bearings at this fixed speed
    f_const = np.zeros(system.n_free)
    if gravity is not None:
        f_const += gravity_load(system, gravity, direction)
    for i, (node, dof, value) in enumerate(loads):
        f_const += nodal_load(system, int(node), str(dof), float(value),
                              where=f"{WHERE}.excitation.loads[{i}]")
    static, held = static_start(system, mats.K, f_const, speed, 0.0, stats)
    active = np.setdiff1d(np.arange(system.n_free), held).astype(np.int64)
    ix = np.ix_(active, active)
    nl = system.nonlinear
    assert nl is not None  # common_vc_order checked it
    keep = np.isin(nl.dofs, active)
    positions = np.flatnonzero(keep).astype(np.int64)
    nl_dofs = np.searchsorted(active, nl.dofs[keep]).astype(np.int64)
    damped = any(getattr(el, "contact_damping", "unknown") != "none" for el in nl.elements)
    force = TorusBearingForce(nl, positions, order, float(speed), damped)
    P = np.zeros((harmonics.rows, active.size))
    P[0] = f_const[active]
    if unbalance:
        U = unbalance_amplitudes(system, unbalance)[active] * speed**2
        j = harmonics.index(1, 0)
        P[1 + 2 * j], P[2 + 2 * j] = U.real, -U.imag
    G = sp.csr_matrix(mats.G)[ix] if mats.G.nnz else None
    problem = QuasiProblem(sp.csr_matrix(mats.M)[ix], sp.csr_matrix(mats.C)[ix],
                           sp.csr_matrix(mats.K)[ix], G, nl_dofs=nl_dofs, force=force,
                           excitation=P, spin=float(speed), spin_ratio=0.0)
    return RotorQuasiProblem(problem, active, static, order, float(speed))
