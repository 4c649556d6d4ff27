"""FlexibleRingRollerBearing (seed 001): roller potential, condensation, tangent, limits."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium
from rotorsim.elements.rolling.flexible_ring.bearing import FlexibleRingRollerBearing
from rotorsim.elements.rolling.roller.bearing import RollerBearing
from rotorsim.elements.rolling.roller.profile import LogarithmicProfile
from rotorsim.errors import ConvergenceError

# seed 001 section 3.1 bearing, 5 slices to keep the tests fast
SEED = dict(n_rollers=24, pitch_radius=75e-3, roller_radius=6.5e-3, effective_length=16e-3,
            shaft_radius=54e-3, housing_radius=97e-3, ring_width=30e-3, n_slices=5)
SPEED = 12000.0 * math.pi / 30.0
SCALE = np.array([1.0, 1.0, 1.0, 1.0 / 75e-3, 1.0 / 75e-3])  # rotations x pitch radius


def _bearing(g: float = -40e-6, **kw) -> FlexibleRingRollerBearing:
    return FlexibleRingRollerBearing(**{**SEED, "diametral_clearance": g, **kw})


def _states(n: int, seed: int, size: float = 8e-6):
    rng = np.random.default_rng(seed)
    delta = rng.normal(size=(n, 5)) * size / SCALE
    return delta, rng.uniform(0.0, 2 * math.pi, n)


def _pi_scalar(b: FlexibleRingRollerBearing, y, z, m_omega2: float) -> float:
    """Seed 001 eq 19 written out slice by slice (eqs 9, 10, 13, 15, 17, 18)."""
    v, phi, w_i, w_e = y
    u_r, gam = z
    g, n, c = b.diametral_clearance, b.exponent, b.line_constant
    total = 0.0
    sl = b.slices
    for h, s, drop in zip(sl.widths, sl.positions, sl.drops, strict=True):
        d_i = -g / 4 - v - w_i - drop - phi * s
        d_e = -g / 4 - u_r + v - w_e - drop + (phi - gam) * s
        total += c * h / (n + 1) * (max(d_i, 0.0) ** (n + 1) + max(d_e, 0.0) ** (n + 1))
    theta = 2 * math.pi / b.n_rollers
    for sec, w, sign in ((b.sections[0], w_i, -1.0), (b.sections[1], w_e, 1.0)):
        r = sec.mean_radius
        total += 0.5 * b.E * sec.area * theta * w * w / r
        total += 0.5 * b.E * sec.inertia * theta * w * w / (r * (r + sign * w) ** 2)
    return total - 0.5 * m_omega2 * ((b.pitch_radius + v) ** 2 - b.pitch_radius**2)


def _roller_points(n: int, seed: int):
    rng = np.random.default_rng(seed)
    y = rng.normal(size=(4, n)) * np.array([[3e-6], [2e-4], [3e-6], [3e-6]])
    z = rng.normal(size=(2, n)) * np.array([[6e-6], [4e-4]])
    return y, z, rng.uniform(0.0, 8e3, n)


def test_roller_potential_matches_eq19_and_its_derivatives():
    b = _bearing()
    pot = b.potential
    y, z, mw = _roller_points(30, 1)
    local = pot.evaluate(y, z, mw)
    ref = [_pi_scalar(b, y[:, k], z[:, k], mw[k]) for k in range(30)]
    assert np.allclose(local.energy, ref, rtol=1e-12, atol=1e-18)
    q = np.concatenate([y, z])
    steps = np.array([1e-10, 1e-8, 1e-10, 1e-10, 1e-10, 1e-8])
    for j in range(6):
        qp, qm = q.copy(), q.copy()
        qp[j] += steps[j]
        qm[j] -= steps[j]
        ep, em = pot.evaluate(qp[:4], qp[4:], mw), pot.evaluate(qm[:4], qm[4:], mw)
        fd_g = (ep.energy - em.energy) / (2 * steps[j])
        fd_h = (ep.grad - em.grad) / (2 * steps[j])
        scale = np.abs(local.grad[j]).max()
        # central differences: truncation O(h^2), round-off 1e-16 Pi / h
        assert np.abs(fd_g - local.grad[j]).max() <= 1e-5 * scale
        assert np.abs(fd_h - local.hess[:, j]).max() <= 1e-5 * np.abs(local.hess[j, j]).max()


@pytest.mark.parametrize("case", ["preload_speed", "clearance", "clearance_speed", "no_tilt",
                                  "rigid_speed", "crowned"])
def test_condensed_tangent_is_the_fd_jacobian_of_the_force(case):
    kw = {"preload_speed": dict(), "clearance": dict(g=10e-6),
          "clearance_speed": dict(g=10e-6), "no_tilt": dict(tilt=False),
          "rigid_speed": dict(rigid_rings=True),
          "crowned": dict(profile=LogarithmicProfile.with_end_drop(2e-6, 6e-6))}[case]
    b = _bearing(**kw)
    speed = 0.0 if case == "clearance" else SPEED
    delta, phi = _states(12, 7)
    psi = b.element_angles(phi)
    st = b.state(delta, psi, speed)
    assert 0 < st.loaded.mean() <= 1.0
    h = 1e-9 / SCALE
    for j in range(5):
        e = np.zeros(5)
        e[j] = h[j]
        fd = (b.state(delta + e, psi, speed).force - b.state(delta - e, psi, speed).force) \
            / (2 * h[j])
        ref = np.abs(st.stiffness / SCALE[None, :, None] / SCALE[None, None, :]).max()
        # step 1e-9 m: truncation ~ (h/delta)^2 ~ 1e-8, inner tolerance 1e-10 (second order
        # in the force through eq 25)
        err = np.abs((fd - st.stiffness[:, :, j]) / SCALE[None, :] / SCALE[j]).max()
        assert err <= 1e-6 * ref, (j, err / ref)
    assert np.allclose(st.stiffness, np.swapaxes(st.stiffness, 1, 2), rtol=0, atol=1e-12 * ref)


def test_force_is_the_gradient_of_the_energy_and_rollers_are_at_equilibrium():
    b = _bearing(g=10e-6)
    delta, phi = _states(6, 11)
    psi = b.element_angles(phi)
    st = b.state(delta, psi, SPEED)
    for j in range(5):
        e = np.zeros(5)
        e[j] = 1e-9 / SCALE[j]
        fd = (b.energy(delta + e, psi, SPEED) - b.energy(delta - e, psi, SPEED)) / (2 * e[j])
        assert np.allclose(fd, st.force[:, j], rtol=1e-6,
                           atol=1e-6 * np.abs(st.force / SCALE).max() / SCALE[j])
    # stationarity of eq 19 in the internal DOFs at the returned roller states
    y = np.moveaxis(st.internal, -1, 0).reshape(4, -1)
    c, s = np.cos(psi), np.sin(psi)
    z = np.stack([-(delta[:, :1] * c + delta[:, 1:2] * s),
                  delta[:, 3:4] * s - delta[:, 4:5] * c]).reshape(2, -1)
    mw = np.full(y.shape[1], b.mass * (b.centrifugal_cage_ratio * SPEED) ** 2)
    grad = b.potential.evaluate(y, z, mw).grad[:4] * np.array([[1.0], [2 / 16e-3], [1], [1]])
    # the inner tolerance: 1e-10 of the sample's largest roller force Q_i + Q_e + F_c [N]
    ref = (st.element_load + st.outer_load + mw[0] * b.pitch_radius).max(axis=1)
    assert np.all(np.abs(grad).reshape(4, 6, 24).max(axis=(0, 2)) <= 1.01e-10 * ref)


def test_condensed_force_equals_the_monolithic_solution_of_the_full_system():
    """Seed 001 eqs 6-7 solved on all unknowns at once (4 bearing DOFs + 4 per roller) by a
    plain dense Newton, against bearing statics on the condensed element (eqs 23-26)."""
    b = _bearing(n_slices=4, speed=SPEED)
    load = np.array([5000.0, 2000.0, 0.0, 3.0, 13.7])
    res = bearing_equilibrium(b, load, tol=1e-12)
    pot, n_r = b.potential, b.n_rollers
    psi = b.element_angles()[0]
    free = [0, 1, 3, 4]
    t = np.zeros((n_r, 2, 4))  # z_j = T_j delta on (x, y, rx, ry)
    t[:, 0, 0], t[:, 0, 1] = -np.cos(psi), -np.sin(psi)
    t[:, 1, 2], t[:, 1, 3] = np.sin(psi), -np.cos(psi)
    mw = np.full(n_r, b.mass * (b.centrifugal_cage_ratio * SPEED) ** 2)
    x = np.zeros(4 + 4 * n_r)

    def system(x):
        d, y = x[:4], x[4:].reshape(n_r, 4).T
        loc = pot.evaluate(y, np.einsum("jad,d->aj", t, d), mw)
        grad = np.concatenate([np.einsum("jad,aj->d", t, loc.grad[4:]) - load[free],
                               loc.grad[:4].T.reshape(-1)])
        hess = np.zeros((x.size, x.size))
        hess[:4, :4] = np.einsum("jad,abj,jbe->de", t, loc.hess[4:, 4:], t)
        for j in range(n_r):
            rows = slice(4 + 4 * j, 8 + 4 * j)
            hess[rows, rows] = loc.hess[:4, :4, j]
            hess[rows, :4] = loc.hess[:4, 4:, j] @ t[j]
            hess[:4, rows] = hess[rows, :4].T
        return loc.energy.sum() - load[free] @ d, grad, hess

    for _ in range(40):
        energy, grad, hess = system(x)
        if np.abs(grad).max() < 1e-9:
            break
        step, alpha = -np.linalg.solve(hess, grad), 1.0
        while system(x + alpha * step)[0] > energy + 1e-4 * alpha * grad @ step + 1e-12:
            alpha *= 0.5
        x = x + alpha * step
    assert np.abs(system(x)[1]).max() < 1e-8  # N, N m
    d = res.displacement
    assert np.allclose(x[:4], d[free], rtol=1e-9, atol=1e-9 * np.abs(d).max())
    st = b.state(d[None, :], b.element_angles())
    assert np.allclose(x[4:].reshape(n_r, 4), st.internal[0], rtol=1e-7, atol=1e-13)


def test_uniform_preload_matches_the_series_spring_solution():
    """No external load, no speed: every roller carries the same Q with
    ``2 (Q / (C L))^(1/n) + w_i(Q) + w_e(Q) = -g/2`` (eqs 13, 16, 21c) solved by brentq."""
    b = _bearing(speed=0.0)
    st = b.state(np.zeros((1, 5)), b.element_angles())
    c_l, n = b.line_constant * b.effective_length, b.exponent
    theta = 2 * math.pi / b.n_rollers

    def ring_w(q, sec, sign):  # N = E A theta w / R + E I theta w / (R -+ w)^3 = Q
        r = sec.mean_radius
        return brentq(lambda w: b.E * theta * w * (sec.area / r + sec.inertia
                                                   / (r + sign * w) ** 3) - q, 0.0, 1e-3,
                      xtol=1e-18)

    def gap(q):
        return 2 * (q / c_l) ** (1 / n) + ring_w(q, b.sections[0], -1) \
            + ring_w(q, b.sections[1], 1) + b.diametral_clearance / 2

    q_ref = brentq(gap, 1.0, 1e5, xtol=1e-12)
    assert np.allclose(st.element_load, q_ref, rtol=1e-9)
    assert np.allclose(st.outer_load, q_ref, rtol=1e-9)


def _rotation(alpha: float) -> np.ndarray:
    r = np.eye(5)
    c, s = math.cos(alpha), math.sin(alpha)
    r[:2, :2] = r[3:, 3:] = [[c, -s], [s, c]]
    return r


def test_rotating_load_and_rollers_together_rotates_the_result():
    b = _bearing()
    delta, phi = _states(4, 3)
    psi = b.element_angles(phi)
    st = b.state(delta, psi, SPEED)
    alpha = 0.7
    rot = _rotation(alpha)
    st2 = b.state(delta @ rot.T, psi + alpha, SPEED)
    assert np.allclose(st2.force, st.force @ rot.T, rtol=1e-9, atol=1e-9 * np.abs(st.force).max())
    k_rot = rot @ st.stiffness @ rot.T
    assert np.allclose(st2.stiffness, k_rot, rtol=1e-8, atol=1e-9 * np.abs(k_rot).max())
    assert np.allclose(st2.element_load, st.element_load, rtol=1e-9)


@pytest.mark.parametrize("g", [-40e-6, 10e-6])
@pytest.mark.parametrize("crowned", [False, True])
def test_rigid_ring_limit_is_the_sliced_rigid_roller_bearing(g, crowned):
    """At rest, the rigid-ring model equals RollerBearing(model="slices") with the
    whole-roller constant ``Kn = C L / 2^n``, ``radial_clearance = g / 2`` and the profile
    drop of both contacts (twice the roller's); exact up to the inner tolerance."""
    profile = LogarithmicProfile(scale=1e-6, shape=0.9) if crowned else None
    extra = {"profile": profile} if crowned else {}
    flexible = _bearing(g, **extra)
    rigid = dataclasses.replace(flexible, rigid_rings=True)
    stiff = dataclasses.replace(flexible, ring_modulus=2e11 * 1e6)
    ref = RollerBearing(n_rollers=24, pitch_diameter=0.15, roller_diameter=0.013,
                        effective_length=16e-3, Kn=flexible.Kn, radial_clearance=g / 2,
                        model="slices", n_slices=5, cage="fixed",
                        **({"profile": LogarithmicProfile(scale=2e-6, shape=0.9)}
                           if crowned else {}))
    delta, phi = _states(8, 5)
    psi = ref.element_angles(phi)
    want = ref.state(delta, psi)
    f_ref = np.abs(want.force * SCALE).max()
    for model, rtol in ((rigid, 1e-9), (stiff, 1e-5)):
        got = model.state(delta, psi, 0.0)
        # rigid flag: inner tolerance 1e-10; rings 1e6 times stiffer: their compliance is
        # ~1e-6 of the contacts' (ring 3e14 N/m against contact < 1e9 N/m)
        assert np.allclose(got.force * SCALE, want.force * SCALE, atol=rtol * f_ref)
        assert np.allclose(got.element_load, want.element_load,
                           atol=rtol * want.element_load.max())
        k_scale = np.abs(want.stiffness).max()
        assert np.allclose(got.stiffness, want.stiffness, atol=10 * rtol * k_scale)
    assert rigid.clearance == ref.clearance


def test_warm_start_needs_fewer_iterations_and_nan_rows_start_cold():
    b = _bearing()
    delta, phi = _states(16, 9)
    psi = b.element_angles(phi)
    cold = b.state(delta, psi, SPEED)
    same = b.state(delta, psi, SPEED, internal=cold.internal)
    near = b.state(delta * (1 + 1e-6), psi, SPEED, internal=cold.internal)
    assert cold.iterations >= 1 and same.iterations == 0 and near.iterations <= 1
    assert np.allclose(same.force, cold.force, rtol=0, atol=1e-12 * np.abs(cold.force).max())
    assert cold.inner.failures == 0 and cold.inner.systems == 16 * 24
    mixed = cold.internal.copy()
    mixed[3] = np.nan
    again = b.state(delta, psi, SPEED, internal=mixed)
    assert np.allclose(again.force, cold.force, rtol=1e-9, atol=1e-9 * np.abs(cold.force).max())


def test_non_converging_roller_names_roller_and_sample():
    b = _bearing(max_iter=1)
    delta, phi = _states(3, 2)
    far = np.zeros((3, 24, 4))  # a poor warm start: undeformed rings, roller centred at 0
    with pytest.raises(ConvergenceError, match=r"roller \d+ of sample \d+"):
        b.state(delta, b.element_angles(phi), SPEED, internal=far)


def test_without_tilt_the_bearing_carries_no_moment():
    b = _bearing(tilt=False)
    delta, phi = _states(4, 4)
    st = b.state(delta, b.element_angles(phi), SPEED)
    assert np.all(st.force[:, 2:] == 0.0) and np.all(st.stiffness[:, 2:, :] == 0.0)
    res = bearing_equilibrium(b.at_speed(SPEED), [5000.0, 0.0, 0.0, 0.0, 0.0])
    assert res.held_dofs == ("z", "rx", "ry")
    assert np.allclose(res.force[:2], [5000.0, 0.0], atol=1e-6)
