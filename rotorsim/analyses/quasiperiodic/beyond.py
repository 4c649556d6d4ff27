"""What a rotor does where its torus is unstable (issue 17 part 2).

Past a loss of stability the torus is still a solution of the harmonic balance, but not
the response. The motion is found by integrating the full model in time
(:func:`~rotorsim.transient`, rolling elements moving), started on the unstable torus with
a small random perturbation. The record, after ``settle`` revolutions, is then classified:

* **by its spectrum.** Least squares fit the nonlinear DOFs' signals on the tones
  ``(k1 w1 + k2 w2) / q``, ``|k1| <= a q``, ``|k2| <= b q``, for ``q = 1, 2, ...``. The
  box ``(a, b)`` is the torus's. The first ``q`` whose tones leave at most
  :data:`UNEXPLAINED` of every signal's variance unexplained is the motion's order:
  * ``q = 1``: a torus of the same two frequencies. The motion either stays on the
    unstable torus or has jumped to another torus.
  * ``q = 2``: a doubled torus.
  * ``q >= 3``: a torus locked to a subharmonic of order ``q``.

  A tone set is only tried while it has at most a third as many columns as the record
  has degrees of freedom in the band the tones cover (``2 f_max T / 2 pi``, ``T`` the
  record's length): a denser set fits any signal of that band (measured: a line at
  ``sqrt(2) / 7`` of the shaft speed, in no tone set, was "explained" by the 425 columns
  of order 4 over a record of 749 degrees of freedom). Orders beyond that are reported as
  not tried (a longer record tries them).
* **by its largest Lyapunov exponent**, from a twin: once settled, the record and a twin
  started :data:`TWIN` of the motion away are integrated side by side, and the exponent is
  the growth rate of their distance (displacements, and velocities over ``W``), fitted
  between 100 times the start and 1e-2 of the motion. When no order explains the record
  and the twins grow apart by :data:`GROWTH` within it, at a rate above
  ``ln(GROWTH) / T``, the motion is ``"chaotic"``. Otherwise it is quasi-periodic with a
  third frequency, and its strongest line is reported.

  Exponential divergence of nearby trajectories is the defining property of chaos, and it
  is robust: past the textbook rotor's fold the twins part by nine decades in 20
  revolutions. A Benettin estimate along the record (the variational equation,
  :func:`~rotorsim.harmonic_balance.quasi.lyapunov.trajectory_lyapunov_exponent`) was
  tried first. It needs the Hertz contacts resolved, so it read +58 1/s at T / 256 and +82
  at T / 512 against the twins' 105-174. Its verdict over 30 recorded revolutions also
  changed with the BLAS kernel (chaos amplifies round-off): +145 against a three-sigma
  resolution of 80 under one kernel, +54 against 133 under another.

The spectral test needs no threshold on amplitudes, and a chaotic signal is never
explained to 1e-3 of its variance by a few hundred lines.

References
----------
G. Benettin et al., *Meccanica* 15 (1980) 9-20 (Lyapunov exponents); issue 17 part 2.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rotorsim.errors import ModelError
from rotorsim.results.torus_motion import KINDS, MotionBeyond

FloatArray = NDArray[np.float64]
UNEXPLAINED = 1e-3
"""Largest share of a signal's variance a tone set may leave for it to explain the signal."""
ORDERS = 4
"""Subharmonic orders ``q`` tried."""
SAMPLES_PER_REVOLUTION = 256
"""Time steps of the transient per shaft revolution, each one a sample of the record and a
step of the variational equation. Measured on the textbook rigid rotor at 1300 rad/s: 128
steps of the variational equation per revolution gave a trajectory exponent of +37 1/s,
256 and 512 gave -6 1/s (the Hertz contacts' stiffness needs the finer step)."""
FIT_EVERY = 2
"""The spectral fit takes every second sample (128 per revolution: above twice the highest
tone of the boxes used, and a quarter of the least squares cost)."""
PERTURBATION = 1e-3
"""Size of the random start perturbation, as a fraction of the torus's largest motion."""
STAYS = 1e-2
"""Largest distance from the torus, as a fraction of its peak-to-peak, of a motion that
stays on it."""
TWIN = 1e-9
"""Distance of the twin trajectory's start from the record's, as a fraction of the torus's
largest motion."""
GROWTH = 1e4
"""Growth of the twins' distance within the record that marks exponential divergence."""
def tones(w1: float, w2: float, box: tuple[int, int], q: int) -> FloatArray:
    """Distinct positive frequencies ``(k1 w1 + k2 w2) / q`` [rad/s] with ``|k1| <= a q``,
    ``|k2| <= b q``."""
    a, b = (int(v) * q for v in box)
    k1, k2 = np.meshgrid(np.arange(-a, a + 1), np.arange(-b, b + 1))
    f = np.abs(k1.ravel() * w1 + k2.ravel() * w2) / q
    f = np.sort(f[f > 1e-9 * max(w1, w2)])
    keep = np.concatenate([[True], np.diff(f) > 1e-9 * f[1:]])
    return np.asarray(f[keep])


