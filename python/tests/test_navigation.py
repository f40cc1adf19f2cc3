"""integrate and evaluate against the CLI's files and JSON written in the same run, to the last bit."""

import json
import subprocess

import numpy as np
import pytest

import thermonav
from thermonav import ThermonavError

LEVER_ARM = [0.3, 0.0, -2.5]  # the simulated vessel's antenna, body forward/right/down, m
RUN_KEYS_THAT_ARE_WALL_TIME = {"processing_time_s", "real_time_factor"}


def cli(binary, *args):
    done = subprocess.run([str(binary), *map(str, args)], check=True, capture_output=True, text=True)
    return done.stdout


@pytest.fixture(scope="module")
def data(binary, tmp_path_factory):
    """A bank of three 10-minute 50 Hz chamber records and a 120 s vessel run at 17 °C (seeded)."""
    out = tmp_path_factory.mktemp("navigation")
    cli(binary, "simulate", "chamber", "--out", out / "chamber", "--temperatures-c=-10,20,50",
        "--duration-s", 600, "--rate-hz", 50, "--seed", 5, "--quiet")
    bank = out / "bank.json"
    cli(binary, "characterize", *sorted((out / "chamber").glob("imu_*C.csv")), "--out", bank, "--quiet")
    vessel = out / "vessel"
    cli(binary, "simulate", "vessel", "--out", vessel, "--duration-s", 120, "--seed", 4, "--quiet")
    return {"dir": out, "bank": bank, "imu": vessel / "imu.csv", "gnss": vessel / "gnss.csv",
            "reference": vessel / "reference.csv"}


def read_csv(path):
    """A CSV's columns by header name, each parsed by Python's float (the shortest round trip)."""
    return np.genfromtxt(path, delimiter=",", names=True, dtype=float)


def assert_columns_equal(table, ours):
    for name in table.dtype.names:
        expected = table[name]
        got = ours[name].astype(float) if name == "in_outage" else ours[name]
        assert np.array_equal(got, expected), name  # bit for bit: same numbers, same text


def assert_report_equal(ours, document):
    for key, value in document.items():
        # The CLI's own keys around the run report: its inputs, how it read the IMU file
        # (`imu_reading`: streamed or whole), the files it wrote, and its notes on how the
        # bank's records differ from the IMU file (`record_notes`, the CLI's check of its
        # input files; Python's integrate does not make it yet).
        cli_keys = ("imu", "gnss", "bank", "profile", "files", "imu_reading", "record_notes")
        if key in RUN_KEYS_THAT_ARE_WALL_TIME or key in cli_keys:
            continue
        assert ours[key] == value, key


def test_integrate_equals_the_clis_solution_and_json(binary, data, tmp_path):
    out = tmp_path / "solution.csv"
    document = json.loads(cli(binary, "integrate", "--imu", data["imu"], "--gnss", data["gnss"],
                              "--bank", data["bank"], "--outages", "60+20", "--lever-arm-m",
                              "0.3,0,-2.5", "--out", out, "--json"))
    ours = thermonav.integrate(data["imu"], data["gnss"], bank=data["bank"], outages="60+20",
                               lever_arm_m=LEVER_ARM)
    assert_report_equal(ours, document)
    assert ours.schedule.kind == "scheduled" and ours.compensation.status == "applied"
    assert_columns_equal(read_csv(out), ours.solution)
    assert_columns_equal(read_csv(tmp_path / "solution.states.csv"), ours.solution)
    assert ours.solution.t_ns.dtype == np.int64 and ours.smoothed is None
    assert ours.solution.in_outage.any() and ours.notes == []


def test_integrate_with_a_profile_a_fixed_model_and_the_smoother(binary, data, tmp_path):
    out = tmp_path / "solution.csv"
    profile = thermonav_profile()
    document = json.loads(cli(binary, "integrate", "--imu", data["imu"], "--gnss", data["gnss"],
                              "--profile", profile, "--model-temperature-c", 25, "--smooth",
                              "--initial-from", data["reference"], "--no-heading",
                              "--lever-arm-m", "0.3,0,-2.5", "--out", out, "--json"))
    ours = thermonav.integrate(data["imu"], data["gnss"], profile=profile, model_temperature_c=25,
                               smooth=True, initial_from=data["reference"], heading=False,
                               lever_arm_m=LEVER_ARM)
    assert_report_equal(ours, document)
    assert ours.initial == "reference" and ours.schedule.kind == "fixed"
    assert_columns_equal(read_csv(out), ours.solution)
    assert_columns_equal(read_csv(tmp_path / "solution.smoothed.csv"), ours.smoothed)
    assert_columns_equal(read_csv(tmp_path / "solution.smoothed.states.csv"), ours.smoothed)


def thermonav_profile():
    from conftest import REPO

    return REPO / "examples" / "profiles" / "drive_0708_imu.toml"


