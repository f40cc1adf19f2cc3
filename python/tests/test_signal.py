"""kaiser_fir, zero_phase/filtfilt and decimate against SciPy (taps to 1e-12)."""

import numpy as np
import pytest
from scipy import signal

import thermonav

SPECS = [
    (200.0, 5.0, 1.0, 60.0),
    (100.0, 0.4, 0.2, 60.0),
    (1000.0, 50.0, 10.0, 80.0),
    (50.0, 10.0, 4.0, 30.0),
]


def scipy_taps(fs, cutoff, width, ripple):
    numtaps, beta = signal.kaiserord(ripple, width / (fs / 2))
    return signal.firwin(numtaps, cutoff, window=("kaiser", beta), fs=fs), beta


@pytest.mark.parametrize("spec", SPECS)
def test_kaiser_taps_equal_kaiserord_and_firwin(spec):
    design = thermonav.kaiser_fir(*spec)
    taps, beta = scipy_taps(*spec)
    assert design.num_taps == len(taps)
    np.testing.assert_allclose(design.taps, taps, rtol=0, atol=1e-12)
    assert design.beta == pytest.approx(beta, abs=1e-12)
    assert design.group_delay_s == pytest.approx((len(taps) - 1) / 2 / spec[0])


@pytest.fixture(scope="module")
def noisy():
    rng = np.random.default_rng(1)
    t = np.arange(20_000) / 200.0
    return np.sin(2 * np.pi * 0.7 * t) + rng.standard_normal(t.size)


@pytest.mark.parametrize("spec", [SPECS[0], (200.0, 20.0, 10.0, 40.0)])
def test_filtfilt_equals_scipy_filtfilt(spec, noisy):
    taps, _ = scipy_taps(*spec)
    expected = signal.filtfilt(taps, [1.0], noisy)  # odd extension of 3 x taps, as ours
    ours = thermonav.filtfilt(noisy, *spec)
    # FFT against direct convolution: rounding of sums over thousands of taps.
    np.testing.assert_allclose(ours, expected, rtol=0, atol=1e-10)


def test_zero_phase_is_the_delay_compensated_convolution_of_the_odd_extension(noisy):
    fs, cutoff, width, ripple = SPECS[0]
    taps = thermonav.kaiser_fir(fs, cutoff, width, ripple).taps
    if len(taps) % 2 == 0:  # the one-pass mode runs an odd design
        numtaps, beta = signal.kaiserord(ripple, width / (fs / 2))
        taps = signal.firwin(numtaps + 1, cutoff, window=("kaiser", beta), fs=fs)
    pad = 3 * len(taps)
    extended = np.concatenate(
        [2 * noisy[0] - noisy[pad:0:-1], noisy, 2 * noisy[-1] - noisy[-2 : -pad - 2 : -1]]
    )
    full = signal.lfilter(taps, [1.0], extended, zi=signal.lfilter_zi(taps, [1.0]) * extended[0])[0]
    delay = (len(taps) - 1) // 2
    expected = full[pad + delay : pad + delay + len(noisy)]
    np.testing.assert_allclose(thermonav.zero_phase(noisy, fs, cutoff, width, ripple), expected, atol=1e-10)


def test_decimate_keeps_every_factor_th_filtered_output_whose_window_is_inside(noisy):
    out = thermonav.decimate(noisy, 200.0, 1.0, 0.4, 0.2)
    filtered = thermonav.zero_phase(noisy, 200.0, 0.4, 0.2)
    assert out.decimation_factor == 200 and out.output_rate_hz == 1.0
    edge = out.edge_samples_dropped
    assert edge == (out.num_taps - 1) // 2
    first = -(-edge // 200) * 200  # the first multiple of the factor at or after the edge
    expected = filtered[first : len(noisy) - edge : 200]
    np.testing.assert_array_equal(out.samples, expected)


def test_decimation_refuses_a_stop_band_past_the_new_nyquist(noisy):
    with pytest.raises(thermonav.ThermonavError, match="to_hz 1"):
        thermonav.decimate(noisy, 200.0, 1.0, 0.4, 0.4)
