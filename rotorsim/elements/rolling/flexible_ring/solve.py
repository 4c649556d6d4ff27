"""The batched roller solve of the flexible-ring bearing: start, inner Newton, condensation.

For ``S`` samples of ``N`` rollers, :func:`solve_state` sets up the ``M = S N`` roller
problems (local DOFs of eq 3, centrifugal ``m omega_c^2`` of eq 18), starts them warm from
``internal`` or cold (:func:`cold_start`), minimises eq 19 over the internal DOFs by the
batched Newton method of :mod:`~rotorsim.elements.rolling.condensation` (eq 22), condenses
(eqs 25-26) and assembles the bearing force and tangent (eqs 6-7).

The cold start is a roller whose two contacts and two ring segments share the central
approach ``A = -g/2 - u_r`` (eqs 13, 21 with ``w_a = Q_a / k_a``,
``k_a = E A theta / R + E I theta / R^3`` at ``w = 0``)::

    delta_i + delta_e + Q_i / k_i + Q_e / k_e = A,   Q_e = Q_i + F_c,   Q_a = C L delta_a^n

In ``delta_i`` the left side is convex and increasing, so Newton from ``delta_i = A/2``
converges monotonically (clipped at 0: the roller rides on the outer ring). Without
centrifugal force and with a gap, the roller starts centred in the gap. Its tilt balances
the contact moments of two uniform contacts of tilt stiffness ``~ delta_a^(n-1)``:
``phi = gamma_n delta_e^(n-1) / (delta_i^(n-1) + delta_e^(n-1))`` (``gamma_n / 2`` for
equal contacts).

References
----------
Seed 001 eqs 3, 6-7, 13, 18-26.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rotorsim.elements.rolling.condensation import InnerSolution, LocalProblem, condense
from rotorsim.elements.rolling.flexible_ring.geometry import FloatArray
from rotorsim.elements.rolling.flexible_ring.roller import RollerPotential
from rotorsim.elements.rolling.flexible_ring.state import FlexibleRingState, assemble
from rotorsim.errors import ConvergenceError, ModelError

_COLD_ITERATIONS = 6
"""Newton iterations of the scalar cold-start equation (quadratic, monotone)."""


def local_dofs(delta: FloatArray, psi: FloatArray, tilt: bool) -> FloatArray:
    """``z = [u_r, gamma_n]`` (2, S N) of every roller (eq 3 with ``y_rel = -delta``)."""
    c, s = np.cos(psi), np.sin(psi)
    z = np.zeros((2, psi.size))
    z[0] = (-(delta[:, :1] * c + delta[:, 1:2] * s)).reshape(-1)
    if tilt:
        z[1] = (delta[:, 3:4] * s - delta[:, 4:5] * c).reshape(-1)
    return z


def cold_start(pot: RollerPotential, z: FloatArray, m_omega2: FloatArray) -> FloatArray:
    """Cold-start internal DOFs (4, M) (module docstring)."""
    n = pot.exponent
    c_l = pot.contact_constant * float(pot.slices.widths.sum())
    rigid = 2 not in pot.internal
    comp = [0.0 if rigid else 1.0 / (kt + ei / r**3)  # ring compliances [m/N]
            for kt, ei, r in (pot.inner_ring, pot.outer_ring)]
    fc = m_omega2 * pot.pitch_radius / c_l  # F_c / (C L) [m^n]
    gap = -0.5 * pot.clearance - z[0]
    approach = np.maximum(gap, 0.0)
    d_i = 0.5 * approach
    for _ in range(_COLD_ITERATIONS):
        p = d_i ** (n - 1.0)
        d_e = (p * d_i + fc) ** (1.0 / n)
        slope_e = p * np.where(d_e > 0.0, d_e, 1.0) ** (1.0 - n)
        res = d_i + d_e + c_l * (p * d_i * (comp[0] + comp[1]) + fc * comp[1]) - approach
        d_i = np.maximum(d_i - res / (1.0 + slope_e + n * c_l * p * (comp[0] + comp[1])),
                         0.0)
    q_i = c_l * d_i**n
    d_e = (d_i**n + fc) ** (1.0 / n)
    d_e = np.where((fc == 0.0) & (gap < 0.0), 0.5 * gap, d_e)  # centred in the gap
    cold = np.zeros((4, z.shape[1]))
    cold[2], cold[3] = q_i * comp[0], (q_i + c_l * fc) * comp[1]
    cold[0] = d_e + 0.25 * pot.clearance + z[0] + cold[3]
    # tilt: equal contact moments, k_i phi = k_e (gamma - phi), k_a ~ delta_a^(n-1)
    k_i, k_e = np.maximum(d_i, 0.0) ** (n - 1.0), np.maximum(d_e, 0.0) ** (n - 1.0)
    total = k_i + k_e
    cold[1] = z[1] * np.where(total > 0.0, k_e / np.where(total > 0.0, total, 1.0), 0.5)
    return cold


def _start(bearing: Any, z: FloatArray, internal: Any, m_omega2: FloatArray) -> FloatArray:
    """Start (4, M): warm from ``internal`` (S, N, 4); NaN rows and ``None`` start cold."""
    size = z.shape[1]
    if internal is None:
        return cold_start(bearing.potential, z, m_omega2)
    guess = np.asarray(internal, dtype=float)
    if guess.size != size * 4 or guess.ndim != 3 or guess.shape[2] != 4:
        raise ModelError(f"internal must have shape (S, {bearing.n_rollers}, 4) "
                         f"(state.internal of a call with the same samples), got "
                         f"{guess.shape}", bearing.label)
    guess = np.array(guess.reshape(size, 4).T)
    nan = np.flatnonzero(~np.isfinite(guess).all(axis=0))
    if nan.size:
        guess[:, nan] = cold_start(bearing.potential, z[:, nan], m_omega2[nan])
    return guess


def newton_scales(bearing: Any) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Residual scale (gradient to force), step cap [m, rad] and pivot floor of the
    active internal DOFs; the length scale is ``|g|/2 + R_b / 1000``."""
    half = 0.5 * bearing.effective_length
    length = 0.5 * abs(bearing.diametral_clearance) + 1e-3 * bearing.roller_radius
    k_ref = bearing.exponent * bearing.line_constant * bearing.effective_length \
        * length ** (bearing.exponent - 1.0)
    scale = np.array([1.0, 1.0 / half, 1.0, 1.0])
    step = np.array([length, length / half, length, length])
    floor = 1e-9 * k_ref * np.array([1.0, half * half, 1.0, 1.0])
    idx = list(bearing.potential.internal)
    return scale[idx], step[idx], floor[idx]


