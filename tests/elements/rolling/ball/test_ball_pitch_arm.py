"""``groove_center_radius="pitch"``: the ISO/TS 16281 tilt lever arm (issue 18, item 8)."""

from __future__ import annotations

import pytest

import rotorsim as rs
from rotorsim.io.rolling_schema import validate_rolling_bearings


def test_pitch_arm_is_the_pitch_radius_and_changes_only_the_tilt_terms():
    kw = {"n_balls": 9, "pitch_diameter": 38.5e-3, "ball_diameter": 7.938e-3, "Kn": 9e9,
          "f_i": 0.52, "f_o": 0.52}
    pitch = rs.BallBearing(groove_center_radius="pitch", **kw)
    explicit = rs.BallBearing(groove_center_radius=38.5e-3 / 2, **kw)
    default = rs.BallBearing(**kw)
    assert pitch.moment_arm == 38.5e-3 / 2
    assert default.moment_arm > pitch.moment_arm
    delta = [[5e-6, 0.0, 2e-6, 1e-4, 0.0]]
    psi = pitch.element_angles()
    assert (pitch.state(delta, psi).force == explicit.state(delta, psi).force).all()
    with pytest.raises(rs.ModelError, match="'pitch'"):
        rs.BallBearing(groove_center_radius="mean", **kw)


def test_model_file_accepts_pitch():
    body = {"type": "ball", "z": 0.0, "n_balls": 9, "pitch_diameter": "38.5 mm",
            "ball_diameter": "7.938 mm", "f_i": 0.52, "f_o": 0.52}
    [table] = validate_rolling_bearings([{**body, "groove_center_radius": "pitch"}])
    assert table.groove_center_radius == "pitch"
    [table] = validate_rolling_bearings([{**body, "groove_center_radius": "20 mm"}])
    assert table.groove_center_radius == pytest.approx(0.02)
