"""Balls with their centrifugal force: each ball free in the plane of its azimuth.

In the plane of ball ``j`` (radial coordinate ``r``, axial ``z``) the outer groove curvature
centre ``C_o`` is fixed at the origin and the inner one is at ``C_i = (R_j, Z_j)`` (seed 000
eq 2, the rigid-ring model of :mod:`~rotorsim.elements.rolling.ball.bearing`). The ball centre
``b = (b_r, b_z)`` is free; it is solved for in polar coordinates about ``C_o``,
``x = (delta_o, rho_o theta)`` with ``theta`` the outer contact angle (the outer contact is
linear in them: no Newton overshoot along the curved outer groove), which are
``state.internal`` [m]. With the groove radii ``r_o = f_o d``,
``r_i = f_i d`` (``rho = r - d/2``; equal ``A0 / 2`` when only ``A0`` is given)::

    delta_o = |b| - rho_o,          e_o = b / |b|                  (outer contact)
    delta_i = |C_i - b| - rho_i,    e_i = (C_i - b) / |C_i - b|    (inner contact)
    Pi = K_c / (n+1) (delta_i^(n+1) + delta_o^(n+1)) - Fc (b_r - rho_o)

with ``K_c = 2^n Kn`` for both contacts (their series gives back ``Kn``). ``dPi/db = 0``
is the ball equilibrium ``Q_o e_o = Q_i e_i + Fc e_r``: the outer contact carries more load
and turns towards the radial direction (``alpha_o < alpha_i``). The bearing sees only the
inner contact: ``F = sum Q_i g_j`` with ``g_j`` of seed 000 eq 4 at the inner contact angle
``alpha_i``, and the condensed 2x2 tangent in ``(R, Z)``,
``K* = H_i - H_i (H_i + H_o)^-1 H_i`` with ``H = k e e^T + (Q / |.|)(I - e e^T)`` (contact
stiffness along the normal and the turning of the normal), is mapped to the 5 DOFs as in
the rigid model (:mod:`~rotorsim.elements.rolling.ball.tangent`).

Without ``Fc`` the ball sits on the line of centres and the model is the Lim & Singh ball
exactly (series of the two contacts along the same line, transverse term ``Q / A``). This is
the quasi-static ball equilibrium of Jones (1960) **without** gyroscopic moments, friction
and raceway control: exact (within Hertz theory) where the ball's spin axis stays parallel
to the bearing axis (deep-groove bearings under radial load), approximate for angular-contact
bearings at high speed, where the gyroscopic moment reacted by friction adds contact forces
of order ``0.4 (1 + gamma) sin(alpha) Fc`` (``gamma = d cos(alpha) / d_m``).
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any, NamedTuple

import numpy as np

from rotorsim.elements.rolling.ball.tangent import assemble, ball_sums, directions
from rotorsim.elements.rolling.element_equilibrium import (
    ElementEvaluation,
    Mask,
    check_solution,
    solve_elements,
)
from rotorsim.elements.rolling.state import BearingState, FloatArray


class _Geometry(NamedTuple):
    rho_i: float  # inner groove centre to ball centre, unloaded [m]
    rho_o: float  # outer groove centre to ball centre, unloaded [m]
    kc: float  # per-contact Hertz constant [N/m^n]
    n: float  # exponent
    cos0: float
    sin0: float


class _Contact(NamedTuple):
    load: FloatArray  # Q (S, N) [N]
    slope: FloatArray  # dQ/d delta [N/m]
    dist: FloatArray  # distance of the ball centre from the groove centre [m]
    er: FloatArray  # unit vector from the groove centre to the ball centre (inner: from
    ez: FloatArray  # the ball centre to the groove centre), radial and axial components
    deflection: FloatArray  # delta (may be negative) [m]


def _geometry(model: Any) -> _Geometry:
    d = model.ball_diameter
    if model.f_i is not None and model.f_o is not None:
        rho_i, rho_o = (model.f_i - 0.5) * d, (model.f_o - 0.5) * d
    else:
        rho_i = rho_o = 0.5 * model.center_distance
    n = float(model.exponent)
    a0 = model.contact_angle
    return _Geometry(rho_i, rho_o, 2.0**n * model.Kn, n, math.cos(a0), math.sin(a0))


def _contact(vr: FloatArray, vz: FloatArray, rho: float, geo: _Geometry) -> _Contact:
    """Contact of a ball whose centre is at ``(vr, vz)`` from the groove centre."""
    dist = np.hypot(vr, vz)
    inv = 1.0 / np.where(dist > 0.0, dist, 1.0)
    deflection = dist - rho
    # touching needs the ball on the raceway side of the groove centre (as in ball.py)
    loaded = (deflection > 0.0) & (vr * geo.cos0 + vz * geo.sin0 > 0.0)
    pos = np.where(loaded, deflection, 0.0)
    power = pos ** (geo.n - 1.0) if geo.n != 1.0 else loaded.astype(float)
    return _Contact(geo.kc * power * pos, geo.n * geo.kc * power, dist, vr * inv, vz * inv,
                    deflection)


def _hessian(ct: _Contact) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``k e e^T + (Q / dist)(I - e e^T)`` as (h_rr, h_rz, h_zz)."""
    geo = ct.load / np.where(ct.dist > 0.0, ct.dist, 1.0)
    diff = ct.slope - geo
    return (geo + diff * ct.er * ct.er, diff * ct.er * ct.ez, geo + diff * ct.ez * ct.ez)


