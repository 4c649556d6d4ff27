"""Spectra, peaks, harmonic fits, waterfalls and order tracks on synthetic signals whose
amplitudes, frequencies and phases are known exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rotorsim.assembly.dof_map import DofMap
from rotorsim.errors import ModelError
from rotorsim.results.order_tracking import order_track, waterfall
from rotorsim.results.spectra import (
    amplitude_spectrum,
    harmonic_fit,
    peaks,
    sampling_step,
)
from rotorsim.results.transient import TransientResult

DT = 5e-4
T = np.arange(2000) * DT  # 1 s: bins 1 Hz apart
TONES = [(25.0, 3e-5, 0.4), (60.0, 1e-5, -1.2), (137.0, 4e-6, 2.0)]  # Hz, amplitude, phase


def _tones(t: np.ndarray, tones, offset: float = 0.0) -> np.ndarray:
    return offset + sum(a * np.cos(2 * np.pi * f * t + p) for f, a, p in tones)


# ---------------------------------------------------------------------------- spectrum
@pytest.mark.parametrize("window", ["hann", "boxcar", "blackman", "flattop"])
def test_on_bin_sinusoids_recovered_exactly(window):
    # Cosine-sum windows (boxcar, Hann, Blackman, flat-top) have a DFT that vanishes at
    # integer bin offsets beyond their few terms (<= 4 bins), so tones on bins >= 35 bins
    # apart do not leak into each other: amplitude and phase are exact to round-off.
    s = amplitude_spectrum(T, _tones(T, TONES, offset=1e-3), window=window)
    assert s.frequency_hz[1] == pytest.approx(1.0, rel=1e-12)
    assert s.n_samples == T.size and s.amplitude.shape == (T.size // 2 + 1,)
    for f, a, p in TONES:
        j = round(f)
        assert s.amplitude[j] == pytest.approx(a, rel=1e-9)
        assert s.phase[j] == pytest.approx(p, abs=1e-9)
    assert s.amplitude[0] < 1e-15  # the 1 mm offset is removed by detrend="mean"
    kept = amplitude_spectrum(T, _tones(T, TONES, offset=1e-3), window=window, detrend="none")
    assert kept.amplitude[0] == pytest.approx(1e-3, rel=1e-9)


def test_phase_referred_to_t_zero_and_columns():
    t = 0.37 + T  # record starting later: phases still refer to t = 0
    x = np.column_stack([_tones(t, TONES), 2.0 * _tones(t, TONES[:1])])
    s = amplitude_spectrum(t, x)
    assert s.amplitude.shape == (T.size // 2 + 1, 2)
    assert s.phase[25, 0] == pytest.approx(0.4, abs=1e-9)
    assert s.amplitude[25, 1] == pytest.approx(6e-5, rel=1e-9)
    single = amplitude_spectrum(t, x[:, 1])
    # one column alone or among others: the FFT may take another (vectorised) path; its
    # round-off is O(eps log2 N) of the largest amplitude
    np.testing.assert_allclose(single.amplitude, s.amplitude[:, 1], rtol=0,
                               atol=1e-13 * s.amplitude[:, 1].max())


def test_half_bin_scalloping_of_hann_matches_its_kernel():
    # Hann kernel at half a bin: sinc(1/2) / (1 - 1/4) = (2/pi) / 0.75 = 0.8488 (the 1.42 dB
    # scalloping loss, Harris 1978, Table 1).
    s = amplitude_spectrum(T, np.cos(2 * np.pi * 40.5 * T))
    assert s.amplitude[40] == pytest.approx(2 / math.pi / 0.75, rel=1e-3)


def test_t_min_skips_the_start():
    x = np.where(T < 0.5, 1.0, 0.0) + np.cos(2 * np.pi * 50.0 * T)
    s = amplitude_spectrum(T, x, t_min=0.5)
    assert s.n_samples == 1000 and s.t_start == pytest.approx(0.5)
    assert s.amplitude[25] == pytest.approx(1.0, rel=1e-9)  # 2 Hz bins now


# ---------------------------------------------------------------------------- peaks
OFF_BIN = [(40.37, 1.5e-5, 0.7), (97.81, 4e-6, -2.1), (161.5, 2e-6, 1.0)]


def test_off_bin_peaks_ratio_interpolation():
    s = amplitude_spectrum(T, _tones(T, OFF_BIN))
    found = sorted(peaks(s, n=3), key=lambda p: p.frequency)
    assert len(found) == 3
    for p, (f, a, ph) in zip(found, OFF_BIN, strict=True):
        # exact for one Hann-windowed tone; what is left is leakage of the others and of
        # the negative-frequency images (measured: 2e-6 bin, 4e-7 relative, 4e-6 rad)
        assert p.frequency_hz == pytest.approx(f, abs=1e-3)  # 1e-3 bin
        assert p.amplitude == pytest.approx(a, rel=1e-3)
        assert abs(np.angle(np.exp(1j * (p.phase - ph)))) < 1e-3
        assert p.bin == pytest.approx(f, abs=1e-3)


@pytest.mark.parametrize("window", ["blackman", "flattop"])
def test_ratio_interpolation_for_other_windows(window):
    s = amplitude_spectrum(T, _tones(T, OFF_BIN[:1]), window=window)
    p = peaks(s, n=1)[0]
    assert p.frequency_hz == pytest.approx(40.37, abs=1e-3)
    assert p.amplitude == pytest.approx(1.5e-5, rel=1e-3)


def test_parabolic_interpolations_beat_the_nearest_bin():
    worst = {"log-parabolic": 0.0, "parabolic": 0.0}
    for delta in np.linspace(0.05, 0.5, 10):
        s = amplitude_spectrum(T, np.cos(2 * np.pi * (40.0 + delta) * T))
        for method in worst:
            p = peaks(s, n=1, interpolation=method)[0]
            worst[method] = max(worst[method], abs(p.frequency_hz - 40.0 - delta))
    # Gaussian (log-parabolic) interpolation of the Hann main lobe is biased by under
    # 0.02 bin, the plain parabola by under 0.06 bin (measured 0.016 and 0.053); the
    # nearest bin alone is up to 0.5 bin off
    assert worst["log-parabolic"] < 0.02
    assert worst["parabolic"] < 0.06


def test_peaks_min_height_and_order():
    s = amplitude_spectrum(T, _tones(T, TONES))
    found = peaks(s, n=5, min_height=5e-6)
    assert [round(p.frequency_hz) for p in found] == [25, 60]
    assert found[0].amplitude > found[1].amplitude
    with pytest.raises(TypeError, match="unknown interpolation"):
        peaks(s, interpolation="cubic")
    with pytest.raises(ModelError, match="column 1"):
        peaks(s, column=1)


# ---------------------------------------------------------------------------- harmonic fit
def test_harmonic_fit_exact_on_clean_signals():
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0.0, 0.173, 300))  # non-uniform, not a whole number of periods
    w = 2 * np.pi * 31.0
    x = np.column_stack([0.2 + 1e-5 * np.cos(w * t + 0.9), -3e-6 * np.sin(w * t)])
    fit = harmonic_fit(t, x, w)
    np.testing.assert_allclose(fit.amplitude, [1e-5, 3e-6], rtol=1e-10)
    # -sin(wt) = cos(wt + pi/2): leads by 90 degrees, X = i * 3e-6
    np.testing.assert_allclose(fit.phase, [0.9, np.pi / 2], atol=1e-9)
    np.testing.assert_allclose(fit.mean, [0.2, 0.0], atol=1e-12)
    assert np.all(fit.residual_rms < 1e-15)
    np.testing.assert_allclose(fit.complex_amplitude[1], 3e-6j, atol=1e-15)
    assert fit.n_samples == 300


def test_harmonic_fit_agrees_with_on_bin_spectrum_phase():
    x = _tones(T, TONES)
    s = amplitude_spectrum(T, x)
    # the other tones are orthogonal over the whole-period record, so the fit is exact
    fit = harmonic_fit(T, x, 2 * np.pi * 60.0)
    assert float(fit.amplitude) == pytest.approx(s.amplitude[60], rel=1e-9)
    assert float(fit.phase) == pytest.approx(s.phase[60], abs=1e-9)


# ---------------------------------------------------------------------------- run-ups
W0, ALPHA, DT_RUN = 50.0, 100.0, 2e-4  # 50 -> 450 rad/s in 4 s
T_RUN = np.arange(20001) * DT_RUN
SPEED = W0 + ALPHA * T_RUN
PHI = W0 * T_RUN + 0.5 * ALPHA * T_RUN**2


def test_order_track_recovers_integer_and_non_integer_orders():
    x = 2e-6 + 1e-5 * np.cos(PHI + 0.4) + 3e-6 * np.cos(3.6 * PHI - 1.1)
    track = order_track(T_RUN, x, PHI, [1.0, 3.6])
    assert track.amplitude.shape == (19, 2) and track.revolutions_per_block == 8
    # speed at the angular centre of each block: W(t) is known exactly (spline error only)
    np.testing.assert_allclose(track.speed, W0 + ALPHA * track.times, rtol=1e-9)
    assert track.speed[0] < 100.0 and track.speed[-1] > 400.0
    # brief: within 1 %; measured 7e-6 (1X) and 9e-5 (3.6X, Hann leakage of 1X 20.8 bins away)
    np.testing.assert_allclose(track.amplitude[:, 0], 1e-5, rtol=1e-3)
    np.testing.assert_allclose(track.amplitude[:, 1], 3e-6, rtol=1e-3)
    np.testing.assert_allclose(track.phase, np.broadcast_to([0.4, -1.1], (19, 2)), atol=1e-3)
    # the FFT order spectrum puts 1X on bin R = 8 with the same amplitude
    assert track.order_axis[8] == 1.0
    np.testing.assert_allclose(track.order_spectrum[:, 8], track.amplitude[:, 0], rtol=1e-9)


def test_order_track_follows_a_speed_dependent_amplitude():
    # an unbalance-like 1X growing as W^2: W^2 is linear in phi for a linear run-up, so the
    # window-weighted block average equals the value at the block's angular centre
    amplitude = 1e-5 * (SPEED / 450.0) ** 2
    track = order_track(T_RUN, amplitude * np.cos(PHI), PHI, [1.0], revolutions_per_block=16)
    np.testing.assert_allclose(track.amplitude[:, 0], 1e-5 * (track.speed / 450.0) ** 2,
                               rtol=1e-3)  # measured 3e-5


def test_waterfall_peak_follows_the_speed():
    x = np.cos(PHI) + 0.3 * np.cos(2 * np.pi * 60.0 * T_RUN)  # 1X and a fixed 60 Hz tone
    wf = waterfall(T_RUN, x, SPEED, segment=0.2, overlap=0.5)
    n_seg = (T_RUN.size - 1000) // 500 + 1
    assert wf.amplitude.shape == (n_seg, 501) and wf.segment_samples == 1000
    np.testing.assert_allclose(wf.speeds, W0 + ALPHA * wf.times, rtol=1e-9)
    resolution = wf.frequency[1]  # 5 Hz
    ridge = wf.frequency[np.argmax(wf.amplitude, axis=1)]  # 1X is 3 x the tone
    clear = np.abs(wf.speeds - 2 * np.pi * 60.0) > 40.0  # away from the 1X/tone crossing
    assert clear.sum() >= 30
    assert np.all(np.abs(ridge - wf.speeds)[clear] <= resolution)
    # the tone sits on a bin (5 Hz spacing); 1X >= 150 rad/s (4.8 bins) away leaks at most
    # 1 / (pi 4.8 (4.8^2 - 1)) = 0.3 % of its amplitude (Hann sidelobe), 1 % of the tone's
    tone = np.argmin(np.abs(wf.frequency - 2 * np.pi * 60.0))
    far = np.abs(wf.speeds - 2 * np.pi * 60.0) > 150.0
    np.testing.assert_allclose(wf.amplitude[far, tone], 0.3, rtol=0.01)


# ---------------------------------------------------------------------------- bad input
def test_bad_input_raises_model_error():
    jitter = T + np.where(np.arange(T.size) == 7, 1e-5, 0.0)
    with pytest.raises(ModelError, match="OutputSpec"):
        amplitude_spectrum(jitter, np.sin(T))
    with pytest.raises(ModelError, match="too few"):
        amplitude_spectrum(T[:5], T[:5])
    with pytest.raises(ModelError, match="too few"):
        amplitude_spectrum(T, T, t_min=10.0)
    with pytest.raises(ModelError, match="increase"):
        sampling_step(T[::-1])
    with pytest.raises(ModelError, match=r"\(k,\)"):
        amplitude_spectrum(T, np.ones((3, 4)))
    with pytest.raises(TypeError, match="unknown window"):
        amplitude_spectrum(T, T, window="triangle-ish")
    with pytest.raises(TypeError, match="unknown detrend"):
        amplitude_spectrum(T, T, detrend="quadratic")
    with pytest.raises(ModelError, match="frequency must be > 0"):
        harmonic_fit(T, T, 0.0)
    with pytest.raises(ModelError, match="too few"):
        harmonic_fit(T[:2], T[:2], 1.0)
    with pytest.raises(ModelError, match="segment"):
        waterfall(T, T, T, segment=2.0)
    with pytest.raises(ModelError, match="overlap"):
        waterfall(T, T, T, segment=0.1, overlap=1.0)
    with pytest.raises(ModelError, match="fewer than one block"):
        order_track(T_RUN[:100], PHI[:100], PHI[:100], [1.0])
    with pytest.raises(ModelError, match="speed > 0"):
        order_track(T_RUN, PHI, -PHI, [1.0])
    with pytest.raises(ModelError, match="orders must be positive"):
        order_track(T_RUN, PHI, PHI, [0.0])


# ---------------------------------------------------------------------------- TransientResult
def _transient() -> TransientResult:
    x = 1e-5 * np.cos(PHI + 0.4) + 3e-6 * np.cos(3.6 * PHI)
    q = np.column_stack([x, 2 * x])
    return TransientResult(
        t=T_RUN, q=q, v=None, dofs=np.array([6, 7]), speed=SPEED, angle=PHI,
        acceleration=np.full(T_RUN.size, ALPHA), bearing_loads=np.zeros((T_RUN.size, 1, 5)),
        bearing_tags=("B",), bearing_elements=np.array([9]), bearing_kappa=np.array([0.4]),
        reduced={}, dof_map=DofMap(3), nodes_pos=np.array([0.0, 0.5, 1.0]))


def test_transient_result_methods_delegate():
    r = _transient()
    assert r.varying_compliance_orders.tolist() == pytest.approx([3.6])
    s = r.spectrum(1, "uy", t_min=1.0)
    ref = amplitude_spectrum(T_RUN, r.q[:, 1], t_min=1.0)
    np.testing.assert_array_equal(s.amplitude, ref.amplitude)
    track = r.order_track(1, "ux", (1.0, *r.varying_compliance_orders))
    np.testing.assert_allclose(track.amplitude, np.broadcast_to([1e-5, 3e-6],
                                                                track.amplitude.shape),
                               rtol=1e-3)
    assert r.waterfall(1, "ux", segment=0.5).amplitude.shape[1] == 1251
    late = r.window(3.0)
    fit = r.harmonic(1, "ux", 2 * np.pi * 10.0, t_min=3.0)
    assert fit.t_start == pytest.approx(3.0) and fit.n_samples == late.sum()
    default = r.harmonic(1, "ux", t_min=3.0)
    assert default.frequency == pytest.approx(SPEED[late].mean())
    with pytest.raises(ModelError, match="not kept"):
        r.spectrum(2, "ux")
    with pytest.raises(ModelError, match="no samples"):
        r.harmonic(1, "ux", t_min=99.0)