def _raise(sol: InnerSolution, n_r: int, where: str) -> None:
    bad = np.flatnonzero(~sol.converged)
    first = int(bad[0])
    more = f" (and {bad.size - 1} more rollers)" if bad.size > 1 else ""
    raise ConvergenceError(
        f"inner Newton did not converge for roller {first % n_r} of sample "
        f"{first // n_r}{more}", where, iteration=sol.stats.iterations,
        residual=float(sol.residual[bad].max()))


def solve_state(bearing: Any, delta: FloatArray, psi: FloatArray, speed: FloatArray,
                internal: Any, details: bool) -> FlexibleRingState:
    """The state of a :class:`~rotorsim.elements.rolling.flexible_ring.bearing.
    FlexibleRingRollerBearing` at checked inputs ``delta`` (S, 5), ``psi`` (S, N) and
    ``speed`` (S,) (see its ``state``)."""
    n_s, n_r = psi.shape
    pot: RollerPotential = bearing.potential
    m_omega2 = np.repeat(bearing.mass * (bearing.centrifugal_cage_ratio * speed) ** 2, n_r)
    z = local_dofs(delta, psi, bearing.tilt)
    active = list(pot.internal)
    full = _start(bearing, z, internal, m_omega2)
    full[[k for k in range(4) if k not in active]] = 0.0

    def evaluate(y: FloatArray, index: np.ndarray) -> LocalProblem:
        full_y = np.zeros((4, y.shape[1]))
        full_y[active] = y
        return pot.evaluate(full_y, z[:, index], m_omega2[index])

    scale, step, floor = newton_scales(bearing)
    # far from the clearance (large displacements) the steps grow with |z|
    reach = np.abs(z[0]) + 0.5 * bearing.effective_length * np.abs(z[1])
    cap = step[:, None] * (1.0 + reach / step[0])
    sol = bearing.newton.solve(evaluate, full[active], n_r, scale, cap, floor,
                               1e-9 * bearing.Kn * step[0] ** bearing.exponent)
    if sol.stats.failures:
        _raise(sol, n_r, bearing.label)
    full[active] = sol.y
    g_star, h_star = condense(sol.local, len(active), floor)
    e = g_star.shape[0]
    force, stiffness = assemble(psi, g_star.reshape(e, n_s, n_r),
                                h_star.reshape(e, e, n_s, n_r))
    shape = (n_s, n_r)
    aux = sol.local.aux.reshape(3, *shape)
    slices: tuple[FloatArray | None, FloatArray | None] = (None, None)
    if details:
        det = pot.contacts(full, z)
        slices = (det.inner_slice_load.reshape(*shape, -1),
                  det.outer_slice_load.reshape(*shape, -1))
    internal_out = np.moveaxis(full.reshape(4, *shape), 0, -1)
    return FlexibleRingState(
        force=force, stiffness=stiffness, energy=sol.local.energy.reshape(shape).sum(axis=1),
        element_load=aux[0], contact_angle=np.zeros(shape), deflection=aux[2],
        outer_load=aux[1], internal=internal_out, iterations=sol.stats.iterations,
        ring_deflection=internal_out[..., 2:], slice_load=slices[0],
        outer_slice_load=slices[1], local_force=-np.moveaxis(g_star.reshape(e, *shape), 0, -1),
        local_stiffness=np.moveaxis(h_star.reshape(e, e, *shape), (0, 1), (2, 3)),
        inner=sol.stats)
