"""The factors of the iteration matrix at a speed node, and how far they reach.

A run-up factorises the Newmark iteration matrix at a few speed nodes and iterates with it
in between (:mod:`~rotorsim.time_integration.newmark_step`). :class:`FactorCache` holds
the factors of one node with what the frozen iteration needs: the contraction per unit speed
of the gyroscopic term (:func:`gyroscopic_sensitivity`) and, for bearings tabulated over
speed, the tables folded into the node's matrix
(:class:`~rotorsim.time_integration.folded_tables.FoldedTables`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from rotorsim.solvers.linear import Factorization
from rotorsim.time_integration.banded_lu import BandedLU
from rotorsim.time_integration.base import FloatArray, IntArray
from rotorsim.time_integration.folded_tables import FoldedTables
from rotorsim.time_integration.local_tangent import BaseFactors, LowRankSolve
from rotorsim.time_integration.merged_matrices import MergedMatrices
from rotorsim.time_integration.problem import Matrix, SecondOrderProblem

FOLDED = -3
"""``FactorCache.tangent`` of factors with the speed terms folded in at their node."""
FOLD_MIN_STEPS = 20
"""Tables are folded into a speed node that serves at least this many steps. A folded node
costs its factorisation, the tables' contraction rates and the frozen map (about 0.4 ms at
150 unknowns); the exact alternative, a low-rank update rebuilt at every step, costs about
30 us per step more. Folding pays from about 15 steps on."""
FROZEN_MAP_LIMIT = 400
"""Largest dense problem for which :meth:`FactorCache.frozen_map` is formed (its ``n^2``
entries cost what a dense ``G`` costs)."""
POWER_ITERATIONS = 8
"""Power iterations of :func:`gyroscopic_sensitivity` (the estimate only sets how far a
factorisation is reused: the converged step does not depend on it)."""
SENSITIVITY_SAFETY = 2.0
"""Factor on the power-iteration estimate of ``rho(S_0^-1 G)`` (which it approaches from
below)."""


@dataclass(eq=False)
class FactorCache:
    """The iteration matrix's factors, and for local tangents those of its constant part.

    ``spin`` is the speed node at which they were built; ``kappa`` (filled on first use off
    the node) is the contraction per unit speed difference, ``(1 - alpha_f) gamma h
    rho(S_0^-1 G)`` [s/rad].
    """

    dt: float
    spin: float
    tangent: int
    lu: Factorization | BandedLU | LowRankSolve
    base: BaseFactors | None = None
    kappa: float = math.nan
    merged: MergedMatrices | None = None
    """``M``, ``C``, ``G``, ``K`` on one pattern (for building the next node)."""
    problem: SecondOrderProblem | None = None
    """The problem whose matrices ``merged`` holds."""
    tables: FoldedTables | None = None
    """Speed terms folded into ``lu`` at ``spin`` (linear problems with tables)."""
    mapped: bool = False
    map: tuple[IntArray, FloatArray] | None = None
    """The frozen map (:meth:`frozen_map`) once ``mapped``."""
    last: tuple[float, float] = (math.nan, math.nan)
    """Time [s] and speed [rad/s] of the last step that used these factors."""
    peak: int = 0
    """The DOF where ``|q|`` last peaked when the Newton tolerance's floor was computed."""

    def frozen_map(self, problem: SecondOrderProblem, weight: float, gdt: float,
                   spin: float) -> tuple[IntArray, FloatArray] | None:
        """``R = S_0^-1 dS / (s - s_0)`` for the speed ``spin`` [rad/s] as its nonzero
        columns ``(cols, R[:, cols])``, or None.

        With the matrix frozen at the node ``s_0``, the next correction of a linear step is
        ``-S_0^-1 dS da = -(s - s_0) R da``: ``dS = (s - s_0) (w gamma h G + P dB P^T)``
        with ``dB`` the folded tables' slope on the segment holding both ``s`` and ``s_0``
        (``w = 1 - alpha_f``, ``gdt = gamma h``). One product with ``R`` replaces the
        product with ``G``, the tables' part and a solve. Built once per node from a solve
        per nonzero column, for dense problems of at most :data:`FROZEN_MAP_LIMIT` unknowns
        (``G`` dense, so a product with ``R`` costs what the one with ``G`` did); None for
        others, and when ``spin`` is not on the node's table segment.
        """
        if self.tables is not None and \
                not self.tables.bounds[0] <= spin < self.tables.bounds[1]:
            return None
        if not self.mapped:
            self.mapped, self.map = True, self._frozen_map(problem, weight * gdt)
        return self.map

    def _frozen_map(self, problem: SecondOrderProblem,
                    weight: float) -> tuple[IntArray, FloatArray] | None:
        G, n = problem.gyroscopic, problem.n
        if n > FROZEN_MAP_LIMIT or sp.issparse(G) or self.base is not None:
            return None
        H = np.zeros((n, n)) if G is None else weight * np.asarray(G)
        if self.tables is not None:
            H[np.ix_(self.tables.terms.dofs, self.tables.terms.dofs)] += \
                self.tables.slope(self.tables.segment)
        cols = np.flatnonzero(np.any(H != 0.0, axis=0))
        return cols, np.asarray(self.lu.solve(H[:, cols])).reshape(n, cols.size)

    def base_matches(self, dt: float, spin: float, dofs: IntArray | None) -> bool:
        """True when the cached constant part was built for ``dt``, ``spin`` and ``dofs``."""
        return (self.base is not None and dofs is not None
                and (self.dt, self.spin) == (dt, spin) and np.array_equal(self.base.dofs, dofs))


