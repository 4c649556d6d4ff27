"""``rs.verify_events``: the bifurcations of a periodic branch checked by time integration
of the full model next to them (``rotorsim/verification/periodic_events.py``,
``period_map.py``).

- The measurement against a known answer: a linear rotor whose bearings carry
  cross-coupled stiffness, unstable or stable; its multipliers are ``exp(lambda T)`` with
  ``lambda`` the eigenvalues of the first-order system (scipy, independent of harmonic
  balance, Floquet and the time integrator) -- docs/validation.md case 26.
- The verdicts: a fabricated event with no Floquet crossing, and fabricated Floquet
  multipliers the integration contradicts, are not confirmed and say why.
- Bad input raises ModelError naming the argument.
- The clearance rotor of issue 16 (``models/clearance_rotor.toml``): every event gets a
  verdict with its numbers from a short run on each side. They are not confirmed today
  (the strict xfail below says why; docs/validation.md case 26 has the numbers).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sl

import rotorsim as rs
from rotorsim.verification.period_map import (
    PeriodMap,
    dominant_multipliers,
    linearised_growth,
    trajectory_growth,
)
from rotorsim.verification.periodic_events import _excitation, _perturbation

MODEL = Path(__file__).resolve().parents[3] / "models" / "clearance_rotor.toml"
STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def _rotor(cross: float, damping: float = 1000.0) -> rs.Rotor:
    """A 1 m, 50 mm shaft with a 300 mm disk at mid-span on two bearings of 1e7 N/m with
    cross-coupled stiffness ``kxy = -kyx = cross`` [N/m] (destabilising forward whirl)."""
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=STEEL)] * 4
    disk = rs.DiskElement.from_geometry(n=2, material=STEEL, width=0.05, i_d=0.05, o_d=0.3)
    bearings = [rs.BearingElement(n=n, kxx=1e7, kxy=cross, kyx=-cross, cxx=damping)
                for n in (0, 4)]
    return rs.Rotor(shaft, disk_elements=[disk], bearing_elements=bearings)


def _exact_multipliers(system: rs.RotorSystem, speed: float) -> np.ndarray:
    """``exp(lambda T)`` of the lateral DOFs, by decreasing modulus (axial and torsional
    motions are decoupled and not perturbed)."""
    m = system.matrices(speed)
    lat = np.flatnonzero(np.isin(np.arange(system.n_free) % 6, (0, 1, 3, 4)))
    M, C, K = (A.toarray()[np.ix_(lat, lat)] for A in (m.M, m.C + speed * m.G, m.K))
    n = lat.size
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    mu = np.exp(sl.eigvals(A) * 2.0 * np.pi / speed)
    return mu[np.argsort(-np.abs(mu))]


@pytest.fixture(scope="module")
def linear_branches():
    out = {}
    for cross in (1e6, 2e5):
        rotor = _rotor(cross)
        out[cross] = rotor, rs.periodic(rotor, start=300.0, stop=310.0, harmonics=1,
                                        unbalance=[(2, 1e-4, 0.0)], nodes=None)
    return out


# ------------------------------------------------------------------------- measurement
def test_prony_separates_a_beating_pair_from_growth():
    rng = np.random.default_rng(3)
    k = np.arange(21)[:, None]
    for mu in (1.05 * np.exp(0.2j), 0.97 * np.exp(2.5j)):
        d = np.real(rng.standard_normal(6) * (1 + 1j) * mu**k)
        est = dominant_multipliers(d)
        assert np.allclose(np.sort_complex(est), np.sort_complex([mu, np.conj(mu)]),
                           rtol=1e-10)


@pytest.mark.parametrize("cross", [1e6, 2e5])
def test_measured_growth_matches_the_exact_multipliers_of_a_linear_rotor(
        linear_branches, cross):
    """kxy = 1e6 N/m: forward whirl unstable, max |mu| = 1.0322 at 300 rad/s; 2e5 N/m:
    stable, 0.99662. Both measurements (12 periods each, T/200) find the dominant modulus
    to 2e-4: the error of 12 power iterations against the next pair (0.946 / 1.032 per
    period, fitted exactly by the order-2 recurrence) and of the average-acceleration
    scheme at ``omega h = 0.015`` (relative amplitude error ~1e-5 per period)."""
    rotor, branch = linear_branches[cross]
    system = rs.assemble(rotor)
    W = float(branch.speed[0])
    exact = _exact_multipliers(system, W)
    # the branch's own Floquet multipliers (Hill) are exact too, bar the neutral axial and
    # torsional modes (|mu| = 1) that the lateral comparison leaves out
    hill = branch.multipliers[0]
    lateral = hill[np.abs(np.abs(hill) - 1.0) > 1e-6]
    assert abs(np.abs(lateral[0]) - np.abs(exact[0])) < 1e-8
    pm = PeriodMap(system, W, 2.0 * np.pi / W, _excitation(branch), 0.0, 200)
    q0, v0 = branch.state(0)
    direction = _perturbation(branch, 0, 1e-3)
    local = linearised_growth(pm, q0, v0, direction, 12)
    free, _ = trajectory_growth(pm, q0, v0, direction, 12)
    for growth in (local, free):
        assert abs(growth.rho - abs(exact[0])) < 2e-4
        assert abs(abs(np.angle(growth.multipliers[0])) - abs(np.angle(exact[0]))) < 2e-3
    assert local.periods == 13 and free.periods == 24


# ------------------------------------------------------------------------- verdicts
def _fake_event(branch, index, kind="neimark_sacker"):
    m = branch.dofs.size
    return rs.PeriodicBifurcation(kind, float(branch.parameter[index]), index, True,
                                  "test_function", complex(np.nan), np.zeros(m),
                                  np.zeros(m))


def test_an_event_without_a_floquet_crossing_is_not_confirmed(linear_branches):
    rotor, branch = linear_branches[1e6]            # unstable all along
    fake = dataclasses.replace(branch, bifurcations=(_fake_event(branch, 10),))
    out = rs.verify_events(rotor, fake, iterations=6, periods=0, reach=2)
    (check,) = out.checks
    assert not check.confirmed and not out.all_confirmed
    assert "show no crossing" in check.reason
    assert check.before.point == 10 and check.after.point == 11
    # the measurements are still made and agree with Floquet on both sides
    assert check.before.agrees and check.after.agrees
    assert check.before.local == pytest.approx(branch.max_multiplier[10], abs=1e-3)
    assert "NOT confirmed" in out.summary() and out.stats["points"] == 2


def test_floquet_multipliers_the_integration_contradicts_are_not_confirmed(
        linear_branches):
    """Multipliers of the unstable rotor scaled into the unit circle before point 10: a
    Floquet crossing the transient does not see (it grows on both sides)."""
    rotor, branch = linear_branches[1e6]
    mu = branch.multipliers.copy()
    mu[:11] *= 0.9 / np.abs(mu[:11, :1])
    fake = dataclasses.replace(branch, multipliers=mu,
                               bifurcations=(_fake_event(branch, 10),))
    (check,) = rs.verify_events(rotor, fake, iterations=6, periods=4, reach=2).checks
    assert not check.confirmed
    assert check.before.floquet == pytest.approx(0.9) and not check.before.agrees
    assert check.after.agrees
    assert check.before.local > 1.02 and check.before.trajectory > 1.02
    assert "before (point 10" in check.reason and "after" not in check.reason


def test_bad_input_raises_model_errors(linear_branches):
    rotor, branch = linear_branches[2e5]
    with pytest.raises(rs.ModelError, match=r"verify_events.result: expected a Periodic"):
        rs.verify_events(rotor, object())
    no_stability = rs.periodic(rotor, start=300.0, stop=301.0, harmonics=1,
                               unbalance=[(2, 1e-4, 0.0)], nodes=None, stability=None)
    with pytest.raises(rs.ModelError, match="no Floquet multipliers"):
        rs.verify_events(rotor, no_stability)
    some_nodes = rs.periodic(rotor, start=300.0, stop=301.0, harmonics=1,
                             unbalance=[(2, 1e-4, 0.0)], nodes=[2])
    with pytest.raises(rs.ModelError, match="nodes=None"):
        rs.verify_events(rotor, some_nodes)
    with pytest.raises(rs.ModelError, match=r"verify_events.events\[0\]: 0 is not an index"):
        rs.verify_events(rotor, branch, events=[0])
    fake = dataclasses.replace(branch, bifurcations=(_fake_event(branch, 3),))
    with pytest.raises(rs.ModelError, match=r"verify_events.events\[1\]"):
        rs.verify_events(rotor, fake, events=[0, 1])
    with pytest.raises(rs.ModelError, match=r"verify_events\.steps_per_period"):
        rs.verify_events(rotor, fake, steps_per_period=10)
    with pytest.raises(rs.ModelError, match=r"verify_events\.perturbation"):
        rs.verify_events(rotor, fake, perturbation=0.5)
    other = rs.Rotor([rs.ShaftElement(L=0.5, idl=0.0, odl=0.05, material=STEEL)] * 2,
                     bearing_elements=[rs.BearingElement(n=0, kxx=1e7),
                                       rs.BearingElement(n=2, kxx=1e7)])
    with pytest.raises(rs.ModelError, match=r"verify_events\.model: .*not the model"):
        rs.verify_events(other, fake)
    with pytest.raises(rs.ModelError, match=r"verify_events\.model: expected a Rotor"):
        rs.verify_events("rotor", fake)


# ------------------------------------------------------------------------- clearance rotor
@pytest.fixture(scope="module")
def clearance():
    """The branch over the resonance region only (300 -> 360 rad/s: the events of the
    whole 100 -> 400 branch lie in 339-354 rad/s), and every event checked with short
    runs: 8 power iterations and 2 x 4 free periods per side."""
    model = rs.load_model(MODEL)
    branch = rs.periodic(model, start=300.0, stop=360.0, harmonics=8,
                         unbalance=[(10, 1e-4, 0.0)], nodes=None)
    return branch, rs.verify_events(model, branch, iterations=8, periods=4)


def test_every_event_of_the_clearance_rotor_gets_a_verdict_with_numbers(clearance):
    branch, verified = clearance
    assert branch.bifurcations and len(verified) == len(branch.bifurcations)
    indices = sorted(b.index for b in branch.bifurcations)
    for check in verified.checks:
        ev = check.event
        assert check.reason and check.before is not None and check.after is not None
        # a side on each side of the event, no other event in between
        assert check.before.point <= ev.index < check.after.point
        between = [i for i in indices if check.before.point <= i < check.after.point]
        assert all(i == ev.index for i in between)
        for side in (check.before, check.after):
            assert side.floquet == pytest.approx(branch.max_multiplier[side.point])
            assert np.isfinite(side.local) or "transient failed" in side.message
            assert side.agrees or side.message
    assert verified.stats["periods"] > 0
    print("\n" + verified.summary())


@pytest.mark.xfail(strict=True, reason=(
    "issue 16 finding (docs/validation.md case 26): the measurement does not confirm the "
    "clearance rotor's events. Near the folds the H = 8 orbit is off by ~1 % at the disk "
    "and ~20 % at the journals and the period map is not linear on that scale; the branch "
    "points near 353 rad/s are axial pitchforks (shooting: 1.0908, an axial eigenvector) "
    "that the lateral perturbation and norm cannot see; a direct axial check confirms them "
    "(test_clearance_rotor.py::test_time_integration_confirms_the_axial_pitchforks_near_"
    "353_rad_s)"))
def test_every_event_of_the_clearance_rotor_is_confirmed(clearance):
    _, verified = clearance
    assert verified.all_confirmed, verified.summary()
