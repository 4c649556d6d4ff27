"""Every result type draws its standard figure (Agg backend, no screen)."""

from __future__ import annotations

import numpy as np
import pytest

import rotorsim as rs
from rotorsim.model.material import steel
from rotorsim.plotting import plot


@pytest.fixture(scope="module")
def rotor():
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(6)]
    disks = [rs.DiskElement.from_geometry(2, steel, 0.07, 0.05, 0.28),
             rs.DiskElement.from_geometry(4, steel, 0.07, 0.05, 0.35)]
    bearings = [rs.BearingElement(n=0, kxx=1e6, kyy=1.2e6, cxx=200.0),
                rs.BearingElement(n=6, kxx=1e6, kyy=1.2e6, cxx=200.0)]
    return rs.Rotor(shaft, disks, bearings)


def _axes_count(fig):
    return len(fig.axes)


def test_mode_shape_2d_and_3d(rotor):
    m = rs.modal(rotor, speed=300.0, num_modes=4)
    assert _axes_count(plot(m, mode=1)) == 1
    assert _axes_count(plot(m, mode=1, view="3d")) == 1


def test_bode_and_polar(rotor):
    u = rs.unbalance_response(rotor, np.linspace(10, 600, 60), [(2, 1e-4, 0.0)])
    fig = plot(u, node=2)
    assert _axes_count(fig) == 2
    lines = fig.axes[0].get_lines()
    assert np.allclose(lines[0].get_ydata(), u.amplitude(2, "ux") * 1e6)
    assert _axes_count(plot(u, polar=True)) == 1


def test_static(rotor):
    s = rs.static(rotor)
    fig = plot(s)
    assert _axes_count(fig) == 3


def test_unknown_result_type():
    with pytest.raises(TypeError, match="no standard figure for int"):
        plot(3)


def test_bad_units(rotor):
    m = rs.modal(rotor, num_modes=2)
    with pytest.raises(TypeError, match="unknown units 'furlong'"):
        plot(m, units="furlong")


def test_campbell_with_critical_speeds(rotor):
    c = rs.campbell(rotor, np.linspace(0, 1000, 21), num_modes=6)
    fig = plot(c, units="rad/s")
    ax = fig.axes[0]
    crit = c.critical_speeds(1)
    assert len(crit.speed) > 0
    texts = "/".join(t.get_text() for t in ax.texts)
    assert f"{np.sort(crit.speed)[0]:.0f}" in texts.split("/")
    assert len(plot(c, color_by="log_dec").axes) == 2  # with colour bar


def test_critical_speed_map_with_bearing_curves():
    shaft = [rs.ShaftElement(L=0.25, idl=0.0, odl=0.05, material=steel) for _ in range(4)]
    table = {"kxx": [1e6, 1e8], "frequency": [0.0, 2000.0]}
    rotor = rs.Rotor(shaft, [], [rs.BearingElement(n=0, **table), rs.BearingElement(n=4, **table)])
    res = rs.critical_speed_map(rotor, (1e5, 1e9), num_points=12, num_modes=2)
    fig = plot(res)
    labels = [line.get_label() for line in fig.axes[0].get_lines()]
    assert "bearing 0 kxx" in labels and "intersections" in labels


def test_rotor_layout_draws_every_part(rotor):
    fig = plot(rotor)
    ax = fig.axes[0]
    # 2 patches per shaft element (upper and lower half), 1 per disk, 2 per bearing
    assert len(ax.patches) == 2 * 6 + 2 + 2 * 2
    assert "6 elements, 2 disks, 2 bearings" in ax.get_title()
