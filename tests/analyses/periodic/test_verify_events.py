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
- The Floquet-mode measurement (``measure="floquet"``): the critical mode of the linear
  rotor grows at its exact multiplier; each rule of the side verdict can fail.
- The clearance rotor of issue 16 (``models/clearance_rotor.toml``): every event gets a
  verdict with its numbers from a short run along its critical Floquet mode on each side.
  The branch reports the two folds and the two axial pitchforks, and all four are
  confirmed; the five events it used to report, which the integration did not confirm, are
  unresolved with their reasons (docs/validation.md case 26 has the numbers).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sl

import rotorsim as rs
from rotorsim.verification.floquet_modes import BranchModes
from rotorsim.verification.mode_growth import ModeGrowth, mode_growth, side_verdict
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


def test_the_critical_floquet_mode_of_a_linear_rotor_grows_at_its_exact_multiplier(
        linear_branches):
    """The Floquet-mode measurement (``measure="floquet"``) on the unstable linear rotor:
    Hsu's monodromy of a time-invariant system is ``exp(A T)`` (its steps commute), so its
    largest multiplier is the exact one to round-off; the coordinate of that mode along two
    free transients (8 periods, T/200) grows at it, the other modes (the neutral axial and
    torsional ones included) projected out by the left eigenvector."""
    rotor, branch = linear_branches[1e6]
    W = float(branch.speed[0])
    exact = _exact_multipliers(rs.assemble(rotor), W)[0]
    modes = BranchModes(rotor, branch, "test")
    point = modes.at(0)
    mu = point.multipliers[0]
    assert abs(mu - (exact if exact.imag * mu.imag > 0 else np.conj(exact))) < 1e-9
    pm = PeriodMap(rs.assemble(rotor), W, 2.0 * np.pi / W, _excitation(branch), 0.0, 200)
    q0, v0 = branch.state(0)
    growth, _ = mode_growth(pm, q0, v0, modes, point, 0, 1e-6, 8)
    # modulus: the average-acceleration scheme keeps amplitudes (error ~1e-5 per period,
    # as above); phase: its period elongation (omega h)^2 / 12 per step
    assert abs(abs(growth.measured) - abs(mu)) < 1e-4
    assert abs(np.angle(growth.measured / mu)) < 2e-3
    assert side_verdict(growth, 0.02) == ""
    assert pm.periods_run == [8, 8]


def _growth(mu, c, measured=None):
    c = np.asarray(c, dtype=complex)
    if measured is None:
        measured = np.sum(c[1:] * np.conj(c[:-1])) / np.sum(np.abs(c[:-1]) ** 2)
    return ModeGrowth(0, complex(mu), complex(measured), c)


