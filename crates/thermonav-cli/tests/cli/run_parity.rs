//! `evaluate` takes the run options of `integrate` beyond run_options.rs's (the model
//! temperature, the selection, the initial state, the static alignment and the time-offset
//! search), with the same names, meaning and defaults. For each option: `integrate` given it
//! writes a solution that `evaluate`, given it too, scores as an outside solution with the
//! outage RMS of the tournament's candidate with integrate's model (the two ran the same
//! filter on the same record from the same start), and `evaluate` without it gives that
//! candidate another result (the option reached the tournament; the test is not vacuous).
//! `--output-rate-hz` and `--smooth` stay integrate's: they shape what it writes, not its run.

use crate::navigation::inputs;
use crate::run_options::refused_alike;
use crate::{arg, outcome, thermonav};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The outages of the vessel's runs, inside its 240 s.
const VESSEL: [&str; 4] = ["--outages", "60+30,150+30", "--lever-arm-m", "0.3,0,-2.5"];
/// The outages of the rover's runs, after its still start and pull-away.
const ROVER: [&str; 2] = ["--outages", "80+20,150+20"];
/// integrate's model fixed at the bank's 25 °C entry; evaluate's candidate of that entry.
const ENTRY_25: [&str; 2] = ["--model-temperature-c", "25"];
/// The model at 25 °C, fixed: the candidate `integrate --model-temperature-c 25` runs.
const FIXED_25: [&str; 3] = ["--model-temperature-c", "25", "--no-schedule"];
const ENTRY_25_LABEL: &str = "bank 25.0 °C";

/// The record, the fixes, the reference and the bank of one test.
struct Data {
    imu: PathBuf,
    gnss: PathBuf,
    reference: PathBuf,
    bank: PathBuf,
    /// The outages and lever arm of every run on this data.
    common: &'static [&'static str],
}

/// The 240 s vessel survey at 17 °C (dual-antenna heading) and the bank of 10 and 25 °C.
fn vessel(dir: &Path) -> Data {
    let (bank, vessel) = inputs(dir);
    Data {
        imu: vessel.join("imu.csv"),
        gnss: vessel.join("gnss.csv"),
        reference: vessel.join("reference.csv"),
        bank,
        common: &VESSEL,
    }
}

/// A 200 s ground rover at 2 m/s with position-only fixes, standing still for its first 20 s
/// (a still start to level from), and the same bank: runs against its fixes align from GNSS.
fn rover(dir: &Path) -> Data {
    let (bank, _) = inputs(dir);
    let out = dir.join("rover");
    let args = ["simulate", "vessel", "--out", arg(&out), "--speed-m-s", "2"];
    let more = [
        "--duration-s",
        "200",
        "--gnss-heading",
        "none",
        "--seed",
        "5",
    ];
    json_of(&[&args[..], &more, &["--json"]].concat());
    Data {
        imu: out.join("imu.csv"),
        gnss: out.join("gnss.csv"),
        reference: out.join("reference.csv"),
        bank,
        common: &ROVER,
    }
}

