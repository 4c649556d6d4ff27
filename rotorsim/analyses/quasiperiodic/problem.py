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

**Two spools.** On a machine of several lines the unbalances of the reference line and of
one more spool turning at ``r W`` force ``w1 = W`` and ``w2 = |r| W``
(:func:`torus_plan`): the same torus, with the second spool's unbalance in the tone
``(0, 1)`` (conjugated for a counter-rotating spool, whose unbalance whirls backwards).
The VC of rolling bearings with turning cages would then be a third frequency: their
rolling elements are frozen at the shaft angle 0, and the plan says so.
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
from rotorsim.assembly.loads import (
    gravity_load,
    nodal_load,
    spool_groups,
    unbalance_amplitudes,
)
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
        ``w2 / W``: ``Z kappa`` (VC) or the second spool's ``|r|``.
    speed : float
        ``W`` [rad/s].
    plan : TorusPlan, optional
        Where ``w2`` comes from (VC when omitted).
    """

    problem: QuasiProblem
    active: IntArray
    static: FloatArray
    vc_order: float
    speed: float
    plan: TorusPlan | None = None


@dataclass(frozen=True, eq=False)
class TorusBearingForce:
    """The rolling bearings' forces on the active nonlinear DOFs as a function of the torus
    angles (the cage at ``theta2 / Z``)."""

    assembly: NonlinearAssembly
    positions: IntArray
    vc_order: float
    speed: float
    damped: bool
    frozen: bool = False

    def __call__(self, q: FloatArray, v: FloatArray, theta1: FloatArray,
                 theta2: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        angle = np.zeros_like(theta2) if self.frozen else theta2 / self.vc_order
        return self.assembly.evaluate_on(self.positions, q, v, angle, self.speed,
                                         self.damped)


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


@dataclass(frozen=True)
class TorusPlan:
    """Where the second base frequency comes from.

    Attributes
    ----------
    second : str
        ``"vc"`` (the rolling elements' varying compliance, ``w2 = Z kappa W``) or
        ``"spool"`` (the unbalance of a second spool, ``w2 = |r| W``).
    order : float
        ``w2 / W``.
    tones : tuple of (k1, k2, ratio, unbalance)
        Each unbalance group with its tone and its spool's signed speed ratio.
    frozen : bool
        Rolling elements frozen at the shaft angle 0 (their VC would be a third frequency).
    approximation : str
        What freezing neglects ("" when nothing).
    """

    second: str
    order: float
    tones: tuple[tuple[int, int, float, tuple[tuple[int, float, float], ...]], ...]
    frozen: bool = False
    approximation: str = ""


def torus_plan(system: RotorSystem, unbalance: Sequence[tuple[int, float, float]]
               ) -> TorusPlan:
    """The two base frequencies of the torus: the reference spool's 1X with the VC of the
    rolling bearings, or the 1X of two spools (the reference line and one more; rolling
    elements with turning cages are then frozen and the plan says so).

    Raises
    ------
    ModelError
        Unbalances on three spools, two spools without the reference line, or (VC) no
        turning cage, bearings of different VC orders, an unbalance off the reference
        line.
    """
    groups = spool_groups(system, unbalance) if unbalance else {}
    if len(groups) > 2:
        raise ModelError(f"unbalances on spools at speed ratios {sorted(groups)} force more "
                         "than two frequencies", f"{WHERE}.unbalance")
    if len(groups) == 2:
        if 1.0 not in groups:
            raise ModelError(f"unbalances on spools at speed ratios {sorted(groups)}: one of "
                             "the two must be the reference line (ratio 1)",
                             f"{WHERE}.unbalance")
        other = next(r for r in groups if r != 1.0)
        vc = vc_orders(system.nonlinear.elements) if system.nonlinear is not None else []
        note = (f"rolling elements frozen at the shaft angle 0 (their varying compliance at "
                f"orders {sorted(set(round(o, 6) for o in vc))} would be a third "
                "frequency)") if vc else ""
        return TorusPlan("spool", abs(float(other)),
                         ((1, 0, 1.0, tuple(groups[1.0])), (0, 1, float(other),
                                                            tuple(groups[other]))),
                         bool(vc), note)
    if groups and 1.0 not in groups:
        raise ModelError(f"the unbalance is on a spool at speed ratio {next(iter(groups))}: "
                         "with varying compliance the torus needs it on the reference line",
                         f"{WHERE}.unbalance")
    return TorusPlan("vc", common_vc_order(system),
                     ((1, 0, 1.0, tuple(unbalance)),) if unbalance else ())


def forcing_rows(system: RotorSystem, plan: TorusPlan, harmonics: TorusHarmonics,
                 active: IntArray) -> list[tuple[int, NDArray[np.complex128]]]:
    """``(row, U)`` of every unbalance tone: the complex load ``U (r W)^2`` on the active
    DOFs in coefficient row ``row`` (cosine; the sine row follows) per unit ``W^2``. A
    counter-rotating spool's unbalance whirls backwards: its amplitude is conjugated."""
    out = []
    for k1, k2, ratio, group in plan.tones:
        U = unbalance_amplitudes(system, list(group))[active] * ratio**2
        out.append((1 + 2 * harmonics.index(k1, k2), np.conj(U) if ratio < 0 else U))
    return out


def build_quasi_problem(system: RotorSystem, speed: float, harmonics: TorusHarmonics, *,
                        unbalance: Sequence[tuple[int, float, float]],
                        gravity: float | None, direction: Any,
                        loads: Sequence[tuple[int, str, float]] = (),
                        stats: Stats) -> RotorQuasiProblem:
    """The quasi-periodic problem of ``system`` at ``speed`` [rad/s] (module docstring)."""
    if not (np.isfinite(speed) and speed > 0):
        raise ModelError(f"speed must be positive and finite [rad/s], got {speed!r}",
                         f"{WHERE}.speed")
    plan = torus_plan(system, unbalance)
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
    force, nl_dofs = None, np.zeros(0, dtype=np.int64)
    if nl is not None:
        keep = np.isin(nl.dofs, active)
        positions = np.flatnonzero(keep).astype(np.int64)
        nl_dofs = np.searchsorted(active, nl.dofs[keep]).astype(np.int64)
        damped = any(getattr(el, "contact_damping", "unknown") != "none"
                     for el in nl.elements)
        force = TorusBearingForce(nl, positions, plan.order, float(speed), damped,
                                  plan.frozen or plan.second == "spool")
    P = np.zeros((harmonics.rows, active.size))
    P[0] = f_const[active]
    for row, U in forcing_rows(system, plan, harmonics, active):
        P[row] += U.real * speed**2
        P[row + 1] += -U.imag * speed**2
    G = sp.csr_matrix(mats.G)[ix] if mats.G.nnz else None
    problem = QuasiProblem(sp.csr_matrix(mats.M)[ix], sp.csr_matrix(mats.C)[ix],
                           sp.csr_matrix(mats.K)[ix], G, nl_dofs=nl_dofs, force=force,
                           excitation=P, spin=float(speed), spin_ratio=0.0)
    return RotorQuasiProblem(problem, active, static, plan.order, float(speed), plan)
