"""Machines of several shaft lines (issue 15), checked against closed forms and against the
equivalent one-line models (docs/validation.md, case 27).

Tolerances: the penalty checks (a rigid joint, a rigid casing) converge like
``k_structure / k_penalty``; the penalty is chosen so that this is below 1e-7 and the
frequencies are compared to 1e-6, well above both it and the eigensolver's accuracy
(relative 1e-10 on these well-separated modes), whatever the BLAS.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.elements.rolling.element import RollingBearing
from rotorsim.model.lines import ShaftLine

MODELS = Path(__file__).resolve().parents[2] / "models"
STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
STIFF = 1e14  # penalty [N/m, N m/rad]: 1e-7 of it is above every shaft stiffness here


def _shaft(n: int, length: float = 0.8, od: float = 0.04) -> list[rs.ShaftElement]:
    return [rs.ShaftElement(L=length / n, idl=0.0, odl=od, material=STEEL) for _ in range(n)]


def _joint(n: int, link: int, tag: str) -> rs.BearingElement:
    """A rigid joint of all six DOFs between two nodes (penalty)."""
    return rs.BearingElement(n=n, n_link=link, kxx=STIFF, kzz=STIFF, krr=STIFF,
                             stiffness_matrix=np.diag([0, 0, 0, 0, 0.0]), tag=tag)


def _supports(a: int, b: int) -> list[rs.BearingElement]:
    return [rs.BearingElement(n=a, kxx=2e7, kyy=3e7, kzz=1e8, cxx=300.0, tag="left"),
            rs.BearingElement(n=b, kxx=2e7, kyy=3e7, cxx=300.0, tag="right")]


def _frequencies(rotor: rs.Rotor, speed: float) -> np.ndarray:
    return rs.modal(rotor, speed=speed, num_modes=10).wd


@pytest.mark.verification
@pytest.mark.parametrize("speed", [0.0, 800.0, 3000.0])
def test_two_lines_joined_rigidly_equal_the_single_line(speed: float) -> None:
    shaft = _shaft(8)
    disks = [rs.DiskElement(n=4, m=12.0, Id=0.06, Ip=0.11, tag="disk")]
    one = rs.Rotor(shaft, disks, _supports(0, 8))
    left, right = ShaftLine("A", shaft[:4]), ShaftLine("B", shaft[4:], z0=0.4)
    two = rs.Rotor([], disks, [*_supports(0, 9), _joint(4, 5, "joint")],
                   lines=[left, right])
    expected, got = _frequencies(one, speed), _frequencies(two, speed)
    np.testing.assert_allclose(got, expected, rtol=1e-6)


@pytest.mark.verification
def test_gyroscopic_matrix_of_a_machine_is_the_ratio_weighted_sum_of_its_lines() -> None:
    """``G = sum_k r_k G_k`` (DESIGN section 12): assembled with ratios (1, 1.45), (1, 0) and
    (0, 1) on the same two lines."""
    def machine(r_a: float, r_b: float) -> rs.RotorSystem:
        lines = [ShaftLine("A", _shaft(6), speed_ratio=r_a),
                 ShaftLine("B", _shaft(4, 0.5, 0.08), z0=0.1, speed_ratio=r_b)]
        lines = [line for line in lines]
        disks = [rs.DiskElement(n=3, m=5.0, Id=0.02, Ip=0.04, tag="a"),
                 rs.DiskElement(n=9, m=8.0, Id=0.05, Ip=0.09, tag="b")]
        bearings = [*_supports(0, 6), rs.BearingElement(n=7, n_link=1, kxx=1e7, tag="c"),
                    rs.BearingElement(n=11, n_link=5, kxx=1e7, tag="d")]
        # a line at ratio 0 has no rotating parts unless its shaft is gyroscopic: it is
        return rs.assemble(rs.Rotor([], disks, bearings, lines=lines))

    both = machine(1.0, 1.45).matrices().G.toarray()
    only_a = machine(1.0, 0.0).matrices().G.toarray()
    only_b = machine(0.0, 1.0).matrices().G.toarray()
    np.testing.assert_allclose(both, only_a + 1.45 * only_b, rtol=0, atol=1e-12 * abs(both).max())
    assert abs(only_b).max() > 0 and abs(only_a).max() > 0


def _rigid_disk(ratio: float, kr: float = 4e4, k: float = 1e6) -> rs.Rotor:
    """A rigid disk (m, Id, Ip) at a line's only node on a spring (k, kr): the classic
    gyroscopic rotor with a closed-form Campbell diagram."""
    line = ShaftLine("HP", [], speed_ratio=ratio)
    disk = rs.DiskElement(n=0, m=10.0, Id=0.05, Ip=0.02, tag="disk")
    spring = rs.BearingElement(n=0, kxx=k, kzz=k, krr=kr, tag="spring")
    return rs.Rotor([], [disk], [spring], lines=[line])


@pytest.mark.validation
@pytest.mark.parametrize("ratio", [1.45, 0.7, -1.3])
def test_critical_speeds_of_a_spool_match_the_closed_form(ratio: float) -> None:
    """A rigid disk spinning at ``r W`` on a spring (lateral ``k``, tilt ``kr``), excited by
    its own spool's 1X, ``w = |r| W`` (Friswell et al. 2010, section 3.5, rigid rotor):
    - cylindrical whirl, both senses: ``w = sqrt(k / m)``, so ``W = sqrt(k / m) / |r|``;
    - conical whirl ``kr - Id w^2 + Ip (r W) (s w) = 0``, ``s = +1`` forward and ``-1``
      backward in the fixed frame: ``W^2 = kr / (Id r^2 - s Ip r |r|)``."""
    rotor = _rigid_disk(ratio)
    cs = rs.critical_speeds(rotor, spool="HP", num_modes=6)
    m, Id, Ip, k, kr = 10.0, 0.05, 0.02, 1e6, 4e4
    a = abs(ratio)
    conical = [math.sqrt(kr / (Id * a * a - s * Ip * ratio * a)) for s in (1, -1)]
    cylindrical = math.sqrt(k / m) / a
    lateral = cs.select(kind="lateral")
    # rtol 1e-9: dense QZ on a 6-DOF pencil is accurate to ~1e-13 relative
    assert sorted(lateral.speed) == pytest.approx(sorted([cylindrical] * 2 + conical),
                                                  rel=1e-9)
    # a static unbalance drives only the cylindrical mode whirling with the spool
    sense = "forward" if ratio > 0 else "backward"
    driven = lateral.excitation > 0.99
    assert driven.sum() == 1 and lateral.whirl[driven][0] == sense
    assert lateral.speed[driven][0] == pytest.approx(cylindrical, rel=1e-9)
    assert np.all(lateral.excitation[~driven] < 1e-9)


@pytest.mark.verification
def test_a_counter_rotating_line_mirrors_the_whirl_directions() -> None:
    """Reversing a line's rotation (ratio -1 instead of 1) keeps every frequency and swaps
    forward and backward whirl (``G -> -G`` is the mirror image ``y -> -y``)."""
    def rotor(ratio: float) -> rs.Rotor:
        line = ShaftLine("L", _shaft(8), speed_ratio=ratio)
        disk = rs.DiskElement(n=4, m=12.0, Id=0.06, Ip=0.11, tag="disk")
        return rs.Rotor([], [disk], _supports(0, 8), lines=[line])

    ahead, back = rs.modal(rotor(1.0), speed=2000.0, num_modes=8), \
        rs.modal(rotor(-1.0), speed=2000.0, num_modes=8)
    np.testing.assert_allclose(back.wd, ahead.wd, rtol=1e-9)
    lateral = np.asarray(ahead.kind) == "lateral"
    swapped = {"forward": "backward", "backward": "forward"}
    assert lateral.sum() >= 6
    assert [swapped.get(w, w) for w in np.asarray(ahead.whirl)[lateral]] == \
        list(np.asarray(back.whirl)[lateral])


@pytest.mark.verification
def test_campbell_crossings_of_each_spool_match_the_exact_critical_speeds() -> None:
    rotor = _two_spool_undamped()
    campbell = rs.campbell(rotor, np.linspace(0.0, 1500.0, 301), num_modes=10)
    for spool in ("LP", "HP"):
        exact = rs.critical_speeds(rotor, spool=spool, num_modes=4, whirl="forward")
        crossing = campbell.critical_speeds(spool=spool, whirl="forward")
        below = exact.speed[exact.speed < 1450.0]
        assert below.size >= 2
        # the local cubic through grid points 5 rad/s apart: better than 1e-4 relative
        for w in below:
            assert np.min(np.abs(crossing.speed - w)) < 1e-4 * w


def _two_spool_undamped() -> rs.Rotor:
    lp = ShaftLine("LP", _shaft(12, 1.2, 0.05))
    hp = ShaftLine("HP", [rs.ShaftElement(L=0.1, idl=0.08, odl=0.1, material=STEEL)] * 5,
                   z0=0.3, speed_ratio=1.45)
    disks = [rs.DiskElement(n=2, m=20.0, Id=0.3, Ip=0.55, tag="fan"),
             rs.DiskElement(n=17, m=12.0, Id=0.1, Ip=0.19, tag="hp_disk")]
    bearings = [rs.BearingElement(n=0, kxx=5e7, kzz=1e8, tag="lp_front"),
                rs.BearingElement(n=12, kxx=3e7, tag="lp_rear"),
                rs.BearingElement(n=13, kxx=1e8, kzz=1e8, tag="hp_front"),
                rs.BearingElement(n=18, n_link=8, kxx=2e7, tag="inter")]
    return rs.Rotor([], disks, bearings, lines=[lp, hp])


@pytest.mark.verification
def test_a_rigid_casing_equals_ground() -> None:
    """The spool on bearings to a casing line held everywhere by penalty springs equals the
    spool on the same bearings to ground."""
    spool = ShaftLine("rotor", _shaft(8))
    casing = ShaftLine("casing", [rs.ShaftElement(L=0.1, idl=0.3, odl=0.32, material=STEEL,
                                                  gyroscopic=False)] * 8, speed_ratio=0.0)
    disk = [rs.DiskElement(n=4, m=12.0, Id=0.06, Ip=0.11, tag="disk")]
    grounded = rs.Rotor(_shaft(8), disk, _supports(0, 8))
    held = [rs.BearingElement(n=n, kxx=STIFF, kzz=STIFF, krr=STIFF, tag=f"g{n}")
            for n in range(9, 18)]
    bearings = [rs.BearingElement(n=0, n_link=9, kxx=2e7, kyy=3e7, kzz=1e8, cxx=300.0,
                                  tag="left"),
                rs.BearingElement(n=8, n_link=17, kxx=2e7, kyy=3e7, cxx=300.0, tag="right")]
    machine = rs.Rotor([], disk, [*bearings, *held], lines=[spool, casing])
    expected = _frequencies(grounded, 1500.0)
    got = rs.modal(machine, speed=1500.0, num_modes=10).wd
    np.testing.assert_allclose(got[: expected.size], expected, rtol=1e-6)


@pytest.mark.validation
def test_unbalance_of_each_spool_responds_at_its_own_speed() -> None:
    """A rigid disk at ratio r on an isotropic spring: ``|X| = me (r W)^2 /
    |k - m (r W)^2 + i c r W|`` (closed form), circular, whirling with the spool."""
    m, k, c, me = 10.0, 1e6, 200.0, 1e-4
    lines = [ShaftLine("LP", []), ShaftLine("HP", [], z0=0.5, speed_ratio=-1.3)]
    disks = [rs.DiskElement(n=0, m=m, Id=0.05, Ip=0.02, tag="lp"),
             rs.DiskElement(n=1, m=m, Id=0.05, Ip=0.02, tag="hp")]
    bearings = [rs.BearingElement(n=n, kxx=k, cxx=c, kzz=k, krr=1e5, tag=f"b{n}")
                for n in (0, 1)]
    weak = rs.BearingElement(n=0, n_link=1, kxx=1e-3, tag="weak")  # joins the two lines
    rotor = rs.Rotor([], disks, [*bearings, weak], lines=lines)
    W = np.linspace(50.0, 600.0, 12)
    result = rs.unbalance_response(rotor, W, [(0, me, 0.0), (1, me, 0.0)])
    assert result.input_ratios is not None and result.input_ratios.tolist() == [1.0, -1.3]
    for column, ratio in enumerate((1.0, -1.3)):
        w = abs(ratio) * W
        closed = me * w**2 / np.abs(k - m * w**2 + 1j * c * w)
        node = column
        # the 1e-3 N/m link perturbs the response by ~1e-9 relative
        np.testing.assert_allclose(result.amplitude(node, "ux", column), closed, rtol=1e-7)
        assert np.allclose(result.orbit(node, column).whirl_ratio, np.sign(ratio),
                           atol=1e-6)
        np.testing.assert_allclose(result.input_frequencies(column), w)
    peak = result.peak_amplitude(0, "ux")
    np.testing.assert_allclose(peak, result.amplitude(0, "ux", 0) + result.amplitude(0, "ux", 1))


@pytest.mark.verification
def test_transient_unbalance_of_a_spool_turns_with_the_spool() -> None:
    """Time integration of the linear two-spool rotor at constant speed with the HP spool's
    unbalance only: after the start-up transient decays the motion at the HP disk is the
    harmonic response at ``r W`` (the steady-state amplitude of the frequency-domain
    solution, to the accuracy of the time step)."""
    rotor = _two_spool_damped()
    W, r = 300.0, 1.45
    unbalance = [(17, 1e-4, 0.0)]
    steady = rs.unbalance_response(rotor, [W], unbalance)
    amp = float(steady.amplitude(17, "ux", 0)[0])
    period = 2 * np.pi / (r * W)
    result = rs.transient(rotor, speed=W, t_end=160 * period, dt=period / 40,
                          unbalance=unbalance)
    t, x = result.t, result.displacement(17, "ux")
    last = t > t[-1] - 5 * period
    # 1e-2: the slowest free mode (log dec 0.045 at 243 rad/s) has decayed to ~3e-3 of its
    # start after 160 HP periods; Newmark's amplitude error at 40 steps per period is ~1e-3
    assert np.max(np.abs(x[last])) == pytest.approx(amp, rel=1e-2)
    # the motion repeats with the HP period, not the LP one
    n = round(5 * period / (t[1] - t[0]))
    spectrum = np.abs(np.fft.rfft(x[last][:n]))
    freq = np.fft.rfftfreq(n, t[1] - t[0]) * 2 * np.pi
    assert freq[np.argmax(spectrum)] == pytest.approx(r * W, rel=0.05)


def _two_spool_damped() -> rs.Rotor:
    rotor = _two_spool_undamped()
    bearings = [rs.BearingElement(n=b.n, n_link=b.n_link, kxx=b.kxx, kzz=b.kzz, cxx=4e4,
                                  tag=b.tag) for b in rotor.bearing_elements]
    return rotor.with_bearings(bearings)


@pytest.mark.validation
def test_inter_shaft_bearing_varying_compliance_at_the_kinematic_cage_speed() -> None:
    """The rolling elements of a bearing whose inner ring turns at ``W_i`` and outer ring at
    ``W_o`` orbit at ``W_c = ((1 - g) W_i + (1 + g) W_o) / 2``, ``g = D cos(a) / d_m``:
    the force at a fixed displacement then varies at ``Z |W_c|`` (a fixed load)."""
    ball = BallBearing(n_balls=9, pitch_diameter=0.05, ball_diameter=0.01, Kn=8e9,
                       f_i=0.52, f_o=0.52, radial_clearance=0.0)
    W, r_i, r_o = 500.0, 1.45, 1.0
    element = RollingBearing(ball, n=0, n_link=1, inner_speed_ratio=r_i,
                             outer_speed_ratio=r_o)
    g = 0.01 / 0.05
    w_cage = ((1 - g) * r_i + (1 + g) * r_o) / 2 * W
    assert element.cage_speed_ratio * W == pytest.approx(w_cage, rel=1e-12)
    n = 4096
    t = np.arange(n) * (2 * np.pi / (9 * w_cage)) * 16 / n  # 16 element passes
    u = np.zeros((n, 12))
    u[:, 1] = 2e-5  # inner ring pushed along y, outer held
    force = element.force(u, np.zeros_like(u), W * t, W).f[:, 1]
    spectrum = np.abs(np.fft.rfft(force - force.mean()))
    freq = np.fft.rfftfreq(n, t[1] - t[0]) * 2 * np.pi
    assert freq[np.argmax(spectrum)] == pytest.approx(9 * w_cage, rel=1e-9)


def test_a_machine_sets_the_ring_speeds_of_its_rolling_bearings_from_the_lines() -> None:
    ball = BallBearing(n_balls=9, pitch_diameter=0.05, ball_diameter=0.01, Kn=8e9,
                       f_i=0.52, f_o=0.52)
    rotor = _two_spool_undamped()
    inter = RollingBearing(ball, n=18, n_link=8, tag="inter_rb")
    to_ground = RollingBearing(ball, n=0, tag="lp_rb")
    machine = rotor.with_nonlinear([inter, to_ground])
    by_tag = {el.tag: el for el in machine.nonlinear_elements}
    assert (by_tag["inter_rb"].inner_speed_ratio, by_tag["inter_rb"].outer_speed_ratio) \
        == (1.45, 1.0)
    assert by_tag["lp_rb"] is to_ground  # (1, 0): left as given


def test_the_two_spool_example_model_runs_its_linear_analyses(tmp_path: Path) -> None:
    model = rs.load_model(MODELS / "two_spool.toml")
    rotor = model.rotor
    assert [line.name for line in rotor.lines] == ["LP", "HP", "casing"]
    assert [line.speed_ratio for line in rotor.lines] == [1.0, 1.45, 0.0]
    lp = rs.critical_speeds(rotor, spool="LP", num_modes=3, whirl="forward")
    hp = rs.critical_speeds(rotor, spool="HP", num_modes=3, whirl="forward")
    assert np.all(np.diff(lp.speed) > 0) and np.all(hp.excitation >= 0)
    assert not np.allclose(lp.speed[:2], hp.speed[:2])
    unb = rs.unbalance_response(rotor, np.linspace(50, 1500, 30), model.loads.unbalance)
    assert unb.n_inputs == 2 and unb.input_ratios is not None


def _plain_rotor(damping: rs.SystemDamping | None) -> rs.Rotor:
    disk = rs.DiskElement(n=3, m=12.0, Id=0.06, Ip=0.11, tag="disk")
    bearings = [rs.BearingElement(n=0, kxx=2e7, kyy=3e7, kzz=1e8, ktt=1e4, tag="left"),
                rs.BearingElement(n=8, kxx=2e7, kyy=3e7, tag="right")]
    return rs.Rotor(_shaft(8), [disk], bearings, damping=damping)


@pytest.mark.validation
def test_system_rayleigh_damping_gives_the_proportional_damping_ratios() -> None:
    """``C = alpha M + beta K`` over the whole system (disk included): every undamped mode
    at rest has ``zeta = alpha / (2 w) + beta w / 2`` (classical proportional damping)."""
    alpha, beta = 8.0, 2e-5
    modes = rs.modal(_plain_rotor(rs.SystemDamping(alpha=alpha, beta=beta)), speed=0.0,
                     num_modes=8)
    wn = modes.wn
    # 1e-9: the modes of a proportionally damped system are the undamped ones exactly
    np.testing.assert_allclose(modes.damping_ratio, alpha / (2 * wn) + beta * wn / 2, rtol=1e-9)


@pytest.mark.validation
def test_modal_damping_sets_the_ratio_of_each_mode() -> None:
    """``C = M Phi diag(2 zeta w) Phi^T M``: mode ``j`` at rest has exactly ``zeta_j`` (the
    undamped modes diagonalise it); the anisotropic supports split every pair."""
    ratios = (0.01, 0.02, 0.03, 0.04, 0.05, 0.06)
    modes = rs.modal(_plain_rotor(rs.SystemDamping(modal_ratios=ratios)), speed=0.0,
                     num_modes=8)
    order = np.argsort(modes.wn)  # the ratios go to the elastic modes by frequency,
    assert np.asarray(modes.kind)[order][0] == "torsional"  # whatever their kind
    # 1e-8: the damped modes are the undamped ones exactly (Phi^T C Phi diagonal)
    np.testing.assert_allclose(modes.damping_ratio[order][:6], ratios, rtol=1e-8)
    assert np.all(modes.damping_ratio[order][6:] < 1e-12)


@pytest.mark.validation
def test_a_coupling_carries_torque_between_two_lines() -> None:
    """Two rigid disks on two lines joined by a torsional coupling ``kt``: the torsional
    mode has ``w^2 = kt (1/Ip1 + 1/Ip2)`` (two inertias on a spring)."""
    kt, ip1, ip2 = 5e4, 0.2, 0.3
    lines = [ShaftLine("motor", []), ShaftLine("pump", [], z0=0.1)]
    disks = [rs.DiskElement(n=0, m=10.0, Id=0.1, Ip=ip1, tag="rotor"),
             rs.DiskElement(n=1, m=10.0, Id=0.1, Ip=ip2, tag="impeller")]
    supports = [rs.BearingElement(n=n, kxx=1e7, kzz=1e7, krr=1e5, tag=f"b{n}")
                for n in (0, 1)]
    coupling = rs.BearingElement.coupling(0, 1, torsional=kt, tag="coupling")
    modes = rs.modal(rs.Rotor([], disks, [*supports, coupling], lines=lines), speed=0.0,
                     num_modes=12)
    torsion = np.asarray(modes.kind) == "torsional"
    assert torsion.sum() == 1
    expected = math.sqrt(kt * (1 / ip1 + 1 / ip2))
    assert modes.wn[torsion][0] == pytest.approx(expected, rel=1e-9)


@pytest.mark.validation
def test_inter_shaft_bearing_varying_compliance_in_a_machine_transient() -> None:
    """The HP disk rides on the LP shaft through a 9-ball inter-shaft bearing (inner ring on
    HP at 1.45 W, outer on LP at W) under gravity: the relative motion's spectrum peaks at
    the element passes of the fixed load direction, ``Z W_c`` with the kinematic cage speed
    of both rings turning (2124 rad/s), not at the value of a standing outer ring (1044) nor
    at the passes over the outer ring (324)."""
    ball = rs.BallBearing(n_balls=9, pitch_diameter=0.05, ball_diameter=0.01, Kn=8e9,
                          f_i=0.52, f_o=0.52, radial_clearance=0.0)
    lines = [ShaftLine("LP", []), ShaftLine("HP", [], speed_ratio=1.45)]
    disks = [rs.DiskElement(n=0, m=20.0, Id=0.1, Ip=0.15, tag="lp"),
             rs.DiskElement(n=1, m=5.0, Id=0.02, Ip=0.03, tag="hp")]
    supports = [rs.BearingElement(n=0, kxx=5e8, kzz=5e8, krr=1e7, cxx=2e3, tag="lp"),
                rs.BearingElement(n=1, kzz=1e8, krr=1e6, tag="hp_thrust")]
    inter = rs.RollingBearing(ball, n=1, n_link=0, tag="inter",
                              contact_damping="proportional", damping_factor=2e-5)
    rotor = rs.Rotor([], disks, supports, lines=lines, nonlinear_elements=[inter])
    W, g = 200.0, 0.01 / 0.05
    passes = 9 * ((1 - g) * 1.45 + (1 + g) * 1.0) / 2 * W
    result = rs.transient(rotor, speed=W, t_end=0.12, dt=5e-5,
                          excitation=rs.Excitation(gravity=9.81))
    t = result.t
    y = result.displacement(1, "uy") - result.displacement(0, "uy")
    keep = t > 0.04
    signal = (y[keep] - y[keep].mean()) * np.hanning(keep.sum())
    spectrum = np.abs(np.fft.rfft(signal))
    freq = np.fft.rfftfreq(signal.size, t[1] - t[0]) * 2 * np.pi
    # 0.05: the 0.08 s window resolves 79 rad/s, 3.7 % of the line
    assert freq[np.argmax(spectrum)] == pytest.approx(passes, rel=0.05)


@pytest.mark.validation
def test_a_torque_drive_sees_the_inertia_of_every_spool_through_its_ratio() -> None:
    """Constant motor torque ``T`` on a machine of two rigid-disk spools at ratios 1 and
    1.45 (and a casing at 0): the kinetic energy ``sum_k I_k (r_k W)^2 / 2`` makes
    ``W' = T / (I_LP + 1.45^2 I_HP)`` (the casing's inertia does not count)."""
    lines = [ShaftLine("LP", []), ShaftLine("HP", [], speed_ratio=1.45),
             ShaftLine("casing", [], speed_ratio=0.0)]
    disks = [rs.DiskElement(n=0, m=20.0, Id=0.1, Ip=0.4, tag="lp"),
             rs.DiskElement(n=1, m=5.0, Id=0.05, Ip=0.1, tag="hp"),
             rs.DiskElement(n=2, m=50.0, Id=1.0, Ip=2.0, tag="casing")]
    bearings = [rs.BearingElement(n=n, kxx=1e8, kzz=1e8, krr=1e6, tag=f"b{n}")
                for n in (0, 1, 2)]
    rotor = rs.Rotor([], disks, bearings, lines=lines)
    T, W0 = 20.0, 100.0
    result = rs.transient(rotor, 0.05, 1e-3, speed=rs.TorqueDrive(motor=T, initial_speed=W0),
                          excitation=rs.Excitation(gravity=None), initial="zero")
    J = 0.4 + 1.45**2 * 0.1
    assert result.options["speed"]["inertia"] == pytest.approx(J, rel=1e-12)
    # a constant torque on a linear speed law: exact up to the drive integrator's rounding
    np.testing.assert_allclose(result.speed, W0 + T * result.t / J, rtol=1e-9)