fn json_of(args: &[&str]) -> Value {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "{args:?}: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

/// The bank of `data` on the raw record: the noise of every run but the tests' of noise.
fn uncompensated_bank(data: &Data) -> [&str; 3] {
    ["--bank", arg(&data.bank), "--no-compensation"]
}

/// `integrate` on `data` (uncompensated) with `option`, writing `dir/NAME.csv`: its JSON and
/// its solution.
fn integrate(data: &Data, dir: &Path, name: &str, option: &[&str]) -> (Value, PathBuf) {
    integrate_with(data, (dir, name), &uncompensated_bank(data), option)
}

/// `integrate` on `data` with `noise` (a bank or a profile, with their options) and `option`,
/// writing `dir/NAME.csv`: its JSON and its solution.
fn integrate_with(
    data: &Data,
    (dir, name): (&Path, &str),
    noise: &[&str],
    option: &[&str],
) -> (Value, PathBuf) {
    let solution = dir.join(format!("{name}.csv"));
    let mut args = vec![
        "integrate",
        "--imu",
        arg(&data.imu),
        "--gnss",
        arg(&data.gnss),
    ];
    args.extend(noise);
    args.extend(["--out", arg(&solution), "--json"]);
    args.extend(data.common);
    args.extend(option);
    (json_of(&args), solution)
}

/// `evaluate` on `data` against `reference` (EKF, uncompensated candidates) with `option`,
/// scoring `solution` as the outside solution "integrate", into `dir/NAME`.
fn evaluate(
    data: &Data,
    out: (&Path, &str),
    reference: &Path,
    solution: &Path,
    option: &[&str],
) -> Value {
    let noise = uncompensated_bank(data);
    evaluate_with(data, out, (reference, solution), &noise, option)
}

/// `evaluate` (EKF) on `data` against `reference` with `noise` and `option`, scoring
/// `solution` as the outside solution "integrate", into `dir/NAME`.
fn evaluate_with(
    data: &Data,
    (dir, name): (&Path, &str),
    (reference, solution): (&Path, &Path),
    noise: &[&str],
    option: &[&str],
) -> Value {
    let out = dir.join(name);
    let mut args = vec![
        "evaluate",
        "--imu",
        arg(&data.imu),
        "--gnss",
        arg(&data.gnss),
    ];
    args.extend(["--reference", arg(reference), "--filter", "ekf"]);
    args.extend(noise);
    args.extend(["--solution", arg(solution), "--solution-label", "integrate"]);
    args.extend(["--out", arg(&out), "--json"]);
    args.extend(data.common);
    args.extend(option);
    json_of(&args)
}

/// The RMS horizontal error of an evaluation's row `label`.
fn rms(evaluation: &Value, label: &str) -> f64 {
    let models = evaluation["models"].as_array().unwrap();
    let row = models.iter().find(|m| m["label"] == label);
    let row = row.unwrap_or_else(|| panic!("no row {label}: {models:?}"));
    row["rms_horizontal_m"].as_f64().unwrap()
}

/// Checks that evaluate's candidate `label` ran integrate's run: the same outage RMS (the
/// solution file's digits agree to far below 1e-6 m).
fn assert_same_run(evaluation: &Value, label: &str, what: &str) {
    let (ours, theirs) = (rms(evaluation, label), rms(evaluation, "integrate"));
    assert!(
        (ours - theirs).abs() < 1e-6,
        "{what}: {label} {ours} vs integrate {theirs}"
    );
}

/// Checks that evaluate's candidate `label` did not run integrate's run.
fn assert_other_run(evaluation: &Value, label: &str, what: &str) {
    let (ours, theirs) = (rms(evaluation, label), rms(evaluation, "integrate"));
    assert!(
        (ours - theirs).abs() > 1e-4,
        "{what}: {label} {ours} vs integrate {theirs}"
    );
}

/// `imu` without its temp_c column, as `dir/imu_no_temp.csv`.
fn without_temperature(imu: &Path, dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(imu).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(header.ends_with(",temp_c"), "{header}");
    let strip = |line: &str| line.rsplit_once(',').unwrap().0.to_string();
    let rows: Vec<String> = std::iter::once(header).chain(lines).map(strip).collect();
    let out = dir.join("imu_no_temp.csv");
    std::fs::write(&out, rows.join("\n") + "\n").unwrap();
    out
}

// On a record without temp_c the model temperature is what both need: integrate runs the
// bank's 25 °C model, the tournament stands its one-temperature candidates at 25 °C and its
// 25 °C entry ran integrate's run; without the option evaluate refuses, naming it. On the
// record with temp_c the candidates stand at its 17 °C instead.
#[test]
fn model_temperature_c() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut data = vessel(d);
    let with_temperature = std::mem::replace(&mut data.imu, PathBuf::new());
    data.imu = without_temperature(&with_temperature, d);
    let start = ["--initial-from", arg(&data.reference)];
    let (run, solution) = integrate(&data, d, "fixed", &[&start[..], &ENTRY_25].concat());
    assert_eq!(run["model"]["temperature_c"], 25.0);
    let evaluation = evaluate(&data, (d, "ev"), &data.reference, &solution, &FIXED_25);
    assert_same_run(&evaluation, ENTRY_25_LABEL, "--model-temperature-c 25");
    assert_eq!(evaluation["operating_temperature_c"], 25.0);
    rms(&evaluation, "interpolated 25.0 °C");
    // Without it: refused, naming the option (exit 2, nothing written).
    let mut args = vec![
        "evaluate",
        "--imu",
        arg(&data.imu),
        "--gnss",
        arg(&data.gnss),
    ];
    let out = d.join("refused");
    args.extend([
        "--reference",
        arg(&data.reference),
        "--bank",
        arg(&data.bank),
    ]);
    args.extend(["--out", arg(&out)]);
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    // The library's words (Python's say `model_temperature_c or operating_temperature_c`).
    let message = "imu_no_temp.csv: no temp_c column; give the temperature \
                   (--model-temperature-c or --operating-temperature-c)";
    assert!(stderr.contains(message), "{stderr}");
    assert!(!out.exists());
    // With temp_c and without the option, the candidates stand at the record's 17 °C.
    data.imu = with_temperature;
    let plain = evaluate(
        &data,
        (d, "plain"),
        &data.reference,
        &solution,
        &["--no-schedule"],
    );
    assert_eq!(plain["operating_temperature_c"], 17.0);
    rms(&plain, "interpolated 17.0 °C");
}