def test_the_side_verdicts_of_the_floquet_mode_measurement():
    """Each rule of ``side_verdict`` can fail: growth, rate (a factor 3 in ``ln |mu|``),
    direction (monotone for a real ``mu > 1``, alternating for ``mu < -1``, the turn of a
    complex pair) and, on a stable side, growth beyond the margin (a neutral mode passes)."""
    k = np.arange(9)
    assert side_verdict(_growth(1.05, 1.05**k), 0.02) == ""
    assert "does not grow" in side_verdict(_growth(1.05, 0.99**k), 0.02)
    assert "factor" in side_verdict(_growth(1.05, 1.3**k), 0.02)
    wobble = 1.05**k * np.where(k == 4, -1.0, 1.0)
    assert "monotone" in side_verdict(_growth(1.05, wobble, 1.05), 0.02)
    assert side_verdict(_growth(-1.06, (-1.06) ** k), 0.02) == ""
    assert "alternate" in side_verdict(_growth(-1.06, 1.06**k, -1.06), 0.02)
    pair = 1.04 * np.exp(0.5j)
    assert side_verdict(_growth(pair, pair**k), 0.02) == ""
    assert "turns" in side_verdict(_growth(pair, (1.04 * np.exp(1.2j)) ** k), 0.02)
    assert side_verdict(_growth(0.97, np.ones(9)), 0.02) == ""     # neutral: stable
    assert "stable side" in side_verdict(_growth(0.97, 1.03**k), 0.02)


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
    with pytest.raises(rs.ModelError, match=r"verify_events\.measure: must be 'orbit'"):
        rs.verify_events(rotor, fake, measure="modes")
    with pytest.raises(rs.ModelError, match=r"verify_events\.periods: .*floquet"):
        rs.verify_events(rotor, fake, measure="floquet", periods=1)
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
    whole 100 -> 400 branch lie in 339-354 rad/s), and every event checked along its
    critical Floquet mode with short runs: 2 x 6 free periods per side (8 sides for the 4
    events the branch reports; the fixture took 46 s on the shared machine, the branch
    about 20 s of it)."""
    model = rs.load_model(MODEL)
    branch = rs.periodic(model, start=300.0, stop=360.0, harmonics=8,
                         unbalance=[(10, 1e-4, 0.0)], nodes=None)
    return branch, rs.verify_events(model, branch, periods=6, measure="floquet")


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
        crossing = check.before.unstable != check.after.unstable
        for side in (check.before, check.after):
            assert side.floquet == pytest.approx(branch.max_multiplier[side.point])
            assert side.agrees or side.message
            if not crossing:          # nothing to follow: reported, not integrated
                assert "no Floquet crossing" in side.message and not check.confirmed
                continue
            # the mode followed is one of the branch's multipliers (the same Hsu
            # monodromy of the same stability model, rebuilt)
            assert np.min(np.abs(branch.multipliers[side.point] - side.mode)) < 1e-8
            c = side.coordinates
            assert c is not None and c.size == 7 and c[0] == pytest.approx(1.0)
            assert np.isfinite(side.measured) or "transient failed" in side.message
    assert verified.stats["periods"] > 0
    print("\n" + verified.summary())


def test_the_folds_and_the_axial_pitchforks_are_confirmed_along_their_critical_modes(
        clearance):
    """The two hysteresis folds (343.64 and 342.00 rad/s) and the two axial pitchforks
    (353.12 and 353.73 rad/s, docs/validation.md case 25) are confirmed: on their unstable
    side (the fold's middle sheet, the window between the pitchforks) the real multiplier
    above 1 is seen as a monotone departure of the critical mode along the free transient of
    the full model, at a rate within a factor 3 of Floquet's in ``ln |mu|`` (measured 1.074
    and 1.103 against 1.049 and 1.040 at the folds, 1.024 and 1.081 against 1.038 and 1.077
    at the pitchforks); on the stable side the same mode does not grow (0.97-0.99 per
    period)."""
    _, verified = clearance
    chosen = [c for c in verified.checks if c.event.kind == "fold"
              or 352.0 < c.event.parameter < 355.0]
    assert [c.event.kind for c in chosen] == ["fold", "fold", "branch_point", "branch_point"]
    for check in chosen:
        assert check.confirmed, check.reason
        sides = sorted((check.before, check.after), key=lambda s: abs(s.mode))
        stable, unstable = sides
        assert unstable.mode.imag == 0.0 and unstable.mode.real > 1.02
        assert unstable.measured.real > 1.01 and np.all(unstable.coordinates.real > 0.0)
        assert abs(stable.measured) < 1.0


def test_every_event_of_the_clearance_rotor_is_confirmed(clearance):
    """Issue 16: every event the branch reports is confirmed by time integration next to
    it. The branch reports only resolved events (``rotorsim/analyses/periodic/
    crossings.py``): the two folds and the two axial pitchforks."""
    branch, verified = clearance
    assert [b.kind for b in branch.bifurcations] == ["fold", "fold", "branch_point",
                                                     "branch_point"]
    assert verified.all_confirmed, verified.summary()


def _reasons_at(branch, kind, speed):
    """Reasons of the unresolved records of ``kind`` whose interval holds ``speed``."""
    out = []
    for u in branch.unresolved:
        head, _, why = u.method.partition(": ")
        lo, hi = (float(v) for v in head.removeprefix("unresolved between ").split(" and "))
        if u.kind == kind and lo <= speed <= hi:
            out.append(why)
    return out


def test_the_clearance_rotors_unresolved_crossings_say_why(clearance):
    """The five events the branch used to report and time integration did not confirm
    (docs/validation.md case 26) are unresolved now, each with its reason:

    - branch points at 341.06, 342.13 and 344.27 rad/s: the determinant changes sign but no
      real multiplier of the branch's Floquet model passes ``1 + tol`` next to them
      (largest real multipliers ~0, 0.84 -> ~0, 0.97 -> ~0);
    - the branch point at 342.33 rad/s: its bracket orbits on the upper sheet next to the
      contact onset do not persist with 12 instead of 8 harmonics (nor does shooting
      converge to a periodic orbit there);
    - the Neimark-Sacker point at 339.26 rad/s: the other edge of a one-point unstable
      window (``|mu| = 1.0009``) whose first edge crosses zero 556 times more steeply than
      between its points.
    """
    branch, _ = clearance
    for speed in (341.06, 342.13, 344.27):
        assert any("no real Floquet multiplier crosses" in why
                   for why in _reasons_at(branch, "branch_point", speed)), speed
    assert any("does not converge with 12 harmonics" in why
               for why in _reasons_at(branch, "branch_point", 342.33))
    assert any("steeply" in why for why in _reasons_at(branch, "neimark_sacker", 339.26))
