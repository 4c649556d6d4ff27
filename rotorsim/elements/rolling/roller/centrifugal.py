"""Rollers with their centrifugal force: the roller between the rings in series.

The whole-roller law of :mod:`~rotorsim.elements.rolling.roller.bearing` (``Kn``, deflection
``delta(xi) = V + xi L omega - c(xi)`` along the roller) is split into an inner and an
outer line contact in series along the contact normal ``n_j``, each with the constant
``K_c = 2^n Kn`` and half the profile drop. The roller's internal DOFs (2 per roller) are
its approach ``a`` to the outer ring at its centre (its displacement along ``n_j``) and its
tilt ``b`` (tilt angle times ``L``) relative to the outer ring::

    delta_o(xi) = a + xi b - c(xi)/2,     delta_i(xi) = (V - a) + xi (L omega - b) - c(xi)/2

With ``I(v, w)`` the whole-roller integrals of ``v + xi w - c`` (so that
``K_c int delta_o^n = Kn I_load(2a, 2b)``), the roller potential is::

    Pi = Kn/2 [I_energy(2V - 2a, 2 L omega - 2b) + I_energy(2a, 2b)] - Fc cos(a0) a

``dPi/da = 0`` is the roller equilibrium along the normal ``Q_o = Q_i + Fc cos(a0)`` and
``dPi/db = 0`` the balance of the contact moments about the roller centre. At ``Fc = 0`` the
solution is the symmetric split ``a = V/2, b = L omega/2`` and the whole-roller law holds
exactly. The inner ring sees only the inner contact: its load ``Q_i = Kn I_load(2V - 2a, .)``
and moment give the force through seed 000 eq 10, and the condensed tangent per roller in
``(V, L omega)`` is ``K* = 2 n Kn [A_i - A_i (A_i + A_o)^-1 A_i]`` with ``A = [[T0, T1],
[T1, T2]]`` the tangent integrals ``int xi^p delta^(n-1)`` of each contact: inner and outer
stiffness in series (for an untilted roller ``k_i k_o / (k_i + k_o)``). A roller whose
approach ``V`` is below the outer deflection that ``Fc`` alone produces rides on the outer
race: ``Q_i = 0`` and it contributes nothing.

Tapered and angular-contact rollers: the model has one contact angle ``a0`` for both
raceways and moves the roller along ``n_j``; the component ``Fc cos(a0)`` along the normal
loads the outer contact, the component ``Fc sin(a0)`` along the roller axis is assumed to be
taken by the guide flange (rib) and does not reach the raceways. A real tapered roller
bearing has a steeper cup than cone, which shares ``Fc`` differently; thrust rollers
(``a0 = 90`` deg) are unaffected.
"""

from __future__ import annotations

import dataclasses
import math
from functools import partial
from typing import Any

import numpy as np

from rotorsim.elements.rolling.element_equilibrium import (
    ElementEvaluation,
    Mask,
    check_solution,
    solve_elements,
)
from rotorsim.elements.rolling.roller.integrals import (
    LineIntegrals,
    assemble_tangent,
    unit_load_directions,
)
from rotorsim.elements.rolling.state import BearingState, FloatArray


def _evaluate(x: FloatArray, mask: Mask | None, model: Any, v: FloatArray, lw: FloatArray,
              fn: FloatArray) -> ElementEvaluation:
    if mask is not None:
        v, lw, fn = v[mask], lw[mask], fn[mask]
    a2, b2 = 2.0 * x[..., 0], 2.0 * x[..., 1]
    inner = model._line.integrals(2.0 * v - a2, 2.0 * lw - b2)
    outer = model._line.integrals(a2, b2)
    kn, n = model.kn, float(model.exponent)
    energy = 0.5 * kn * (inner.energy + outer.energy) - fn * x[..., 0]
    grad = np.stack([kn * (outer.load - inner.load) - fn,
                     kn * (outer.load_moment - inner.load_moment)], axis=-1)
    c = 2.0 * n * kn
    hess = np.stack([c * (inner.tangent0 + outer.tangent0), c * (inner.tangent1
                     + outer.tangent1), c * (inner.tangent2 + outer.tangent2)], axis=-1)
    return ElementEvaluation(energy, grad, hess, kn * (inner.load + outer.load) + fn,
                             (inner, outer))


def roller_state(model: Any, d: FloatArray, p: FloatArray, fc: FloatArray,
                 guess: FloatArray | None, tol: float, max_iter: int,
                 where: str) -> BearingState:
    """Bearing state of a :class:`~rotorsim.elements.rolling.roller.bearing.RollerBearing` whose
    rollers carry ``Fc`` (S,) [N] (module docstring); ``d`` (S, 5), ``p`` (S, Z) checked
    inputs, ``guess`` (S, Z, 2) roller DOFs ``(a, b)`` [m] or ``None``. Sample blocks of
    about 32k roller-slices keep the temporaries in cache (as the rigid model)."""
    parts = [_block_state(model, d[b], p[b], fc[b], None if guess is None else guess[b], tol,
                          max_iter, where) for b in model._blocks(d.shape[0])]
    if len(parts) == 1:
        return parts[0]
    merged: dict[str, Any] = {f.name: np.concatenate([getattr(x, f.name) for x in parts])
                              for f in dataclasses.fields(BearingState)
                              if f.name not in ("iterations", "outer_contact_angle")}
    return BearingState(**merged, iterations=max(int(x.iterations or 0) for x in parts))


