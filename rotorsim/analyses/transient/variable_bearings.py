"""Linear bearings whose coefficients follow the spin speed, in a transient at varying speed.

A fluid-film bearing (plain or tilting-pad) is described by stiffness and damping
coefficients tabulated against speed (:class:`~rotorsim.elements.linear_bearing.BearingElement`
with ``frequency``). In a run-up or coast-down they change at every step. Their force

    r_b(q, v, t) = K_b(W(t)) q + C_b(W(t)) v

acts on the bearing DOFs only. It enters the time integrators as the problem's
``speed_terms`` (:class:`~rotorsim.time_integration.problem.SpeedTerms`): the problem stays
linear, the constant part of the iteration matrix is factorised at a few speed nodes (for
the gyroscopic term), and each step adds ``K_b``, ``C_b`` at its exact speed by a low-rank
(Woodbury) solve on the bearing DOFs (:mod:`~rotorsim.time_integration.newmark_step`).

The coefficients are interpolated linearly in speed between the table points and held at
the end values outside, as in the linear analyses. The tables of all bearings are merged
onto the union of their speed grids, on which the sum is again exactly piecewise linear, so
one interpolation per step serves all bearings.

Added mass tabulated over speed is not followed (it would multiply the acceleration in the
net force); it is refused at a varying speed unless it is constant over the table.
"""

from __future__ import annotations

import bisect
import hashlib
from collections.abc import Sequence
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from rotorsim.assembly.system import RotorSystem, bearing_matrices, relative_speed_ratio
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray
from rotorsim.elements.linear_bearing import BearingElement
from rotorsim.errors import ModelError
from rotorsim.time_integration.problem import (
    FINGERPRINT_VERSION,
    SecondOrderProblem,
    matrix_digest,
)

IntArray = NDArray[np.int64]


@dataclass(eq=False)
class SpeedDependentBearings:
    """``K_b(W)``, ``C_b(W)`` on the free DOFs ``dofs``: the ``speed_terms`` of a
    :class:`~rotorsim.time_integration.problem.SecondOrderProblem`.

    Build it with :meth:`from_system`.

    Attributes
    ----------
    n : int
        Number of unknowns of the problem.
    dofs : int array (k,)
        Free DOFs of the bearings (sorted, distinct).
    grid : array (p,)
        Union of the bearings' speed tables [rad/s], increasing.
    stiffness, damping : arrays (p, k, k)
        ``K_b`` [N/m, N m/rad] and ``C_b`` [N s/m] on ``dofs`` at the grid speeds.
    """

    n: int
    dofs: IntArray
    grid: FloatArray
    stiffness: FloatArray
    damping: FloatArray
    _last: tuple[float, FloatArray, FloatArray] | None = field(default=None, repr=False)
    _origin: FloatArray = field(init=False, repr=False)
    _slopes: FloatArray = field(init=False, repr=False)
    _pattern: NDArray[np.bool_] = field(init=False, repr=False)
    _starts: list[float] = field(init=False, repr=False)
    _breaks: list[float] = field(init=False, repr=False)

    @classmethod
    def from_system(cls, system: RotorSystem, *, check_mass: bool = True
                    ) -> SpeedDependentBearings:
        """The speed-dependent bearings of ``system`` (``system.variable_bearings``).

        Raises
        ------
        ModelError
            When ``check_mass`` and a bearing's added mass varies over its speed table.
        """
        bearings = [b for _, b in system.variable_bearings]
        full = [_element_dofs(b) for b in bearings]
        free = [system.dof_map.full_to_free[d] for d in full]
        dofs = np.unique(np.concatenate([f[f >= 0] for f in free])).astype(np.int64)
        ratios = system.node_speed_ratio
        # each table's speeds as reference speeds (a spool at ratio r reaches them at W/|r|)
        rel = [abs(relative_speed_ratio(b, ratios)) for b in bearings]
        grid = np.unique(np.concatenate([np.asarray(b.frequency, dtype=float) / r if r > 0
                                         else np.zeros(1) for b, r in zip(bearings, rel,
                                                                          strict=True)]))
        K = np.zeros((grid.size, dofs.size, dofs.size))
        C = np.zeros_like(K)
        for b, f in zip(bearings, free, strict=True):
            if check_mass:
                _check_constant_mass(b)
            keep = f >= 0
            pos = np.searchsorted(dofs, f[keep])
            cells = np.ix_(pos, pos)
            for i, s in enumerate(grid):
                mats = bearing_matrices(b, float(s), ratios)
                K[i][cells] += mats.K[np.ix_(keep, keep)]
                C[i][cells] += mats.C[np.ix_(keep, keep)]
        return cls(system.n_free, dofs, grid, K, C)

    def __post_init__(self) -> None:
        # values and slopes per segment, K and C stacked: one interpolation serves both
        # (segment 0 below the grid and segment p above it hold the end values)
        both = np.stack([self.stiffness, self.damping], axis=1)  # (p, 2, k, k)
        self._origin = np.concatenate([both[:1], both])
        slopes = np.zeros_like(self._origin)
        if self.grid.size > 1:
            slopes[1:-1] = np.diff(both, axis=0) / np.diff(self.grid)[:, None, None, None]
        self._slopes = slopes
        self._pattern = np.any(both != 0.0, axis=(0, 1))
        self._starts = [float(self.grid[0]), *(float(g) for g in self.grid)]
        self._breaks = [float(g) for g in self.grid]

    def segment(self, w: float) -> int:
        """Index of the table segment holding ``w`` [rad/s]: 0 below the grid, ``i`` for
        ``[grid[i-1], grid[i])``, ``p`` from the last grid point on."""
        return bisect.bisect_right(self._breaks, w)

    @property
    def pattern(self) -> NDArray[np.bool_]:
        """(k, k) true where ``K_b`` or ``C_b`` is not zero at some grid speed."""
        return self._pattern

    @property
    def slopes(self) -> FloatArray:
        """``dK_b/dW``, ``dC_b/dW`` per segment (p + 1, 2, k, k) [N s/m, N s^2/m]: zero
        below and above the grid."""
        return self._slopes

    def __call__(self, w: float) -> tuple[FloatArray, FloatArray]:
        """``K_b``, ``C_b`` (k, k) on ``dofs`` at spin speed ``w`` [rad/s] (the last speed's
        are kept: a step asks several times). Linear between the grid points, from the
        segment's start value and slope, held at the end values outside."""
        last = self._last
        if last is not None and last[0] == w:
            return last[1], last[2]
        i = bisect.bisect_right(self._breaks, w)
        both = self._origin[i] + (w - self._starts[i]) * self._slopes[i] \
            if 0 < i < len(self._breaks) else self._origin[i]
        K, C = both[0], both[1]
        self._last = (w, K, C)
        return K, C


