"""Result of a quasi-periodic branch: a rotor's tori over speed, with the tones of the
shaft and varying-compliance (VC) frequencies and the stability of each torus."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap
from rotorsim.errors import ModelError, Status
from rotorsim.results.dof_access import KeptDofs
from rotorsim.results.periodic import branch_measure
from rotorsim.results.torus_motion import MotionBeyond

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, eq=False)
class TorusEvent:
    """A change of the torus's stability along the branch.

    Attributes
    ----------
    kind : str
        ``"loss_of_stability"`` (the largest exponent turns positive with speed) or
        ``"regain_of_stability"``.
    parameter : float
        Speed [rad/s] where the largest exponent crosses zero (linear between the points).
    index : int
        Between points ``index`` and ``index + 1``.
    exponents : (float, float)
        The largest real parts [1/s] at the two points (the evidence).
    frequency : float
        ``|Im lam|`` [rad/s] of the critical exponent after the crossing: a perturbation
        growing at this frequency (modulo the tones) replaces the torus.
    lyapunov : float
        Largest Lyapunov exponent [1/s] on the unstable side, from a short integration of
        the variational equation along that torus (independent evidence of the growth;
        NaN when not computed).
    character : str
        What the critical exponent says the motion turns into, from ``frequency`` modulo
        the tones ``k1 W + k2 w2``: ``"fold"`` (a real exponent: the branch folds or
        branches, the response jumps), ``"doubling"`` (half a tone: a subharmonic torus),
        ``"third frequency"`` (a new frequency: a 3-torus, phase locking or chaos; only an
        integration in time says which), or ``""``.
    motion : MotionBeyond or None
        For a loss of stability: what the motion is at the first unstable torus, from a
        transient of the full model started next to it (its kind, its order, and its
        trajectory's Lyapunov exponent); None when not run.
    """

    kind: str
    parameter: float
    index: int
    exponents: tuple[float, float]
    frequency: float
    lyapunov: float = float("nan")
    character: str = ""
    motion: MotionBeyond | None = None


@dataclass(frozen=True, eq=False)
class QuasiPeriodicResult(KeptDofs):
    """Tori over speed: ``q(t) = a_0 + sum_j c_j cos(Omega_j t) + s_j sin(Omega_j t)``,
    ``Omega_j = k1_j W + k2_j w2`` with ``w2 = vc_order W`` (shaft and cage angles 0 at
    ``t = 0``), coefficient rows ``[a_0, c_1, s_1, ...]`` as
    :mod:`rotorsim.harmonic_balance.quasi`.

    Attributes
    ----------
    speed : array (P,)
        Spin speed ``W`` [rad/s] (the shaft frequency ``w1``).
    vc_frequency : array (P,)
        The second base frequency ``w2 = vc_order W`` [rad/s].
    vc_order : float
        ``w2 / W``: ``Z kappa`` of the rolling bearings, or ``|r|`` of a second spool
        (``second``).
    tones : int array (T, 2)
        ``(k1, k2)`` of each tone (one of each pair ``+-k``).
    dofs : int array (m,)
        Kept DOFs among ALL DOFs (``6 node + local``).
    coefficients : array (P, 2T + 1, m)
        [m, rad].
    max_abs, peak_to_peak : arrays (P, m)
        ``max |q|`` and ``max q - min q`` over the torus grid [m, rad].
    exponents : array (P,)
        Largest real part of the torus's characteristic exponents [1/s] (negative:
        stable; NaN without stability).
    exponents_converged : bool array (P,)
        The stability boxes agreed (:class:`~rotorsim.analyses.quasiperiodic.stability.
        TorusStability`); False: the sign is uncertain.
    stability_method : str
        ``"hill"`` or ``"none"``.
    events : tuple of TorusEvent
        Where the torus loses or regains stability: between such events it is not the
        response (an unstable torus is kept on the branch, flagged, never reported as
        the motion).
    iterations : int array (P,)
    residuals : array (P,)
        Scaled residual of each point.
    second : str
        ``"vc"`` (``w2`` the varying compliance) or ``"spool"`` (the 1X of a second spool
        at ``|r| W``, its unbalance in the tone ``(0, 1)``).
    approximation : str
        "" when nothing is frozen (the VC torus); with two spools, rolling elements with
        turning cages are frozen (their VC would be a third frequency) and this says so.
    stability_tol : float
        A torus is stable when its growth per shaft revolution ``exponent 2 pi / W`` is
        below this (an undamped mode's exponent is zero to round-off).
    exponents_checked : bool array (P,) or None
        The stability box was grown at this torus. False: its exponents are those of the
        box (1, 1), their convergence taken from the checked tori on both sides
        (:func:`~rotorsim.analyses.quasiperiodic.branch_stability.branch_stability`).
        None when not recorded.
    held_dofs, dof_map, nodes_pos, options, stats, status, reason, summary
        As :class:`~rotorsim.results.periodic.PeriodicResult`.
    """

    speed: FloatArray
    vc_frequency: FloatArray
    vc_order: float
    tones: IntArray
    dofs: IntArray
    coefficients: FloatArray
    max_abs: FloatArray
    peak_to_peak: FloatArray
    exponents: FloatArray
    exponents_converged: NDArray[np.bool_]
    stability_method: str
    events: tuple[TorusEvent, ...]
    iterations: IntArray
    residuals: FloatArray
    held_dofs: IntArray
    dof_map: DofMap
    nodes_pos: FloatArray
    second: str = "vc"
    approximation: str = ""
    stability_tol: float = 1e-5
    exponents_checked: NDArray[np.bool_] | None = None
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    reason: str = ""
    summary: dict[str, Any] = field(default_factory=dict)

    def __len__(self) -> int:
        return int(self.speed.size)

    @property
    def parameter(self) -> FloatArray:
        """The speed [rad/s] (as ``PeriodicResult.parameter``)."""
        return self.speed

    @property
    def parameter_name(self) -> str:
        return "speed"

    @property
    def has_stability(self) -> bool:
        return bool(np.isfinite(self.exponents).any())

    @property
    def growth(self) -> FloatArray:
        """Growth per shaft revolution ``exponent 2 pi / W`` of each torus (P,) [-]."""
        return self.exponents * 2 * np.pi / self.speed

    @property
    def stable(self) -> NDArray[np.bool_]:
        """Points whose torus is stable (growth per revolution below ``stability_tol``;
        False where not computed)."""
        return np.asarray(np.nan_to_num(self.growth, nan=np.inf) < self.stability_tol)

    def amplitude(self, node: int, dof: str = "uy", measure: str = "max") -> FloatArray:
        """``measure`` of one DOF at every point (P,) [m, rad]: "max", "peak_to_peak",
        "half_peak_to_peak" or "mean"."""
        return branch_measure(self, self.column(node, dof), measure)

    def tone(self, node: int, dof: str, k1: int, k2: int) -> ComplexArray:
        """Complex amplitude ``c - i s`` of the tone ``k1 W + k2 w2`` (P,) [m, rad] (the
        conjugate for ``-k``; the mean for ``(0, 0)``)."""
        j = self.column(node, dof)
        if (k1, k2) == (0, 0):
            return self.coefficients[:, 0, j].astype(complex)
        hit = np.flatnonzero((self.tones[:, 0] == k1) & (self.tones[:, 1] == k2))
        sign = 1.0
        if not hit.size:
            hit = np.flatnonzero((self.tones[:, 0] == -k1) & (self.tones[:, 1] == -k2))
            sign = -1.0
        if not hit.size:
            raise ModelError(f"tone ({k1}, {k2}) is not in the harmonic set",
                             "QuasiPeriodicResult.tone")
        r = 1 + 2 * int(hit[0])
        return self.coefficients[:, r, j] - 1j * sign * self.coefficients[:, r + 1, j]

    def spectrum(self, point: int, node: int, dof: str = "uy"
                 ) -> tuple[FloatArray, FloatArray, IntArray]:
        """Frequencies ``|Omega_j|`` [rad/s], amplitudes [m, rad] and ``(k1, k2)`` of every
        tone of one DOF at one point, by decreasing amplitude (the mean excluded)."""
        j = self.column(node, dof)
        C = self.coefficients[point, :, j]
        amp = np.hypot(C[1::2], C[2::2])
        freq = np.abs(self.tones @ np.array([self.speed[point], self.vc_frequency[point]]))
        order = np.argsort(-amp, kind="stable")
        return freq[order], amp[order], self.tones[order]

    def time_response(self, point: int, t: FloatArray) -> FloatArray:
        """The kept DOFs at times ``t (s,)`` [s]: ``(s, m)`` [m, rad]."""
        C = self.coefficients[point]
        phase = np.outer(np.asarray(t, dtype=float),
                         self.tones @ np.array([self.speed[point], self.vc_frequency[point]]))
        return C[0] + np.cos(phase) @ C[1::2] + np.sin(phase) @ C[2::2]

    def state(self, point: int, t: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """Displacements and velocities on ALL DOFs (``6 n_nodes``,) at time ``t`` [s] of one
        point's torus (shaft and cage angles 0 at ``t = 0``) [m, rad, m/s, rad/s]: the
        ``initial`` of a transient started on it. DOFs not kept are zero."""
        C = self.coefficients[point]
        omega = self.tones @ np.array([self.speed[point], self.vc_frequency[point]])
        cos, sin = np.cos(omega * t), np.sin(omega * t)
        q = C[0] + cos @ C[1::2] + sin @ C[2::2]
        v = (omega * cos) @ C[2::2] - (omega * sin) @ C[1::2]
        q_all, v_all = np.zeros(self.dof_map.ndof), np.zeros(self.dof_map.ndof)
        q_all[self.dofs], v_all[self.dofs] = q, v
        return q_all, v_all

    def orbit(self, point: int, node: int, t: FloatArray) -> tuple[FloatArray, FloatArray]:
        """``(ux, uy)`` of ``node`` at times ``t`` [s] (a torus never closes: pass many
        revolutions to see it filled)."""
        q = self.time_response(point, t)
        return q[:, self.column(node, "ux")], q[:, self.column(node, "uy")]

    def poincare(self, point: int, node: int, revolutions: int = 400
                 ) -> tuple[FloatArray, FloatArray]:
        """``(ux, uy)`` of ``node`` once per shaft revolution [m]: a closed curve for a
        torus (the section at shaft angle 0)."""
        t = 2 * np.pi / self.speed[point] * np.arange(int(revolutions))
        return self.orbit(point, node, t)

    def nearest(self, value: float) -> int:
        """Index of the point whose speed is closest to ``value``."""
        return int(np.argmin(np.abs(self.speed - value)))
