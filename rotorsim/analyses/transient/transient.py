"""Transient response of a rotor on linear and nonlinear bearings (time integration).

``transient`` builds ``M q'' + (C + W(t) G) q' + K q + r(q, q', phi(t), W(t)) = f(t)`` from
the assembled rotor (DESIGN section 3), integrates it with a stepper of
:mod:`rotorsim.time_integration` (Newmark family by default, the enhanced Adams method, or
either under adaptive step control) and returns a :class:`TransientResult` with the kept
DOFs, the speed and angle histories and the load of every nonlinear bearing. The bearing
tangents are local to the bearing DOFs, so the implicit steppers factorise the linear part
once per step size and speed and update it by a low-rank solve in each Newton iteration.

The initial state is, by default, the static equilibrium under the constant loads (gravity
and point loads) at the starting speed and angle, at rest: a balanced rotor then stays at
rest up to the varying compliance of its bearings.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from rotorsim.analyses.keyword_check import checked_keywords
from rotorsim.analyses.statics.linearized_rotor import rolling_start
from rotorsim.analyses.transient import continuation as cont
from rotorsim.analyses.transient import run_control
from rotorsim.analyses.transient.arguments import check_step_count, system_of, time_span
from rotorsim.analyses.transient.equation import rotor_problem
from rotorsim.analyses.transient.loads import (
    BaseExcitation,
)
from rotorsim.analyses.transient.speed_profile import BoundSpeed, SpeedProfile, as_speed_profile
from rotorsim.analyses.transient.start import initial_state
from rotorsim.analyses.transient.torque_drive import BoundTorqueDrive, TorqueDrive
from rotorsim.analyses.transient.torsion_loads import bind_speed
from rotorsim.analyses.transient.variable_bearings import (
    model_identity,
)
from rotorsim.assembly.system import RotorSystem
from rotorsim.elements.base import DOFS_PER_NODE, FloatArray, NonlinearElement
from rotorsim.errors import ModelError
from rotorsim.model.rotor import Rotor
from rotorsim.options import Checkpointing, Excitation, Output, SteadyStop
from rotorsim.results.transient import TransientResult
from rotorsim.results.transient_state import TransientState
from rotorsim.solvers.threads import one_blas_thread
from rotorsim.time_integration.adams import Adams
from rotorsim.time_integration.adaptive import Adaptive
from rotorsim.time_integration.base import TimeStepper
from rotorsim.time_integration.exponential_modes import IllConditionedModes
from rotorsim.time_integration.integrate import IntegrationResult, integrate
from rotorsim.time_integration.newmark import Newmark

WHERE = "transient"
AUTO_FIRST_STEPS = 1000
"""Without ``dt`` the first trial step is the span over this (the error control adapts
it at once)."""
OUTPUT_DEFAULTS = Output(every=1)
CHECKPOINT_DEFAULTS = Checkpointing(every=1000)
"""Defaults of the group fields left at None."""


@checked_keywords
@one_blas_thread()  # the static start and the reduction too, not only the steps
def transient(
    model: Rotor | RotorSystem,
    t_end: float | Sequence[float],
    dt: float | None = None,
    *,
    nonlinear: Sequence[NonlinearElement] = (),
    speed: float | SpeedProfile | TorqueDrive | Callable[[float], float] = 0.0,
    unbalance: Sequence[tuple[int, float, float]] = (),
    excitation: Excitation | None = None,
    method: str | TimeStepper | None = None,
    rtol: float | None = None,
    initial: str | tuple[ArrayLike, ArrayLike] | TransientResult | TransientState = "static",
    nodes: Sequence[int] | None = None,
    output: Output | None = None,
    checkpoint: str | os.PathLike[str] | Checkpointing | None = None,
    reduction: int | bool | None = None,
    on_failure: str = "raise",
    steady: SteadyStop | None = None,
) -> TransientResult:
    """Integrate the rotor's equation of motion from 0 (or ``t0``) to ``t_end``.

    Parameters
    ----------
    model : Rotor or RotorSystem
        The rotor with its linear bearings and its nonlinear elements (rolling bearings),
        or a RotorSystem assembled with them.
    t_end : float or (t0, t_end)
        End time [s] (from 0, or from the end of the run given as ``initial``), or the
        time span.
    dt : float, optional
        Time step [s] (first trial step when adaptive). Without it the run is
        error-controlled (``method="auto"``).
    nonlinear : sequence of NonlinearElement
        More nonlinear elements, e.g.
        :class:`~rotorsim.elements.rolling.element.RollingBearing` (with a Rotor only).
    speed : float, callable, speed profile or TorqueDrive
        Spin speed [rad/s]: a constant, :class:`~.speed_profile.LinearSpeed` (run-up or
        coast-down), :class:`~.speed_profile.SpeedFunction` or any ``W(t)``; or a
        :class:`~.torque_drive.TorqueDrive`: the speed then follows from motor, load and
        friction torques, the torsional DOFs are loaded by them, and
        ``options["spin_feedback"]`` reports the neglected torque of the lateral motion.
    unbalance : list of (node, me, angle)
        Unbalances [kg m, rad] rotating with the shaft angle ``phi(t)``, with the
        angular-acceleration term (module :mod:`~.transient_loads`); or
        ``excitation.unbalance``, not both.
    excitation : Excitation, optional
        Gravity [m/s^2] (None for none) and its direction, constant point forces and
        moments [N, N m], ``forces(t)`` -> array (n_free,) of extra loads on the free DOFs
        (``system.dofs_of(node, dofs)`` gives indices) and ``base``: a
        :class:`~.transient_loads.BaseExcitation` (acceleration of the base, seed 002
        eq 3.43; coordinates are then relative to it). Default: standard gravity along
        ``-y``, nothing else.
    method : str or TimeStepper
        ``"average_acceleration"`` (default, alias ``"newmark"``), ``"linear_acceleration"``,
        ``"hht"``,
        ``"generalized_alpha"``, ``"adams"`` (enhanced 4th-order Adams, seed 002 App. F),
        ``"adaptive"`` (error-controlled average acceleration), ``"auto"`` (the
        error-controlled fifth-order Radau IIA at ``rtol`` of the motion, module
        :mod:`~.auto`) or a stepper object. Default: ``"auto"`` when ``dt`` is omitted or
        ``rtol`` is given, else ``"average_acceleration"``.
    rtol : float, optional
        Accuracy asked of the automatic path, relative to the motion (default 1e-4).
    initial : {"static", "zero"}, (q0, v0) or TransientResult
        Static equilibrium at rest (default), zero, given displacements and velocities
        on ALL DOFs (``6 * n_nodes``), or a finished run to continue
        (:mod:`~.continuation`): from its end time, with its final state (the stepper's
        too, so the result equals an uninterrupted run up to round-off) and its final
        shaft angle; same model, method and reduction, and a ``speed`` that continues its
        final speed.
    nodes : sequence of int, optional
        Nodes whose DOFs are kept (default all); the nonlinear elements' DOFs are always
        kept to compute the bearing loads (or ``output.nodes``, not both).
    output : Output, optional
        Kept nodes; every n-th step (default 1, ignored with ``times``) or the sample
        times [s] (dense output by the stepper's interpolant); the load and contact angle
        of every rolling element of each bearing at every sample (``rolling_elements``:
        ``result.element_loads``, ``result.contact_angles``); the velocities (default not
        kept); reducers of the kept DOFs over every step (``result.reduced``: max_abs,
        peak-to-peak per revolution, radial max_amplitude, rms, from ``after`` on); the
        progress bar.
    checkpoint : path or Checkpointing, optional
        As in :func:`~rotorsim.time_integration.integrate.integrate`: an HDF5 checkpoint
        every ``every`` steps (default 1000), resume from one (same result as an
        uninterrupted run).
    reduction : int or False, optional
        Craig-Bampton reduction of the linear part with this many fixed-interface modes,
        the nonlinear DOFs kept physical (:mod:`~.transient_reduction`); the accuracy check
        is in ``result.options["reduction"]``. Left out on the automatic path, the
        reduction is chosen (or not) from ``rtol`` by a-priori checks
        (:mod:`~.auto_reduction`; the decision is in ``result.options["auto_reduction"]``);
        ``False`` integrates the full model.
    on_failure : {"raise", "stop"}
        When a step fails: raise, or return the run up to the last accepted step with
        ``status`` ``NOT_CONVERGED`` and the error in ``options["failure"]`` (what the
        command line does: partial results are written and the exit code is 3).
    steady : SteadyStop, optional
        Stop at the end of a shaft revolution once the per-revolution peak-to-peak of the
        watched DOFs has settled (status ``OK``; ``result.stopped`` says why and when).

    Returns
    -------
    TransientResult

    Raises
    ------
    ModelError
        For bad input (checked before the first step): ``dt <= 0``, an empty span, a speed
        function returning NaN, unknown nodes or method, speed-dependent linear bearings
        with a varying speed.
    ConvergenceError
        When a step diverges (time, step, iteration and worst DOF in the message); the last
        checkpoint is kept.

    Examples
    --------
    >>> import rotorsim as rs
    >>> steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    >>> shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel)] * 4
    >>> rotor = rs.Rotor(shaft, bearing_elements=[rs.BearingElement(n=0, kxx=1e7, cxx=1e3),
    ...                                           rs.BearingElement(n=4, kxx=1e7, cxx=1e3)])
    >>> res = transient(rotor, 0.05, 1e-4, speed=300.0, unbalance=[(2, 1e-4, 0.0)],
    ...                 excitation=rs.Excitation(gravity=None), initial="zero", nodes=[2])
    >>> res.q.shape, res.dof_labels[:2]
    ((501, 6), ['node 2 ux', 'node 2 uy'])
    """
    ex, out, ck = _groups(unbalance, excitation, nodes, output, checkpoint)
    auto = method == "auto" or (method is None and (dt is None or rtol is not None))
    if dt is not None and not (isinstance(dt, int | float) and np.isfinite(dt) and dt > 0):
        raise ModelError(f"dt must be a positive number [s], got {dt!r}", f"{WHERE}.dt")
    if reduction is True:
        raise ModelError("reduction is a number of modes, or False for none",
                         f"{WHERE}.reduction")
    if rtol is not None and not auto:
        raise ModelError(f"rtol is the accuracy of method='auto', not of {method!r}",
                         f"{WHERE}.rtol")
    if dt is None and not auto:
        raise ModelError("give dt, or leave method to 'auto'", f"{WHERE}.dt")
    system = system_of(model, nonlinear)
    previous = cont.previous_state(initial)
    t0, t_end = time_span(t_end) if previous is None else cont.continued_span(previous, t_end)
    if dt is not None:
        check_step_count(dt, t_end - t0)
    dt = (t_end - t0) / AUTO_FIRST_STEPS if dt is None else dt
    schedule = as_speed_profile(speed) if not isinstance(speed, TorqueDrive) else speed
    if previous is not None:
        schedule = cont.continued_speed(schedule, previous)
    profile = bind_speed(schedule, system, model if isinstance(model, Rotor) else None,
                         (t0, t_end), max(4096, int((t_end - t0) / dt)))
    problem, loads_fn = rotor_problem(system, profile, t0, ex)
    stepper = _stepper("average_acceleration" if method is None else method) \
        if not auto else None
    q0: FloatArray | None = None
    v0: FloatArray | None = None
    if previous is None:
        start = None
        if initial == "static" and isinstance(model, Rotor) and system.nonlinear is not None:
            start = rolling_start(model, nonlinear, system, ex.gravity, ex.direction,
                                  list(ex.loads), profile.speed(t0), profile.angle(t0))
        q0, v0 = initial_state(system, initial, loads_fn.constant, profile, t0, start)  # type: ignore[arg-type]
    else:
        cont.check_start(previous, system, profile, t0)
    kept = _kept_dofs(system, out.nodes)
    if isinstance(profile, BoundTorqueDrive) and out.nodes is not None and ex.unbalance:
        # the spin-feedback report needs the motion of the unbalance nodes
        kept = np.union1d(kept, _kept_dofs(system, [int(u[0]) for u in ex.unbalance]))
    full, basis, report, full_q0 = problem, None, None, q0
    basis_speed = profile.speed(t0) if previous is None else previous.reduction_speed
    if reduction is not None and reduction is not False:
        from rotorsim.analyses.transient.reduction import reduce_problem

        if problem.speed_terms is not None:
            raise ModelError("reduction keeps only rolling-bearing DOFs physical; with "
                             "speed-dependent bearings at a varying speed run without it",
                             f"{WHERE}.reduction")

        problem, basis, report = reduce_problem(system, problem, loads_fn, int(reduction),
                                                basis_speed)
        if q0 is not None and v0 is not None:
            q0, v0 = basis.project(q0), basis.project(v0)
    decision, fallback = None, None
    if stepper is None:
        from rotorsim.analyses.transient.auto import DEFAULT_RTOL, auto_path

        if previous is not None and previous.reduction and reduction is None:
            raise ModelError(f"the run being continued was reduced to {previous.reduction} "
                             "coordinates: give its reduction (the modes of "
                             "options['reduction']) again", f"{WHERE}.reduction")
        may_reduce = reduction is None and previous is None and \
            not isinstance(profile, BoundTorqueDrive)
        start_q = full_q0 if full_q0 is not None else \
            previous.stepper.q  # type: ignore[union-attr]
        path = auto_path(system, (full, problem), loads_fn, profile, (t0, t_end), start_q,
                         DEFAULT_RTOL if rtol is None else rtol, basis, basis_speed,
                         may_reduce, None if previous is None else previous.method)
        stepper, decision, fallback = path.stepper, path.decision, path.fallback
        if path.basis is not None and basis is None:
            problem, basis, report = path.problem, path.basis, path.report
            if q0 is not None and v0 is not None:
                # one least-squares solve for both (its SVD of T is most of the cost)
                q0, v0 = basis.project(np.column_stack([q0, v0])).T
    identity = model_identity(system, full)
    resumed = None if previous is None else cont.start_state(previous, identity, problem,
                                                            stepper, dt, basis)
    detector = run_control.steady_detector(steady, out.nodes, system, basis, profile)
    def run_with(stepper: TimeStepper) -> IntegrationResult:
        return integrate(problem, stepper, (t0, t_end), q0, v0, dt=dt,
                         output=run_control.output_spec(out, system, kept, basis, profile),
                         checkpoint=ck.path, checkpoint_every=int(ck.every or 0),
                         resume=ck.resume, progress=out.progress, on_failure=on_failure,
                         start=resumed, stop_when=detector)

    try:
        run = run_with(stepper)
    except IllConditionedModes:  # exponential collocation refused the model at its start
        if fallback is None:
            raise
        stepper = fallback
        run = run_with(stepper)
    final = cont.final_state(run, identity, problem, basis, profile, dt, basis_speed)
    if basis is not None:
        run = run_control.expanded(run, basis, kept)
    options = {"t_span": [t0, t_end], "dt": dt, "method": stepper.name, "rtol": rtol,
               "speed": profile.describe(), "gravity": ex.gravity,
               "unbalance": [list(map(float, u)) for u in ex.unbalance],
               "base": None if ex.base is None else list(ex.base.direction),
               "initial": initial if isinstance(initial, str) else
               "given" if previous is None else "continued",
               "every": out.every, "reduction": report}
    if decision is not None:
        options["auto_reduction"] = decision
    if out.reducers:
        options["reducers"] = {"names": list(out.reducers), "after": out.after}
    if run.message:
        options["failure"] = run.message
    stopped = run_control.stop_record(run, detector, profile)
    if stopped is not None:
        options["stopped"] = stopped
    result = _result(system, run, profile, kept, options)
    result = dataclasses.replace(result, v=run_control.kept_velocities(run, out), final=final)
    if out.rolling_elements and system.nonlinear is not None:
        from rotorsim.analyses.transient.element_histories import rolling_element_histories

        loads_, angles = rolling_element_histories(system, result)
        result = dataclasses.replace(result, element_loads=loads_, contact_angles=angles)
    if isinstance(profile, BoundTorqueDrive):
        from rotorsim.analyses.transient.spin_feedback import with_spin_feedback

        g = 0.0 if ex.gravity is None else float(ex.gravity)
        direction = np.asarray(ex.direction, dtype=float)
        result = with_spin_feedback(result, profile, list(ex.unbalance),
                                    g * direction / np.linalg.norm(direction))
    return result


def _groups(unbalance: Sequence[tuple[int, float, float]], excitation: Excitation | None,
            nodes: Sequence[int] | None, output: Output | None,
            checkpoint: str | os.PathLike[str] | Checkpointing | None
            ) -> tuple[Excitation, Output, Checkpointing]:
    """The option groups of a call: shortcuts merged, defaults filled, errors naming
    ``transient.<keyword>``."""
    ex = Excitation.coerce(excitation, f"{WHERE}.excitation").merged(WHERE,
                                                                     unbalance=unbalance)
    if ex.base is not None and not isinstance(ex.base, BaseExcitation):
        raise ModelError(f"expected rs.BaseExcitation, got {type(ex.base).__name__}",
                         f"{WHERE}.excitation.base")
    out = Output.coerce(output, f"{WHERE}.output").merged(WHERE, nodes=nodes)
    ck = Checkpointing.coerce(checkpoint, f"{WHERE}.checkpoint")
    return ex, out.resolved(OUTPUT_DEFAULTS), ck.resolved(CHECKPOINT_DEFAULTS)


def _stepper(method: str | TimeStepper) -> TimeStepper:
    if not isinstance(method, str):
        if not isinstance(method, TimeStepper):
            raise ModelError(f"not a time stepper: {method!r}", f"{WHERE}.method")
        return method
    if method == "newmark":
        return Newmark.average_acceleration()
    if method == "adams":
        return Adams()
    if method == "adaptive":
        return Adaptive(Newmark.average_acceleration())
    try:
        return Newmark.from_name(method)
    except TypeError as exc:
        raise ModelError(f"{exc}, 'adams', 'adaptive' or 'auto'", f"{WHERE}.method") from None


def _kept_dofs(system: RotorSystem, nodes: Sequence[int] | None) -> np.ndarray:
    dm = system.dof_map
    if nodes is None:
        kept = np.arange(system.n_free)
    else:
        full: list[int] = []
        for node in nodes:
            if not 0 <= int(node) < dm.n_nodes:
                raise ModelError(f"node {node} outside 0..{dm.n_nodes - 1}", f"{WHERE}.nodes")
            full.extend(DOFS_PER_NODE * int(node) + k for k in range(DOFS_PER_NODE))
        free = dm.full_to_free[np.asarray(full, dtype=np.int64)]
        kept = free[free >= 0]
    if system.nonlinear is not None:
        kept = np.union1d(kept, system.nonlinear.dofs)
    return np.asarray(kept, dtype=np.int64)


def _result(system: RotorSystem, run: IntegrationResult, profile: BoundSpeed,
            kept: np.ndarray, options: dict[str, Any]) -> TransientResult:
    t = run.t
    speed = np.array([profile.speed(float(x)) for x in t])
    angle = np.array([profile.angle(float(x)) for x in t])
    accel = np.array([profile.acceleration(float(x)) for x in t])
    loads, tags, counts, kappa = _bearing_histories(system, run, angle, speed)
    return TransientResult(
        t=t, q=run.q, v=run.v, dofs=system.dof_map.free[kept], speed=speed, angle=angle,
        acceleration=accel, bearing_loads=loads, bearing_tags=tags,
        bearing_elements=counts, bearing_kappa=kappa, reduced=dict(run.reduced),
        dof_map=system.dof_map, nodes_pos=np.asarray(system.nodes_pos, dtype=float),
        method=run.method, options=options, stats=dict(run.stats), status=run.status,
        summary=dict(system.summary))


def _bearing_histories(system: RotorSystem, run: IntegrationResult,
                       angle: FloatArray, speed: FloatArray
                       ) -> tuple[FloatArray, tuple[str, ...], np.ndarray, FloatArray]:
    nl = system.nonlinear
    if nl is None:
        return (np.zeros((run.t.size, 0, 5)), (), np.zeros(0, dtype=np.int64), np.zeros(0))
    loads = run_control.bearing_loads(run, system, angle, speed)
    tags = tuple(str(getattr(el, "tag", None) or i) for i, el in enumerate(nl.elements))
    models = [getattr(el, "bearing", None) for el in nl.elements]
    counts = np.array([int(getattr(b, "n_elements", 0) or 0) for b in models], dtype=np.int64)
    kappa = np.array([float(getattr(b, "kappa", 0.0) or 0.0) for b in models])
    return loads, tags, counts, kappa
