"""Bad input raises exceptions with the CLI's messages, never crashes."""

import numpy as np
import pytest

import thermonav
from thermonav import ThermonavError

WHITE = np.random.default_rng(0).standard_normal(5000)


def with_nan(x, index=7):
    y = x.copy()
    y[index] = np.nan
    return y


@pytest.mark.parametrize(
    "call",
    [
        lambda x: thermonav.allan(x, 100.0),
        lambda x: thermonav.allan(x, 100.0, kind="totdev"),
        lambda x: thermonav.noise_terms(x, 100.0, "gyro"),
        lambda x: thermonav.ar(x, "burg", 2),
        lambda x: thermonav.zero_phase(x, 100.0, 5.0),
        lambda x: thermonav.gauss_markov(np.arange(len(x)) / 100.0, x),
    ],
)
def test_nan_is_refused_with_its_index(call):
    with pytest.raises(ThermonavError, match="7"):
        call(with_nan(WHITE))


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: thermonav.allan(np.array([1.0, 2.0]), 1.0), "too few"),
        (lambda: thermonav.zero_phase(WHITE[:100], 100.0, 5.0), "samples"),
        (lambda: thermonav.ar(WHITE[:3], "burg", 5), "too few"),
        (lambda: thermonav.gauss_markov(np.arange(5.0), WHITE[:5]), "20"),
    ],
)
def test_too_short_is_refused(call, message):
    with pytest.raises(ThermonavError, match=message):
        call()


@pytest.mark.parametrize("x", [np.arange(100), WHITE.astype(np.float32), ["a", "b", "c"]])
def test_another_dtype_is_a_type_error(x):
    with pytest.raises(TypeError, match="float64"):
        thermonav.allan(x, 1.0)


def test_a_two_dimensional_array_is_refused():
    with pytest.raises(ThermonavError, match="1-D"):
        thermonav.allan(WHITE.reshape(50, 100), 1.0)


@pytest.mark.parametrize("family", ["irregular_ml", "ar_based", "acf_fit"])
def test_time_going_back_is_refused(family):
    t = np.arange(len(WHITE)) / 100.0
    t[100], t[101] = t[101], t[100]
    with pytest.raises(ThermonavError, match="strictly increasing times"):
        thermonav.gauss_markov(t, WHITE, family=family)


def test_a_record_whose_time_goes_back_is_refused():
    t = np.arange(len(WHITE)) / 100.0
    t[10] = t[9]
    record = {"t_s": t, "temp_c": np.full(len(t), 20.0)}
    record.update({name: WHITE.copy() for name in
                   ["gx_rad_s", "gy_rad_s", "gz_rad_s", "ax_m_s2", "ay_m_s2", "az_m_s2"]})
    with pytest.raises(ThermonavError, match="repeat"):
        thermonav.characterize(record)


def test_settings_are_named():
    with pytest.raises(ThermonavError, match="unknown deviation kind"):
        thermonav.allan(WHITE, 1.0, kind="xdev")
    with pytest.raises(ThermonavError, match="method"):
        thermonav.ar(WHITE, "lasso", 2)
    with pytest.raises(ThermonavError, match="order 0"):
        thermonav.ar(WHITE, "burg", 0)
    with pytest.raises(ThermonavError, match="confidence"):
        thermonav.allan(WHITE, 1.0, confidence=1.5)
    with pytest.raises(ThermonavError, match="Nyquist"):
        thermonav.kaiser_fir(100.0, 60.0)


def test_a_bad_file_names_its_line(tmp_path):
    path = tmp_path / "imu.csv"
    path.write_text("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n"
                    "0.00,0,0,0,0,0,-9.8\n0.01,0,0,0,0,0,-9.8\n0.005,0,0,0,0,0,-9.8\n")
    with pytest.raises(ThermonavError, match=r"imu\.csv:4"):
        thermonav.read_imu(path)
    with pytest.raises(ThermonavError, match=r"imu\.csv:4"):
        thermonav.characterize(path, [20.0])


def test_a_missing_file_and_a_missing_temperature(tmp_path):
    with pytest.raises(ThermonavError, match="nothing.csv"):
        thermonav.read_imu(tmp_path / "nothing.csv")
    path = tmp_path / "imu.csv"
    rows = "".join(f"{k / 100:.2f},{WHITE[k]},0.1,0.2,0.3,0.4,-9.8\n" for k in range(3000))
    path.write_text("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n" + rows)
    with pytest.raises(ThermonavError, match="no temp_c column"):
        thermonav.characterize(path)
    with pytest.raises(ThermonavError, match="outside -80..150"):
        thermonav.characterize(path, [300.0])
