"""Result of a steady-state harmonic (unbalance or receptance) analysis."""

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
class DeflectedShape:
    """Complex lateral deflection of every node at one frequency.

    Attributes
    ----------
    frequency, speed : float
        Excitation frequency and spin speed [rad/s].
    nodes_pos : array (n_nodes,)
        Axial node positions [m].
    ux, uy : complex array (n_nodes,)
        Complex amplitudes [m] (``x(t) = Re(ux e^{i w t})``).
    orbit : Ellipse
        Orbit of every node; ``orbit.major`` is the major semi-axis [m].
    """

    frequency: float
    speed: float
    nodes_pos: FloatArray
    ux: ComplexArray
    uy: ComplexArray
    orbit: Ellipse

    @property
    def major(self) -> FloatArray:
        """Major semi-axis of every node's orbit [m]."""
        return self.orbit.major


@dataclass(frozen=True, eq=False)
class FrequencyResponseResult:
    """Steady-state complex response at a list of excitation frequencies.

    The response of DOF ``j`` to input ``k`` at frequency ``w`` is the complex amplitude
    ``X`` of ``q_j(t) = Re(X e^{i w t})``: ``|X|`` is the amplitude and ``angle(X)`` the phase,
    positive when the response leads the reference (the unbalance at angle 0, or the unit
    force ``cos(w t)``). For an unbalance the reference is the rotating frame ``phi = W t``,
    so a response in phase with an unbalance at angle ``a`` has phase ``a``.

    Attributes
    ----------
    frequencies : array (F,)
        Excitation frequencies w [rad/s].
    speeds : array (F,)
        Spin speed W at each point [rad/s] (equal to ``frequencies`` when synchronous).
    response : complex array (F, ndof, n_inputs)
        Complex amplitudes on ALL DOFs (zeros at fixed ones) [m or rad per unit input];
        an unbalance response has one input, the whole unbalance distribution, in [m, rad].
    dof_map : DofMap
    nodes_pos : array (n_nodes,)
        Axial node positions [m].
    inputs : tuple of str
        Description of each input column.
    kind : str
        ``"unbalance"`` or ``"receptance"``.
    point_status : int array (F,)
        :class:`~rotorsim.errors.Status` of each frequency (``FAILED`` points hold NaN).
    options, stats, status, summary
        Options used, cost counters (``factorizations`` = one per frequency), overall status
        and model summary.
    input_ratios : array (n_inputs,), optional
        Unbalance response of a machine whose unbalanced spools turn at different speeds:
        input ``k`` is spool ``k``'s unbalance, which turns at ``input_ratios[k]`` times the
        reference speed ``speeds``, so its response has the frequency
        ``|input_ratios[k]| * speeds``. A counter-rotating spool (negative ratio) drives a
        force that turns backwards; its column is written at the positive frequency
        (``q = Re(X e^{i |r| W t})``), so its orbits whirl backwards and its phase is
        measured against the reversed reference angle. ``frequencies`` then holds the
        reference speed. ``None``: every input at ``frequencies``.
    """

    frequencies: FloatArray
    speeds: FloatArray
    response: ComplexArray
    dof_map: DofMap
    nodes_pos: FloatArray
    inputs: tuple[str, ...]
    kind: str
    point_status: NDArray[np.int64]
    options: dict[str, Any] = field(default_factory=dict)
    stats: dict[str, float] = field(default_factory=dict)
    status: Status = Status.OK
    summary: dict[str, Any] = field(default_factory=dict)
    input_ratios: FloatArray | None = None

    @property
    def n_inputs(self) -> int:
        return int(self.response.shape[2])

    def input_frequencies(self, input: int = 0) -> FloatArray:
        """Excitation frequency of input ``input`` at every point [rad/s]."""
        self._check_input(input)
        if self.input_ratios is None:
            return self.frequencies
        return abs(float(self.input_ratios[input])) * self.speeds

    def peak_amplitude(self, node: int, dof: str | int) -> FloatArray:
        """Largest value over time of ``|dof|`` when every input acts at once ``(F,)``.

        Inputs at incommensurate frequencies (the unbalances of two spools) add to a
        quasi-periodic motion whose supremum is the sum of their amplitudes; inputs at one
        frequency add as complex amplitudes.
        """
        X = self.response[:, self.dof_map.index(node, dof), :]
        if self.input_ratios is None:
            return np.abs(X.sum(axis=1))
        ratios = np.abs(np.asarray(self.input_ratios))  # all columns at |r| W
        return np.sum([np.abs(X[:, ratios == r].sum(axis=1)) for r in np.unique(ratios)],
                      axis=0)

    def complex(self, node: int, dof: str | int, input: int = 0) -> ComplexArray:
        """Complex amplitude ``(F,)`` of ``dof`` at ``node`` for input ``input`` [m or rad]."""
        self._check_input(input)
        return self.response[:, self.dof_map.index(node, dof), input]

    def amplitude(self, node: int, dof: str | int, input: int = 0) -> FloatArray:
        """Amplitude ``|X|`` ``(F,)`` [m or rad].

        Examples
        --------
        >>> r = _example()
        >>> r.amplitude(0, "ux").tolist()
        [1.0, 2.0]
        """
        return np.abs(self.complex(node, dof, input))

    def phase(self, node: int, dof: str | int, input: int = 0) -> FloatArray:
        """Phase ``angle(X)`` ``(F,)`` in (-pi, pi] [rad], lead positive.

        Examples
        --------
        >>> r = _example()
        >>> r.phase(0, "uy").round(4).tolist()
        [-1.5708, -1.5708]
        """
        return np.angle(self.complex(node, dof, input))

    def orbit(self, node: int, input: int = 0) -> Ellipse:
        """Orbit ellipse of ``node`` at every frequency (arrays ``(F,)``).

        Examples
        --------
        >>> _example().orbit(0).whirl_ratio.tolist()
        [1.0, 1.0]
        """
        return ellipse(self.complex(node, "ux", input), self.complex(node, "uy", input))

    def deflected_shape(
        self, index: int | None = None, *, frequency: float | None = None, input: int = 0
    ) -> DeflectedShape:
        """Lateral shape of the shaft at point ``index``, or at the point nearest ``frequency``.

        Parameters
        ----------
        index : int, optional
            Index into :attr:`frequencies`.
        frequency : float, optional
            Frequency (= speed for an unbalance response) [rad/s]; the nearest computed point
            is used.
        input : int
            Input column.

        Examples
        --------
        >>> s = _example().deflected_shape(frequency=90.0)
        >>> s.frequency, s.major.tolist()
        (100.0, [2.0])
        """
        self._check_input(input)
        if (index is None) == (frequency is None):
            raise ModelError("give exactly one of index and frequency", "deflected_shape")
        if index is None:
            index = int(np.argmin(np.abs(self.frequencies - float(frequency))))  # type: ignore[arg-type]
        if not -len(self.frequencies) <= index < len(self.frequencies):
            raise ModelError(f"index {index} outside 0..{len(self.frequencies) - 1}",
                             "deflected_shape")
        nodes = self.response[index, :, input].reshape(-1, 6)
        return DeflectedShape(
            frequency=float(self.frequencies[index]), speed=float(self.speeds[index]),
            nodes_pos=self.nodes_pos, ux=nodes[:, 0], uy=nodes[:, 1],
            orbit=ellipse(nodes[:, 0], nodes[:, 1]),
        )

    def peak(self, node: int, dof: str | int, input: int = 0) -> tuple[float, float]:
        """Frequency [rad/s] and amplitude of the largest computed amplitude of ``dof``.

        Examples
        --------
        >>> _example().peak(0, "ux")
        (100.0, 2.0)
        """
        amp = self.amplitude(node, dof, input)
        i = int(np.nanargmax(amp))
        return float(self.frequencies[i]), float(amp[i])

    def _check_input(self, input: int) -> None:
        if not 0 <= input < self.n_inputs:
            raise ModelError(f"input {input} outside 0..{self.n_inputs - 1}",
                             "FrequencyResponseResult")


def _example() -> FrequencyResponseResult:
    """A one-node forward circular response used by the doctests."""
    response = np.zeros((2, 6, 1), dtype=complex)
    response[:, 0, 0] = [1.0, 2.0]
    response[:, 1, 0] = [-1j, -2j]
    return FrequencyResponseResult(
        frequencies=np.array([50.0, 100.0]), speeds=np.array([50.0, 100.0]),
        response=response, dof_map=DofMap(1), nodes_pos=np.zeros(1), inputs=("example",),
        kind="unbalance", point_status=np.zeros(2, dtype=np.int64),
    )
