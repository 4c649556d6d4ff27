"""The stepper contract shared by every time integrator (DESIGN section 6, STYLE practice 4).

A stepper is a frozen options dataclass with

* ``init(problem, t0, q0, v0, *, dt, a0=None) -> State``: the state at ``t0``;
* ``step(problem, state) -> State``: one accepted step, of size ``state.dt`` for a fixed-step
  method; the returned state carries the counters and the size proposed for the next step;
* ``interpolate(old, new, t, dofs) -> (q, v)``: dense output between two accepted states.

A :class:`State` holds only numbers and arrays, so :mod:`rotorsim.time_integration.checkpoint`
writes it to HDF5 and a run continues from it bit for bit. The one exception is
:attr:`State.cache`, the LU factors of the current iteration matrix: it is rebuilt after a
resume from the key fields stored beside it (the same matrix gives the same factors).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.time_integration.problem import SecondOrderProblem

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class Counters:
    """Cost counters of a run (STYLE practice 8), carried by every :class:`State`.

    Attributes
    ----------
    rejected_steps : int
        Steps rejected by the error control or by a failed Newton solve.
    newton_failures : int
        Rejections caused by a Newton solve that did not converge.
    factorizations : int
        LU factorisations (of ``M`` for the initial acceleration and of the iteration
        matrix).
    solves : int
        Solves with an existing factorisation.
    residual_evaluations : int
        Calls of the restoring-force callback.
    iterations : int
        Newton iterations (linear solves of the step equation) over all attempted steps,
        rejected ones included.
    max_iterations : int
        Largest number of Newton iterations in one step.
    """

    rejected_steps: int = 0
    newton_failures: int = 0
    factorizations: int = 0
    solves: int = 0
    residual_evaluations: int = 0
    iterations: int = 0
    max_iterations: int = 0

    def plus(self, other: Counters) -> Counters:
        """Counters of ``self`` followed by ``other`` (the maximum is a maximum)."""
        return Counters(self.rejected_steps + other.rejected_steps,
                        self.newton_failures + other.newton_failures,
                        self.factorizations + other.factorizations,
                        self.solves + other.solves,
                        self.residual_evaluations + other.residual_evaluations,
                        self.iterations + other.iterations,
                        max(self.max_iterations, other.max_iterations))


@dataclass(frozen=True, eq=False)
class State:
    """Everything a stepper needs to continue from time ``t``.

    Attributes
    ----------
    t : float
        Time [s].
    q, v, a : array (n,)
        Displacements [m, rad], velocities and accelerations. For the alpha methods ``a``
        is the algorithmic acceleration of the method, not ``M^-1`` of the force balance.
    force : array (n,)
        Net force ``g = (C + s G) v + K q + r - f`` at ``(q, v, t)`` [N], reused by the
        alpha methods (the equation of motion reads ``M a + g = 0``).
    step : int
        Accepted steps since the initial time.
    dt : float
        Size of the next step to take [s].
    error : float
        Scaled local error estimate of the last accepted step (0 if not estimated).
    peak : array (n,) or (0,)
        Largest ``|q_i|`` reached so far, kept by error-controlled steppers as the scale
        of the relative tolerance (empty otherwise).
    counters : Counters
    status : int
        A :class:`rotorsim.errors.Status` value.
    factor_dt, factor_spin : float
        Step size and schedule value of the cached factorisation (NaN when none).
    factor_tangent : int
        Digest of the tangents in the cached factorisation (-1 when none).
    factor_kappa : float
        Contraction per unit speed difference of the cached factorisation when it is
        reused at other speeds [s/rad] (NaN until estimated; see
        :mod:`~rotorsim.time_integration.newmark_step`).
    history : array (k, n)
        Past accelerations of multistep methods, newest first (``(0, n)`` for one-step
        methods): the Adams stepper keeps ``a_{n-1}, a_{n-2}`` here.
    history_dt : float
        Uniform step of ``history`` (NaN when it is not uniform or empty).
    cache : object
        Runtime-only LU factors matching the three ``factor_*`` keys; never written to a
        checkpoint.
    """

    t: float
    q: FloatArray
    v: FloatArray
    a: FloatArray
    force: FloatArray
    step: int = 0
    dt: float = 0.0
    error: float = 0.0
    peak: FloatArray = field(default_factory=lambda: np.zeros(0))
    counters: Counters = field(default_factory=Counters)
    status: int = int(Status.OK)
    factor_dt: float = float("nan")
    factor_spin: float = float("nan")
    factor_tangent: int = -1
    factor_kappa: float = float("nan")
    history: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))
    history_dt: float = float("nan")
    cache: Any = field(default=None, compare=False, repr=False)

    RUNTIME_FIELDS: ClassVar[tuple[str, ...]] = ("cache",)
    """Fields that a checkpoint does not store."""


@runtime_checkable
class TimeStepper(Protocol):
    """What :func:`rotorsim.time_integration.integrate.integrate` needs of a method."""

    @property
    def name(self) -> str:
        """Method name used in results and checkpoints."""
        ...

    @property
    def order(self) -> int:
        """Declared global order of accuracy of ``q`` and ``v``."""
        ...

    def init(self, problem: SecondOrderProblem, t0: float, q0: FloatArray, v0: FloatArray,
             *, dt: float, a0: FloatArray | None = None) -> State:
        """State at ``t0``; ``dt`` is the first step size."""
        ...

    def step(self, problem: SecondOrderProblem, state: State) -> State:
        """Take one accepted step from ``state``."""
        ...

    def interpolate(self, old: State, new: State, t: FloatArray,
                    dofs: IntArray) -> tuple[FloatArray, FloatArray]:
        """``q`` and ``v`` (len(t), len(dofs)) at times ``old.t < t <= new.t``."""
        ...


def cubic_hermite(old: State, new: State, t: FloatArray,
                  dofs: IntArray) -> tuple[FloatArray, FloatArray]:
    """Cubic Hermite interpolant of ``q`` through both states with slopes ``v``.

    Parameters
    ----------
    old, new : State
        Consecutive accepted states.
    t : array (k,)
        Times in ``[old.t, new.t]`` [s].
    dofs : int array (m,)
        Unknowns to interpolate.

    Returns
    -------
    q, v : arrays (k, m)
        The cubic and its time derivative; exact at both ends (``q(new.t) = new.q``).
        Both are accurate to O(h^3) or better, more than the second-order methods need.

    Examples
    --------
    >>> z = np.zeros(1)
    >>> s0 = State(0.0, np.zeros(1), np.ones(1), z, z)
    >>> s1 = State(2.0, np.full(1, 2.0), np.ones(1), z, z)
    >>> q, v = cubic_hermite(s0, s1, np.array([0.5, 2.0]), np.arange(1))
    >>> q.ravel().tolist(), v.ravel().tolist()
    ([0.5, 2.0], [1.0, 1.0])
    """
    h = new.t - old.t
    s = ((np.asarray(t, dtype=float) - old.t) / h)[:, None]
    s2, s3 = s * s, s * s * s
    q0, q1 = old.q[dofs][None, :], new.q[dofs][None, :]
    v0, v1 = old.v[dofs][None, :], new.v[dofs][None, :]
    q = ((2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * h * v0
         + (3 * s2 - 2 * s3) * q1 + (s3 - s2) * h * v1)
    v = (6 * (s2 - s) / h * (q0 - q1) + (3 * s2 - 4 * s + 1) * v0 + (3 * s2 - 2 * s) * v1)
    return q, v


def retry_step(method: Any, ladder: Any, h: float, factor: float, t: float,
               step: int) -> float:
    """The next trial step [s] of an error-controlled implicit method after a rejected
    attempt of ``h`` [s]: ``h`` times the controller's ``factor``, kept within
    ``[method.min_shrink, 0.9]``, put on the method's step ladder (``ladder(h, dt_max)``)
    below ``method.dt_max``.

    Raises
    ------
    ConvergenceError
        The step fell below 1e-14 of ``t`` [s] (:func:`step_size_failure`).
    """
    h = ladder(h * max(method.min_shrink, min(factor, 0.9)), method.dt_max)
    if h < 1e-14 * max(abs(t), 1e-300):
        raise step_size_failure(method, h, t, step)
    return h


def step_size_failure(method: Any, h: float, t: float, step: int) -> ConvergenceError:
    """The error of a method that found no acceptable step at ``t`` [s] (the last trial
    ``h`` [s], after ``method.max_rejections`` rejections or below 1e-14 of ``t``)."""
    return ConvergenceError(f"step size {h:.3e} s after {method.max_rejections} rejections "
                            f"at t = {t:.9g} s", method.name, step=step)


def check_step_control(owner: str, method: Any,
                       extra: tuple[tuple[bool, str], ...] = ()) -> None:
    """ModelError naming the first bad step-control option of an error-controlled implicit
    method (``rtol``, ``max_newton``, ``max_growth``, ``min_shrink``, ``dt_max``,
    ``max_rejections``; ``extra``: the method's own ``(ok, need)`` checks)."""
    m = method
    checks = [(1e-12 <= m.rtol < 1.0, f"1e-12 <= rtol < 1, got {m.rtol!r}"), *extra,
              (m.max_newton >= 2, "max_newton >= 2"),
              (m.max_growth > 1.0 > m.min_shrink > 0.0, "max_growth > 1 > min_shrink > 0"),
              (m.dt_max > 0, "dt_max > 0"), (m.max_rejections >= 1, "max_rejections >= 1")]
    for ok, text in checks:
        if not ok:
            raise ModelError(f"need {text}", owner)
