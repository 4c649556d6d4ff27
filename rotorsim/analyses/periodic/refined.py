"""Branch points corrected on a finer discretisation: the check behind "stable against the
sampling" (:mod:`.confirm`).

:class:`SamplingCheck` corrects the points that bracket a candidate event again with
:data:`REFINE` times the AFT samples (and, for a reduced Floquet model, :data:`REFINE` times
the fixed-interface modes), optionally with more harmonics as well, and tells whether the
candidate's test function still changes between them. More harmonics: the coarse unknowns
are padded with zero coefficients of the added harmonics (the unknowns are stored harmonic
by harmonic, the constant first), and their scales with those of the highest coarse
harmonic.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rotorsim.analyses.periodic.crossings import KIND_INDEX, real_unstable
from rotorsim.analyses.periodic.events import unstable_counts
from rotorsim.analyses.periodic.stability import StabilityModel, stability_model
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ConvergenceError, ModelError
from rotorsim.harmonic_balance.residual import HBResidual, continuation_function
from rotorsim.solvers.continuation import Branch
from rotorsim.solvers.continuation_core import (
    CorrectorOptions,
    ScaledSystem,
    Tangent,
    correct,
    tangent,
)
from rotorsim.solvers.stats import Stats

REFINE = 2
"""Sampling factor of the confirmation grid (``N -> REFINE N``)."""

HOLD_SLOPE = 0.5
"""A branch point is corrected on the finer grid at its own parameter (every Newton
iteration at one ``omega``: one condensation) when the parameter component of its tangent
is at least this fraction of the largest one of its neighbours (no fold next to it, where
``dR/dx`` is singular); otherwise, or if that fails, on its tangent's normal hyperplane."""

MAX_ITER = 6
"""Newton iterations of a fine-grid correction (from a converged coarse point)."""

HARMONIC_ITER = 20
"""Newton iterations of a correction with more harmonics: their coefficients start at 0
(the axial pitchforks of ``models/clearance_rotor.toml``, ``H = 8 -> 12``, converge in 5-10;
the orbits next to its contact onsets that ``H = 12`` does not reproduce fail in 20 and in
50 iterations alike, docs/validation.md case 26)."""


@dataclass
class _FinePoint:
    """A branch point corrected on the fine grid: tangent, and multipliers (computed
    when a candidate first asks; None where Floquet fails)."""

    tangent: Tangent | None
    x: FloatArray
    lam: float
    model: StabilityModel | None
    _mu: tuple[Any] | None = None

    @property
    def multipliers(self) -> Any:
        if self._mu is None:
            self._mu = (self._floquet(),)
        return self._mu[0]

    @property
    def counts(self) -> tuple[int, int] | None:
        mu = self.multipliers
        return None if mu is None else unstable_counts(mu, self.model.tol)  # type: ignore[union-attr]

    def _floquet(self) -> Any:
        if self.model is None:
            return None
        try:
            return self.model.floquet(self.x, self.lam).multipliers
        except (ModelError, ConvergenceError, np.linalg.LinAlgError):
            return None


