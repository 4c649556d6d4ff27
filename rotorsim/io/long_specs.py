"""Specs of the long analyses, each of which can resume: time integration and
harmonic-balance branches (checkpoint files, :class:`RestartableSpec`) and parameter
sweeps (their results store is the checkpoint).

Transients and periodic branches run with the rolling bearings' full nonlinear force.
Each spec holds the options of one ``rotorsim`` verb in SI units; the common reporting
options are those of :class:`~rotorsim.io.analysis_spec.AnalysisSpec`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from rotorsim.errors import ModelError
from rotorsim.io.analysis_spec import AnalysisSpec, Grid, Unbalance
from rotorsim.options import (
    Checkpointing,
    ContinuationOptions,
    Harmonics,
    Output,
    StabilityOptions,
    SteadyStop,
)


@dataclass(frozen=True, kw_only=True)
class RestartableSpec(AnalysisSpec):
    """Checkpoint options of a long analysis (a transient or a periodic branch).

    Parameters
    ----------
    checkpoint : bool
        Write a checkpoint file (``<out>/<model>/<analysis>.checkpoint.h5`` on the command
        line) every ``checkpointing.every`` steps or branch points and at the end.
    resume : bool
        Continue from that checkpoint when it exists (same model and options, else a
        :class:`~rotorsim.time_integration.checkpoint.CheckpointError`); the result equals
        that of an uninterrupted run.
    checkpointing : Checkpointing
        Steps (transient, default 1000) or branch points (periodic, default 25) between
        checkpoints (key ``checkpoint_every``); the file and resume come from the flags
        above.
    """

    FILE_OPTIONS: ClassVar[dict[str, tuple[str, ...]]] = {"checkpointing": ("every",)}
    checkpoint: bool = False
    resume: bool = False
    checkpointing: Checkpointing = Checkpointing()  # noqa: RUF009  (frozen)


LAW_KEYS: dict[str, tuple[str, ...]] = {
    "constant": ("torque", "reactive"),
    "quadratic": ("coefficient",),
    "viscous": ("coefficient",),
    "curve": ("speeds", "torques", "reactive"),
    "induction": ("breakdown_torque", "breakdown_slip", "synchronous_speed"),
}
"""Torque-law types of model files and their keys (SI: N m, N m s^2/rad^2, N m s/rad,
rad/s); a motor may add ``ripple = {amplitude, order, phase}``."""

Law = dict[str, Any]


@dataclass(frozen=True, eq=False)
class DriveSpec:
    """The ``drive`` of a transient analysis (:class:`rotorsim.TorqueDrive`): the motor
    at ``node``, loads and friction ``(node, law)``, the polar inertia [kg m^2] (None: the
    model's) and the torque damping switch; laws as ``{"type": ..., <SI keys>}``
    (:data:`LAW_KEYS`), turned into law objects by :mod:`rotorsim.io.drive_build`.

    Examples
    --------
    >>> spec = DriveSpec(node=0, motor={"type": "constant", "torque": 15.0},
    ...                  loads=((4, {"type": "quadratic", "coefficient": 1e-3}),))
    >>> spec.to_toml()["loads"]
    [{'node': 4, 'type': 'quadratic', 'coefficient': 0.001}]
    """

    node: int
    motor: Law
    loads: tuple[tuple[int, Law], ...] = ()
    friction: tuple[tuple[int, Law], ...] = ()
    inertia: float | None = None
    torque_damping: bool = True

    def to_toml(self) -> dict[str, Any]:
        """Model-file form in SI numbers."""
        out: dict[str, Any] = {"node": self.node, "motor": dict(self.motor)}
        for key in ("loads", "friction"):
            items = getattr(self, key)
            if items:
                out[key] = [{"node": node, **law} for node, law in items]
        if self.inertia is not None:
            out["inertia"] = self.inertia
        if not self.torque_damping:
            out["torque_damping"] = False
        return out


RTOL_RANGE = (1e-10, 0.1)
"""Accuracies ``rtol`` that ``rs.transient`` accepts (checked there again)."""
AUTO_METHOD = "auto"
"""The error-controlled method that ``rtol`` sets the accuracy of."""


def accuracy_problem(dt: float | None, rtol: float | None,
                     method: str | None) -> tuple[str, str] | None:
    """What is wrong with the step options of a transient, as ``(message, key)``, or None:
    a fixed step ``dt`` [s] or the accuracy ``rtol`` of the error-controlled method
    ``"auto"``, one of them (``method = "auto"`` alone runs at ``rs.transient``'s default
    accuracy)."""
    auto = method == AUTO_METHOD
    if rtol is not None:
        if not (isinstance(rtol, int | float) and not isinstance(rtol, bool)
                and RTOL_RANGE[0] <= rtol <= RTOL_RANGE[1]):
            return (f"rtol must be a number in [{RTOL_RANGE[0]:g}, {RTOL_RANGE[1]:g}] (the "
                    f"accuracy relative to the motion, e.g. 1e-4), got {rtol!r}", "rtol")
        if dt is not None:
            return ("give dt (a fixed step) or rtol (the accuracy of the error-controlled "
                    "method 'auto', which chooses its own steps), not both", "rtol")
        if method is not None and not auto:
            return (f"rtol is the accuracy of method 'auto'; method {method!r} takes a fixed "
                    "dt instead", "rtol")
    if dt is None and rtol is None and not auto:
        return ("give dt (a fixed step) or rtol (the accuracy of the error-controlled method "
                "'auto')", "dt")
    if dt is not None and auto:
        return ("method 'auto' chooses its own steps: give rtol (default 1e-4), not dt",
                "dt")
    return None


@dataclass(frozen=True, kw_only=True)
class TransientSpec(RestartableSpec):
    """Time integration: :func:`rotorsim.transient` over ``t_end`` [s] with step ``dt`` [s],
    or error-controlled at the accuracy ``rtol`` (relative to the motion; method
    ``"auto"``, :func:`accuracy_problem` says which combinations are valid), at constant
    ``speed`` [rad/s], or a linear ramp to ``speed_stop`` over ``ramp_time``
    [s] (default ``t_end``); ``unbalance=None`` uses the model's ``[[loads.unbalance]]``;
    rolling bearings act with their full nonlinear force. ``on_failure="stop"`` (default)
    keeps the run up to a failed step with status ``NOT_CONVERGED``; ``"raise"`` raises.
    ``output`` holds the kept samples, velocities and reducers (keys ``every``,
    ``velocities``, ``reducers``, ``after``); ``stop_when_steady`` stops the run once steady
    by the criterion of ``steady`` (keys ``steady_rtol``, ``steady_atol``,
    ``steady_revolutions``; the watched nodes are ``nodes``). With a ``drive``
    (:class:`DriveSpec`) the speed follows from torques (:class:`rotorsim.TorqueDrive`)
    and ``speed`` is the initial speed."""

    type: ClassVar[str] = "transient"
    FILE_OPTIONS: ClassVar[dict[str, tuple[str, ...]]] = {
        **RestartableSpec.FILE_OPTIONS, "output": ("every", "velocities", "reducers", "after"),
        "steady": ("rtol", "atol", "revolutions")}
    t_end: float
    dt: float | None = None
    rtol: float | None = None
    speed: float = 0.0
    speed_stop: float | None = None
    ramp_time: float | None = None
    method: str | None = None
    initial: str = "static"
    on_failure: str = "stop"
    unbalance: Unbalance | None = None
    output: Output = Output()  # noqa: RUF009  (frozen)
    drive: DriveSpec | None = None
    stop_when_steady: bool = False
    steady: SteadyStop = SteadyStop()  # noqa: RUF009  (frozen)

    def __post_init__(self) -> None:
        problem = accuracy_problem(self.dt, self.rtol, self.method)
        if problem is not None:
            raise ModelError(problem[0], f"transient.{problem[1]}")


_BRANCH_OPTIONS: dict[str, tuple[str, ...]] = {
    **RestartableSpec.FILE_OPTIONS, "harmonics": ("count", "samples"),
    "continuation": ("max_step", "max_points"), "stability": ("method",)}
"""Group fields of a harmonic-balance branch in model files (keys ``harmonics``,
``samples``, ``max_step``, ``max_points``, ``stability``, ``checkpoint_every``)."""


@dataclass(frozen=True, kw_only=True)
class PeriodicSpec(RestartableSpec):
    """Harmonic-balance branch over the speed range ``start`` .. ``stop`` [rad/s]:
    :func:`rotorsim.periodic` with its ``harmonics``, ``continuation`` and ``stability``
    groups (``stability = "none"`` skips the multipliers); ``unbalance=None`` uses the
    model's ``[[loads.unbalance]]``; rolling bearings act with their full nonlinear force."""

    type: ClassVar[str] = "periodic"
    FILE_OPTIONS: ClassVar[dict[str, tuple[str, ...]]] = _BRANCH_OPTIONS
    start: float
    stop: float
    varying_compliance: bool | None = None
    unbalance: Unbalance | None = None
    harmonics: Harmonics = Harmonics()  # noqa: RUF009  (frozen)
    continuation: ContinuationOptions = ContinuationOptions()  # noqa: RUF009  (frozen)
    stability: StabilityOptions = StabilityOptions()  # noqa: RUF009  (frozen)


@dataclass(frozen=True, kw_only=True)
class PeriodicParameterSpec(RestartableSpec):
    """Harmonic-balance branch at the fixed ``speed`` [rad/s] over the model parameter
    ``vary`` from ``start`` to ``stop`` (SI): :func:`rotorsim.periodic_parameter` with
    ``vary`` a key path of the model file
    (:class:`~rotorsim.io.model_parameter.ModelParameter`), ``"loads"`` (a factor on the
    model's point loads) or ``"forcing"`` (a factor on the unbalance), and the groups of
    :class:`PeriodicSpec`."""

    type: ClassVar[str] = "periodic_parameter"
    FILE_OPTIONS: ClassVar[dict[str, tuple[str, ...]]] = _BRANCH_OPTIONS
    vary: str
    speed: float
    start: float
    stop: float
    unbalance: Unbalance | None = None
    harmonics: Harmonics = Harmonics()  # noqa: RUF009  (frozen)
    continuation: ContinuationOptions = ContinuationOptions()  # noqa: RUF009  (frozen)
    stability: StabilityOptions = StabilityOptions()  # noqa: RUF009  (frozen)


@dataclass(frozen=True, kw_only=True)
class SweepSpec(AnalysisSpec):
    """Parameter study :func:`rotorsim.sweep`: support stiffness [N/m] of ``bearings``
    (indices, default all) over ``stiffness`` times spin speeds [rad/s] over ``speeds``
    (default 0), evaluating ``"min_log_dec"`` or ``"critical_speeds"`` with ``num_modes``.
    Points go to the results file as they finish (the file is the checkpoint); ``resume``
    continues from it."""

    type: ClassVar[str] = "sweep"
    stiffness: Grid
    speeds: Grid | None = None
    bearings: tuple[int, ...] | None = None
    evaluate: str = "min_log_dec"
    num_modes: int = 6
    resume: bool = False