def _peak(model: Any, v: FloatArray, lw: FloatArray) -> FloatArray:
    """Largest deflection ``max_xi (v + xi lw - c(xi))`` along each roller [m]."""
    if model.model == "tilt_integral":
        return np.asarray(v + 0.5 * np.abs(lw))
    return np.asarray((v[..., None] + lw[..., None] * model._line.xi
                       - model._line.drop).max(axis=-1))


def _block_state(model: Any, d: FloatArray, p: FloatArray, fc: FloatArray,
                 guess: FloatArray | None, tol: float, max_iter: int,
                 where: str) -> BearingState:
    c, s, v, lw = model._kinematics(d, p)
    ca = math.cos(model.contact_angle)
    kn, n = model.kn, float(model.exponent)
    fn = np.broadcast_to(ca * fc[:, None], v.shape)
    a_fc = 0.5 * (fn / kn) ** (1.0 / n)  # outer approach under Fc alone (straight roller)
    # cold start: the split at rest, or (when the inner contact is open with the roller
    # resting untilted on the outer race under Fc alone) that riding position, exact for
    # straight profiles
    riding = _peak(model, 2.0 * v - 2.0 * a_fc, 2.0 * lw) <= 0.0
    x0 = np.where(riding[..., None], np.stack([a_fc, np.zeros_like(a_fc)], axis=-1),
                  np.stack([np.maximum(0.5 * v, a_fc), 0.5 * lw], axis=-1))
    if guess is not None:
        x0 = np.where(np.isfinite(guess).all(axis=-1, keepdims=True), guess, x0)
    k_fc = 2.0 * n * kn * (2.0 * a_fc) ** (n - 1.0)
    floor = np.stack([k_fc, k_fc / 12.0], axis=-1)
    length = np.abs(v) + np.abs(lw) + a_fc
    sol = solve_elements(partial(_evaluate, model=model, v=v, lw=lw, fn=fn), x0, floor,
                         length, length, tol=tol, max_iter=max_iter)
    check_solution(sol, where, "a roller lost both raceways")
    inner, outer = sol.evaluation.aux
    return _assemble_state(model, c, s, v, lw, inner, outer, sol.evaluation.energy, sol.x,
                           sol.iterations)


def _assemble_state(model: Any, c: FloatArray, s: FloatArray, v: FloatArray, lw: FloatArray,
                    inner: LineIntegrals, outer: LineIntegrals, energy: FloatArray,
                    x: FloatArray, iterations: int) -> BearingState:
    """Force (seed 000 eq 10), condensed tangent and per-roller output at the equilibrium."""
    kn, n, length = model.kn, float(model.exponent), model.effective_length
    ca, sa = math.cos(model.contact_angle), math.sin(model.contact_angle)
    r_sa = 0.5 * model.pitch_diameter * sa
    q = kn * inner.load
    arm = r_sa * q - kn * length * inner.load_moment  # Q_j (r_p sin a0 - e_j)
    force = np.stack([ca * (q * c).sum(1), ca * (q * s).sum(1), sa * q.sum(1),
                      (arm * s).sum(1), -(arm * c).sum(1)], axis=1)
    k00, k01, k11 = _series(inner, outer, 2.0 * n * kn)
    w1 = r_sa * k00 - length * k01
    w2 = r_sa**2 * k00 - 2.0 * r_sa * length * k01 + length**2 * k11
    stiffness = assemble_tangent(c, s, k00, w1, w2, ca, sa)
    loaded = q > 0.0
    unit_arm = np.where(loaded, arm / np.where(loaded, q, 1.0), r_sa)
    total = _peak(model, v, lw)  # approach of the rings at the roller, independent of x
    return BearingState(
        force=force, stiffness=stiffness, energy=energy.sum(axis=1), element_load=q,
        contact_angle=np.full(q.shape, model.contact_angle),
        deflection=np.where(loaded, total, 0.0),
        contact_direction=unit_load_directions(c, s, unit_arm, ca, sa),
        element_stiffness=k00, outer_load=kn * outer.load, internal=x,
        iterations=iterations)


def _series(inner: LineIntegrals, outer: LineIntegrals, factor: float
            ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``factor [A_i - A_i (A_i + A_o)^-1 A_i]`` per roller as ``(k00, k01, k11)``."""
    a = (inner.tangent0, inner.tangent1, inner.tangent2)
    s00, s01, s11 = (a[k] + t for k, t in enumerate((outer.tangent0, outer.tangent1,
                                                     outer.tangent2)))
    # a roller resting on one slice of the outer ring has a singular A_o: regularise
    # its tilt (the inner contact then carries no tilt stiffness through it either)
    s00 = s00 + 1e-14 * (s00 + s11)
    s11 = s11 + 1e-14 * (s00 + s11)
    det = s00 * s11 - s01 * s01
    inv = 1.0 / np.where(det > 0.0, det, 1.0)
    m00 = (s11 * a[0] - s01 * a[1]) * inv
    m01 = (s11 * a[1] - s01 * a[2]) * inv
    m10 = (s00 * a[1] - s01 * a[0]) * inv
    m11 = (s00 * a[2] - s01 * a[1]) * inv
    k00 = a[0] - (a[0] * m00 + a[1] * m10)
    k11 = a[2] - (a[1] * m01 + a[2] * m11)
    k01 = a[1] - 0.5 * (a[0] * m01 + a[1] * m11 + a[1] * m00 + a[2] * m10)
    return factor * k00, factor * k01, factor * k11