@dataclass
class SamplingCheck:
    """Re-evaluates points of a branch on a grid of ``REFINE`` times the samples, and with
    ``harmonics`` harmonics when given (module docstring).

    Parameters
    ----------
    residual : HBResidual
        The residual the branch was traced with.
    branch : Branch
    model : StabilityModel, optional
        The branch's Floquet model; its method and reduction are kept on the fine grid.
    harmonics : int, optional
        Harmonics of the finer discretisation (default: the branch's).
    max_iter : int
        Newton iterations of a correction.
    """

    residual: HBResidual
    branch: Branch
    model: StabilityModel | None
    harmonics: int | None = None
    max_iter: int = MAX_ITER
    stats: Stats = field(default_factory=Stats)
    _points: dict[int, _FinePoint | None] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.fine = self.residual.with_discretization(
            harmonics=self.harmonics, samples=REFINE * self.residual.samples)
        b = self.branch
        self.system = ScaledSystem(continuation_function(self.fine, "omega", terms=True),
                                   self._pad(b.x_scale, scale=True),
                                   self._pad(b.r_scale, scale=True), b.lam_scale)
        self.what = (f"{REFINE} times the samples" if self.harmonics is None else
                     f"{self.fine.harmonics} harmonics and {REFINE} times the samples")
        self.corrector = CorrectorOptions(b.options.tol, min(self.max_iter, b.options.max_iter),
                                          b.options.max_backtracks,
                                          stall_tol=b.options.stall_tol)
        self.fine_model = None
        if self.model is not None:
            m = self.model
            if m.residual is m.main or m.modes < 0:
                self.fine_model = StabilityModel(self.fine, self.fine, m.method, m.modes, m.tol)
            else:  # a reduced Floquet model: twice the fixed-interface modes as well
                self.fine_model = stability_model(
                    self.fine, m.method, modes=REFINE * m.modes, tol=m.tol,
                    omega_max=float(np.max(self.branch.lam)))

    def confirms(self, candidate: Any, coarse: np.ndarray | None) -> str:
        """"" when ``candidate`` survives the fine grid, else the reason it does not
        (``coarse``: the branch's multipliers (P, r), for the direction of a count
        change). A fold must turn the finer branch too (the parameter component of the
        finer tangent changes sign). The fine grid may move an event across a bracket
        point: the change is also sought between the neighbours ``i - 1`` and ``j + 1``
        (with more harmonics only when both bracket points converged: an orbit that the
        finer truncation does not reproduce is not resolved, whatever its neighbours)."""
        last = len(self.branch) - 1
        reason = ""
        for i, j in ((candidate.i, candidate.j),
                     (max(candidate.i - 1, 0), min(candidate.j + 1, last))):
            reason = self._changes(candidate, i, j, coarse)
            if not reason or (self.harmonics is not None
                              and reason.startswith("a bracket point does not converge")):
                return reason
        return reason

    def _changes(self, candidate: Any, i: int, j: int,
                 coarse: np.ndarray | None) -> str:
        """"" when the fine test changes between points ``i`` and ``j`` as the coarse
        one does across ``candidate``."""
        lo, hi = self._point(i), self._point(j)
        if lo is None or hi is None:
            return f"a bracket point does not converge with {self.what}"
        if candidate.kind in ("branch_point", "fold"):
            if lo.tangent is None or hi.tangent is None:
                return f"no tangent with {self.what}"
            if candidate.kind == "fold":   # the finer branch turns between them too
                changed = lo.tangent.t[-1] * hi.tangent.t[-1] < 0
            else:
                changed = lo.tangent.det_sign * hi.tangent.det_sign < 0
                if changed and self.model is not None:   # a real multiplier crosses +1
                    if lo.multipliers is None or hi.multipliers is None:
                        return f"no multipliers with {self.what}"
                    tol = self.model.tol
                    changed = real_unstable(lo.multipliers, tol) != real_unstable(
                        hi.multipliers, tol)
        else:
            if lo.counts is None or hi.counts is None or coarse is None \
                    or self.model is None:
                return f"no multipliers with {self.what}"
            c = KIND_INDEX[candidate.kind]
            step = (unstable_counts(coarse[candidate.j], self.model.tol)[c]
                    - unstable_counts(coarse[candidate.i], self.model.tol)[c])
            changed = (hi.counts[c] - lo.counts[c]) * step > 0
        if changed:
            return ""
        return f"the sign change disappears with {self.what}"

    def _point(self, i: int) -> _FinePoint | None:
        if i not in self._points:
            self._points[i] = self._correct(i)
        return self._points[i]

    def _correct(self, i: int) -> _FinePoint | None:
        b = self.branch
        y0 = self.system.to_y(self._pad(b.x[i]), float(b.lam[i]))
        border = np.append(self._pad(b.tangents[i][:-1]), b.tangents[i][-1])
        corr = None
        if abs(border[-1]) >= HOLD_SLOPE * _steepest(b.tangents, i):
            # at the point's own parameter: one condensation for the whole correction
            e_lam = np.zeros(y0.size)
            e_lam[-1] = 1.0
            corr = correct(self.system, y0, e_lam, float(y0[-1]), self.corrector,
                           self.stats, hold_parameter=True)
        if corr is None or (self.harmonics is None and not (
                corr.converged and corr.evaluation is not None)):
            # on the hyperplane through the point normal to its tangent: well posed at
            # folds. (With more harmonics a point whose correction at its own speed, well
            # posed away from folds, fails is not tried again: an orbit the finer
            # truncation does not reproduce there is not resolved.)
            corr = correct(self.system, y0, border, float(border @ y0), self.corrector,
                           self.stats)
        if not corr.converged or corr.evaluation is None:
            return None
        tan = tangent(corr.evaluation, border, self.stats)
        x, lam = self.system.from_y(corr.y)
        return _FinePoint(tan, x, lam, self.fine_model)


    def _pad(self, v: FloatArray, scale: bool = False) -> FloatArray:
        """Unknowns (or their scales) of the branch on the finer discretisation: the added
        harmonics' coefficients are 0 (scales: those of the highest coarse harmonic)."""
        rows, fine_rows = self.residual.aft.rows, self.fine.aft.rows
        if fine_rows == rows:
            return v
        V = np.asarray(v, dtype=float).reshape(rows, -1)
        extra = np.resize(V[-2:], (fine_rows - rows, V.shape[1])) if scale else \
            np.zeros((fine_rows - rows, V.shape[1]))
        return np.vstack((V, extra)).reshape(-1)


def _steepest(tangents: FloatArray, i: int) -> float:
    """Largest ``|t_lam|`` among point ``i`` and its neighbours."""
    return float(np.max(np.abs(tangents[max(i - 1, 0): i + 2, -1])))
