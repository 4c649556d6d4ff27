"""Result of a periodic-response (harmonic balance + continuation) analysis of a rotor."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap
from rotorsim.errors import ModelError, Status
from rotorsim.results.dof_access import KeptDofs

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
ComplexArray = NDArray[np.complex128]

MEASURES = ("max", "peak_to_peak", "half_peak_to_peak", "mean")
"""Amplitude measures of :meth:`PeriodicResult.amplitude`."""


def branch_measure(result: Any, column: int, measure: str) -> FloatArray:
    """``measure`` of the kept DOF ``column`` at every point of a branch with ``max_abs``,
    ``peak_to_peak`` and ``coefficients`` (row 0 the mean): "max", "peak_to_peak",
    "half_peak_to_peak" or "mean"."""
    if measure == "max":
        return np.asarray(result.max_abs[:, column])
    if measure == "peak_to_peak":
        return np.asarray(result.peak_to_peak[:, column])
    if measure == "half_peak_to_peak":
        return 0.5 * np.asarray(result.peak_to_peak[:, column])
    if measure == "mean":
        return np.asarray(result.coefficients[:, 0, column])
    raise TypeError(f"unknown measure {measure!r}; valid: {', '.join(MEASURES)}")


@dataclass(frozen=True, eq=False)
class PeriodicBifurcation:
    """A bifurcation located on a periodic branch.

    Attributes
    ----------
    kind : str
        "fold", "branch_point", "period_doubling" or "neimark_sacker".
    parameter : float
        Parameter value at the bifurcation (the branch's units).
    index : int
        It lies between branch points ``index`` and ``index + 1``.
    located : bool
        True when located to tolerance (folds: extended system converged).
    method : str
        "extended_system" or "test_function".
    multiplier : complex
        The critical Floquet multiplier there (NaN for folds and branch points located
        without multipliers).
    max_abs, peak_to_peak : arrays (m,)
        Amplitude measures of the kept DOFs at the bifurcation [m, rad] (plot markers).
    """

    kind: str
    parameter: float
    index: int
    located: bool
    method: str
    multiplier: complex
    max_abs: FloatArray
    peak_to_peak: FloatArray


@dataclass(frozen=True, eq=False)
class PeriodicPeak:
    """An amplitude extremum located on a periodic branch (``periodic(..., peaks=...)``).

    Attributes
    ----------
    node : int
    dof : str
        "ux" ... "rz" (``max |q(t)|`` of that DOF), or "orbit" (largest radius of the
        node's ``(ux, uy)`` orbit).
    kind : str
        "max" (a peak) or "min".
    parameter : float
        Parameter at the extremum [rad/s].
    amplitude : float
        The amplitude there [m, rad].
    index : int
        It lies between branch points ``index`` and ``index + 1``.
    located : bool
        True when located to the tolerance (1e-10 in scaled arclength).
    """

    node: int
    dof: str
    kind: str
    parameter: float
    amplitude: float
    index: int
    located: bool


@dataclass(frozen=True, eq=False)
class PeriodicResult(KeptDofs):
    """A branch of periodic responses with their stability and bifurcations.

    The response at point ``i`` is ``q(t) = sum_h Q_hc cos(h tau) + Q_hs sin(h tau)``,
    ``tau = fundamental[i] t``, with the coefficient rows ``[Q_0, Q_1c, Q_1s, ..., Q_Hs]``
    (:mod:`rotorsim.harmonic_balance.fourier`); complex amplitudes ``X_h = Q_hc - i Q_hs``
    follow ``x(t) = Re(X_h e^{i h omega t})``. :attr:`dof_labels` and :meth:`column`
    (:class:`~.dof_access.KeptDofs`) label and find the kept DOFs (last axis).

    Attributes
    ----------
    parameter : array (P,)
        Continuation parameter at each point: the spin speed [rad/s] or the excitation
        frequency [rad/s] (``parameter_name``).
    parameter_name : str
        "speed" or "frequency".
    speed : array (P,)
        Spin speed ``W`` [rad/s].
    fundamental : array (P,)
        Fundamental frequency ``omega`` [rad/s].
    order : float
        ``omega / W`` for speed continuation (1 unbalance, ``Z kappa`` varying compliance,
        ``1/2`` a period-2 branch...); 0 when the frequency is the parameter.
    harmonics, samples : int
        ``H`` and the AFT samples ``N`` per period.
    dofs : int array (m,)
        Kept DOFs as indices among ALL DOFs (``6 * node + local``).
    coefficients : array (P, 2H + 1, m)
        Fourier coefficients of the kept DOFs [m, rad].
    max_abs, peak_to_peak : arrays (P, m)
        ``max |q(t)|`` and ``max q - min q`` over a period [m, rad].
    multipliers : complex array (P, r)
        Floquet multipliers by decreasing modulus (``r = 0`` without stability analysis).
    stability_method : str
        "hill", "hsu", "variational" or "none".
    stability_tol : float
        A point is stable when ``max |mu| < 1 + stability_tol``.
    bifurcations : tuple of PeriodicBifurcation
    iterations : int array (P,)
        Corrector iterations of the step to each point.
    residuals : array (P,)
        Scaled residual ``max |R / r_scale|`` at each point.
    approximation : str
        "" for an exact periodic problem; otherwise what was neglected (e.g. varying
        compliance with unbalance: rolling elements frozen).
    held_dofs : int array
        DOFs (among all) held at zero: free rigid motions no element restrains.
    dof_map : DofMap
    nodes_pos : array (n_nodes,)
        Axial node positions [m].
    peaks : tuple of PeriodicPeak
        Amplitude extrema located on request (``peaks=`` of ``periodic``).
    stability_checks : dict of arrays (P,)
        Per-point checks of the multipliers (``analyses.periodic.stability_checks``):
        ``method`` (the method that gave the stored multipliers, "shooting" where a check
        failed and shooting replaced them), ``passed`` (the first method passed the
        Liouville and tangent-jump checks), ``liouville_error``, ``tangent_jumps``,
        ``fallback_liouville_error``; empty without stability analysis or in files written
        before these checks existed.
    options, stats, status, reason, summary
        Options used (JSON-able), cost counters (points, residual evaluations,
        factorisations, Newton iterations, rejected steps, Floquet time, wall time), status
        of the branch (OK when it reached its bound), why it ended, model summary.
    unresolved : tuple of PeriodicBifurcation
        Sign changes of a test function that did not survive confirmation
        (:mod:`rotorsim.analyses.periodic.confirm`): not bifurcations, but listed so that
        nothing is silently dropped. ``located`` is False, ``parameter`` the middle of the
        interval and ``method`` says how many sign changes were merged, where, and why
        they were rejected.
    """

    parameter: FloatArray
    parameter_name: str
    speed: FloatArray
    fundamental: FloatArray
    order: float
    harmonics: int
    samples: int
    dofs: IntArray
    coefficients: FloatArray
    max_abs: FloatArray
    peak_to_peak: FloatArray
    multipliers: ComplexArray
    stability_method: str
    stability_tol: float
    bifurcations: tuple[PeriodicBifurcation, ...]
    iterations: IntArray
    residuals: FloatArray
    approximation: str
    held_dofs: IntArray
    dof_map: DofMap
    nodes_pos: FloatArray
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    reason: str = ""
    summary: dict[str, Any] = field(default_factory=dict)
    unresolved: tuple[PeriodicBifurcation, ...] = ()
    peaks: tuple[PeriodicPeak, ...] = ()
    stability_checks: Any = field(default_factory=dict)   # dict[str, array]

    def __len__(self) -> int:
        return int(self.parameter.size)

    # ------------------------------------------------------------------ stability
    @property
    def has_stability(self) -> bool:
        """Whether Floquet multipliers were computed."""
        return self.multipliers.shape[1] > 0

    @property
    def max_multiplier(self) -> FloatArray:
        """``max |mu|`` at each point (P,); raises without a stability analysis."""
        if not self.has_stability:
            raise ModelError("no stability analysis was made (stability=None)",
                             "PeriodicResult")
        return np.abs(self.multipliers[:, 0])

    @property
    def stable(self) -> NDArray[np.bool_]:
        """Stable points (P,): ``max |mu| < 1 + stability_tol``."""
        return self.max_multiplier < 1.0 + self.stability_tol

    def events(self, kind: str) -> tuple[PeriodicBifurcation, ...]:
        """The bifurcations of one kind."""
        return tuple(b for b in self.bifurcations if b.kind == kind)

    # ------------------------------------------------------------------ responses
    def amplitude(self, node: int, dof: str = "uy", measure: str = "max") -> FloatArray:
        """Amplitude measure of one DOF at every point (P,) [m, rad].

        ``measure``: "max" (``max |q|``), "peak_to_peak", "half_peak_to_peak" or "mean"
        (harmonic 0).
        """
        return branch_measure(self, self.column(node, dof), measure)

    def harmonic(self, node: int, dof: str = "uy", h: int = 1) -> ComplexArray:
        """Complex amplitude ``X_h = Q_hc - i Q_hs`` of harmonic ``h`` (P,) [m, rad]."""
        if not 0 <= h <= self.harmonics:
            raise ModelError(f"harmonic {h} outside 0..{self.harmonics}", "PeriodicResult")
        j = self.column(node, dof)
        if h == 0:
            return self.coefficients[:, 0, j].astype(complex)
        return self.coefficients[:, 2 * h - 1, j] - 1j * self.coefficients[:, 2 * h, j]

    def harmonic_amplitudes(self, point: int, node: int, dof: str = "uy") -> FloatArray:
        """``|X_h|``, ``h = 0..H`` (H + 1,) of one DOF at one point [m, rad]."""
        j = self.column(node, dof)
        C = self.coefficients[point, :, j]
        return np.concatenate([[abs(C[0])], np.hypot(C[1::2], C[2::2])])

    def time_response(self, point: int, samples: int = 256) -> tuple[FloatArray, FloatArray]:
        """Times ``t`` (samples,) [s] over one period and the kept DOFs ``q`` (samples, m)."""
        H = self.harmonics
        tau = 2.0 * np.pi * np.arange(samples) / samples
        h = np.arange(1, H + 1)[None, :]
        basis = np.empty((samples, 2 * H + 1))
        basis[:, 0] = 1.0
        basis[:, 1::2] = np.cos(h * tau[:, None])
        basis[:, 2::2] = np.sin(h * tau[:, None])
        return tau / self.fundamental[point], basis @ self.coefficients[point]

    def orbit(self, point: int, node: int, samples: int = 256) -> tuple[FloatArray, FloatArray]:
        """``(ux, uy)`` of ``node`` over one period at one point [m]."""
        _, q = self.time_response(point, samples)
        return q[:, self.column(node, "ux")], q[:, self.column(node, "uy")]

    def state(self, point: int, phase: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """Displacements and velocities on ALL DOFs (``6 n_nodes``,) at the phase
        ``tau = phase`` [rad] of one point's orbit [m, rad, m/s, rad/s]: the initial
        ``(q0, v0)`` of a transient started on the orbit (its shaft angle at ``t = 0``
        must be ``options["shaft_angle"] + phase / order``). DOFs not kept are zero: keep
        all nodes (``nodes=None``) for a complete state.
        """
        H = self.harmonics
        h = np.arange(1, H + 1)
        C = self.coefficients[point]
        cos, sin = np.cos(h * phase), np.sin(h * phase)
        q = C[0] + cos @ C[1::2] + sin @ C[2::2]
        v = self.fundamental[point] * ((h * cos) @ C[2::2] - (h * sin) @ C[1::2])
        q_all, v_all = np.zeros(self.dof_map.ndof), np.zeros(self.dof_map.ndof)
        q_all[self.dofs], v_all[self.dofs] = q, v
        return q_all, v_all

    def nearest(self, value: float) -> int:
        """Index of the point whose parameter is closest to ``value``."""
        return int(np.argmin(np.abs(self.parameter - value)))
