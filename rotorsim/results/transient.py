"""Result of a transient (time-integration) analysis of a rotor."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rotorsim.assembly.dof_map import DofMap
from rotorsim.elements.base import DOF_NAMES
from rotorsim.errors import ModelError, Status
from rotorsim.results.dof_access import KeptDofs
from rotorsim.results.transient_state import TransientState, radial_pairs

if TYPE_CHECKING:
    from rotorsim.results.order_tracking import OrderTrack, Waterfall
    from rotorsim.results.spectra import HarmonicFit, Spectrum

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class TransientResult(KeptDofs):
    """Time histories of a rotor transient: kept DOFs, speed, angle and bearing loads.

    :attr:`dof_labels` and :meth:`column` (:class:`~.dof_access.KeptDofs`) label and find
    the columns of ``q`` and ``v``.

    Attributes
    ----------
    t : array (k,)
        Sample times [s].
    q : array (k, m)
        Displacements of the kept DOFs [m, rad].
    v : array (k, m) or None
        Their velocities [m/s, rad/s], kept on request only (``rs.Output(velocities=True)``;
        None otherwise).
    dofs : int array (m,)
        Indices of the kept DOFs among ALL DOFs (``6 * node + local``).
    speed, angle, acceleration : arrays (k,)
        Spin speed W [rad/s], shaft angle phi [rad] and W' [rad/s^2] at the samples.
    bearing_loads : array (k, b, 5)
        Load ``[Fx, Fy, Fz, Mx, My]`` [N, N m] that each nonlinear bearing's inner ring
        carries (the force the bearing exerts on its inner node).
    bearing_tags : tuple of str
        Name of each bearing (index when untagged).
    bearing_elements : int array (b,)
        Number of rolling elements of each bearing (``0`` when not a rolling bearing).
    bearing_kappa : array (b,)
        Cage speed ratio of each bearing: the varying-compliance (ball pass) frequency is
        ``bearing_elements * bearing_kappa * W``.
    reduced : dict of str to array
        Reductions over all accepted steps with ``t >= after`` (``rs.Output(reducers=...)``):
        ``max_abs`` and ``rms`` (m,) on the columns of ``q``; ``max_amplitude`` (p,) the
        largest radial amplitude ``sqrt(ux^2 + uy^2)`` of each of :attr:`amplitude_nodes`;
        ``peak_to_peak`` (r, m) per shaft revolution, with the revolution index
        ``floor(phi / 2 pi)`` of each row in ``peak_to_peak_revolution`` (r,) (the first and
        last rows may cover part of a revolution).
    dof_map : DofMap
    nodes_pos : array (n_nodes,)
        Axial node positions [m].
    method : str
        Integration method.
    options, stats, status, summary
        Options used (JSON-able), cost counters (steps, factorisations, Newton iterations,
        rejected steps, wall time), overall status and model summary.
    element_loads, contact_angles : dict of str to array (k, Z)
        With ``rolling_elements=True``: the (inner-contact) load [N] and contact angle [rad]
        of every rolling element of each bearing (by tag) at every sample; element ``j``
        sits at ``psi_0 + 2 pi j / Z + kappa phi``.
    final : TransientState or None
        The final full state (all free DOFs, shaft angle and speed, the stepper's state):
        pass the result as ``initial=`` to continue the run (None in files of older
        versions).
    """

    t: FloatArray
    q: FloatArray
    v: FloatArray | None
    dofs: IntArray
    speed: FloatArray
    angle: FloatArray
    acceleration: FloatArray
    bearing_loads: FloatArray
    bearing_tags: tuple[str, ...]
    bearing_elements: IntArray
    bearing_kappa: FloatArray
    reduced: dict[str, FloatArray]
    dof_map: DofMap
    nodes_pos: FloatArray
    method: str = ""
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    element_loads: dict[str, FloatArray] = field(default_factory=dict)
    contact_angles: dict[str, FloatArray] = field(default_factory=dict)
    final: TransientState | None = None

    @property
    def amplitude_nodes(self) -> IntArray:
        """Nodes whose ``ux`` and ``uy`` are both kept, in increasing order: the entries of
        ``reduced["max_amplitude"]``."""
        return radial_pairs(self.dofs).nodes

    @property
    def stopped(self) -> dict[str, Any] | None:
        """Why and when the run stopped before ``t_end`` (``options["stopped"]``: reason,
        time, revolution), or None when it ran to the end."""
        return self.options.get("stopped")

    def displacement(self, node: int, dof: str = "uy") -> FloatArray:
        """Time history of one DOF [m, rad]."""
        return self.q[:, self.column(node, dof)]

    def node_displacement(self, node: int) -> FloatArray:
        """All 6 DOFs ``ux, uy, uz, rx, ry, rz`` of ``node`` at every sample (k, 6) [m, rad];
        fixed DOFs are zero.

        Raises
        ------
        ModelError
            When a free DOF of the node was not kept.
        """
        out = np.zeros((self.t.size, 6))
        for j in range(6):
            full = self.dof_map.index(node, j)
            if self.dof_map.full_to_free[full] >= 0:
                out[:, j] = self.q[:, self.column(node, DOF_NAMES[j])]
        return out

    def velocity(self, node: int, dof: str = "uy") -> FloatArray:
        """Velocity history of one DOF (requires velocities to be kept)."""
        if self.v is None:
            raise ModelError("velocities were not kept: run with "
                             "output=rs.Output(velocities=True)", "TransientResult.velocity")
        return self.v[:, self.column(node, dof)]

    def orbit(self, node: int, t_min: float | None = None) -> tuple[FloatArray, FloatArray]:
        """``(ux, uy)`` of ``node`` for ``t >= t_min`` [m]."""
        sel = self.window(t_min)
        return self.displacement(node, "ux")[sel], self.displacement(node, "uy")[sel]

    def window(self, t_min: float | None = None, t_max: float | None = None
               ) -> NDArray[np.bool_]:
        """Mask of the samples with ``t_min <= t <= t_max``."""
        lo = -np.inf if t_min is None else t_min
        hi = np.inf if t_max is None else t_max
        return (self.t >= lo) & (self.t <= hi)

    def varying_compliance_frequency(self, bearing: int = 0) -> FloatArray:
        """Ball/roller pass frequency ``Z kappa W(t)`` of a bearing at each sample [rad/s]."""
        return self.bearing_elements[bearing] * self.bearing_kappa[bearing] * self.speed

    # ------------------------------------------------------------------ post-processing
    @property
    def varying_compliance_orders(self) -> FloatArray:
        """Varying-compliance order ``Z kappa`` of each bearing (0 for non-rolling ones)."""
        return np.asarray(self.bearing_elements * self.bearing_kappa, dtype=float)

    def spectrum(self, node: int, dof: str = "uy", t_min: float | None = None, *,
                 t_max: float | None = None, window: str = "hann", detrend: str = "mean"
                 ) -> Spectrum:
        """Amplitude spectrum of one DOF over ``t_min <= t <= t_max`` (see
        :func:`rotorsim.results.spectra.amplitude_spectrum`; samples must be uniform)."""
        from rotorsim.results.spectra import amplitude_spectrum

        return amplitude_spectrum(self.t, self.displacement(node, dof), t_min=t_min,
                                  t_max=t_max, window=window, detrend=detrend)

    def waterfall(self, node: int, dof: str = "uy", *, segment: float,
                  overlap: float = 0.5, window: str = "hann") -> Waterfall:
        """Short-time spectra of one DOF, each segment labelled by its mean speed (see
        :func:`rotorsim.results.order_tracking.waterfall`)."""
        from rotorsim.results.order_tracking import waterfall

        return waterfall(self.t, self.displacement(node, dof), self.speed, segment=segment,
                         overlap=overlap, window=window)

    def order_track(self, node: int, dof: str = "uy", orders: ArrayLike = (1.0,), *,
                    revolutions_per_block: int = 8, t_min: float | None = None,
                    window: str = "hann") -> OrderTrack:
        """Amplitude and phase of shaft ``orders`` of one DOF against speed, resampled at
        uniform shaft angle (see :func:`rotorsim.results.order_tracking.order_track`);
        e.g. ``orders=(1, 2, *result.varying_compliance_orders)``."""
        from rotorsim.results.order_tracking import order_track

        sel = self.window(t_min)
        return order_track(self.t[sel], self.displacement(node, dof)[sel], self.angle[sel],
                           orders, revolutions_per_block=revolutions_per_block,
                           window=window)

    def harmonic(self, node: int, dof: str = "uy", frequency: float | None = None,
                 t_min: float | None = None) -> HarmonicFit:
        """Least-squares amplitude and phase of one DOF at ``frequency`` [rad/s] over
        ``t >= t_min`` (default: the mean speed there, i.e. 1X), in the convention
        ``x = Re(X e^{i w t})`` of the frequency-domain analyses (see
        :func:`rotorsim.results.spectra.harmonic_fit`)."""
        from rotorsim.results.spectra import harmonic_fit

        sel = self.window(t_min)
        if frequency is None:
            if not sel.any():
                raise ModelError(f"no samples at t >= {t_min}", "TransientResult.harmonic")
            frequency = float(np.mean(self.speed[sel]))
        return harmonic_fit(self.t[sel], self.displacement(node, dof)[sel], frequency)