// The selection picks the model of integrate's run; in evaluate, the model of the run the
// time offset is estimated with (the tournament runs each rule as a candidate of its own):
// with --select linear both estimate the same offset from the same likelihood profile, and the
// tournament's scheduled linear candidate is integrate's run; the default (nearest) profiles
// another model's likelihood.
#[test]
fn select() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = vessel(d);
    let start = ["--initial-from", arg(&data.reference)];
    let option = ["--select", "linear", "--estimate-time-offset"];
    let (run, solution) = integrate(&data, d, "linear", &[&start[..], &option].concat());
    let evaluation = evaluate(&data, (d, "ev"), &data.reference, &solution, &option);
    assert_eq!(evaluation["time_offset"], run["time_offset"]);
    assert_same_run(&evaluation, "scheduled linear", "--select linear");
    let nearest = ["--estimate-time-offset"];
    let other = evaluate(&data, (d, "nearest"), &data.reference, &solution, &nearest);
    let likelihood = |e: &Value| e["time_offset"]["log_likelihood"].as_f64().unwrap();
    assert_ne!(likelihood(&other), likelihood(&evaluation));
}

// --initial-from: every candidate starts from this trajectory, as integrate does, instead of
// aligning from the rover's fixes (a reference of positions only); a trajectory of positions
// only is refused by both alike.
#[test]
fn initial_from() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = rover(d);
    let option = ["--initial-from", arg(&data.reference)];
    let (run, solution) = integrate(&data, d, "started", &[&option[..], &ENTRY_25].concat());
    assert_eq!(run["initial"], "reference");
    let fixes = &data.gnss;
    let fixed = ["--no-schedule"];
    let evaluation = evaluate(
        &data,
        (d, "ev"),
        fixes,
        &solution,
        &[&option[..], &fixed].concat(),
    );
    assert_same_run(&evaluation, ENTRY_25_LABEL, "--initial-from");
    let aligned = evaluate(&data, (d, "aligned"), fixes, &solution, &fixed);
    assert_other_run(&aligned, ENTRY_25_LABEL, "without --initial-from");
    let position_only = ["--initial-from", arg(fixes)];
    let refusals = [("integrate", "refused.csv"), ("evaluate", "refused")].map(|(command, out)| {
        let out = d.join(out);
        let mut args = vec![command, "--imu", arg(&data.imu), "--gnss", arg(fixes)];
        args.extend(["--bank", arg(&data.bank), "--out", arg(&out)]);
        if command == "evaluate" {
            args.extend(["--reference", arg(fixes)]);
        }
        args.extend(position_only);
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert!(!out.exists(), "{command}");
        // The error itself (integrate notes the bank's rate against the record's first).
        let error = stderr.lines().filter(|l| l.starts_with("error:"));
        (status, error.collect::<Vec<_>>().join("\n"))
    });
    assert_eq!(refusals[0], refusals[1]);
    assert_eq!(refusals[0].0, 1);
    assert!(
        refusals[0].1.contains("leave out --initial-from"),
        "{refusals:?}"
    );
}

