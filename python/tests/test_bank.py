"""characterize against the CLI's bank.json written in the same run, to the last bit."""

import json
import subprocess

import numpy as np
import pytest

import thermonav


def run(binary, *args):
    subprocess.run([str(binary), *map(str, args), "--quiet"], check=True, capture_output=True)


@pytest.fixture(scope="module")
def chamber(binary, tmp_path_factory):
    """Three 15-minute 50 Hz chamber records simulated by the CLI (seeded)."""
    out = tmp_path_factory.mktemp("chamber")
    run(binary, "simulate", "chamber", "--out", out, "--temperatures-c=-20,20,60",
        "--duration-s", 900, "--rate-hz", 50)
    return sorted(out.glob("imu_*C.csv"))


@pytest.fixture(scope="module")
def cli_bank(binary, chamber, tmp_path_factory):
    out = tmp_path_factory.mktemp("bank") / "bank.json"
    run(binary, "characterize", *chamber, "--out", out)
    return out.read_text()


def test_the_bank_of_files_is_the_clis_bank_json_byte_for_byte(chamber, cli_bank):
    bank = thermonav.characterize(chamber)
    assert bank.to_json() == cli_bank
    assert bank.to_dict() == json.loads(cli_bank)  # every float to the last bit
    assert bank.thermal is not None and bank.notes == []


def test_the_bank_of_read_arrays_equals_the_bank_of_files(chamber, cli_bank):
    records = [thermonav.read_imu(path) for path in chamber]
    assert thermonav.characterize(records).to_json() == cli_bank


def test_given_temperatures_and_conditioning_as_the_cli(binary, chamber, tmp_path):
    out = tmp_path / "bank.json"
    run(binary, "characterize", chamber[0], chamber[1], "--temperature-c=-21,19",
        "--cutoff-hz", 0.3, "--transition-hz", 0.2, "--modelling-rate-hz", 1, "--out", out)
    bank = thermonav.characterize(chamber[:2], [-21, 19], cutoff_hz=0.3, transition_hz=0.2,
                                  modelling_rate_hz=1.0)
    assert bank.to_json() == out.read_text()


def test_one_temperature_has_no_thermal_calibration_and_says_why(binary, chamber, tmp_path):
    out = tmp_path / "bank.json"
    run(binary, "characterize", chamber[1], "--out", out)
    bank = thermonav.characterize(chamber[1])
    assert bank.to_json() == out.read_text()
    assert bank.thermal is None and "no thermal calibration" in bank.notes[0]


def test_the_bank_reads_back_and_reads_as_attributes(chamber, cli_bank, tmp_path):
    bank = thermonav.characterize(chamber)
    path = tmp_path / "again.json"
    bank.save(path)
    assert thermonav.load_bank(path) == bank
    np.testing.assert_allclose(bank.temperatures_c, [-20, 20, 60], atol=0.2)
    assert bank.channels == ["gx", "gy", "gz", "ax", "ay", "az"]
    gx = bank.entries[0].channels.gx
    assert gx.unit == "rad/s"
    assert gx.gauss_markov.irregular_ml.status in ("model", "no_equivalent")
    assert gx.allan.tau_s == json.loads(cli_bank)["entries"][0]["channels"]["gx"]["allan"]["tau_s"]


def test_to_pandas_is_a_long_table(chamber):
    pd = pytest.importorskip("pandas")
    table = thermonav.characterize(chamber).to_pandas()
    assert isinstance(table, pd.DataFrame)
    assert list(table.columns) == ["temperature_c", "source", "channel", "unit", "quantity", "value"]
    tc = table[(table.quantity == "gauss_markov.irregular_ml.correlation_time_s")]
    assert len(tc) <= 18 and set(tc.channel) <= {"gx", "gy", "gz", "ax", "ay", "az"}


def test_allan_of_a_read_channel_equals_allan_json(binary, chamber):
    done = subprocess.run([str(binary), "allan", str(chamber[0]), "--json"], check=True,
                          capture_output=True, text=True)
    cli = json.loads(done.stdout)
    imu = thermonav.read_imu(chamber[0])
    ours = thermonav.allan(imu.gx_rad_s, cli["sample_rate_hz"])
    channel = cli["channels"]["gx"]
    for key in ("tau_s", "adev", "n_terms", "ci_low", "ci_high", "noise_type_alpha"):
        assert ours[key].tolist() == channel[key], key
    terms = thermonav.noise_terms(imu.gx_rad_s, cli["sample_rate_hz"], "gx")
    assert terms.to_dict() == channel["terms"]
