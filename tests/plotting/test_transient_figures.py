"""Transient figures draw from synthetic results (Agg) with the expected artists and labels."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.collections import QuadMesh

from rotorsim.assembly.dof_map import DofMap
from rotorsim.plotting import plot
from rotorsim.plotting import transient_figures as tf
from rotorsim.results.transient import TransientResult

Z, KAPPA = 8, 0.4  # varying-compliance order Z kappa = 3.2
HZ = 1.0 / (2.0 * np.pi)


def _result(*, run_up: bool = True, bearings: int = 2, uniform: bool = True
            ) -> TransientResult:
    """Two kept nodes (1 and 2, node 2 moving twice as much) with 1X and a VC component."""
    t = np.arange(5001) * 4e-4
    if not uniform:
        t = t + 1e-5 * np.sin(t * 1e3)
    speed = 50.0 + 150.0 * t if run_up else np.full(t.size, 150.0)
    phi = 50.0 * t + 75.0 * t**2 if run_up else 150.0 * t
    one_x = 10e-6 * np.column_stack([np.cos(phi), np.sin(phi)])
    vc = 1e-6 * np.cos(Z * KAPPA * phi)
    q = np.column_stack([one_x, 2 * one_x]) + vc[:, None]
    loads = np.zeros((t.size, bearings, 5))
    loads[:, :, 0] = 50.0 * np.cos(phi)[:, None]
    loads[:, :, 1] = -300.0 + 30.0 * vc[:, None] / 1e-6
    return TransientResult(
        t=t, q=q, v=None, dofs=np.array([6, 7, 12, 13]), speed=speed, angle=phi,
        acceleration=np.full(t.size, 150.0 if run_up else 0.0), bearing_loads=loads,
        bearing_tags=("B0", "B3")[:bearings], bearing_elements=np.full(bearings, Z),
        bearing_kappa=np.full(bearings, KAPPA), reduced={}, dof_map=DofMap(4),
        nodes_pos=np.array([0.0, 0.2, 0.4, 0.6]), method="newmark",
        summary={"tag": "synthetic"})


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _labels(ax) -> list[str]:
    return [line.get_label() for line in ax.get_lines()]


def test_default_figure_of_a_run_up():
    r = _result()
    fig = plot(r)
    titles = [ax.get_title() for ax in fig.axes]
    assert titles[:4] == ["time history", "orbit of node 2", titles[2],
                          "bearing loads on the inner rings"]
    assert titles[2].startswith("spectrum of 2:uy\n(speed varies")
    assert len(fig.axes) == 5  # four panels and the speed axis twinned on the time history
    assert fig.axes[4].get_ylabel() == "speed [rpm]"
    assert "transient of 'synthetic' (newmark" in fig.texts[0].get_text()
    spectrum_labels = _labels(fig.axes[2])
    assert {"1X", "2X", "3X", "VC B0, B3 (3.2X)", "2VC B0, B3 (6.4X)"} <= set(spectrum_labels)


def test_default_figure_at_constant_speed_uses_the_second_half():
    r = _result(run_up=False)
    fig = plot(r)
    assert len(fig.axes) == 4  # no speed axis when the speed is constant
    assert fig.axes[1].get_title() == "orbit of node 2, t >= 1 s"
    spec = fig.axes[2]
    assert spec.get_title() == "spectrum of 2:uy, t >= 1 s"
    one_x = next(line for line in spec.get_lines() if line.get_label() == "1X")
    assert one_x.get_xdata()[0] == pytest.approx(150.0 * HZ)
    vc = next(line for line in spec.get_lines() if line.get_label().startswith("VC"))
    assert vc.get_xdata()[0] == pytest.approx(Z * KAPPA * 150.0 * HZ)
    # the spectrum curve peaks at 1X with the 1X amplitude of node 2 (20 um)
    curve = spec.get_lines()[0]
    x, y = curve.get_xdata(), curve.get_ydata()
    assert x[np.argmax(y)] == pytest.approx(150.0 * HZ, abs=1.0)
    assert y.max() == pytest.approx(20.0, rel=0.16)  # off-bin: Hann scalloping <= 15 %


def test_default_figure_without_bearings_shows_the_waterfall():
    fig = plot(_result(bearings=0))
    panel = fig.axes[3]
    assert panel.get_title() == "waterfall of 2:uy"
    assert any(isinstance(c, QuadMesh) for c in panel.collections)
    assert {"1X", "2X"} <= set(_labels(panel))


def test_default_figure_survives_non_uniform_samples():
    fig = plot(_result(run_up=False, uniform=False))
    texts = [t.get_text() for t in fig.axes[2].texts]
    assert any("not uniform" in t for t in texts)


def test_time_history_with_rotations_and_speed_axis():
    r = _result()
    fig = tf.time_history_figure(r, dofs=[(1, "ux"), (2, "uy")], t_max=1.0,
                                 amplitude_units="mm")
    ax = fig.axes[0]
    assert _labels(ax) == ["1:ux [mm]", "2:uy [mm]"]
    np.testing.assert_allclose(ax.get_lines()[0].get_ydata(), r.q[r.t <= 1.0, 0] * 1e3)
    assert ax.get_ylabel() == "displacement [mm]" and ax.get_xlabel() == "time [s]"
    assert fig.axes[1].get_ylabel() == "speed [rpm]"
    no_speed = tf.time_history_figure(r, show_speed=False)
    assert len(no_speed.axes) == 1


def test_orbit_of_the_most_responsive_node():
    r = _result()
    assert tf.most_responsive_node(r) == 2
    fig = tf.orbit_figure(r, t_min=1.5)
    ax = fig.axes[0]
    orbit = ax.get_lines()[0]
    late = r.t >= 1.5
    np.testing.assert_allclose(orbit.get_xdata(), r.q[late, 2] * 1e6)
    np.testing.assert_allclose(orbit.get_ydata(), r.q[late, 3] * 1e6)
    assert ax.get_xlabel() == "ux [um]" and ax.get_title() == "orbit of node 2, t >= 1.5 s"


def test_spectrum_object_draws_with_given_markers():
    r = _result(run_up=False)
    s = r.spectrum(2, "ux", t_min=1.0)
    bare = plot(s)
    assert len(bare.axes[0].get_lines()) == 1  # the curve only: no markers without a speed
    assert bare.axes[0].get_legend() is None
    fig = tf.spectrum_figure(s, speed=150.0, vc_orders=[("B9", 4.5)], harmonics=(1,),
                             units="rpm")
    labels = _labels(fig.axes[0])
    assert labels[1:] == ["1X", "VC B9 (4.5X)", "2VC B9 (9X)"]
    assert fig.axes[0].get_xlabel() == "frequency [rpm]"


def test_waterfall_and_order_lines():
    r = _result()
    fig = tf.waterfall_figure(r, segment=0.2, units="rad/s", speed_units="rad/s")
    ax = fig.axes[0]
    assert any(isinstance(c, QuadMesh) for c in ax.collections)
    assert ax.get_ylabel() == "speed [rad/s]" and ax.get_xlabel() == "frequency [rad/s]"
    lines = {line.get_label(): line for line in ax.get_lines()}
    assert set(lines) == {"1X", "2X", "VC B0, B3 (3.2X)"}
    np.testing.assert_allclose(lines["VC B0, B3 (3.2X)"].get_xdata(),
                               Z * KAPPA * lines["1X"].get_ydata())
    assert fig.axes[1].get_ylabel() == "amplitude [um]"  # colour bar
    steady = tf.waterfall_figure(_result(run_up=False))
    assert steady.axes[0].get_ylabel() == "time [s]"  # speed not monotonic: time axis


def test_order_track_lines():
    r = _result()
    fig = tf.order_track_figure(r, revolutions_per_block=4)
    ax = fig.axes[0]
    lines = {line.get_label(): line for line in ax.get_lines()}
    assert set(lines) == {"1X", "2X", "VC B0, B3 (3.2X)"}
    # node 2: 1X circle of radius 20 um seen in uy; VC 1 um; no 2X
    np.testing.assert_allclose(lines["1X"].get_ydata(), 20.0, rtol=1e-3)
    np.testing.assert_allclose(lines["VC B0, B3 (3.2X)"].get_ydata(), 1.0, rtol=1e-2)
    assert np.all(lines["2X"].get_ydata() < 0.05)
    assert ax.get_xlabel() == "speed [rpm]"


def test_bearing_loads():
    r = _result(run_up=False)
    fig = tf.bearing_loads_figure(r, bearings=[1])
    ax = fig.axes[0]
    assert _labels(ax) == ["B3 Fx", "B3 Fy", "B3 |F|"]
    np.testing.assert_allclose(ax.get_lines()[2].get_ydata(),
                               np.hypot(r.bearing_loads[:, 1, 0], r.bearing_loads[:, 1, 1]))
    assert ax.get_ylabel() == "bearing load [N]"
    empty = tf.bearing_loads_figure(_result(bearings=0))
    assert empty.axes[0].texts[0].get_text() == "no nonlinear bearings"


def test_bad_units():
    with pytest.raises(TypeError, match="unknown amplitude units"):
        tf.orbit_figure(_result(), amplitude_units="furlong")
    with pytest.raises(TypeError, match="unknown units"):
        tf.spectrum_figure(_result(), units="furlong")
