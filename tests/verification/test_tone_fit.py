"""``fit_tones``: amplitudes of known incommensurate tones by least squares (issue 17)."""

from __future__ import annotations

import numpy as np
import pytest

from rotorsim.verification.tone_fit import fit_tones, tone_frequencies

GOLDEN = (1 + 5**0.5) / 2


def test_a_sum_of_incommensurate_tones_is_recovered_exactly() -> None:
    """A signal made of the fitted tones only: the least-squares fit is exact up to the
    round-off of the columns (1e-9 relative asserted; the 1-norm condition of the columns
    of tones 0.38 apart over 60 units of time is about 10)."""
    w1, w2 = 1.0, 2 + GOLDEN
    k = np.array([[1, 0], [0, 1], [1, -1], [2, 0], [4, -1]])
    w = tone_frequencies(k, w1, w2)
    assert w[4] == pytest.approx(abs(4 - w2), rel=1e-15)
    t = np.linspace(3.0, 63.0, 6001)  # the window need not start at 0
    amp = np.array([1.0, 0.3, 0.02, 0.1, 1e-3])
    phase = np.array([0.1, -2.0, 1.0, 3.0, -0.5])
    y = 0.25 + np.cos(np.outer(t, w) + phase) @ amp
    c = fit_tones(t, y, w)
    np.testing.assert_allclose(c[0].real, 0.25, rtol=1e-9)
    np.testing.assert_allclose(np.abs(c[1:]), amp, rtol=1e-9)
    np.testing.assert_allclose(np.angle(c[1:]), phase, atol=1e-8)
    both = fit_tones(t, np.stack([y, 2 * y], axis=1), w)  # channels at once
    np.testing.assert_allclose(both[:, 1], 2 * both[:, 0], rtol=1e-12)


def test_a_tone_left_out_leaks_by_about_one_over_the_window_times_its_distance() -> None:
    t = np.linspace(0.0, 200.0, 20001)
    y = np.cos(t) + 0.1 * np.cos(1.5 * t)
    leak = abs(abs(fit_tones(t, y, [1.0])[1]) - 1.0)
    assert 0 < leak < 0.1 / (200.0 * 0.5)


def test_bad_frequencies_and_shapes_are_refused() -> None:
    t = np.linspace(0.0, 1.0, 11)
    with pytest.raises(ValueError, match="positive and distinct"):
        fit_tones(t, np.ones(11), [1.0, 1.0])
    with pytest.raises(ValueError, match="positive"):
        fit_tones(t, np.ones(11), [0.0])
    with pytest.raises(ValueError, match="samples"):
        fit_tones(t, np.ones(10), [1.0])
    with pytest.raises(ValueError, match="unknowns"):
        fit_tones(t, np.ones(11), np.arange(1.0, 7.0))
