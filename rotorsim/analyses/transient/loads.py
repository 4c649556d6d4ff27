"""The time-dependent loads and nonlinear forces of a rotor transient, as the callbacks of a
:class:`~rotorsim.time_integration.problem.SecondOrderProblem`.

Loads (DESIGN section 3): constant gravity and point loads; unbalance
``me (W^2 [cos(phi + a), sin(phi + a)] + W' [sin(phi + a), -cos(phi + a)])``, the reaction
of the eccentric mass on the shaft (``-me`` times the acceleration of its offset
``e [cos, sin](phi + a)``; DESIGN section 3 prints the ``W'`` term with the opposite sign,
which would push a spinning-up shaft along the direction of rotation); base (housing)
excitation as the inertial load ``-M e a_b(t)`` of seed 002 eq 3.43 (``e`` the rigid
translation along the excitation direction, coordinates relative to the moving base); and
user forces ``f(t)``. The restoring force of the nonlinear elements is gathered on the
nonlinear DOFs with the shaft angle ``phi(t)`` and speed ``W(t)`` of the speed profile.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.transient.speed_profile import BoundSpeed
from rotorsim.assembly.loads import unit_direction
from rotorsim.assembly.nonlinear import NonlinearAssembly
from rotorsim.elements.base import FloatArray
from rotorsim.errors import ModelError
from rotorsim.time_integration.local_tangent import LocalMatrix, embed

ComplexArray = np.ndarray


@dataclass(frozen=True)
class BaseExcitation:
    """Acceleration of the base (housing, foundation) that carries the rotor.

    The coordinates of the analysis are then relative to the base, and every mass feels the
    inertial load ``-M e a_b(t)`` (seed 002 eq 3.43).

    Parameters
    ----------
    acceleration : callable
        ``a_b(t)`` [m/s^2] along ``direction``.
    direction : 3 floats
        Direction of the base motion (normalised).

    Examples
    --------
    >>> b = BaseExcitation.harmonic(1e-4, 100.0)    # displacement 0.1 mm at 100 rad/s
    >>> round(b.acceleration(0.0), 6)               # -a w^2 cos(0)
    -1.0
    """

    acceleration: Callable[[float], float]
    direction: tuple[float, float, float] = (0.0, 1.0, 0.0)

    def __post_init__(self) -> None:
        if not callable(self.acceleration):
            raise ModelError("acceleration must be callable a(t) [m/s^2]",
                             "BaseExcitation")
        object.__setattr__(self, "direction",
                           tuple(unit_direction(self.direction, "BaseExcitation.direction")))

    @classmethod
    def harmonic(cls, amplitude: float, frequency: float, *, phase: float = 0.0,
                 direction: ArrayLike = (0.0, 1.0, 0.0)) -> BaseExcitation:
        """Base displacement ``amplitude cos(frequency t + phase)`` [m, rad/s, rad]: the
        acceleration is ``-amplitude frequency^2 cos(frequency t + phase)`` (seed 002
        section 3.5.2.3)."""
        for name, value in (("amplitude", amplitude), ("frequency", frequency),
                            ("phase", phase)):
            if not math.isfinite(value):
                raise ModelError(f"{name} must be finite, got {value!r}",
                                 "BaseExcitation.harmonic")
        a, w, p = float(amplitude), float(frequency), float(phase)
        return cls(_HarmonicAcceleration(a, w, p),
                   tuple(float(x) for x in np.asarray(direction, dtype=float)))  # type: ignore[arg-type]


@dataclass(frozen=True)
class _HarmonicAcceleration:
    amplitude: float
    frequency: float
    phase: float

    def __call__(self, t: float) -> float:
        return -self.amplitude * self.frequency ** 2 * math.cos(self.frequency * t + self.phase)


@dataclass(frozen=True, eq=False)
class TransientLoads:
    """``f(t)`` of a rotor transient (module docstring).

    Attributes
    ----------
    constant : array (n,)
        Gravity and point loads [N, N m].
    unbalance : complex array (n,)
        Unbalance amplitudes per unit ``W^2`` (``me e^{i a}`` on ux, ``-i me e^{i a}`` on
        uy), or None.
    unbalance_ratio : array (n,), optional
        On a machine whose unbalanced spools turn at different speeds: the speed ratio
        ``r`` of the line under every DOF. The unbalance of a spool then turns with the
        spool's own angle ``r phi`` at its own speed ``r W`` and acceleration ``r W'``.
    base : array (n,) or None
        ``-M e`` for the base acceleration [kg].
    torsion : callable or None
        ``torsion(t)`` (n,): the torques of a torque drive on the torsional DOFs minus the
        inertial load of the spinning-up frame
        (:class:`~rotorsim.analyses.transient.torsion_loads.TorsionLoad`).
    """

    n: int
    speed: BoundSpeed
    constant: FloatArray
    unbalance: ComplexArray | None = None
    base: FloatArray | None = None
    base_acceleration: Callable[[float], float] | None = None
    forces: Callable[[float], ArrayLike] | None = None
    torsion: Callable[[float], FloatArray] | None = None
    unbalance_ratio: FloatArray | None = None

    def __call__(self, t: float) -> FloatArray:
        f = self.constant.copy()
        if self.torsion is not None:
            f += self.torsion(t)
        if self.unbalance is not None:
            w, dw = self.speed.speed(t), self.speed.acceleration(t)
            r = self.unbalance_ratio
            if r is None:
                rot = np.exp(1j * self.speed.angle(t)) * (w * w - 1j * dw)
            else:  # each spool at its own angle r phi, speed r W, acceleration r W'
                rot = np.exp(1j * r * self.speed.angle(t)) * (r * r * w * w - 1j * r * dw)
            f += (self.unbalance * rot).real
        if self.base is not None and self.base_acceleration is not None:
            a = float(self.base_acceleration(t))
            if not math.isfinite(a):
                raise ModelError(f"base acceleration is {a!r} at t = {t!r} s",
                                 "BaseExcitation.acceleration")
            f += self.base * a
        if self.forces is not None:
            user = np.asarray(self.forces(t), dtype=float).reshape(-1)
            if user.shape != (self.n,) or not np.all(np.isfinite(user)):
                raise ModelError(f"forces({t!r}) must be {self.n} finite numbers (free DOFs),"
                                 f" got shape {user.shape}", "transient.forces")
            f += user
        return f

    def many(self, times: FloatArray) -> FloatArray:
        """``f`` at several times (S,) as rows (S, n): the stages of a Runge-Kutta step.
        The same numbers as :meth:`__call__` at each time, with the unbalance (the only
        part that varies at every step of a plain run) in one vectorised pass."""
        if self.torsion is not None or self.forces is not None or \
                (self.base is not None and self.base_acceleration is not None):
            return np.stack([self(float(t)) for t in times])
        f = np.repeat(self.constant[None, :], len(times), axis=0)
        if self.unbalance is not None:
            sp = self.speed
            w = np.array([sp.speed(float(t)) for t in times])
            dw = np.array([sp.acceleration(float(t)) for t in times])
            phi = np.array([sp.angle(float(t)) for t in times])
            r = self.unbalance_ratio
            if r is None:
                rot = np.exp(1j * phi) * (w * w - 1j * dw)
                f += (self.unbalance[None, :] * rot[:, None]).real
            else:
                rot = np.exp(1j * r[None, :] * phi[:, None]) * (
                    r[None, :] * r[None, :] * (w * w)[:, None] - 1j * r[None, :] * dw[:, None])
                f += (self.unbalance[None, :] * rot).real
        return f


@dataclass(eq=False)
class RestoringForce:
    """``r(q, v, t)`` of the nonlinear elements with :class:`LocalMatrix` tangents; keeps
    the elements' internal state (warm start) between calls.

    ``index`` and ``size`` place the nonlinear DOFs in the problem's unknowns: by default
    the free DOFs themselves; in a reduced problem the leading boundary coordinates.
    ``damping`` adds the speed damping of a torque drive
    (:class:`~rotorsim.analyses.transient.torque_damping.TorqueDamping`).
    """

    assembly: NonlinearAssembly
    speed: BoundSpeed
    internal: Any = None
    index: Any = None
    size: int | None = None
    damping: Callable[[FloatArray, FloatArray, float],
                      tuple[FloatArray, None, LocalMatrix]] | None = None

    def __post_init__(self) -> None:
        if self.index is None:
            self.index = self.assembly.dofs
        if self.size is None:
            self.size = self.assembly.n_free

    def __call__(self, q: FloatArray, v: FloatArray, t: float
                 ) -> tuple[FloatArray, LocalMatrix, LocalMatrix]:
        a, index, size = self.assembly, self.index, int(self.size or 0)
        out = a.evaluate(q[index], v[index], self.speed.angle(t), self.speed.speed(t),
                         self.internal)
        self.internal = out.internal
        r = np.zeros(size)
        r[index] = out.f[0]
        K = LocalMatrix.trusted(size, index, out.K[0])
        C = LocalMatrix.trusted(size, index, out.C[0])
        if self.damping is not None:  # a torque drive's speed damping (torque_damping)
            r_d, _, C_d = self.damping(q, v, t)
            r += r_d
            C = _joined(C, C_d)
            # both tangents on the same DOFs: steppers then keep one low-rank update
            K = _joined(K, LocalMatrix.trusted(size, C_d.dofs,
                                               np.zeros((C_d.dofs.size, C_d.dofs.size))))
        return r, K, C

    def batch(self, q: FloatArray, v: FloatArray, t: FloatArray
              ) -> tuple[Any, FloatArray, FloatArray, FloatArray]:
        """Several samples in one call of the elements (the stages of a Runge-Kutta step).

        Parameters
        ----------
        q, v : arrays (S, size)
            Unknowns of each sample.
        t : array (S,)
            Times [s].

        Returns
        -------
        dofs : int array (k,)
            Where the forces act (``index``).
        r : array (S, k)
            Restoring forces on ``dofs`` [N, N m].
        dr_dq, dr_dv : arrays (S, k, k)
            Their tangents.
        """
        a, index = self.assembly, self.index
        phi = np.array([self.speed.angle(float(x)) for x in t])
        speed = np.array([self.speed.speed(float(x)) for x in t])
        out = a.evaluate(q[:, index], v[:, index], phi, speed)
        if self.damping is None:
            return index, out.f, out.K, out.C
        return _with_damping(self.damping, index, out.f, out.K, out.C, q, v, t)


def _joined(a: LocalMatrix, b: LocalMatrix) -> LocalMatrix:
    """``a + b``: block-diagonal when their DOFs are disjoint (the ``rz`` DOFs of a torque
    drive and the bearings' lateral ones), else on the union of the DOFs."""
    k = a.dofs.size
    if np.intersect1d(a.dofs, b.dofs, assume_unique=True).size:
        return LocalMatrix.trusted(a.n, *embed([(1.0, a), (1.0, b)]))
    block = np.zeros((k + b.dofs.size, k + b.dofs.size))
    block[:k, :k] = a.block
    block[k:, k:] = b.block
    return LocalMatrix.trusted(a.n, np.concatenate([a.dofs, b.dofs]), block)


def _with_damping(damping: Any, index: Any, f: FloatArray, K: FloatArray, C: FloatArray,
                  q: FloatArray, v: FloatArray, t: FloatArray
                  ) -> tuple[Any, FloatArray, FloatArray, FloatArray]:
    """The batch of :meth:`RestoringForce.batch` with a torque drive's speed damping added
    on the union of the DOFs."""
    S = f.shape[0]
    extra = [damping(q[s], v[s], float(t[s])) for s in range(S)]
    dofs = np.union1d(index, extra[0][2].dofs).astype(np.int64)
    k = dofs.size
    at = np.searchsorted(dofs, index)
    r_all, K_all, C_all = np.zeros((S, k)), np.zeros((S, k, k)), np.zeros((S, k, k))
    r_all[:, at] = f
    K_all[:, at[:, None], at[None, :]] = K
    C_all[:, at[:, None], at[None, :]] = C
    for s, (r_d, _, C_d) in enumerate(extra):
        pos = np.searchsorted(dofs, C_d.dofs)
        r_all[s, pos] += r_d[C_d.dofs]
        C_all[s, pos[:, None], pos[None, :]] += C_d.block
    return dofs, r_all, K_all, C_all