// --no-static-alignment: runs that align from GNSS (evaluate against the rover's fixes,
// integrate without --initial-from) level their start from the still span unless told not
// to; told, the candidate is integrate's unlevelled run, and the run options say so alike.
#[test]
fn no_static_alignment() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = rover(d);
    let option = ["--no-static-alignment"];
    let (run, solution) = integrate(&data, d, "unlevelled", &[&option[..], &ENTRY_25].concat());
    assert_eq!(run["static_alignment"]["decision"], "off");
    let fixed = ["--no-schedule"];
    let fixes = &data.gnss;
    let evaluation = evaluate(
        &data,
        (d, "ev"),
        fixes,
        &solution,
        &[&option[..], &fixed].concat(),
    );
    assert_same_run(&evaluation, ENTRY_25_LABEL, "--no-static-alignment");
    assert_eq!(evaluation["run_options"], run["run_options"]);
    assert_eq!(evaluation["run_options"]["static_alignment"], "off");
    let levelled = evaluate(&data, (d, "levelled"), fixes, &solution, &fixed);
    assert_other_run(&levelled, ENTRY_25_LABEL, "with static alignment");
    assert_eq!(levelled["run_options"]["static_alignment"], "when_still");
}

/// `integrate` from the reference's point with the 25 °C model and the time-offset `option`,
/// and `evaluate` of the same with `option`: both report the same offset search and run the
/// same filter. Returns integrate's JSON and its solution.
fn time_offset_runs(data: &Data, d: &Path, option: &[&str]) -> (Value, PathBuf) {
    let start = ["--initial-from", arg(&data.reference)];
    let (run, solution) = integrate(data, d, "run", &[&start[..], &ENTRY_25, option].concat());
    let with_option = [&FIXED_25[..], option].concat();
    let evaluation = evaluate(data, (d, "ev"), &data.reference, &solution, &with_option);
    assert_eq!(evaluation["time_offset"], run["time_offset"]);
    assert_same_run(&evaluation, ENTRY_25_LABEL, &option.join(" "));
    (run, solution)
}

// --estimate-time-offset: evaluate estimates the offset once with integrate's run (the same
// estimate, to the last bit) and runs every candidate on the record shifted by it; without
// the option the candidate runs on the record as read.
#[test]
fn estimate_time_offset() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = vessel(d);
    let (run, solution) = time_offset_runs(&data, d, &["--estimate-time-offset"]);
    let offset = run["time_offset"]["time_offset_s"].as_f64().unwrap();
    assert!(offset.abs() > 0.01, "{offset}");
    let unshifted = evaluate(
        &data,
        (d, "unshifted"),
        &data.reference,
        &solution,
        &FIXED_25,
    );
    assert!(unshifted.get("time_offset").is_none());
    assert_other_run(&unshifted, ENTRY_25_LABEL, "without --estimate-time-offset");
}

// --time-offset-bracket-s: both search the same bracket and find the same offset; the default
// bracket profiles another range.
#[test]
fn time_offset_bracket_s() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = vessel(d);
    let option = ["--estimate-time-offset", "--time-offset-bracket-s", "0.3"];
    let (run, solution) = time_offset_runs(&data, d, &option);
    assert_eq!(
        run["time_offset"]["bracket_s"],
        serde_json::json!([-0.3, 0.3])
    );
    let wide = [&FIXED_25[..], &["--estimate-time-offset"]].concat();
    let default = evaluate(&data, (d, "wide"), &data.reference, &solution, &wide);
    assert_eq!(
        default["time_offset"]["bracket_s"],
        serde_json::json!([-0.5, 0.5])
    );
}

// A bad value of these options is refused by both in the same words, before any file is read;
// evaluate refuses the time-offset search in a sharded run (every shard would search).
#[test]
fn both_refuse_a_bad_option_alike() {
    let cases: [&[&str]; 4] = [
        &["--estimate-time-offset", "--time-offset-bracket-s", "20"],
        &["--estimate-time-offset", "--time-offset-bracket-s", "0"],
        &["--model-temperature-c", "NaN"],
        &["--operating-temperature-c", "inf"],
    ];
    for option in cases {
        let error = refused_alike(option);
        let flag = option[option.len() - 2];
        assert!(error.contains(flag), "{option:?}: {error}");
    }
    let missing = "/nonexistent/file.csv";
    let mut sharded = vec!["evaluate", "--imu", missing, "--gnss", missing];
    sharded.extend(["--reference", missing, "--bank", missing]);
    sharded.extend(["--out", "/nonexistent/out", "--shard", "1/2"]);
    sharded.push("--estimate-time-offset");
    let (status, _, stderr) = outcome(&thermonav(&sharded));
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--shard with --estimate-time-offset"),
        "{stderr}"
    );
}