def gyroscopic_sensitivity(lu: Factorization | BandedLU | LowRankSolve, G: Matrix,
                           n: int) -> float:
    """Estimate of the spectral radius ``rho(S_0^-1 G)`` [1], from above.

    ``POWER_ITERATIONS`` power iterations from a fixed pseudo-random start; the largest of
    the last three growth ratios (a dominant complex pair makes them oscillate) times
    ``SENSITIVITY_SAFETY``.
    """
    x = np.random.default_rng(14).standard_normal(n)
    x /= np.linalg.norm(x)
    ratios = []
    for _ in range(POWER_ITERATIONS):
        y = np.asarray(lu.solve(G @ x), dtype=float)
        r = float(np.linalg.norm(y))
        if not (math.isfinite(r) and r > 0.0):
            return 0.0 if r == 0.0 else math.inf
        ratios.append(r)
        x = y / r
    return SENSITIVITY_SAFETY * max(ratios[-3:])


def node_rate(c: FactorCache, a: float, b: float) -> float:
    """Predicted contraction per unit speed difference between ``a`` and ``b`` [s/rad] of
    the factors ``c``: the gyroscopic term's plus the folded tables' on the segments
    between."""
    return c.kappa if c.tables is None else c.kappa + c.tables.rate(b, a)


def new_node(kappa: float, tables: FoldedTables | None, spin: float, previous: float,
             max_contraction: float) -> tuple[float, float, bool]:
    """A new speed node for the step at ``spin`` (the last step's speed ``previous``):
    ``(node, theta, fold)``.

    While the speed moves by less than ``reach = max_contraction / rate`` per step, the
    node lies ``reach`` ahead of ``spin`` in the direction the speed moves, so that it
    serves the steps on both sides of it (about twice as many as a node at ``spin``).
    Otherwise (fast changes, or a speed that has stopped moving, where the steps that follow
    need no correction) it is ``spin``. ``rate`` is the gyroscopic term's ``kappa``, plus
    the tables' (``tables``: their rates near the old node) when they are folded into the
    node, which they are when it would serve at least :data:`FOLD_MIN_STEPS` steps (else
    they are added exactly at each step). ``theta`` is the predicted contraction at
    ``spin``.
    """
    change = spin - previous
    if change == 0.0:
        return spin, 0.0, True
    rate, fold = kappa, tables is not None
    if tables is not None:
        fold_rate = kappa + tables.rate(spin, spin)
        if fold_rate > 0.0:  # with the segments up to the node
            ahead = spin + math.copysign(max_contraction / fold_rate, change)
            fold_rate = kappa + tables.rate(ahead, spin)
        fold = 2.0 * max_contraction >= FOLD_MIN_STEPS * fold_rate * abs(change)
        rate = fold_rate if fold else kappa
    if not (math.isfinite(rate) and rate > 0.0):
        return spin, 0.0, fold
    reach = max_contraction / rate
    if abs(change) > reach:
        return spin, 0.0, fold
    return spin + math.copysign(reach, change), max_contraction, fold
