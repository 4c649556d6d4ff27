"""Shooting on the period map of a second-order problem (``full_shooting``) and the events
of a shooting branch (``full_branch``)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from rotorsim.errors import ConvergenceError, ModelError, Status
from rotorsim.time_integration.local_tangent import LocalMatrix
from rotorsim.time_integration.problem import SecondOrderProblem
from rotorsim.verification.full_branch import FullEvent, match_events, shooting_branch
from rotorsim.verification.full_shooting import shoot_full_model
from rotorsim.verification.shooting_sides import kind_multiplier


def _forced(w0: float = 2.0, zeta: float = 0.02, omega: float = 1.5, force: float = 1.0):
    return SecondOrderProblem(mass=np.eye(1), stiffness=np.array([[w0 * w0]]),
                              damping=np.array([[2 * zeta * w0]]),
                              load=lambda t: np.array([force * np.cos(omega * t)]))


def test_shooting_finds_the_forced_response_of_a_linear_oscillator():
    """``q'' + 2 zeta w0 q' + w0^2 q = cos(W t)``: the periodic response is ``Re(X e^{iWt})``
    with ``X = 1 / (w0^2 - W^2 + 2i zeta w0 W)``, and the multipliers are ``exp(lambda T)``.
    The scheme is second order: with 400 steps per period (``W h = 0.016``) its orbit is
    within ``(W h)^2 / 12 ~ 2e-5`` of the exact one (1e-4 asserted), and each multiplier
    lies within its own error estimate (``accuracy / 2``) of the exact one."""
    w0, zeta, omega = 2.0, 0.02, 1.5
    T = 2 * np.pi / omega
    X = 1.0 / (w0 ** 2 - omega ** 2 + 2j * zeta * w0 * omega)
    orbit = shoot_full_model(_forced(w0, zeta, omega), np.zeros(1), np.zeros(1), T, 400,
                             scale_q=abs(X), scale_v=abs(X) * omega, max_move=2.0)
    assert abs(orbit.q[0] - X.real) < 1e-4 * abs(X)
    assert abs(orbit.v[0] - (1j * omega * X).real) < 1e-4 * abs(X) * omega
    assert orbit.newton <= 3                       # linear: one correction, then the check
    lam = -zeta * w0 + 1j * w0 * np.sqrt(1 - zeta ** 2)
    for exact in (np.exp(lam * T), np.exp(np.conj(lam) * T)):
        j = int(np.argmin(np.abs(orbit.multipliers - exact)))
        assert abs(orbit.multipliers[j] - exact) <= 0.5 * orbit.accuracy[j]
        assert orbit.accuracy[j] < 1e-3


def test_shooting_converges_on_a_hardening_oscillator_and_stays_next_to_its_start():
    """A forced Duffing oscillator (``q'' + 0.1 q' + q + q^3 = 0.5 cos t``, one stable
    response at this forcing): from two rough guesses Newton ends below the tolerance on
    the same orbit, and with the default trust region (steps of 5 % of the scale, made
    for starting next to an orbit) a far guess is refused rather than followed."""
    def restoring(q, v, t):
        return (q ** 3, LocalMatrix(1, np.array([0]), np.array([[3 * q[0] ** 2]])),
                LocalMatrix(1, np.array([0]), np.zeros((1, 1))))

    p = SecondOrderProblem(mass=np.eye(1), stiffness=np.eye(1), damping=0.1 * np.eye(1),
                           restoring=restoring, load=lambda t: np.array([0.5 * np.cos(t)]))
    orbits = [shoot_full_model(p, np.array([a]), np.zeros(1), 2 * np.pi, 300, scale_q=1.0,
                               scale_v=1.0, max_move=1.0) for a in (0.3, 0.9)]
    assert all(o.residual < 1e-9 for o in orbits)
    assert abs(orbits[0].q[0] - orbits[1].q[0]) < 1e-8
    assert abs(orbits[0].v[0] - orbits[1].v[0]) < 1e-8
    assert np.all(np.abs(orbits[0].multipliers) < 1.0)          # a stable, damped response
    with pytest.raises(ConvergenceError, match="no progress"):
        shoot_full_model(p, np.array([5.0]), np.zeros(1), 2 * np.pi, 300, scale_q=1.0,
                         scale_v=1.0)


def test_shooting_says_when_it_finds_no_orbit_and_checks_its_scales():
    p = _forced()
    with pytest.raises(ModelError, match="scales"):
        shoot_full_model(p, np.zeros(1), np.zeros(1), 1.0, 50, scale_q=0.0, scale_v=1.0)
    with pytest.raises(ConvergenceError, match="shooting"):
        # two Newton periods are not enough with a trust region of 1e-3 of the scale
        shoot_full_model(p, np.zeros(1), np.zeros(1), 2 * np.pi / 1.5, 50, scale_q=1e-3,
                         scale_v=1e-3, max_newton=2, max_move=1e-3)


def test_the_multiplier_of_an_events_kind():
    mu = np.array([-1.35, 1.03, 0.9 + 0.5j, 0.9 - 0.5j, 0.5])
    assert kind_multiplier(mu, "fold") == 1
    assert kind_multiplier(mu, "branch_point") == 1
    assert kind_multiplier(mu, "period_doubling") == 0
    assert kind_multiplier(mu, "neimark_sacker") == 2
    assert kind_multiplier(np.array([0.5, 0.2]), "period_doubling") is None


def test_events_are_matched_in_order_and_by_kind():
    """Harmonic balance's events against a shooting branch's: in branch order, each takes
    the next unused event of its kind (a fold or a branch point match either)."""
    nan = complex("nan")
    full = (FullEvent("fold", 3, 1.0, nan), FullEvent("period_doubling", 5, 1.1, -1.2),
            FullEvent("fold", 9, 1.2, nan), FullEvent("branch_point", 12, 1.3, 1.1))
    assert match_events(["fold", "period_doubling", "fold", "fold"], full) == [0, 1, 2, 3]
    assert match_events(["period_doubling", "fold", "neimark_sacker"], full) == [1, 2, None]
    assert match_events(["neimark_sacker", "fold"], full) == [None, 0]


DOF = np.array([0])


def _nlvib_duffing(omega: float) -> SecondOrderProblem:
    """NLvib's example 01, ``q'' + 0.05 q' + q + 0.1 q^3 = 0.18 cos(Omega t)``."""
    def restoring(q, v, t):
        return (0.1 * q ** 3, LocalMatrix.trusted(1, DOF, np.array([[0.3 * q[0] ** 2]])),
                LocalMatrix.trusted(1, DOF, np.zeros((1, 1))))

    return SecondOrderProblem(mass=np.eye(1), stiffness=np.eye(1), damping=0.05 * np.eye(1),
                              restoring=restoring,
                              load=lambda t: np.array([0.18 * np.cos(omega * t)]))


def test_a_shooting_branch_turns_at_the_folds_of_the_duffing_oscillator():
    """NLvib's Duffing oscillator traced by shooting continuation in the forcing frequency
    (100 steps per period) from 1.0 to 1.3 rad/s: its two turning points lie at 1.269602
    and 1.115719 rad/s in NLvib's own shooting (docs/harmonic_balance_guide.md; 1.269602
    and 1.115700 with ``rs.hb``, H = 7). The scheme's period error is second order,
    ``(W h)^2 / 12 = 3.3e-4`` of the period here (about 4e-4 rad/s), and a turn is placed
    midway between the two points it lies between: asserted within 1e-3 rad/s plus half
    that gap (measured 5.4e-4 and 4.6e-4 with gaps of 1e-4 and 1.5e-3). Between the turns
    the real multiplier is above 1 (the saddle); at both ends every multiplier is inside
    the circle. About 5 s."""
    T = lambda w: 2 * np.pi / w                                    # noqa: E731
    start = shoot_full_model(_nlvib_duffing(1.0), np.array([0.3]), np.zeros(1), T(1.0), 100,
                             scale_q=1.0, scale_v=1.0, max_move=1.0)
    full = shooting_branch(_nlvib_duffing, T, (np.concatenate([start.q, start.v]), 1.0),
                           1.3, steps=100, max_step=0.3)
    assert full.branch.status.name == "OK" and full.speed[-1] == 1.3
    assert [e.kind for e in full.events] == ["fold", "fold"]
    for e, reference in zip(full.events, (1.269602, 1.115719), strict=True):
        gap = abs(full.speed[e.index + 1] - full.speed[e.index])
        assert abs(e.speed - reference) < 1e-3 + 0.5 * gap
        # the saddle's real multiplier at the point next to the turn (1.14 at the lower
        # turn, whose neighbours lie 1.5e-3 rad/s apart): real and above 1
        assert e.multiplier.imag == 0.0 and e.multiplier.real > 1.0
    middle = (full.events[0].index + full.events[1].index) // 2
    assert np.max(np.abs(full.multipliers[middle])) > 1.0
    assert np.max(np.abs(full.multipliers[0])) < 1.0
    assert np.max(np.abs(full.multipliers[-1])) < 1.0


class _Branch:
    """What ``trace_unconfirmed`` reads of a periodic result."""

    def __init__(self, speeds, events):
        self.speed = np.asarray(speeds, dtype=float)
        self.bifurcations = [SimpleNamespace(kind=k, index=i, parameter=float(speeds[i]))
                             for k, i in events]

    def __len__(self):
        return self.speed.size


def test_trace_confirms_the_unconfirmed_events_that_the_full_branch_has_in_order(monkeypatch):
    """The glue of ``verify_events(..., trace=True)``: the trace starts at the nearest
    point before the first unconfirmed event whose orbit shooting finds, ends at the first
    point past the last one faster than the whole stretch, and an unconfirmed event is
    confirmed by the full branch's event of its kind in the same place of the sequence;
    one without a match keeps its verdict, with the full branch's events in the reason."""
    from rotorsim.results.event_verification import EventCheck
    from rotorsim.verification import full_branch as fb

    speeds = [10, 11, 12, 12.5, 12.2, 11.8, 12.1, 12.6, 13, 14]
    result = _Branch(speeds, [("fold", 3), ("fold", 5), ("period_doubling", 6)])
    checks = [EventCheck(b, k, None, None, k == 2, "point-wise")
              for k, b in enumerate(result.bifurcations)]
    shots = {3: "no orbit"}                     # point 3 failed: the trace starts at 2
    seen = {}

    def shoot(res, p, run):
        seen.setdefault("shot", []).append(p)
        return SimpleNamespace(q=np.zeros(1), v=np.zeros(1))

    def branch(system, res, start, stop, run, max_points):
        seen["span"] = (start[1], stop)
        events = (fb.FullEvent("fold", 4, 12.45, complex(1.01)),
                  fb.FullEvent("period_doubling", 6, 12.05, complex(-1.02)))
        return fb.FullBranch(np.array([11.0, 12.7]), np.zeros((2, 2)), np.zeros((2, 2)),
                             events, SimpleNamespace(status=Status.OK, reason="done"))

    monkeypatch.setattr("rotorsim.verification.shooting_sides.shoot_point", shoot)
    monkeypatch.setattr(fb, "full_model_branch", branch)
    out = fb.trace_unconfirmed(result, checks, {"system": None, "reach": 2}, shots)
    assert seen["shot"] == [2] and seen["span"] == (12.0, 12.6)
    assert out[0].confirmed and "12.45" in out[0].reason and "point-wise" in out[0].reason
    assert not out[1].confirmed and "has no fold in its place" in out[1].reason
    assert out[2] is checks[2]                  # confirmed before: untouched