def unexplained_share(t: FloatArray, signals: FloatArray, frequencies: FloatArray
                      ) -> tuple[float, FloatArray]:
    """Largest share of a signal's variance (columns of ``signals (S, m)``) left by a least
    squares fit on a mean and the ``frequencies`` [rad/s], and the residuals ``(S, m)``.
    Signals whose variance is below 1e-12 of the largest are skipped (held DOFs)."""
    basis = np.column_stack([np.ones_like(t), np.cos(np.outer(t, frequencies)),
                             np.sin(np.outer(t, frequencies))])
    coef, *_ = np.linalg.lstsq(basis, signals, rcond=None)
    residual = signals - basis @ coef
    var = signals.var(axis=0)
    live = var > 1e-12 * var.max(initial=0.0)
    if not live.any():
        return 0.0, residual
    return float((residual.var(axis=0)[live] / var[live]).max()), residual


def spectral_order(t: FloatArray, signals: FloatArray, w1: float, w2: float,
                   box: tuple[int, int], orders: int = ORDERS
                   ) -> tuple[int, FloatArray, float]:
    """``(order, unexplained, frequency)`` of a record (module docstring): the first ``q``
    whose tones explain every signal, the share each order leaves, and the strongest line
    [rad/s] left by the ``q = 1`` tones (NaN when they explain the record)."""
    shares = np.full(orders, np.nan)
    frequency, order = float("nan"), 0
    length = float(t[-1] - t[0])
    for q in range(1, orders + 1):
        f = tones(w1, w2, box, q)
        band = 2 * f.max(initial=0.0) * length / (2 * np.pi) + 1   # degrees of freedom
        if 3 * (2 * f.size + 1) > min(band, t.size):
            break
        shares[q - 1], residual = unexplained_share(t, signals, f)
        if q == 1 and shares[0] > UNEXPLAINED:
            frequency = strongest_line(t, residual)
        if shares[q - 1] <= UNEXPLAINED:
            order = q
            break
    return order, shares, frequency


def strongest_line(t: FloatArray, residual: FloatArray) -> float:
    """Frequency [rad/s] of the largest peak of the Hann-windowed spectra of ``residual``
    (summed over its columns)."""
    window = np.hanning(t.size)[:, None]
    power = (np.abs(np.fft.rfft((residual - residual.mean(axis=0)) * window, axis=0)) ** 2
             ).sum(axis=1)
    freq = 2 * np.pi * np.fft.rfftfreq(t.size, float(t[1] - t[0]))
    return float(freq[1 + int(np.argmax(power[1:]))])


