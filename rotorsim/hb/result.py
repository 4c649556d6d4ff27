"""Results of :mod:`rotorsim.hb`: a solved point and a frequency response.

Both hold the Fourier coefficients of every DOF and read amplitudes through
:mod:`rotorsim.hb.measures`. A :class:`FrequencyResponse` also carries the Floquet
stability of each point, the located bifurcations, the status of the continuation and its
cost counters; :meth:`FrequencyResponse.peak` refines the largest amplitude between branch
points (:mod:`rotorsim.hb.peaks`) and :meth:`FrequencyResponse.plot` draws the curve.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import Status
from rotorsim.harmonic_balance.fourier import AFT, ComplexArray, FloatArray
from rotorsim.hb import measures


@dataclass(frozen=True, eq=False)
class Point:
    """One periodic solution.

    Attributes
    ----------
    omega : float
        Response (fundamental) frequency ``Omega`` [rad/s].
    coefficients : array (2H + 1, n)
        Fourier coefficients of every DOF [m].
    harmonics, samples : int
        ``H`` and the AFT time samples ``N``.
    residual : float
        Final scaled residual of the Newton solve.
    x : array
        Unknowns of the (condensed) residual, a start for further solves.
    stats : dict
        Cost counters of the solve.
    """

    omega: float
    coefficients: FloatArray
    harmonics: int
    samples: int
    residual: float
    x: FloatArray
    stats: dict[str, float]

    def amplitude(self, dof: int = 0, measure: str = "fundamental",
                  harmonic: int = 1) -> float:
        """Amplitude of DOF ``dof`` (:func:`~rotorsim.hb.measures.amplitude`) [m]."""
        return float(measures.amplitude(self.coefficients, dof, measure, harmonic))

    def time_response(self, samples: int = 256) -> tuple[FloatArray, FloatArray]:
        """Times ``t`` (samples,) [s] over one period and displacements (samples, n) [m]."""
        tau = 2.0 * np.pi * np.arange(samples) / samples
        return tau / self.omega, AFT(self.harmonics).basis(tau) @ self.coefficients


@dataclass(frozen=True, eq=False)
class Bifurcation:
    """A located bifurcation of a frequency response.

    Attributes
    ----------
    kind : str
        "fold", "branch_point", "period_doubling" or "neimark_sacker".
    omega : float
        [rad/s].
    coefficients : array (2H + 1, n)
        The periodic solution at the bifurcation [m].
    index : int
        Between branch points ``index`` and ``index + 1``.
    located : bool
        False when the location did not converge (the estimate is kept).
    multiplier : complex or None
        The critical Floquet multiplier (period doubling and Neimark-Sacker).
    """

    kind: str
    omega: float
    coefficients: FloatArray
    index: int
    located: bool
    multiplier: complex | None = None

    def amplitude(self, dof: int = 0, measure: str = "fundamental",
                  harmonic: int = 1) -> float:
        """Amplitude of DOF ``dof`` at the bifurcation [m]."""
        return float(measures.amplitude(self.coefficients, dof, measure, harmonic))


@dataclass(frozen=True)
class Peak:
    """Largest amplitude along a branch: ``omega`` [rad/s], ``amplitude`` [m], the branch
    point ``index`` nearest to it and ``refined`` (False: the branch point itself)."""

    omega: float
    amplitude: float
    index: int
    refined: bool


@dataclass(frozen=True, eq=False)
class FrequencyResponse:
    """A continued frequency response.

    Attributes
    ----------
    omega : array (P,)
        Response frequency at each point [rad/s].
    coefficients : array (P, 2H + 1, n)
        Fourier coefficients of every DOF at each point [m].
    harmonics, samples : int
    stable : bool array (P,) or None
        Floquet stability (None when not computed).
    multipliers : complex array (P, 2n) or None
        Floquet multipliers, largest modulus first.
    bifurcations : tuple of Bifurcation
        Located events, in branch order.
    status : Status
        OK when the branch reached ``stop`` (or ``max_points``).
    reason : str
        Why the branch ended.
    stats : dict
        ``points``, ``residual_evaluations``, ``factorizations``, ``rejected_steps``,
        ``wall_time`` [s], ``stability_time`` [s], ``bifurcation_time`` [s], ...
    stability_method : str or None
    branch : Branch
        The underlying :class:`~rotorsim.solvers.continuation.Branch` (unknowns, tangents).
    """

    omega: FloatArray
    coefficients: FloatArray
    harmonics: int
    samples: int
    stable: NDArray[np.bool_] | None
    multipliers: ComplexArray | None
    bifurcations: tuple[Bifurcation, ...]
    status: Status
    reason: str
    stats: dict[str, float]
    stability_method: str | None
    branch: Any = field(repr=False)
    _refiner: Any = field(default=None, repr=False)

    def __len__(self) -> int:
        return int(self.omega.size)

    def amplitude(self, dof: int = 0, measure: str = "fundamental",
                  harmonic: int = 1) -> FloatArray:
        """Amplitude (P,) of DOF ``dof`` at every point
        (:func:`~rotorsim.hb.measures.amplitude`) [m]."""
        return measures.amplitude(self.coefficients, dof, measure, harmonic)

    def harmonic_amplitudes(self, dof: int = 0) -> FloatArray:
        """``|X_h|`` (P, H + 1) of DOF ``dof`` [m]."""
        return measures.harmonic_amplitudes(self.coefficients, dof)

    def point(self, index: int) -> Point:
        """Branch point ``index`` as a :class:`Point`."""
        return Point(float(self.omega[index]), self.coefficients[index], self.harmonics,
                     self.samples, float(self.branch.residuals[index]),
                     self.branch.x[index], {})

    def peak(self, dof: int = 0, measure: str = "fundamental", *,
             refine: bool = True) -> Peak:
        """Largest ``measure`` of DOF ``dof``, refined between the neighbouring branch
        points by re-solving on the branch (:func:`rotorsim.hb.peaks.refine_peak`)."""
        a = self.amplitude(dof, measure)
        i = int(np.argmax(a))
        if refine and self._refiner is not None and 0 < i < len(self) - 1:
            return self._refiner(i, dof, measure)
        return Peak(float(self.omega[i]), float(a[i]), i, False)

    def events(self, kind: str) -> tuple[Bifurcation, ...]:
        """The bifurcations of one ``kind``."""
        return tuple(b for b in self.bifurcations if b.kind == kind)

    def plot(self, dof: int = 0, measure: str = "fundamental", ax: Any = None) -> Any:
        """Amplitude against frequency, unstable points dashed, bifurcations marked;
        returns the matplotlib Figure (:mod:`rotorsim.hb.figure`)."""
        from rotorsim.hb.figure import response_figure

        return response_figure(self, dof, measure, ax)
