"""Lives and pressures of a double-row bearing (issue 18): each row rated at its own ring
loads, the rows combined with the Weibull slope, in statics, duty cycles, transients,
periodic orbits, model files, ``rotorsim bearing`` and HDF5."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.analyses.statics.bearing_history import history_life_result
from rotorsim.cli.main import main
from rotorsim.elements.rolling.rating.double_row import ROW_RATING_POWER, DoubleRowRating
from rotorsim.errors import ModelError
from rotorsim.io.model_file import load_model

STEEL = rs.Material(name="steel", E=211e9, G_s=81.2e9, rho=7810)
BALL = rs.BallBearing.from_geometry(n_balls=12, pitch_diameter=0.05, ball_diameter=0.008,
                                    f_i=0.52, f_o=0.53, contact_angle=math.radians(30.0),
                                    radial_clearance=-2e-6)
TAPERED = rs.RollerBearing(n_rollers=20, pitch_diameter=0.2, roller_diameter=0.02,
                           effective_length=0.03, contact_angle=math.radians(10.0),
                           radial_clearance=-3e-6, model="slices", n_slices=10)
SLOPE = {"ball": 10.0 / 9.0, "roller": 9.0 / 8.0}


@pytest.mark.parametrize(("row", "arrangement", "load"), [
    (BALL, "back_to_back", [3000.0, -1000.0, 800.0, 20.0, -50.0]),
    (TAPERED, "face_to_face", [60000.0, -20000.0, 8000.0, 200.0, -900.0]),
], ids=["ball O", "tapered X"])
def test_the_unit_life_is_two_single_row_bearings_at_the_row_loads(row, arrangement, load):
    """Rigid limit: each row of the unit is a single-row bearing carrying that row's ring
    load (its force in its own frame); rated alone, with its share ``C / 2^0.7`` of the
    unit's catalogue ``C``, each gives the unit's row life, and the unit's life is their
    Weibull combination. Tolerance 1e-6: the single rows' equilibria are solved anew
    (Newton to 1e-10 of the displacement scale; life ~ displacement^(3 to 4.5))."""
    unit = rs.DoubleRowBearing(row, 0.03 if row is BALL else 0.1, arrangement)
    c_unit = 40e3 if row is BALL else 300e3
    life = rs.bearing_life(unit, load, options=rs.RatingOptions(C=c_unit))
    kind = life.kind
    c_row = c_unit / 2.0 ** ROW_RATING_POWER[kind]
    eq = rs.bearing_equilibrium(unit, load)
    singles = []
    for k, st in enumerate(unit.row_states(eq.displacement[None], eq.element_angles[None])):
        single = rs.bearing_life(row, st.force[0], options=rs.RatingOptions(C=c_row))
        assert single.L10r == pytest.approx(life.row_life[k], rel=1e-6)
        singles.append(single)
    e = SLOPE[kind]
    assert life.L10r == pytest.approx((life.row_life ** -e).sum() ** (-1 / e), rel=1e-12)
    assert life.P_ref == pytest.approx(c_unit * life.L10r ** (-1 / (3 if kind == "ball"
                                                                    else 4)), rel=1e-12)
    # the same as DoubleRowRating's per-row life at the equilibrium
    ref = DoubleRowRating(unit, rs.RatingOptions(C=c_unit)).life(eq.displacement,
                                                                  eq.element_angles)
    assert life.L10r == pytest.approx(float(ref.L10r[0]), rel=1e-12)
    n = row.n_elements
    assert life.max_pressure.shape == (2 * n, 2) and life.element_load.shape == (2 * n,)
    np.testing.assert_allclose(life.max_pressure[n:], singles[1].max_pressure, rtol=1e-5)
    assert life.C == c_unit and life.summary["bearing"] == "DoubleRowBearing"


def test_iso281_life_of_the_unit_uses_the_double_row_factors():
    unit = rs.DoubleRowBearing(BALL, 0.03)
    r = rs.bearing_life(unit, [2000.0, 0.0, 500.0, 0.0, 0.0])
    # 30 deg, F_a/F_r = 0.25 <= e = 0.8: P = F_r + 0.78 F_a (ISO 281 Table 3)
    assert r.P == pytest.approx(2000.0 + 0.78 * 500.0, rel=1e-12)
    assert r.L10 == pytest.approx((r.C / r.P) ** 3, rel=1e-12)
    assert r.row_life.shape == (2,) and "rows:" in r.table()


def test_reversed_unit_and_element_are_rated_like_the_unit():
    unit = rs.DoubleRowBearing(BALL, 0.03)
    load = [1000.0, 200.0, 600.0, 5.0, -8.0]
    a = rs.bearing_life(unit, load)
    b = rs.bearing_life(rs.RollingBearing(unit, n=0, tag="U"), load)
    assert b.L10r == pytest.approx(a.L10r, rel=1e-9) and b.summary["tag"] == "U"
    mirrored = [load[0], load[1], -load[2], -load[3], -load[4]]
    c = rs.bearing_life(rs.ReversedBearing(unit), mirrored)
    assert c.L10r == pytest.approx(a.L10r, rel=1e-6)


def test_duty_cycle_and_history_of_a_steady_load_agree():
    """One cage revolution of a fixed ring displacement rated as a history (the transient
    and periodic path) against the duty-cycle path: 0.5 % (the history samples the cage
    at 80 steps per pitch, the duty cycle at 16)."""
    unit = rs.DoubleRowBearing(BALL, 0.03)
    element = rs.RollingBearing(unit, n=0)
    load = [2500.0, 0.0, 700.0, 0.0, 10.0]
    cycle = rs.duty_cycle_life(element, [(1.0, load, None)])
    eq = rs.bearing_equilibrium(unit, load)
    kappa = (1.0 - BALL.ball_diameter * math.cos(BALL.contact_angle) / BALL.pitch_diameter) / 2
    phi = np.linspace(0.0, 2.0 * math.pi / kappa, 12 * 80 + 1)
    hist = history_life_result(element, np.broadcast_to(eq.displacement, (phi.size, 5)), phi,
                               source="transient")
    assert hist.L10r == pytest.approx(cycle.L10r, rel=5e-3)
    np.testing.assert_allclose(hist.row_life, cycle.row_life, rtol=5e-3)
    assert cycle.P == pytest.approx(rs.bearing_life(unit, load).P, rel=1e-12)


def _rotor():
    shaft = [rs.ShaftElement(L=0.15, idl=0.0, odl=0.04, material=STEEL) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=STEEL, width=0.04, i_d=0.04, o_d=0.2)
    unit = rs.DoubleRowBearing(rs.BallBearing(
        n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=9.3e9, f_i=0.52,
        f_o=0.52, contact_angle=math.radians(25.0), radial_clearance=-2e-6), 0.02)
    bearings = [rs.RollingBearing(unit, n=0, tag="DR"),
                rs.RollingBearing(BALL, n=2, tag="B2")]
    dampers = [rs.BearingElement(n=n, kxx=0.0, cxx=3000.0, cyy=3000.0) for n in (0, 2)]
    return rs.Rotor(shaft, [disk], dampers, nonlinear_elements=bearings,
                    fixed=[(1, "uz")]), bearings


def test_transient_and_periodic_lives_of_a_double_row_element():
    """Both history paths rate the unit (short runs; the agreement of the history and
    steady rules is checked above and, for single rows, in test_bearing_life.py)."""
    rotor, bearings = _rotor()
    unbalance = [(1, 2e-5, 0.0)]
    tr = rs.transient(rotor, 0.02, 5e-5, speed=400.0, unbalance=unbalance)
    life = rs.transient_life(tr, bearings[0], t_min=0.01)
    assert life.source == "transient" and life.row_life.shape == (2,)
    assert 0 < life.L10r <= life.row_life.min()
    branch = rs.periodic(rotor, start=400.0, stop=401.0, harmonics=3, nodes=[0, 1, 2],
                         unbalance=unbalance,
                         continuation=rs.ContinuationOptions(max_points=2, tol=1e-9),
                         stability=rs.StabilityOptions(None, bifurcations=False))
    orbit = rs.periodic_life(branch, bearings[0], 0, samples=16, cage_revolutions=1.0)
    assert orbit.source == "periodic" and orbit.max_pressure.shape == (18, 2)
    assert 0 < orbit.L10r <= orbit.row_life.min()


def test_results_file_keeps_the_row_lives(tmp_path):
    r = rs.bearing_life(rs.DoubleRowBearing(TAPERED, 0.1), [50000.0, 0, 3000.0, 0, 0])
    back = rs.load(rs.save(r, tmp_path / "dr.h5"))
    np.testing.assert_array_equal(back.row_life, r.row_life)
    assert back.L10r == r.L10r and back.slice_pressure.shape == (40, 10, 2)


def test_a_row_rating_alone_refuses_unit_loads():
    from rotorsim.elements.rolling.rating.rated_bearing import RatedBearing

    rb = RatedBearing(rs.DoubleRowBearing(BALL, 0.03))
    assert rb.geometric_cage_ratio > 0
    with pytest.raises(ModelError, match="one row's rating"):
        rb.life(np.zeros((1, 5)), np.zeros((1, 24)))


MODELS = Path(__file__).resolve().parents[3] / "models"


def test_a_model_file_double_row_is_rated_by_rotorsim_bearing(tmp_path, capsys):
    """``rows = 2`` with a ``[rolling_bearings.rating]`` table: ``rotorsim bearing`` prints
    and writes the unit's life (catalogue C of the unit, the two row lives)."""
    text = (MODELS / "rolling_ball.toml").read_text()
    marker = 'damping_factor = "20 us"\n'
    head, tail = text.split(marker, 1)
    path = tmp_path / "dr.toml"
    path.write_text(head + marker + 'rows = 2\nrow_spacing = "20 mm"\n'
                    '\n[rolling_bearings.rating]\nC = "20 kN"\n' + tail)
    model = load_model(path)
    assert model.ratings[0].C == 20e3
    assert main(["bearing", str(path), "--out", str(tmp_path), "--no-plots", "--fast",
                 "--tag", "DE"]) == 0
    out = capsys.readouterr().out
    life = rs.load(tmp_path / "rolling_ball" / "bearing_DE_life.h5")
    assert life.C == 20e3 and life.row_life.shape == (2,) and life.max_pressure.shape == (18, 2)
    assert "rows:" in out and f"L10r = {life.L10r:.4g} Mrev" in out