def _evaluate(x: FloatArray, mask: Mask | None, radial: FloatArray, axial: FloatArray,
              fc: FloatArray, geo: _Geometry) -> ElementEvaluation:
    """Potential and derivatives in the polar DOFs ``x = (delta_o, rho_o theta)``."""
    if mask is not None:
        radial, axial, fc = radial[mask], axial[mask], fc[mask]
    theta = x[..., 1] / geo.rho_o
    cos_t, sin_t = np.cos(theta), np.sin(theta)
    r = geo.rho_o + x[..., 0]
    outer = _outer(x[..., 0], cos_t, sin_t, geo)
    inner = _contact(radial - r * cos_t, axial - r * sin_t, geo.rho_i, geo)
    half = np.sin(0.5 * theta)  # b_r - rho_o = delta_o cos(theta) - 2 rho_o sin^2(theta/2)
    energy = (inner.load * np.maximum(inner.deflection, 0.0)
              + outer.load * np.maximum(outer.deflection, 0.0)) / (geo.n + 1.0) \
        - fc * (x[..., 0] * cos_t - 2.0 * geo.rho_o * half * half)
    # G = d(U_i - Fc b_r)/db = -Q_i e_i - Fc e_r; db/dx0 = e_o, db/dx1 = (r / rho_o) t_o
    g_r, g_z = -inner.load * inner.er - fc, -inner.load * inner.ez
    g_e, g_t = g_r * cos_t + g_z * sin_t, g_z * cos_t - g_r * sin_t
    scale = r / geo.rho_o
    grad = np.stack([outer.load + g_e, scale * g_t], axis=-1)
    h_rr, h_rz, h_zz = _hessian(inner)
    h_ee = h_rr * cos_t * cos_t + 2.0 * h_rz * cos_t * sin_t + h_zz * sin_t * sin_t
    h_tt = h_rr * sin_t * sin_t - 2.0 * h_rz * cos_t * sin_t + h_zz * cos_t * cos_t
    h_et = (h_zz - h_rr) * cos_t * sin_t + h_rz * (cos_t * cos_t - sin_t * sin_t)
    hess = np.stack([outer.slope + h_ee, scale * h_et + g_t / geo.rho_o,
                     scale * scale * h_tt - g_e * scale / geo.rho_o], axis=-1)
    return ElementEvaluation(energy, grad, hess, inner.load + outer.load + fc,
                             (inner, outer))


def _outer(approach: FloatArray, cos_t: FloatArray, sin_t: FloatArray,
           geo: _Geometry) -> _Contact:
    """Outer contact of a ball at the polar position ``(rho_o + approach, theta)``."""
    loaded = (approach > 0.0) & (cos_t * geo.cos0 + sin_t * geo.sin0 > 0.0)
    pos = np.where(loaded, approach, 0.0)
    power = pos ** (geo.n - 1.0) if geo.n != 1.0 else loaded.astype(float)
    return _Contact(geo.kc * power * pos, geo.n * geo.kc * power, geo.rho_o + approach,
                    cos_t, sin_t, approach)


def _start(radial: FloatArray, axial: FloatArray, dist: FloatArray, a0: float,
           fc: FloatArray, geo: _Geometry, guess: FloatArray | None) -> FloatArray:
    """Start: the exact solution at the bottom of the outer groove when the inner contact
    is open there; else the guess, or the ball midway on the line of centres."""
    delta_fc = (fc / geo.kc) ** (1.0 / geo.n)
    bottom = _contact(radial - geo.rho_o - delta_fc, axial, geo.rho_i, geo)
    riding = bottom.load == 0.0
    front = radial * geo.cos0 + axial * geo.sin0 > 0.0
    angle = np.where(front, np.arctan2(axial, radial), math.atan2(geo.sin0, geo.cos0))
    line = np.stack([0.5 * np.maximum(dist - a0, 0.0) + delta_fc, geo.rho_o * angle], axis=-1)
    if guess is not None:
        line = np.where(np.isfinite(guess).all(axis=-1, keepdims=True), guess, line)
    at_bottom = np.stack([delta_fc, np.zeros_like(delta_fc)], axis=-1)
    return np.where(riding[..., None], at_bottom, line)