def test_evaluate_equals_the_clis_evaluation_json_and_error_csvs(binary, data, tmp_path):
    outages = "35+20,80+20"
    cli(binary, "evaluate", "--imu", data["imu"], "--gnss", data["gnss"], "--reference",
        data["reference"], "--bank", data["bank"], "--outages", outages, "--monte-carlo", 2,
        "--seed", 11, "--filter", "ekf", "--lever-arm-m", "0.3,0,-2.5", "--out", tmp_path,
        "--json")
    document = json.loads((tmp_path / "evaluation.json").read_text())
    ours = thermonav.evaluate(data["imu"], data["gnss"], data["reference"], bank=data["bank"],
                              outages=outages, monte_carlo=2, seed=11, filter="ekf",
                              lever_arm_m=LEVER_ARM)
    assert set(document) - set(ours) == {"report_file"}
    for key in document:
        if key not in ("report_file", "models"):
            assert ours[key] == document[key], key
    assert ours.significance.replicates == 2 and ours.filters == ["ekf"]
    assert len(ours.models) == len(document["models"]) >= 4 and ours.excluded
    for model, theirs in zip(ours.models, document["models"]):
        csv = theirs.pop("errors_csv")
        assert {k: v for k, v in model.items() if k not in ("errors", "errors_csv")} == theirs
        if csv is not None:
            table = read_csv(tmp_path / csv)  # errors_csv is relative to evaluation.json
            for name in table.dtype.names:
                assert np.array_equal(model.errors[name], table[name]), (model.label, name)


def test_evaluate_takes_the_run_keywords_of_integrate_as_the_cli_does(binary, data, tmp_path):
    outages = "35+20,80+20"
    cli(binary, "evaluate", "--imu", data["imu"], "--gnss", data["gnss"], "--reference",
        data["reference"], "--bank", data["bank"], "--outages", outages, "--filter", "ekf",
        "--lever-arm-m", "0.3,0,-2.5", "--process-noise-scale", 3, "--gate-window", 0,
        "--velocity-sd-m-s", "0.2", "--no-schedule", "--no-compensation", "--out", tmp_path)
    document = json.loads((tmp_path / "evaluation.json").read_text())
    ours = thermonav.evaluate(data["imu"], data["gnss"], data["reference"], bank=data["bank"],
                              outages=outages, filter="ekf", lever_arm_m=LEVER_ARM,
                              process_noise_scale=3, gate_window=0, velocity_sd_m_s=[0.2],
                              schedule=False, compensation=False)
    assert ours["run_options"] == document["run_options"]
    assert document["run_options"]["process_noise_scale"] == 3.0
    assert [m.rms_horizontal_m for m in ours.models] == [
        m["rms_horizontal_m"] for m in document["models"]]
    run = thermonav.integrate(data["imu"], data["gnss"], bank=data["bank"], lever_arm_m=LEVER_ARM,
                              process_noise_scale=3, gate_window=0, velocity_sd_m_s=[0.2])
    assert run["run_options"] == ours["run_options"]


def test_evaluate_takes_the_model_temperature_and_the_start_as_the_cli_does(binary, data, tmp_path):
    """model_temperature_c and initial_from are evaluate's --model-temperature-c and --initial-from:
    the candidates at one temperature stand there, and every run starts from that trajectory (here
    integrate's solution, not the reference)."""
    outages = "35+20,80+20"
    start = tmp_path / "start.csv"
    cli(binary, "integrate", "--imu", data["imu"], "--gnss", data["gnss"], "--bank", data["bank"],
        "--lever-arm-m", "0.3,0,-2.5", "--out", start)
    out = tmp_path / "evaluation"
    cli(binary, "evaluate", "--imu", data["imu"], "--gnss", data["gnss"], "--reference",
        data["reference"], "--bank", data["bank"], "--outages", outages, "--filter", "ekf",
        "--lever-arm-m", "0.3,0,-2.5", "--model-temperature-c", 25, "--initial-from", start,
        "--out", out)
    document = json.loads((out / "evaluation.json").read_text())
    ours = thermonav.evaluate(data["imu"], data["gnss"], data["reference"], bank=data["bank"],
                              outages=outages, filter="ekf", lever_arm_m=LEVER_ARM,
                              model_temperature_c=25, initial_from=start)
    assert ours.operating_temperature_c == document["operating_temperature_c"] == 25.0
    assert [m.rms_horizontal_m for m in ours.models] == [
        m["rms_horizontal_m"] for m in document["models"]]
    from_reference = thermonav.evaluate(data["imu"], data["gnss"], data["reference"],
                                        bank=data["bank"], outages=outages, filter="ekf",
                                        lever_arm_m=LEVER_ARM, model_temperature_c=25)
    assert [m.rms_horizontal_m for m in from_reference.models] != [
        m.rms_horizontal_m for m in ours.models]
    with pytest.raises(ThermonavError, match="model_temperature_c"):
        thermonav.evaluate(data["imu"], data["gnss"], data["reference"], bank=data["bank"],
                           model_temperature_c=25, operating_temperature_c=20)