def without_variable_bearings(system: RotorSystem, speed: float) -> dict[str, sp.csr_matrix]:
    """``M, C, G, K`` of ``system`` without the stiffness and damping of its
    speed-dependent bearings (their constant added mass kept), at ``speed`` [rad/s]."""
    data = {k: v.copy() for k, v in system.constant.items()}
    for group, bearing in system.variable_bearings:
        mass = bearing.matrices(speed).M
        data["M"] = data["M"] + system.pattern.scatter(group, mass[None])
    return {k: system.pattern.matrix(v) for k, v in data.items()}


def model_identity(system: RotorSystem, problem: SecondOrderProblem) -> Any:
    """What a continued run compares with the run it continues: ``problem`` itself, or,
    when ``system`` has bearings tabulated over speed, an object whose ``fingerprint``
    digests their tables and the matrices without them. A run at constant speed folds the
    bearings into its matrices at that speed and a run at varying speed does not, so the
    problems' own fingerprints would differ for the same model."""
    if not system.variable_bearings:
        return problem
    digest = hashlib.blake2b(digest_size=16)
    for matrix in without_variable_bearings(system, 0.0).values():
        digest.update(matrix_digest(matrix).to_bytes(8, "little"))
    tables = SpeedDependentBearings.from_system(system, check_mass=False)
    for array in (tables.dofs, tables.grid, tables.stiffness, tables.damping):
        digest.update(np.ascontiguousarray(array).tobytes())
    for name in ("restoring", "load"):
        digest.update(f"{name}:{getattr(problem, name) is not None}".encode())
    return SimpleNamespace(fingerprint=FINGERPRINT_VERSION + digest.hexdigest())


def _element_dofs(bearing: BearingElement) -> IntArray:
    nodes = np.asarray(bearing.nodes, dtype=np.int64)
    return (DOFS_PER_NODE * nodes[:, None] + np.arange(DOFS_PER_NODE)).reshape(-1)


def _check_constant_mass(bearing: BearingElement) -> None:
    grid = np.asarray(bearing.frequency, dtype=float)
    masses = np.stack([bearing.matrices(float(s)).M for s in grid])
    if not np.all(masses == masses[:1]):
        raise ModelError("added mass tabulated over speed is not supported at a varying "
                         "speed (it multiplies the acceleration); give constant mxx, myy, "
                         "mxy, myx or run at a constant speed", bearing.label)


def speed_range_notes(bearings: Sequence[BearingElement], w_min: float, w_max: float,
                      where: str) -> list[str]:
    """Check the speed-dependent ``bearings`` over a run's speed range [rad/s] before it
    starts, and say where their coefficients are held at the table's end values.

    Raises
    ------
    ModelError
        When the speed varies (``w_min < w_max``) and a bearing's added mass varies over
        its table (``where`` names the analysis).

    Examples
    --------
    >>> b = BearingElement(n=0, kxx=[1e7, 2e7], frequency=[100.0, 200.0], tag="DE")
    >>> print(speed_range_notes([b], 0.0, 300.0, "runup")[0])  # doctest: +NORMALIZE_WHITESPACE
    BearingElement 'DE': coefficients tabulated over 100..200 rad/s, held at the end values
    below 100 and above 200 rad/s
    """
    notes = []
    for b in bearings:
        if not b.speed_dependent:
            continue
        if w_max > w_min:
            try:
                _check_constant_mass(b)
            except ModelError as exc:
                raise ModelError(f"{exc}", where) from None
        grid = np.asarray(b.frequency, dtype=float)
        outside = [f"below {grid[0]:.6g}" if w_min < grid[0] else "",
                   f"above {grid[-1]:.6g}" if w_max > grid[-1] else ""]
        held = " and ".join(x for x in outside if x)
        if held:
            notes.append(f"{b.label}: coefficients tabulated over {grid[0]:.6g}.."
                         f"{grid[-1]:.6g} rad/s, held at the end values {held} rad/s")
    return notes
