"""Speed terms folded into the iteration matrix at a speed node (run-ups of linear problems
whose bearings are tabulated over speed).

A run-up factorises the Newmark iteration matrix at a few speed nodes ``W_0``
(:mod:`~rotorsim.time_integration.newmark_step`). The speed terms ``K_s(W)``, ``C_s(W)`` of
bearings tabulated over speed
(:class:`~rotorsim.analyses.transient.variable_bearings.SpeedDependentBearings`) are
piecewise linear in ``W``. They are folded into the node's matrix at ``W_0``,

    S_0 = c_M M + c_C (C + W_0 G + P C_s(W_0) P^T) + c_K (K + P K_s(W_0) P^T),

and their change since the node is left to the frozen iteration with the gyroscopic term:
the iteration error of a step at ``W`` obeys ``e_{k+1} = -S_0^-1 dS e_k`` with

    dS = c_C (W - W_0) G + P D P^T,   D = c_C (C_s(W) - C_s(W_0)) + c_K (K_s(W) - K_s(W_0)),

``P`` the columns of the identity at the bearing DOFs. The tables' part contracts by
``rho(D Z_d)``, ``Z_d = P^T S_0^-1 P``; on a table segment with slopes ``dK_s/dW``,
``dC_s/dW`` it is bounded by ``|W - W_0| ||(c_C dC_s/dW + c_K dK_s/dW) Z_d||_inf`` (a norm
bounds the spectral radius; over several segments, by their largest rate).
:class:`FoldedTables` holds these rates per segment, computed once per node from ``k``
solves with the node's factors, so no low-rank update is rebuilt per step.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class PiecewiseLinearTerms(Protocol):
    """Speed terms that are linear in the speed between break points (tables)."""

    @property
    def dofs(self) -> IntArray:
        """Distinct indices (k,) of the unknowns they act on."""
        ...

    @property
    def slopes(self) -> FloatArray:
        """``dK_s/dW``, ``dC_s/dW`` per segment (p + 1, 2, k, k)."""
        ...

    @property
    def pattern(self) -> NDArray[np.bool_]:
        """(k, k) true where ``K_s`` or ``C_s`` is not zero at some speed."""
        ...

    @property
    def grid(self) -> FloatArray:
        """Break points (p,) [rad/s], increasing: segment ``i`` is ``[grid[i-1],
        grid[i])``, segment 0 below ``grid[0]``, segment ``p`` from ``grid[-1]`` on."""
        ...

    def segment(self, w: float, /) -> int:
        """Index of the segment holding the speed ``w`` [rad/s]."""
        ...

    def __call__(self, w: float, /) -> tuple[FloatArray, FloatArray]:
        """``K_s(w)``, ``C_s(w)`` (k, k) on ``dofs``."""
        ...


def piecewise_linear(terms: Any) -> PiecewiseLinearTerms | None:
    """``terms`` when it tells its segments and slopes (tables), else None (the steppers
    then add the speed terms at each step's exact speed by a low-rank update)."""
    if terms is None or not callable(getattr(terms, "segment", None)):
        return None
    return terms


@dataclass(frozen=True, eq=False)
class WeightedSlopes:
    """``c_C dC_s/dW + c_K dK_s/dW`` per segment (p + 1, k, k) [kg s], and the same on the
    rows and columns ``active`` where the tables are not zero (p + 1, a, a): what the nodes
    of one step size share."""

    c_K: float
    c_C: float
    full: FloatArray
    active: IntArray
    reduced: FloatArray

    @classmethod
    def of(cls, terms: PiecewiseLinearTerms, c_K: float, c_C: float) -> WeightedSlopes:
        slopes = terms.slopes
        full = c_C * slopes[:, 1] + c_K * slopes[:, 0]
        nonzero = slopes != 0.0
        active = np.flatnonzero(np.any(nonzero, axis=(0, 1, 2)) | np.any(nonzero, axis=(0, 1, 3)))
        return cls(c_K, c_C, full, active, full[:, active][:, :, active])


@dataclass(frozen=True, eq=False)
class FoldedTables:
    """The speed terms at the node ``node`` [rad/s] with the iteration matrix's weights
    ``c_K``, ``c_C`` (module docstring).

    Attributes
    ----------
    block : array (k, k)
        ``c_C C_s(W_0) + c_K K_s(W_0)``, the part of ``S_0`` on ``terms.dofs`` [kg].
    rates : array (p + 1,)
        Contraction per unit speed difference on each table segment [s/rad] (filled by
        :meth:`with_rates` once the node is factorised).
    """

    terms: PiecewiseLinearTerms
    node: float
    slopes: WeightedSlopes
    block: FloatArray
    segment: int
    rates: FloatArray
    bounds: tuple[float, float]
    """Speeds [rad/s] between which ``segment`` lies, ``[lower, upper)``."""

    @classmethod
    def at_node(cls, terms: PiecewiseLinearTerms, node: float, c_K: float, c_C: float,
                previous: FoldedTables | None = None) -> FoldedTables:
        """The tables at ``node`` (their rates still unknown: NaN); ``previous`` lends its
        slopes when built with the same weights."""
        slopes = previous.slopes if previous is not None and previous.terms is terms and \
            (previous.slopes.c_K, previous.slopes.c_C) == (c_K, c_C) \
            else WeightedSlopes.of(terms, c_K, c_C)
        K, C = terms(node)
        i, grid = terms.segment(node), terms.grid
        bounds = (float(grid[i - 1]) if i > 0 else -math.inf,
                  float(grid[i]) if i < grid.size else math.inf)
        return cls(terms, node, slopes, c_C * C + c_K * K, i,
                   np.full(terms.slopes.shape[0], np.nan), bounds)

    def with_rates(self, lu: Any) -> FoldedTables:
        """With the rates from the node's factors ``lu`` (``lu.n``, ``lu.solve``):
        ``||(c_C dC_s/dW + c_K dK_s/dW) Z_d||_inf`` per segment, on the rows and columns
        where the tables are not zero."""
        active = self.slopes.active
        if active.size == 0:
            return dataclasses.replace(self, rates=np.zeros(self.rates.size))
        dofs = self.terms.dofs[active]
        P = np.zeros((int(lu.n), active.size))
        P[dofs, np.arange(active.size)] = 1.0
        Zd = np.asarray(lu.solve(P))[dofs]
        return dataclasses.replace(
            self, rates=np.abs(self.slopes.reduced @ Zd).sum(axis=2).max(axis=1))

    def rate(self, w: float, start: float | None = None) -> float:
        """Contraction per unit speed difference between ``start`` (default: the node) and
        ``w`` [s/rad]: the largest rate of the segments between them."""
        j = self.segment if start is None or start == self.node else self.terms.segment(start)
        if j == self.segment and self.bounds[0] <= w < self.bounds[1]:
            return float(self.rates[j])
        i = self.terms.segment(w)
        return float(self.rates[i] if i == j else self.rates[min(i, j):max(i, j) + 1].max())

    def slope(self, segment: int) -> FloatArray:
        """``c_C dC_s/dW + c_K dK_s/dW`` (k, k) on the table segment ``segment`` [kg s]."""
        return np.asarray(self.slopes.full[segment])

    def frozen(self, w: float, da: FloatArray) -> FloatArray:
        """``D da[dofs]`` (k,): the tables' part of the residual left by the correction
        ``da`` with the matrix frozen at the node, at the step's speed ``w`` [N]."""
        K, C = self.terms(w)
        D = self.slopes.c_C * C + self.slopes.c_K * K - self.block
        return np.asarray(D @ da[self.terms.dofs])
