"""rs.bearing_life, rs.duty_cycle_life, rs.transient_life, rs.periodic_life: lives and
pressures of rolling bearings from rotorsim's own load distributions."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.elements.rolling import CircularCrown
from rotorsim.errors import ModelError

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)


def ball(**kw):
    return rs.BallBearing.from_geometry(n_balls=9, pitch_diameter=38.5e-3,
                                        ball_diameter=7.938e-3, f_i=0.52, f_o=0.53, **kw)


def test_equilibrium_life_fields_and_conventions():
    r = rs.bearing_life(ball(), [2000.0, 0.0, 0.0, 0.0, 0.0])
    assert r.kind == "ball" and r.rating_source.startswith("ISO 281 geometry")
    assert r.L10 == pytest.approx((r.C / 2000.0) ** 3)
    assert r.P_ref == pytest.approx(r.C * r.L10r ** (-1 / 3))
    assert r.Lnmr == r.L10r and r.a_iso == 1.0 and r.a1 == 1.0
    assert r.max_pressure.shape == (9, 2) and np.isnan(r.shoulder_margin).all()
    # a catalogue C scales the life as (C/P)^3 and the reference loads with it
    cat = rs.bearing_life(ball(), [2000.0, 0, 0, 0, 0], options=rs.RatingOptions(C=14.8e3))
    assert cat.rating_source == "catalogue"
    assert cat.L10r / r.L10r == pytest.approx((14.8e3 / r.C) ** 3, rel=1e-9)
    assert cat.hours(3000.0) == pytest.approx(cat.L10r * 1e6 / 180000.0)
    assert "L10r" in r.table()
    rows = r.pressure_table().splitlines()
    assert len(rows) == 2 + 9 and rows[0].split()[:2] == ["element", "angle"]
    assert float(rows[2].split()[3]) == pytest.approx(r.max_pressure[0, 0] / 1e6, abs=0.05)


def test_a_iso_reliability_and_truncation():
    opts = rs.RatingOptions(viscosity_ratio=1.0, contamination=0.5, fatigue_load_limit=335.0,
                            reliability=99.0, shoulder_heights=(0.8e-3, 0.8e-3))
    r = rs.bearing_life(ball(diametral_clearance=20e-6), [500.0, 0.0, 1500.0, 0.0, 0.0],
                        options=opts)
    assert r.a1 == 0.25 and r.a_iso > 1
    assert r.Lnmr == pytest.approx(0.25 * r.a_iso * r.L10r)
    assert r.truncated  # 1.5 kN axial, shoulders of 0.8 mm (10 % of the ball): 36 deg
    low = rs.bearing_life(ball(diametral_clearance=20e-6), [500.0, 0.0, 200.0, 0.0, 0.0],
                          options=opts)
    assert not low.truncated


def test_tilt_shortens_the_life_of_a_roller_bearing():
    """The ISO/TS 16281 lamina life sees the edge load of a misaligned roller; ISO 281's
    ``L10`` does not (it ignores moments)."""
    rb = rs.RollerBearing(14, 65e-3, 10e-3, 9.6e-3, model="slices", n_slices=20,
                          profile=CircularCrown(crown_drop=4e-6))
    straight = rs.bearing_life(rb, [8000.0, 0.0, 0.0, 0.0, 0.0])
    tilted = rs.bearing_life(rb, [8000.0, 0.0, 0.0, 0.0, 8.0])
    assert tilted.L10 == straight.L10
    assert tilted.L10r < 0.9 * straight.L10r
    assert tilted.slice_pressure.shape == (14, 20, 2)
    j = int(np.argmax(tilted.max_pressure[:, 0]))
    edges = tilted.slice_pressure[j, [0, -1], 0]
    assert edges.max() > 1.2 * edges.min()


def test_reversed_bearing_and_element_are_rated_like_the_base_model():
    base = rs.BallBearing.from_geometry(n_balls=12, pitch_diameter=50e-3, ball_diameter=8e-3,
                                        f_i=0.52, f_o=0.53, contact_angle=math.radians(25))
    a = rs.bearing_life(base, [1000.0, 0.0, 1500.0, 0.0, 0.0])
    b = rs.bearing_life(rs.ReversedBearing(base), [1000.0, 0.0, -1500.0, 0.0, 0.0])
    assert b.L10r == pytest.approx(a.L10r, rel=1e-6)
    assert a.P == pytest.approx(0.41 * 1000.0 + 0.87 * 1500.0)
    element = rs.RollingBearing(base, n=0)
    c = rs.bearing_life(element, [1000.0, 0.0, 1500.0, 0.0, 0.0])
    assert c.L10r == pytest.approx(a.L10r, rel=1e-9)


def test_duty_cycle_combines_cases_by_their_revolutions():
    b = ball()
    light, heavy = [1000.0, 0, 0, 0, 0], [3000.0, 0, 0, 0, 0]
    one = rs.duty_cycle_life(b, [(1.0, heavy, None)])
    two = rs.duty_cycle_life(b, [(0.5, light, None), (0.5, heavy, None)])
    lone = rs.duty_cycle_life(b, [(1.0, light, None)])
    # equal shares: the damage rates add, 1/L = (1/L_a + 1/L_b)/2 per point; with the load
    # zone in the same place the ring powers p e stay near additive: 3 % here
    harmonic = 2.0 / (1.0 / one.L10r + 1.0 / lone.L10r)
    assert two.L10r == pytest.approx(harmonic, rel=0.03)
    by_time = rs.duty_cycle_life(b, [(0.5, light, 1000.0), (0.5, heavy, 3000.0)],
                                 basis="time")
    assert by_time.L10r < two.L10r  # more of the revolutions under the heavy load
    assert two.P == pytest.approx((0.5 * 1000.0**3 + 0.5 * 3000.0**3) ** (1 / 3))
    with pytest.raises(ModelError, match="speed"):
        rs.duty_cycle_life(b, [(1.0, light, None)], basis="time")
    with pytest.raises(ModelError, match="no load cases"):
        rs.duty_cycle_life(b, [])


def test_steady_transient_life_equals_the_cage_average_of_the_static_load():
    """A rotor on two ball bearings under gravity at constant speed: the history life of a
    transient equals the duty-cycle (one cage revolution at the static equilibrium) life
    within 1 % (the transient keeps a small vibration from the start)."""
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    bearings = [rs.RollingBearing(ball(), n=n, tag=f"B{n}") for n in (0, 2)]
    dampers = [rs.BearingElement(n=n, kxx=0.0, cxx=3000.0, cyy=3000.0) for n in (0, 2)]
    rotor = rs.Rotor(shaft, [disk], dampers, nonlinear_elements=bearings, fixed=[(1, "uz")])
    speed = 300.0
    res = rs.transient(rotor, 0.25, 2e-5, speed=speed)
    life = rs.transient_life(res, bearings[0], t_min=0.1)
    load = res.bearing_loads[-1, 0]
    steady = rs.duty_cycle_life(bearings[0], [(1.0, load, None)])
    assert life.source == "transient" and life.stats["samples"] > 1000
    assert life.L10r == pytest.approx(steady.L10r, rel=0.01)
    with pytest.raises(ModelError, match="fewer than 2 samples"):
        rs.transient_life(res, bearings[0], t_min=1.0)


def test_periodic_life_of_an_unbalance_orbit():
    """An unbalance orbit rated over one period (repeated) against a transient started on
    that orbit: within 5 % (the periodic model freezes the balls, the transient lets them
    orbit: the varying compliance the harmonic balance neglects, measured 3 %)."""
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    bearings = [rs.RollingBearing(rs.BallBearing(n_balls=9, pitch_diameter=0.0385,
                                                  ball_diameter=0.00794, Kn=9.3e9, f_i=0.52,
                                                  f_o=0.52, diametral_clearance=10e-6),
                                  n=n, tag=f"B{n}") for n in (0, 2)]
    dampers = [rs.BearingElement(n=n, kxx=0.0, cxx=5000.0) for n in (0, 2)]
    rotor = rs.Rotor(shaft, [disk], dampers, nonlinear_elements=bearings, fixed=[(1, "uz")])
    unbalance = [(1, 3e-5, 0.0)]
    branch = rs.periodic(rotor, start=600.0, stop=610.0, harmonics=6, nodes=[0, 1, 2],
                         unbalance=unbalance, varying_compliance=False,
                         continuation=rs.ContinuationOptions(max_points=2, tol=1e-10),
                         stability=rs.StabilityOptions(None, bifurcations=False))
    assert isinstance(branch, rs.PeriodicResult) and "frozen" in branch.approximation
    life = rs.periodic_life(branch, bearings[0], 0)
    q0, v0 = branch.state(0, 0.0)
    speed = float(branch.speed[0])
    tr = rs.transient(rotor, 0.3, 2 * math.pi / speed / 100, speed=speed, unbalance=unbalance,
                      initial=(q0, v0), nodes=[0, 1, 2])
    reference = rs.transient_life(tr, bearings[0], t_min=0.1)
    assert life.L10r == pytest.approx(reference.L10r, rel=0.05)
    assert life.options["periods"] >= 1
    with pytest.raises(ModelError, match="point 5"):
        rs.periodic_life(branch, bearings[0], 5)
    # with the balls moving (the default): the torus, rated along time over its cage
    # revolutions, against the same transient (balls orbiting in both)
    tori = rs.periodic(rotor, start=600.0, stop=610.0, harmonics=6, nodes=[0, 1, 2],
                       unbalance=unbalance, stability=None,
                       continuation=rs.ContinuationOptions(max_points=4, tol=1e-10))
    assert isinstance(tori, rs.QuasiPeriodicResult)
    on_torus = rs.periodic_life(tori, bearings[0], 0)
    print(f"L10r: frozen {life.L10r:.6g}, torus {on_torus.L10r:.6g}, transient "
          f"{reference.L10r:.6g}")
    assert on_torus.L10r == pytest.approx(reference.L10r, rel=0.05)


def test_bad_input_is_refused_with_a_named_error():
    with pytest.raises(ModelError, match="exactly one of load and equilibrium"):
        rs.bearing_life(ball())
    with pytest.raises(ModelError, match="rotating_ring"):
        rs.RatingOptions(rotating_ring="cage")
    with pytest.raises(ModelError, match="missing contamination, fatigue_load_limit"):
        rs.RatingOptions(viscosity_ratio=1.0)
    with pytest.raises(ModelError, match="C must be positive"):
        rs.RatingOptions(C=0.0)
    with pytest.raises(ModelError, match="not object"):
        rs.bearing_life(object(), [1.0, 0, 0, 0, 0])
    with pytest.raises(ModelError, match="thrust bearing"):
        rs.bearing_life(rs.RollerBearing(14, 65e-3, 10e-3, 9.6e-3, Kn=1e9,
                                         contact_angle=math.radians(60)),
                        [0.0, 0.0, 1000.0, 0.0, 0.0])


def test_results_file_and_figure(tmp_path):
    r = rs.bearing_life(ball(), [1500.0, 0.0, 300.0, 0.0, 0.0],
                        options=rs.RatingOptions(shoulder_heights=(1.5e-3, 1.5e-3)))
    path = rs.save(r, tmp_path / "life.h5")
    back = rs.load(path)
    assert back.L10r == r.L10r
    np.testing.assert_array_equal(back.max_pressure, r.max_pressure)
    assert back.options["shoulder_heights"] == [1.5e-3, 1.5e-3]
    fig = rs.plot(back)
    assert len(fig.axes) == 2


def test_kn_for_exponent():
    """Equal at the reference load; the least-squares fit of the same law is exact."""
    kn = rs.kn_for_exponent(9.3e9, 1.5, 10 / 9, load=1000.0)
    d = (1000.0 / 9.3e9) ** (2 / 3)
    assert kn * d ** (10 / 9) == pytest.approx(1000.0, rel=1e-12)
    assert rs.kn_for_exponent(9.3e9, 1.5, 1.5, load_range=(10.0, 1e4)) == \
        pytest.approx(9.3e9, rel=1e-12)
    with pytest.raises(ModelError, match="exactly one of load and load_range"):
        rs.kn_for_exponent(9.3e9, 1.5, 1.0)
