"""The final state of a rotor transient: what a continued run starts from.

:class:`TransientState` holds the displacements, velocities and accelerations of ALL free
DOFs at the end of a run (expanded to physical DOFs after a Craig-Bampton reduction), the
shaft angle and speed there, and the stepper's own :class:`~rotorsim.time_integration.base.
State` in the coordinates it integrated (reduced ones after a reduction), with the
multistep history of the Adams method, so that ``rs.transient(..., initial=previous)``
continues the run as if it had never stopped. It is written to HDF5 with its result.

Also here: :func:`radial_pairs`, the ``(ux, uy)`` pairs of kept DOFs whose radial amplitude
``sqrt(ux^2 + uy^2)`` the ``max_amplitude`` reducer reports.

Examples
--------
>>> radial_pairs(np.array([0, 1, 2, 6, 7, 13])).nodes.tolist()
[0, 1]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from rotorsim.time_integration.base import State

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class TransientState:
    """Final full state of a transient run (``TransientResult.final``).

    Attributes
    ----------
    t : float
        Time [s].
    q, v, a : arrays (n_free,)
        Displacements [m, rad], velocities [m/s, rad/s] and accelerations [m/s^2, rad/s^2]
        of all free DOFs (``dof_map.free`` of the result), physical also after a reduction.
        For the alpha methods ``a`` is the method's algorithmic acceleration.
    angle, speed : float
        Shaft angle phi [rad] and spin speed W [rad/s] at ``t``.
    method : str
        Stepper name.
    dt : float
        Step size of the run [s] (the next trial step of an adaptive one).
    problem : str
        Fingerprint of the integrated problem (matrices and callbacks present): a
        continuation on another model is refused.
    reduction : int
        Size of the reduced basis the stepper integrated in (0 without reduction).
    reduction_speed : float
        Speed at which that basis was built [rad/s] (a continuation builds it there again).
    stepper : State
        The stepper's state in its own coordinates (counters and factorisation cache
        dropped), restored as it is by a continuation.
    """

    t: float
    q: FloatArray
    v: FloatArray
    a: FloatArray
    angle: float
    speed: float
    method: str
    dt: float
    problem: str
    reduction: int
    reduction_speed: float
    stepper: State


class RadialPairs(NamedTuple):
    """Nodes with both ``ux`` and ``uy`` kept, and the columns of those DOFs."""

    nodes: IntArray
    x: IntArray
    y: IntArray


def radial_pairs(dofs: IntArray) -> RadialPairs:
    """The ``(ux, uy)`` pairs among kept global DOFs ``dofs`` (``6 * node + local``).

    Parameters
    ----------
    dofs : int array (m,)
        Kept global DOF indices, in column order.

    Returns
    -------
    RadialPairs
        ``nodes`` (p,) in increasing order, and the columns ``x``, ``y`` (p,) of their ux
        and uy in ``dofs``.
    """
    dofs = np.asarray(dofs, dtype=np.int64)
    column = {int(d): i for i, d in enumerate(dofs)}
    nodes = np.array(sorted(int(d) // 6 for d in dofs if d % 6 == 0 and int(d) + 1 in column),
                     dtype=np.int64)
    x = np.array([column[6 * int(n)] for n in nodes], dtype=np.int64)
    y = np.array([column[6 * int(n) + 1] for n in nodes], dtype=np.int64)
    return RadialPairs(nodes, x, y)