def motion_beyond(point: Any, unbalance: Any, excitation: Any, *, settle: int = 40,
                  record: int = 60, seed: int = 0,
                  samples: int = SAMPLES_PER_REVOLUTION) -> MotionBeyond:
    """The motion at the speed of the torus ``point`` (a
    :class:`~rotorsim.analyses.quasiperiodic.point.QuasiPeriodicPoint`), from a transient
    started next to it (module docstring).

    Parameters
    ----------
    unbalance, excitation
        Those the torus was computed with (``rs.transient``'s).
    settle, record : int
        Shaft revolutions run before the record, and recorded.
    seed : int
        Of the start perturbation.
    samples : int
        Time steps, and samples of the record, per revolution.

    Raises
    ------
    ModelError
        ``point`` is not a torus point, or ``settle < 0``, ``record < 4`` or
        ``samples < 16``.
    """
    from rotorsim.analyses.transient.transient import transient  # analyses above this one

    if not all(hasattr(point, name) for name in ("solution", "rotor_problem", "system")):
        raise ModelError(f"point must be a QuasiPeriodicPoint (rs.quasi_periodic_point or a "
                         f"branch's points), got {type(point).__name__}", "motion_beyond")
    if settle < 0 or record < 4 or samples < 16:
        raise ModelError(f"need settle >= 0 and record >= 4 revolutions and samples >= 16, "
                         f"got {settle}, {record} and {samples}", "motion_beyond")
    sol, rp = point.solution, point.rotor_problem
    w1, w2 = float(sol.w1), float(sol.w2)
    revolution = 2 * np.pi / w1
    spacing = revolution / samples
    nl = np.asarray(rp.problem.nl_dofs, dtype=np.int64)
    active = point.system.dof_map.free[rp.active]
    q0, v0 = point.state(0.0)
    rng = np.random.default_rng(seed)
    size = float(np.abs(sol.X[1:]).sum(axis=0).max(initial=0.0)) or 1e-9
    q0[active] += PERTURBATION * size * rng.uniform(-1.0, 1.0, active.size)
    t_end = (settle + record) * revolution
    kw: dict[str, Any] = dict(speed=w1, unbalance=unbalance, excitation=excitation,
                              method="average_acceleration")
    t_s, q_s, v_s = 0.0, q0, v0
    if settle > 0:
        final = transient(point.system, settle * revolution, spacing, initial=(q0, v0),
                          **kw).final
        assert final is not None
        free = point.system.dof_map.free
        t_s, q_s, v_s = float(final.t), np.zeros_like(q0), np.zeros_like(v0)
        q_s[free], v_s[free] = final.q, final.v
    times = np.minimum(t_s + spacing * np.arange(record * samples + 1), t_end)
    twin_q = q_s.copy()
    twin_q[active] += TWIN * size * rng.standard_normal(active.size)
    # the record and its twin restart alike from arrays, so that their difference is the
    # twin's perturbation, grown
    run, twin = (transient(point.system, (t_s, t_end), spacing, initial=(q, v_s),
                           output=_output(times), **kw) for q in (q_s, twin_q))
    columns = [int(np.flatnonzero(run.dofs == dof)[0]) for dof in active[nl]]
    t = np.asarray(run.t)
    q = np.asarray(run.q)[:, columns]
    order, shares, frequency = spectral_order(t[::FIT_EVERY], q[::FIT_EVERY], w1, w2,
                                              _box(sol))
    torus = sol.evaluate(t, nl)
    departure = float((np.abs(q - torus).max(axis=0) /
                       np.maximum(np.ptp(torus, axis=0), 1e-300)).max())
    exponent, grew = twin_exponent(t, run, twin, w1, size)
    resolution = float(np.log(GROWTH) / (t[-1] - t[0]))
    kind = _kind(order, departure, exponent if grew else -np.inf, resolution)
    return MotionBeyond(float(point.speed), kind, order, shares,
                        float("nan") if order == 1 else frequency, exponent, resolution,
                        departure, (int(settle), int(record)))


def twin_exponent(t: FloatArray, run: Any, twin: Any, w: float, size: float
                  ) -> tuple[float, bool]:
    """Largest Lyapunov exponent [1/s] of a record from its twin (module docstring), and
    whether the twin grew apart by :data:`GROWTH`: the slope of ``ln d(t)``, ``d`` the
    distance of displacements and velocities over ``w`` [rad/s], fitted where ``d`` lies
    between 100 times its start and 1e-2 of ``size`` [m] (past the alignment with the most
    unstable direction, before saturation), or over the whole record when it never does."""
    dq = np.asarray(run.q) - np.asarray(twin.q)
    dv = (np.asarray(run.v) - np.asarray(twin.v)) / w
    d = np.sqrt((dq * dq).sum(axis=1) + (dv * dv).sum(axis=1))
    d = np.maximum(d, np.finfo(float).tiny)
    window = (d > 100 * d[0]) & (d < 1e-2 * size)
    if np.count_nonzero(window) < 3:
        window = np.ones(d.size, dtype=bool)
    slope = float(np.polyfit(t[window], np.log(d[window]), 1)[0])
    return slope, bool(d.max() >= GROWTH * d[0])


def _kind(order: int, departure: float, lyapunov: float, resolution: float) -> str:
    if order == 1:
        return KINDS[0] if departure <= STAYS else KINDS[1]
    if order == 2:
        return KINDS[2]
    if order >= 3:
        return KINDS[3]
    return KINDS[4] if lyapunov > resolution else KINDS[5]


def _box(solution: Any) -> tuple[int, int]:
    k = np.abs(np.asarray(solution.aft.harmonics.k))
    return int(k[:, 0].max()), int(k[:, 1].max())


def _output(times: Any) -> Any:
    from rotorsim.options import Output

    return Output(times=times, velocities=True)
