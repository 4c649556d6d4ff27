"""A rotor without shaft elements: a rigid rotor or point mass at node 0 on its bearings (the
classic model of the bearing literature), through static, modal, transient and periodic, from
the API and from a model file; and the user's starting point ``x0`` of the static solves."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.errors import ModelError

M, KX, KY = 2.5, 4.0e6, 9.0e6  # kg, N/m
RADIAL = tuple((0, d) for d in ("uz", "rx", "ry", "rz"))
BALL = rs.BallBearing(n_balls=8, pitch_diameter=0.0385, ball_diameter=0.00794, f_i=0.52,
                      f_o=0.52, Kn=9.3e9, radial_clearance=10e-6, tag="B")
LOAD = [(0, "uy", -50.0)]


def linear_rotor(point_mass: bool = False) -> rs.Rotor:
    bearing = rs.BearingElement(n=0, kxx=KX, kyy=KY)
    if point_mass:
        return rs.Rotor([], point_mass_elements=[rs.PointMass(n=0, m=M)],
                        bearing_elements=[bearing])
    disk = rs.DiskElement(n=0, m=M, Id=1e-3, Ip=2e-3)
    return rs.Rotor([], [disk], [bearing], fixed=RADIAL)


def rolling_rotor() -> rs.Rotor:
    disk = rs.DiskElement(n=0, m=1.0, Id=2.5e-4, Ip=4.5e-4)
    return rs.Rotor([], [disk], [rs.RollingBearing(BALL, n=0, tag="B")], fixed=RADIAL)


# ------------------------------------------------------------------ linear bearings
@pytest.mark.parametrize("point_mass", [False, True], ids=["disk", "point mass"])
def test_modal_frequencies_are_sqrt_k_over_m(point_mass):
    rotor = linear_rotor(point_mass)
    assert rotor.n_nodes == 1 and rotor.summary()["shaft_elements"] == 0
    wn = np.sort(rs.modal(rotor, num_modes=2).wn)
    # a 2x2 eigenproblem: exact to the eigensolver's round-off (~1e-15 relative)
    np.testing.assert_allclose(wn, [math.sqrt(KX / M), math.sqrt(KY / M)], rtol=1e-10)


def test_static_deflection_is_weight_over_stiffness():
    s = rs.static(linear_rotor())
    assert s.displacement[1] == pytest.approx(-9.80665 * M / KY, rel=1e-12)  # one solve
    assert s.bearing_forces[0, 1] == pytest.approx(9.80665 * M, rel=1e-12)
    assert s.shear_force.shape == (0, 2, 2) and s.element_z.shape == (0, 2)


def test_transient_free_vibration_is_a_cosine():
    rotor = linear_rotor()
    q0 = np.zeros(rotor.ndof)
    q0[0] = 1e-5
    dt, t_end = 5e-6, 5e-3
    t = rs.transient(rotor, t_end, dt, gravity=None, initial=(q0, np.zeros(rotor.ndof)))
    wn = math.sqrt(KX / M)
    x = t.displacement(0, "ux")
    # average acceleration: period error (wn dt)^2 / 12 = 6.7e-7 relative, i.e. a phase
    # error wn t_end (wn dt)^2 / 12 = 8.4e-6 rad at the end; no amplitude error
    bound = 2 * wn * t_end * (wn * dt) ** 2 / 12 * 1e-5
    np.testing.assert_allclose(x, 1e-5 * np.cos(wn * t.t), rtol=0, atol=bound)


def test_periodic_unbalance_response_is_the_analytic_one():
    rotor, me = linear_rotor(), 1e-4
    res = rs.periodic(rotor, start=500.0, stop=600.0, gravity=None, unbalance=[(0, me, 0.0)],
                      harmonics=1, max_points=30, stability=None, bifurcations=False)
    W = res.parameter
    expected = me * W**2 / np.abs(KX - M * W**2)  # 1X orbit amplitude along x
    x = np.array([res.harmonic_amplitudes(i, 0, "ux")[1] for i in range(len(res))])
    # linear problem: HB with one harmonic is exact, up to the corrector tolerance 1e-10
    np.testing.assert_allclose(x, expected, rtol=1e-8)


def test_a_model_file_without_shaft(tmp_path):
    path = tmp_path / "rigid.toml"
    path.write_text(f"""
[[disks]]
node = 0
m = "{M} kg"
Id = "1e-3 kg*m^2"
Ip = "2e-3 kg*m^2"

[[bearings]]
node = 0
kxx = "{KX} N/m"
kyy = "{KY} N/m"

[[fixed]]
node = 0
dofs = ["uz", "rx", "ry", "rz"]

