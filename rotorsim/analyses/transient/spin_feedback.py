"""How much the neglected feedback of the lateral motion on the spin matters, after a run.

A torque drive (:mod:`~.torque_drive`) integrates the spin alone: the lateral motion does
not act back on it. The torque the lateral motion exerts about the spin axis comes from the
unbalance: a mass-eccentricity ``me`` at ``phi + a`` on a shaft centre accelerating by
``(x'', y'')`` under gravity ``g`` adds to the spin equation (Lagrange's equation in
``phi`` of the eccentric mass; Genta, *Dynamics of Rotating Systems*, Springer 2005, on the
non-ideal drive of an unbalanced rotor, the Sommerfeld effect)

    T_lat = -me [ -(x'' - g_x) sin(phi + a) + (y'' - g_y) cos(phi + a) ]

(the ``me e W'`` term of the eccentric mass's own polar inertia is left out, second order
in ``e``). The bearings of rotorsim act through the shaft axis (their five components
exclude ``rz``): their reactions exert no torque about it, their drag is the friction
law of the drive. The report compares ``T_lat`` with the net drive torque ``J_p W'``
that the one-way model keeps: when the ratio is not small, the speed history is
questionable, and a drive stuck at a resonance (the Sommerfeld effect) is out of scope.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from rotorsim.analyses.transient.torque_drive import BoundTorqueDrive
from rotorsim.errors import ModelError
from rotorsim.results.transient import TransientResult

QUESTIONABLE = 0.1
"""Ratio of the lateral feedback torque to the net drive torque above which the report
calls the one-way coupling questionable."""
DRIVING = 0.01
"""Samples whose net drive torque is below this fraction of its largest value (steady
running) are left out of the sample-wise ratio."""


def with_spin_feedback(result: TransientResult, drive: BoundTorqueDrive,
                       unbalance: Sequence[tuple[int, float, float]],
                       gravity: Sequence[float] | np.ndarray) -> TransientResult:
    """``result`` with ``options["spin_feedback"]``: the largest lateral torque on the
    spin [N m], the largest net drive torque ``J_p |W'|`` [N m], their ratio, the largest
    sample-wise ratio while driving and whether it exceeds :data:`QUESTIONABLE`."""
    net = drive.inertia * np.abs(result.acceleration)
    report: dict[str, object] = {"max_net_torque": float(net.max(initial=0.0))}
    try:
        lateral = np.abs(lateral_torque(result, unbalance, gravity))
    except ModelError as exc:
        report["lateral_torque"] = f"not computed: {exc}"
        return _with(result, report)
    top = float(net.max(initial=0.0))
    driving = net >= DRIVING * top if top > 0 else np.zeros(net.shape, dtype=bool)
    ratio = float(np.max(lateral[driving] / net[driving])) if np.any(driving) else np.inf
    worst = float(lateral.max(initial=0.0))
    report.update({
        "max_lateral_torque": worst,
        "ratio": worst / top if top > 0 else (0.0 if worst == 0 else np.inf),
        "max_ratio_while_driving": ratio if worst > 0 else 0.0,
        "questionable": bool(worst > 0 and ratio > QUESTIONABLE),
    })
    return _with(result, report)


def lateral_torque(result: TransientResult, unbalance: Sequence[tuple[int, float, float]],
                   gravity: Sequence[float] | np.ndarray) -> np.ndarray:
    """``T_lat(t)`` [N m] at the samples of ``result`` (module docstring); the unbalance
    nodes' ``ux, uy`` must have been kept."""
    t = result.t
    total = np.zeros(t.size)
    if not unbalance or t.size < 3:
        return total
    gx, gy = float(gravity[0]), float(gravity[1])
    for node, me, a in unbalance:
        cols = [result.column(int(node), dof) for dof in ("ux", "uy")]
        if result.v is not None:
            acc = np.gradient(result.v[:, cols], t, axis=0)
        else:
            acc = np.gradient(np.gradient(result.q[:, cols], t, axis=0), t, axis=0)
        angle = result.angle + float(a)
        total -= float(me) * (-(acc[:, 0] - gx) * np.sin(angle)
                              + (acc[:, 1] - gy) * np.cos(angle))
    return total


def _with(result: TransientResult, report: dict[str, object]) -> TransientResult:
    return dataclasses.replace(result, options={**result.options, "spin_feedback": report})