/// `integrate` and `evaluate` on `data` with `noise` (a profile, or a bank with its options)
/// and `option`: integrate writes `dir/NAME.csv`, which evaluate (EKF) scores as the outside
/// solution "integrate" beside its candidates. Integrate's JSON and the evaluation.
fn noise_pair(
    data: &Data,
    (dir, name): (&Path, &str),
    noise: &[&str],
    option: &[&str],
) -> (Value, Value) {
    let (run, solution) = integrate_with(data, (dir, name), noise, option);
    let files = (data.reference.as_path(), solution.as_path());
    let out = (dir, &*format!("{name}_ev"));
    (run, evaluate_with(data, out, files, noise, option))
}

// A profile's candidate starts from integrate's initial uncertainty: the profile's turn-on and
// power-on bias sds with its Gauss-Markov σ (integrate's initial_bias_sd source
// "profile_turn_on"), not the built-in 1 °/s and 10 mg. So `evaluate --profile`'s fixed
// candidate at the record's 17 °C is `integrate --profile --no-schedule`'s run; its scheduled
// candidate, integrate's scheduled run. Before, every candidate started from the built-in
// sds, and neither was.
#[test]
fn a_profile_candidate_starts_as_integrate_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = vessel(d);
    let start = ["--initial-from", arg(&data.reference)];
    let profile = ["--profile", "builtin:temperature-sensitive"];
    let fixed = [&start[..], &["--no-schedule"]].concat();
    let (run, evaluation) = noise_pair(&data, (d, "fixed"), &profile, &fixed);
    assert_eq!(run["initial_bias_sd"]["source"], "profile_turn_on");
    assert_same_run(&evaluation, "profile 17.0 °C", "--profile, fixed");
    let (run, evaluation) = noise_pair(&data, (d, "scheduled"), &profile, &start);
    assert_eq!(run["initial_bias_sd"]["source"], "profile_turn_on");
    assert_same_run(&evaluation, "profile scheduled", "--profile, scheduled");
}

/// The bank of three power-ons of the vessel's unit at 10 and 25 °C (the vessel's chamber
/// campaign, repeated): its thermal calibration holds a spread between power-ons.
fn bank_of_three_power_ons(dir: &Path) -> PathBuf {
    let chamber = dir.join("power_ons");
    let mut args = vec!["simulate", "chamber", "--out", arg(&chamber)];
    args.extend(["--temperatures-c", "10,25", "--duration-s", "600"]);
    args.extend([
        "--rate-hz",
        "50",
        "--seed",
        "3",
        "--power-ons",
        "3",
        "--json",
    ]);
    json_of(&args);
    let record = |folder: &str, t: u32| chamber.join(folder).join(format!("imu_{t}C.csv"));
    let pieces = |folder: &str| {
        let [a, b] = [10, 25].map(|t| record(folder, t).to_string_lossy().into_owned());
        format!("{a},{b}")
    };
    let (second, third) = (pieces("power_on_2"), pieces("power_on_3"));
    let bank = dir.join("bank_power_ons.json");
    let [first_10, first_25] = [10, 25].map(|t| record("", t));
    let mut args = vec!["characterize", arg(&first_10), arg(&first_25)];
    args.extend(["--power-on", &second, "--power-on", &third]);
    args.extend(["--out", arg(&bank), "--json"]);
    json_of(&args);
    bank
}

// On the record compensated with a bank's thermal calibration that holds a spread between
// power-ons, integrate starts its biases from that spread with the Gauss-Markov σ
// ("bank_power_on_spread"), and so does the tournament's compensated candidate: the entry
// nearest the record's 17 °C (measured at 10.1 °C), fixed, is `integrate --no-schedule`'s
// compensated run.
#[test]
fn a_compensated_candidate_starts_as_integrate_does() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let data = vessel(d);
    let bank_path = bank_of_three_power_ons(d);
    let bank = ["--bank", arg(&bank_path)];
    let option = ["--initial-from", arg(&data.reference), "--no-schedule"];
    let (run, evaluation) = noise_pair(&data, (d, "compensated"), &bank, &option);
    assert_eq!(run["initial_bias_sd"]["source"], "bank_power_on_spread");
    assert_same_run(&evaluation, "bank 10.1 °C compensated", "compensated");
}
