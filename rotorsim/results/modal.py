"""Result of a complex modal analysis at one speed."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.assembly.dof_map import DofMap
from rotorsim.errors import ModelError, Status
from rotorsim.results.orbits import Ellipse, ellipse

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]


@dataclass(frozen=True, eq=False)
class ModalResult:
    """Modes of the damped gyroscopic system at spin speed ``speed``.

    Elastic modes are sorted by undamped natural frequency; each complex-conjugate pair is
    reported once (positive damped frequency). Rigid-body modes (zero eigenvalues, e.g. the
    axial and torsional motion of a rotor without axial or torsional restraint) are not mixed
    in: they are counted in ``rigid_body_modes`` and spanned by ``rigid_body_shapes``.

    Attributes
    ----------
    speed : float
        Spin speed [rad/s].
    eigenvalues : complex array (num_modes,)
        ``lam = -zeta wn + i wd`` [rad/s].
    wn, wd : array (num_modes,)
        Undamped (``|lam|``) and damped (``Im lam``) natural frequencies [rad/s].
    damping_ratio, log_dec : array (num_modes,)
        ``zeta = -Re(lam) / |lam|`` and ``delta = -2 pi Re(lam) / Im(lam)``
        (``inf`` for an overdamped, non-oscillating mode).
    whirl : tuple of str
        ``"forward"``, ``"backward"`` or ``"mixed"`` for lateral modes (``"none"`` otherwise).
    whirl_ratio : array (num_modes,)
        Amplitude-weighted mean of ``(rf - rb) / (rf + rb)`` over the nodes.
    kind : tuple of str
        ``"lateral"``, ``"axial"`` or ``"torsional"`` by the DOF group carrying most of
        the kinetic energy.
    mode_shapes : complex array (ndof, num_modes)
        All DOFs (zeros at fixed ones); largest translation scaled to 1 with zero phase.
    rigid_body_modes : int
        Number of independent rigid-body modes found.
    rigid_body_shapes : array (ndof, rigid_body_modes)
        Orthonormal basis of the rigid-body modes.
    notes : tuple of str
        Remarks on the solution, e.g. fewer modes than ``num_modes`` asked for.
    """

    speed: float
    eigenvalues: ComplexArray
    wn: FloatArray
    wd: FloatArray
    damping_ratio: FloatArray
    log_dec: FloatArray
    whirl: tuple[str, ...]
    whirl_ratio: FloatArray
    kind: tuple[str, ...]
    mode_shapes: ComplexArray
    rigid_body_modes: int
    rigid_body_shapes: FloatArray
    dof_map: DofMap
    nodes_pos: FloatArray
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()

    @property
    def num_modes(self) -> int:
        """Number of modes (columns of ``mode_shapes``)."""
        return int(self.wn.size)

    def shape(self, mode: int, node: int, dof: str | int) -> complex:
        """Complex mode-shape value of ``dof`` at ``node`` for ``mode``."""
        self._check_mode(mode)
        return complex(self.mode_shapes[self.dof_map.index(node, dof), mode])

    def lateral_shape(self, mode: int) -> tuple[ComplexArray, ComplexArray]:
        """Complex ``ux`` and ``uy`` of ``mode`` at every node."""
        self._check_mode(mode)
        shape = self.mode_shapes[:, mode].reshape(-1, 6)
        return shape[:, 0], shape[:, 1]

    def orbit(self, mode: int, node: int) -> Ellipse:
        """Orbit ellipse of ``node`` in ``mode``."""
        ux, uy = self.lateral_shape(mode)
        return ellipse(ux[node], uy[node])

    def _check_mode(self, mode: int) -> None:
        if not 0 <= mode < self.num_modes:
            raise ModelError(f"mode {mode} outside 0..{self.num_modes - 1}", "ModalResult")