[analyses.modes]
type = "modal"
num_modes = 2
""")
    model = rs.load_model(path)
    assert model.rotor.shaft_elements == ()
    from rotorsim.io.model_file import run_analysis

    wn = np.sort(run_analysis(model, "modes").wn)
    np.testing.assert_allclose(wn, [math.sqrt(KX / M), math.sqrt(KY / M)], rtol=1e-10)


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"shaft_elements": "shaft"}, "sequence of ShaftElement"),
    ({"shaft_elements": None}, "sequence of ShaftElement"),
    ({"shaft_elements": [], "disk_elements": [rs.DiskElement(n=1, m=1.0, Id=0.0, Ip=0.0)]},
     "node 1 is not on the shaft (nodes 0..0)"),
])
def test_bad_rigid_rotors_are_refused_by_name(kwargs, message):
    with pytest.raises(ModelError, match=message.replace("(", r"\(").replace(")", r"\)")):
        rs.Rotor(**kwargs)


# ------------------------------------------------------------------ rolling bearing
def test_rolling_rigid_rotor_modal_at_the_static_load_is_the_hertz_frequency():
    rotor = rolling_rotor()
    s = rs.static(rotor, gravity=None, loads=LOAD)
    d = -s.displacement[1]
    # one ball loaded (psi = -90 deg): k = 1.5 Kn (d - c)^0.5 along y
    k_y = 1.5 * BALL.Kn * (d - BALL.clearance) ** 0.5
    lin = rs.linearize_rolling_bearings(rotor, gravity=None, loads=LOAD)
    wn = rs.modal(lin.rotor, num_modes=1).wn
    assert wn[-1] == pytest.approx(math.sqrt(k_y / 1.0), rel=1e-9)  # d exact to ~1e-11


def test_rolling_rigid_rotor_transient_starts_at_the_static_equilibrium():
    rotor = rolling_rotor()
    s = rs.static(rotor, gravity=None, loads=LOAD)
    t = rs.transient(rotor, 1e-3, 2e-5, speed=100.0, gravity=None, loads=LOAD)
    # both solves stop at relative residuals <= 1e-8 (transient start) and 1e-10 (static)
    assert t.displacement(0, "uy")[0] == pytest.approx(s.displacement[1], rel=1e-7)
    assert np.all(np.isfinite(t.q))


# ------------------------------------------------------------------ x0
def test_static_uses_a_given_start():
    rotor = rolling_rotor()
    centred = rs.static(rotor, gravity=None, loads=LOAD, x0=np.zeros(rotor.ndof))
    assert centred.options["x0_given"] and centred.options["solver"] == "energy"
    again = rs.static(rotor, gravity=None, loads=LOAD, x0=centred.displacement)
    assert again.options["newton_iterations"] == 0 < centred.options["newton_iterations"]
    assert again.displacement[1] == pytest.approx(centred.displacement[1], rel=1e-9)
    energy = rs.static(rotor, gravity=None, loads=LOAD, method="energy",
                       x0=centred.displacement)
    assert energy.options["x0_given"]
    assert energy.displacement[1] == pytest.approx(centred.displacement[1], rel=1e-9)


def test_periodic_uses_a_given_start():
    rotor = rolling_rotor()
    s = rs.static(rotor, gravity=None, loads=LOAD)
    kwargs = {"start": 100.0, "stop": 101.0, "gravity": None, "loads": LOAD, "harmonics": 3,
              "max_points": 3, "stability": None, "bifurcations": False}
    given = rs.periodic(rotor, x0=s.displacement, **kwargs)
    default = rs.periodic(rotor, **kwargs)
    assert given.options["x0_given"] and not default.options["x0_given"]
    # the same equilibrium and branch: HB corrector tolerance 1e-10 on scaled residuals
    np.testing.assert_allclose(given.amplitude(0, "uy", "mean")[0],
                               default.amplitude(0, "uy", "mean")[0], rtol=1e-8)


def _bad_starts(ndof: int) -> list[tuple[object, str]]:
    fixed = np.zeros(ndof)
    fixed[2] = 1e-3
    return [(np.zeros(ndof - 1), r"must have shape \(6,\)"),
            (np.full(ndof, np.nan), "must be finite; DOF 0:ux is nan"),
            (np.r_[0.0, np.inf, np.zeros(ndof - 2)], "must be finite; DOF 0:uy is inf"),
            (fixed, r"is 0.001 on DOF 0:uz, which is fixed \(or connected to nothing\)"),
            ("zero", "must be an array of 6 numbers"),
            (np.zeros((2, 3)), r"must have shape \(6,\)")]


@pytest.mark.parametrize("case", range(6))
def test_bad_starts_are_refused_by_name(case):
    rotor = rolling_rotor()
    x0, message = _bad_starts(rotor.ndof)[case]
    with pytest.raises(ModelError, match="static.x0: " + message):
        rs.static(rotor, gravity=None, loads=LOAD, x0=x0)
    with pytest.raises(ModelError, match="static.x0: " + message):
        rs.static(linear_rotor(), x0=x0)
    with pytest.raises(ModelError, match="periodic.x0: " + message):
        rs.periodic(rotor, start=100.0, stop=101.0, gravity=None, loads=LOAD, x0=x0)


def test_vtk_export_of_a_rigid_rotor(tmp_path):
    meshio = pytest.importorskip("meshio")
    rotor = linear_rotor()
    static_file = rs.export_vtk(rs.static(rotor), tmp_path / "static.vtu")[0]
    mesh = meshio.read(static_file)
    assert [c.type for c in mesh.cells] == ["vertex"]  # node 0, no shaft line
    assert mesh.point_data["displacement"][0, 1] == pytest.approx(-9.80665 * M / KY,
                                                                  rel=1e-12)
    modal_files = rs.export_vtk(rs.modal(rotor, num_modes=2), tmp_path / "modes.vtu",
                                rotor=rotor)
    assert len(modal_files) >= 1 and all(p.exists() for p in modal_files)


def test_a_rigid_rotor_model_file_round_trips(tmp_path):
    from pathlib import Path

    from rotorsim.assembly.system import assemble

    model = rs.load_model(Path(__file__).resolve().parents[2] / "models" / "rigid_rotor_vc.toml")
    again = rs.load_model(rs.save_model(model, tmp_path / "rigid.toml"))
    assert again.rotor.shaft_elements == ()
    assert repr(again.rolling_bearings) == repr(model.rolling_bearings)  # same parameters
    a, b = assemble(again.rotor).matrices(), assemble(model.rotor).matrices()
    for key in "MK":  # the same numbers written and read back
        assert (getattr(a, key) - getattr(b, key)).count_nonzero() == 0