def test_quasi_periodic_life_is_the_life_of_a_transient_on_the_torus():
    """The Jeffcott rotor of tests/analyses/periodic on turning cages, 800 rad/s: the life
    along its quasi-periodic response (box (4, 2)) against ``rs.transient_life`` of a
    transient started on the torus over the same window (11 shaft revolutions, 64 steps per
    revolution, balls moving): within 1 % (measured 0.07 % with (6, 2) over 20
    revolutions; the torus leaves the transient by 0.2 % of the motion, the life goes as
    its cube or more); the window average settles (4 and 8 cage revolutions: 0.11 %,
    bound 0.3 %)."""
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "periodic"))
    from test_periodic import UNBALANCE, jeffcott

    rotor = jeffcott("rotating")
    element = rotor.nonlinear_elements[0]
    point = rs.quasi_periodic_point(rotor, 800.0, unbalance=UNBALANCE, harmonics=(4, 2),
                                    truncation="box")
    life = rs.quasi_periodic_life(point, element, cage_revolutions=4.0)
    longer = rs.quasi_periodic_life(point, element, cage_revolutions=8.0)
    assert life.source == "quasi_periodic" and life.options["shaft_revolutions"] == 11
    assert longer.L10r == pytest.approx(life.L10r, rel=3e-3)
    q0, v0 = point.state(0.0)
    step = 2 * math.pi / 800.0 / 64
    run = rs.transient(rotor, 704 * step, step, speed=800.0, unbalance=UNBALANCE,
                       initial=(q0, v0), nodes=[0, 1, 2])
    assert rs.transient_life(run, element).L10r == pytest.approx(life.L10r, rel=0.01)
    with pytest.raises(ModelError, match="samples"):
        rs.quasi_periodic_life(point, element, samples=4)