def test_the_events_of_a_shooting_branch_turns_crossings_and_grazes():
    """``full_branch._events`` on a stand-in branch: three turns in consecutive intervals
    are one fold (the corrector's jitter), a real multiplier through +1 next to it is the
    fold's own, a complex pair that leaves and re-enters the circle within 3 intervals is
    no event, and an isolated real crossing below -1 is a period doubling."""
    from rotorsim.verification.full_branch import _events

    lam_sign = [1, 1, 1, -1, 1, -1, -1, -1, -1, -1, -1, -1, -1, -1]
    P = len(lam_sign)
    tangents = np.zeros((P, 2))
    tangents[:, -1] = lam_sign
    base = np.array([0.5, 0.9 + 0.1j, 0.9 - 0.1j, -0.5], dtype=complex)
    mu = np.tile(base, (P, 1))
    mu[4:, 0] = 1.01                             # the saddle's real multiplier, from point 4
    mu[8:10, 1:3] = [1.001 + 0.1j, 1.001 - 0.1j]  # a pair grazing out and back in
    mu[12:, 3] = -1.02                           # a doubling between points 11 and 12
    branch = SimpleNamespace(lam=np.linspace(1.0, 2.0, P), tangents=tangents)
    events = _events(branch, mu)
    assert [(e.kind, e.index) for e in events] == [("fold", 3), ("period_doubling", 11)]
    assert events[1].multiplier == -1.02


def test_verify_events_refuses_a_trace_without_shooting():
    import rotorsim as rs

    steel = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
    rotor = rs.Rotor([rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel)] * 2,
                     bearing_elements=[rs.BearingElement(n=0, kxx=1e7, cxx=1e3),
                                       rs.BearingElement(n=2, kxx=1e7, cxx=1e3)])
    branch = rs.periodic(rotor, start=100.0, stop=110.0, harmonics=1,
                         unbalance=[(1, 1e-4, 0.0)], nodes=None)
    with pytest.raises(ModelError, match="measure='shooting'"):
        rs.verify_events(rotor, branch, trace=True)
    with pytest.raises(ModelError, match="trace"):
        rs.verify_events(rotor, branch, measure="shooting", trace="yes")
    assert len(rs.verify_events(rotor, branch, measure="shooting", trace=True)) == 0
