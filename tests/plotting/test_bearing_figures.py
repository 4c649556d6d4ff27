"""Bearing figures: load distribution of an equilibrium and stiffness over an element pass
(Agg backend, no screen); the drawn data are the result's."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.patches import Rectangle

from rotorsim.analyses.statics.bearing_statics import bearing_equilibrium, stiffness_over_pass
from rotorsim.elements.rolling.ball.bearing import BallBearing
from rotorsim.plotting import plot
from rotorsim.plotting.bearing_figures import load_zone_sector, stiffness_variation_figure

BALL = BallBearing(n_balls=9, pitch_diameter=0.0385, ball_diameter=0.00794, Kn=9.3e9,
                   f_i=0.52, f_o=0.52, radial_clearance=5e-6, tag="DE")


@pytest.fixture(scope="module")
def equilibrium():
    return bearing_equilibrium(BALL, [0.0, -800.0, 40.0, 0.0, 0.0])


def test_load_distribution_draws_each_element_load(equilibrium, tmp_path):
    fig = plot(equilibrium)
    polar, right = fig.axes
    assert polar.name == "polar"
    bars = [p for p in polar.patches if isinstance(p, Rectangle)]
    assert len(bars) == equilibrium.n_elements
    heights = sorted(b.get_height() for b in bars)
    np.testing.assert_allclose(heights, np.sort(equilibrium.element_load))
    # the loaded contact angles in degrees, against the element angle
    loaded = right.get_lines()[1]
    np.testing.assert_allclose(loaded.get_ydata(),
                               np.degrees(equilibrium.contact_angle[equilibrium.loaded]))
    assert "load distribution of 'DE'" in fig._suptitle.get_text()
    path = tmp_path / "load.png"
    fig.savefig(path, dpi=80)
    assert path.stat().st_size > 10_000


def test_stiffness_variation_draws_the_coefficients(tmp_path):
    variation = stiffness_over_pass(BALL, [0.0, -800.0, 40.0, 0.0, 0.0], n_points=8)
    fig = plot(variation)
    upper, lower = fig.axes
    labels = [line.get_label() for line in upper.get_lines()]
    assert labels == ["Kxx [N/m]", "Kyy [N/m]", "Kzz [N/m]", "Kxy [N/m]"]
    kxx = upper.get_lines()[0].get_ydata()
    np.testing.assert_allclose(kxx[:-1], variation.stiffness[:, 0, 0])
    assert kxx[-1] == kxx[0]  # the period is closed
    np.testing.assert_allclose(lower.get_lines()[0].get_ydata()[:-1],
                               variation.max_element_load)
    tilt = stiffness_variation_figure(variation, coefficients=("rxrx", "zry", "yrx"))
    assert [line.get_label() for line in tilt.axes[0].get_lines()] == [
        "Krxrx [N m/rad]", "Kzry [N/rad]", "Kyrx [N/rad]"]
    with pytest.raises(TypeError, match="unknown stiffness coefficient"):
        stiffness_variation_figure(variation, coefficients=("xw",))
    path = tmp_path / "pass.png"
    fig.savefig(path, dpi=80)
    assert path.stat().st_size > 10_000


@pytest.mark.parametrize(("loaded", "start", "extent"), [
    ([1, 1, 0, 0, 0, 0, 0, 0], -22.5, 90.0),
    ([1, 0, 0, 0, 0, 0, 0, 1], -67.5, 90.0),
    ([0, 0, 1, 1, 1, 0, 0, 0], 67.5, 135.0),
    ([1] * 8, 0.0, 360.0),
    ([0] * 8, 0.0, 0.0),
])
def test_load_zone_sector(loaded, start, extent):
    psi = np.radians(np.arange(8) * 45.0)
    a, b = load_zone_sector(psi, np.array(loaded, dtype=bool))
    assert (math.degrees(a) - start) % 360.0 == pytest.approx(0.0, abs=1e-9)
    assert math.degrees(b) == pytest.approx(extent, abs=1e-9)