def ball_state(model: Any, d: FloatArray, p: FloatArray, fc: FloatArray,
               guess: FloatArray | None, tol: float, max_iter: int,
               where: str) -> BearingState:
    """Bearing state of a :class:`~rotorsim.elements.rolling.ball.bearing.BallBearing` whose balls
    carry ``Fc`` (S,) [N] (module docstring); ``d`` (S, 5), ``p`` (S, N) checked inputs,
    ``guess`` (S, N, 2) internal DOFs ``(delta_o, rho_o alpha_o)`` [m] or ``None``."""
    c, s = np.cos(p), np.sin(p)
    axial, radial, dist, _ = model._contacts(d, c, s)
    geo = _geometry(model)
    fcn = np.broadcast_to(fc[:, None], p.shape)
    x0 = _start(radial, axial, dist, model.center_distance, fcn, geo, guess)
    delta_fc = (fcn / geo.kc) ** (1.0 / geo.n)
    k_fc = geo.n * geo.kc * delta_fc ** (geo.n - 1.0) if geo.n != 1.0 else \
        np.full(p.shape, geo.kc)
    floor = np.stack([k_fc, fcn / geo.rho_o], axis=-1)
    length = geo.rho_o + dist  # size of the coordinates: sets their round-off
    sol = solve_elements(partial(_evaluate, radial=radial, axial=axial, fc=fcn, geo=geo), x0,
                         floor, length, np.full(p.shape, 0.5 * geo.rho_o), tol=tol,
                         max_iter=max_iter)
    check_solution(sol, where, "the centrifugal force pulls balls out of the outer groove "
                   "(a thrust or steep angular-contact bearing needs an axial load that "
                   "keeps every ball pinched between its races)")
    x, ev, iterations = sol.x, sol.evaluation, sol.iterations
    inner, outer = ev.aux
    k_rr, k_rz, k_zz = _condensed(_hessian(inner), _hessian(outer))
    rows = np.stack([k_rr, k_rz, k_zz, inner.load * inner.er, inner.load * inner.ez], axis=1)
    force, stiffness = assemble(ball_sums(rows, c, s), model.moment_arm)
    loaded = inner.load > 0.0
    return BearingState(
        force=force, stiffness=stiffness, energy=ev.energy.sum(axis=1),
        element_load=inner.load, contact_angle=np.arctan2(inner.ez, inner.er),
        deflection=np.where(loaded, inner.deflection + outer.deflection, 0.0),
        contact_direction=directions(inner.ez, inner.er, c, s, model.moment_arm),
        element_stiffness=(k_rr * inner.er * inner.er + 2.0 * k_rz * inner.er * inner.ez
                           + k_zz * inner.ez * inner.ez),
        outer_load=outer.load, outer_contact_angle=np.arctan2(outer.ez, outer.er),
        internal=x, iterations=iterations)


def _condensed(hi: tuple[FloatArray, ...], ho: tuple[FloatArray, ...]
               ) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``H_i - H_i (H_i + H_o)^-1 H_i`` (inner and outer contact in series), symmetric."""
    s00, s01, s11 = hi[0] + ho[0], hi[1] + ho[1], hi[2] + ho[2]
    det = s00 * s11 - s01 * s01
    inv = 1.0 / np.where(det > 0.0, det, 1.0)  # det = 0 only if H_i = H_o = 0 (then K* = 0)
    # M = S^-1 H_i, K* = H_i - H_i M
    m00 = (s11 * hi[0] - s01 * hi[1]) * inv
    m01 = (s11 * hi[1] - s01 * hi[2]) * inv
    m11 = (s00 * hi[2] - s01 * hi[1]) * inv
    m10 = (s00 * hi[1] - s01 * hi[0]) * inv
    k00 = hi[0] - (hi[0] * m00 + hi[1] * m10)
    k11 = hi[2] - (hi[1] * m01 + hi[2] * m11)
    k01 = hi[1] - 0.5 * (hi[0] * m01 + hi[1] * m11 + hi[1] * m00 + hi[2] * m10)
    return k00, k01, k11
