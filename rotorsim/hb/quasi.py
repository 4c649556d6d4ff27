"""Quasi-periodic responses of a :class:`~rotorsim.hb.system.System` forced at two
incommensurate frequencies (``rs.hb.solve_quasi``).

Two forcings ``cos(w1 t)`` and ``cos(w2 t)`` with ``w2 / w1`` irrational give a response
on a 2-torus: the tones ``k1 w1 + k2 w2``. The System's own forcing counts as harmonics of
``w1`` (``k = (h, 0)``); :class:`ToneForcing` adds tones of any ``(k1, k2)``::

    import rotorsim as rs
    chain = rs.hb.System(mass=[[1, 0], [0, 1]], stiffness=[[2, -1], [-1, 2]],
                         damping=[[0.1, -0.04], [-0.04, 0.1]],
                         elements=[rs.hb.CubicSpring(0, k3=0.5)])
    x = rs.hb.solve_quasi(chain, 1.1, 1.6, forcing=[rs.hb.ToneForcing(0, 0.12, (1, 0)),
                                                    rs.hb.ToneForcing(1, 0.1, (0, 1))])
    x.amplitude(0, 2, -1)      # the combination tone 2 w1 - w2 of DOF 0

The solver is :mod:`rotorsim.harmonic_balance.quasi` (2-D AFT, exact condensation onto the
elements' DOFs, Newton); the result is a
:class:`~rotorsim.harmonic_balance.quasi.QuasiSolution`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rotorsim.errors import ModelError
from rotorsim.harmonic_balance.quasi import (
    QuasiProblem,
    QuasiSolution,
    TorusAFT,
    TorusHarmonics,
)
from rotorsim.harmonic_balance.quasi import (
    solve_quasi as _solve,
)
from rotorsim.hb.system import System

WHERE = "hb.solve_quasi"


@dataclass(frozen=True)
class ToneForcing:
    """Force ``amplitude cos(k1 w1 t + k2 w2 t + phase)`` [N] on one DOF.

    Examples
    --------
    >>> ToneForcing(0, 2.0, (0, 1)).k
    (0, 1)
    """

    dof: int
    amplitude: float
    k: tuple[int, int] = (1, 0)
    phase: float = 0.0

    def __post_init__(self) -> None:
        k = tuple(self.k)
        if len(k) != 2 or not all(isinstance(v, int | np.integer) and not isinstance(v, bool)
                                  for v in k):
            raise ModelError(f"k must be two integers (k1, k2), got {self.k!r}", "ToneForcing")
        if not (math.isfinite(self.amplitude) and math.isfinite(self.phase)):
            raise ModelError("amplitude and phase must be finite", "ToneForcing")
        object.__setattr__(self, "k", (int(k[0]), int(k[1])))


def solve_quasi(system: System, w1: float, w2: float, *,
                forcing: Sequence[ToneForcing] = (), harmonics: int | tuple[int, int] = 7,
                truncation: str = "diamond", samples: tuple[int, int] | None = None,
                tol: float = 1e-10) -> QuasiSolution:
    """The quasi-periodic response of ``system`` at base frequencies ``w1, w2`` [rad/s].

    Parameters
    ----------
    system : System
        Its forcing acts as harmonics of ``w1``; the gyroscopic spin is
        ``spin + spin_ratio w1``.
    forcing : sequence of ToneForcing
        Further tones.
    harmonics : int or (int, int)
        Diamond order ``H`` (``|k1| + |k2| <= H``), or box sizes ``(H1, H2)`` with
        ``truncation="box"``.
    truncation : {"diamond", "box"}
    samples : (int, int), optional
        Torus grid (default: :meth:`TorusHarmonics.default_samples`).
    tol : float
        Newton tolerance, relative to the condensed load.

    Raises
    ------
    ModelError
        An unknown truncation, harmonics of the wrong form, a forcing tone outside the
        harmonic set or on a DOF the system does not have.
    """
    torus = _harmonics(harmonics, truncation)
    aft = TorusAFT(torus, samples)
    P = np.zeros((torus.rows, system.n))
    tones = [ToneForcing(f.dof, f.amplitude, (f.harmonic, 0), f.phase)
             for f in system.forcing] + list(forcing)
    for i, tone in enumerate(tones):
        if not isinstance(tone, ToneForcing):
            raise ModelError(f"expected ToneForcing, got {type(tone).__name__}",
                             f"{WHERE}.forcing[{i}]")
        if isinstance(tone.dof, bool) or not 0 <= int(tone.dof) < system.n:
            raise ModelError(f"DOF {tone.dof!r} is outside [0, {system.n})",
                             f"{WHERE}.forcing[{i}]")
        if tone.k == (0, 0):
            P[0, tone.dof] += tone.amplitude * math.cos(tone.phase)
            continue
        try:
            j = torus.index(*tone.k)
        except ModelError:
            raise ModelError(f"tone {tone.k} is not in the harmonic set "
                             f"({torus.truncation}, {harmonics})", f"{WHERE}.forcing[{i}]"
                             ) from None
        sign = 1.0 if tuple(torus.k[j]) == tone.k else -1.0  # cos(-x + p) = cos(x - p)
        P[1 + 2 * j, tone.dof] += tone.amplitude * math.cos(tone.phase)
        P[2 + 2 * j, tone.dof] -= sign * tone.amplitude * math.sin(tone.phase)
    problem = QuasiProblem(system.mass, system.damping if system.damping is not None
                           else 0.0 * system.mass, system.stiffness, system.gyroscopic,
                           nl_dofs=system.nl_dofs, force=_force(system) if system.elements
                           else None, excitation=P, spin=system.spin,
                           spin_ratio=system.spin_ratio)
    return _solve(problem, aft, w1, w2, tol=tol)


def _harmonics(harmonics: int | tuple[int, int], truncation: str) -> TorusHarmonics:
    if truncation == "diamond":
        if isinstance(harmonics, tuple):
            raise ModelError("a diamond truncation takes one order H", f"{WHERE}.harmonics")
        return TorusHarmonics.diamond(harmonics)
    if truncation == "box":
        if not (isinstance(harmonics, tuple) and len(harmonics) == 2):
            raise ModelError("a box truncation takes (H1, H2)", f"{WHERE}.harmonics")
        return TorusHarmonics.box(*harmonics)
    raise ModelError(f"must be 'diamond' or 'box', got {truncation!r}", f"{WHERE}.truncation")


def _force(system: System):
    """The System's element forces as a torus force (autonomous: no angle dependence)."""
    def force(q, v, theta1, theta2):
        return system._force(q, v, theta1, 0.0, 0.0)
    return force
