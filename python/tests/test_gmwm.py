"""gmwm against the CLI's `gmwm --json` on the same file, and its wavelet variance against allantools."""

import json
import subprocess

import allantools
import numpy as np
import pytest

import thermonav
from thermonav import ThermonavError

RATE_HZ = 100.0
CHANNELS = ["gx", "gy", "gz", "ax", "ay", "az"]


def white_plus_gauss_markov(rng, n, white, sigma, tc_s):
    phi = np.exp(-1.0 / (RATE_HZ * tc_s))
    drive = rng.standard_normal(n) * sigma * np.sqrt(1 - phi**2)
    gm = np.zeros(n)
    for k in range(1, n):
        gm[k] = phi * gm[k - 1] + drive[k]
    return gm + rng.standard_normal(n) * white


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """Six channels of 16384 samples at 100 Hz: white noise plus a 20 s Gauss-Markov bias (seeded)."""
    rng = np.random.default_rng(17)
    n = 16384
    # The bias a third of the white noise's per-sample sd: at 16384 samples (8 correlation
    # times) gmwm resolves it on every channel of wn+gm. At a tenth, as before 183c182, its
    # chi-square test left it out as unresolved on all six (p 0.014-0.29).
    gyro = [white_plus_gauss_markov(rng, n, 3e-3, 1e-3, 20.0) for _ in range(3)]
    accel = [white_plus_gauss_markov(rng, n, 2e-2, 1e-2, 20.0) for _ in range(3)]
    accel[2] = accel[2] - 9.8
    path = tmp_path_factory.mktemp("gmwm") / "imu.csv"
    with open(path, "w") as out:
        out.write("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n")
        for k in range(n):
            out.write(f"{k / RATE_HZ:.2f}," + ",".join(repr(float(c[k])) for c in gyro + accel) + "\n")
    return path


def cli_gmwm(binary, path, *args):
    done = subprocess.run([str(binary), "gmwm", str(path), *args, "--json"], check=True,
                          capture_output=True, text=True)
    return json.loads(done.stdout)


def assert_channel_equal(ours, document, channel):
    theirs = document["channels"][channel]
    for key in ("unit", "selected_model", "wic", "parameters", "candidates", "reported_model",
                "merged", "absent"):
        value = ours[key].to_dict() if isinstance(ours[key], thermonav.Record) else ours[key]
        assert value == theirs[key], (channel, key)  # parsed JSON: every float to the last bit
    for key, values in theirs["wavelet_variance"].items():
        assert ours.wavelet_variance[key].tolist() == values, (channel, key)
    for key in ("sample_rate_hz", "model", "interval_method", "bootstrap_replicates"):
        assert ours[key] == document[key], key


def test_one_model_on_every_channel_equals_gmwm_json(binary, record):
    document = cli_gmwm(binary, record, "--model", "wn+gm", "--replicates", "10", "--seed", "5")
    imu = thermonav.read_imu(record)
    for channel in CHANNELS:
        column = next(v for k, v in imu.items() if k.startswith(channel + "_"))
        sensor = "gyro" if channel.startswith("g") else "accelerometer"
        ours = thermonav.gmwm(column, document["sample_rate_hz"], model="wn+gm", sensor=sensor,
                              replicates=10, seed=5)
        assert_channel_equal(ours, document, channel)
    assert "gm1_sigma_m_per_s2" in ours.parameters


def test_the_automatic_choice_equals_gmwm_json(binary, record):
    document = cli_gmwm(binary, record, "--replicates", "10")
    imu = thermonav.read_imu(record)
    ours = thermonav.gmwm(imu.gx_rad_s, document["sample_rate_hz"], replicates=10)
    assert_channel_equal(ours, document, "gx")
    assert len(ours.candidates) > 1 and ours.candidates[0]["model"] == ours.selected_model
    assert ours.wic == min(c["wic"] for c in ours.candidates)


def test_the_haar_wavelet_variance_is_half_the_allan_variance_of_allantools():
    # nu^2(tau_j) = AVAR(tau_j / 2) / 2 exactly (Percival & Walden 2000, 8.3): the same sums in
    # another order, so agreement to rounding; 1e-9 leaves margin.
    rng = np.random.default_rng(3)
    x = rng.standard_normal(16384) + np.cumsum(rng.standard_normal(16384)) * 1e-2
    wv = thermonav.gmwm(x, RATE_HZ, model="wn+rw", replicates=10).wavelet_variance
    tau, dev, _, _ = allantools.oadev(x, rate=RATE_HZ, data_type="freq", taus=wv.scale_s / 2)
    assert len(tau) == len(wv.scale_s) >= 10
    np.testing.assert_allclose(tau, wv.scale_s / 2, rtol=1e-12)
    np.testing.assert_allclose(wv.variance_unit2, dev**2 / 2, rtol=1e-9)
    assert np.all(wv.ci_low_unit2 < wv.variance_unit2) and np.all(wv.variance_unit2 < wv.ci_high_unit2)


def test_bad_settings_and_data_are_refused():
    x = np.random.default_rng(0).standard_normal(4096)
    with pytest.raises(ThermonavError, match="model wn\\+xx"):
        thermonav.gmwm(x, RATE_HZ, model="wn+xx")
    with pytest.raises(ThermonavError, match="sensor"):
        thermonav.gmwm(x, RATE_HZ, sensor="magnetometer")
    with pytest.raises(ThermonavError, match="10 to 1000 bootstrap replicates, got 3"):
        thermonav.gmwm(x, RATE_HZ, replicates=3)
    y = x.copy()
    y[9] = np.nan
    with pytest.raises(ThermonavError, match="9"):
        thermonav.gmwm(y, RATE_HZ)
    with pytest.raises(TypeError, match="float64"):
        thermonav.gmwm(x.astype(np.float32), RATE_HZ)
    with pytest.raises(ThermonavError):
        thermonav.gmwm(x[:3], RATE_HZ)