def test_a_bad_imu_file_names_its_line(data, tmp_path):
    bad = tmp_path / "imu.csv"
    lines = data["imu"].read_text().splitlines()
    lines[5] = lines[5].split(",", 1)[0] + ",x" + "".join("," + v for v in lines[5].split(",")[2:])
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(ThermonavError, match=r"imu\.csv:6"):
        thermonav.integrate(bad, data["gnss"], bank=data["bank"])
    with pytest.raises(ThermonavError, match=r"imu\.csv:6"):
        thermonav.evaluate(bad, data["gnss"], data["reference"], bank=data["bank"])


def test_bad_inputs_and_settings_are_named(data, tmp_path):
    imu, gnss = data["imu"], data["gnss"]
    with pytest.raises(ThermonavError, match="nothing.json"):
        thermonav.integrate(imu, gnss, bank=tmp_path / "nothing.json")
    with pytest.raises(ThermonavError, match="bank or profile"):
        thermonav.integrate(imu, gnss)
    with pytest.raises(ThermonavError, match="outages"):
        thermonav.integrate(imu, gnss, bank=data["bank"], outages="bogus")
    with pytest.raises(ThermonavError, match="outages: "):
        thermonav.integrate(imu, gnss, bank=data["bank"], outages="500+20")
    with pytest.raises(ThermonavError, match="smooth"):
        thermonav.integrate(imu, gnss, bank=data["bank"], smooth=True, filter="ukf")
    with pytest.raises(ThermonavError, match="filter"):
        thermonav.integrate(imu, gnss, bank=data["bank"], filter="both")
    with pytest.raises(ThermonavError, match="monte_carlo"):
        thermonav.evaluate(imu, gnss, data["reference"], bank=data["bank"], monte_carlo=0)
    empty = tmp_path / "gnss.csv"
    empty.write_text(gnss.read_text().splitlines()[0] + "\n")
    with pytest.raises(ThermonavError, match="gnss.csv"):
        thermonav.integrate(imu, empty, bank=data["bank"])


def test_a_record_without_temperature_asks_for_one_by_its_keyword(data, tmp_path):
    # The library's message, the settings spelt as Python's keywords (the CLI's as its options).
    rows = [line.rsplit(",", 1)[0] for line in data["imu"].read_text().splitlines()]
    assert rows[0].endswith("az_m_s2")
    imu = tmp_path / "imu_no_temp.csv"
    imu.write_text("\n".join(rows) + "\n")
    message = (r"imu_no_temp\.csv: no temp_c column; give the temperature "
               r"\(model_temperature_c or operating_temperature_c\)")
    with pytest.raises(ThermonavError, match=message):
        thermonav.integrate(imu, data["gnss"], bank=data["bank"])
    with pytest.raises(ThermonavError, match=message):
        thermonav.evaluate(imu, data["gnss"], data["reference"], bank=data["bank"])


def test_integrate_and_gmwm_let_other_threads_run(data):
    import threading
    import time

    x = np.random.default_rng(1).standard_normal(65536)
    calls = [lambda: thermonav.integrate(data["imu"], data["gnss"], bank=data["bank"]),
             lambda: thermonav.gmwm(x, 100.0, replicates=10)]
    for call in calls:
        start = time.perf_counter()
        call()
        alone_s = time.perf_counter() - start
        done, ticks = threading.Event(), []
        worker = threading.Thread(target=lambda: (call(), done.set()))
        worker.start()
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)
        worker.join()
        # Holding the GIL would stop this loop for the whole call (see test_threads.py).
        assert len(ticks) > 5 and np.diff(ticks).max() < max(0.5 * alone_s, 0.02)


def test_run_keywords_are_checked_by_the_library_as_the_cli_checks_them(data):
    # The library's RunOptions::validate is the one check: a negative velocity sd (which the
    # Python keywords once let through) and an output rate of 1e9 Hz are refused by name.
    imu, gnss = data["imu"], data["gnss"]
    with pytest.raises(ThermonavError, match=r"velocity_sd_m_s -1: expected a positive number"):
        thermonav.integrate(imu, gnss, bank=data["bank"], velocity_sd_m_s=[-1.0])
    with pytest.raises(ThermonavError, match=r"output_rate_hz 1000000000: above 5000 Hz"):
        thermonav.integrate(imu, gnss, bank=data["bank"], output_rate_hz=1e9)
    with pytest.raises(ThermonavError, match=r"gate_probability 2: expected a probability in \(0, 1\]"):
        thermonav.evaluate(imu, gnss, data["reference"], bank=data["bank"], gate_probability=2.0)
