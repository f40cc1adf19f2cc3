//! Bad input: a clear message naming file, line and expectation; exit 1 for data, 2 for usage;
//! no partial output file; never a panic.

use crate::{IMU_HEADER, arg, files_in, imu_csv, outcome, thermonav, write_file};
use std::path::Path;

/// Runs `filter` on `input` into a fresh output path and checks the failure's shape.
fn filter_fails(dir: &Path, input: &Path, extra: &[&str], code: i32) -> String {
    let out = dir.join("out.csv");
    let mut args = vec!["filter", arg(input), "--cutoff-hz", "5", "--out", arg(&out)];
    args.extend_from_slice(extra);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, code, "stderr: {stderr}");
    assert!(stdout.is_empty(), "nothing on stdout on failure: {stdout}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.exists(), "no output file after a failure");
    assert!(
        !dir.join("out.csv.json").exists(),
        "no sidecar after a failure"
    );
    let leftovers: Vec<_> = files_in(dir)
        .into_iter()
        .filter(|n| n.starts_with("out"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "no temporary file left: {leftovers:?}"
    );
    stderr
}

fn good_rows() -> String {
    imu_csv(400, 200.0, |c, t| (c as f64) + (t * 3.0).sin())
}

#[test]
fn missing_file_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("nope.csv");
    let stderr = filter_fails(dir.path(), &missing, &[], 1);
    assert!(stderr.contains("nope.csv"), "{stderr}");
    let (status, _, stderr) = outcome(&thermonav(&["inspect", arg(&missing)]));
    assert_eq!(status, 1);
    assert!(stderr.contains("nope.csv"), "{stderr}");
}

#[test]
fn empty_file_and_header_only_are_data_errors() {
    let dir = tempfile::tempdir().unwrap();
    let empty = write_file(dir.path(), "empty.csv", "");
    let stderr = filter_fails(dir.path(), &empty, &[], 1);
    assert!(
        stderr.contains("empty.csv") && stderr.contains("empty"),
        "{stderr}"
    );
    let header = write_file(dir.path(), "header.csv", &format!("{IMU_HEADER}\n"));
    let stderr = filter_fails(dir.path(), &header, &[], 1);
    assert!(stderr.contains("header.csv"), "{stderr}");
}

#[test]
fn unknown_and_missing_columns_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let unknown = good_rows().replacen("gy_rad_s", "wobble", 1);
    let path = write_file(dir.path(), "unknown.csv", &unknown);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(
        stderr.contains("wobble") && stderr.contains(":1"),
        "{stderr}"
    );
    let missing = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2\n0,1,2,3,4,5\n";
    let path = write_file(dir.path(), "missing.csv", missing);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(stderr.contains("az_m_s2"), "{stderr}");
}

#[test]
fn wrong_field_count_and_text_name_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut short = good_rows();
    short.push_str("2.5,1,2,3\n");
    let path = write_file(dir.path(), "short.csv", &short);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(stderr.contains("short.csv:402"), "{stderr}");
    let text = good_rows().replacen(",1,", ",abc,", 1);
    let path = write_file(dir.path(), "text.csv", &text);
    let stderr = filter_fails(dir.path(), &path, &[], 1);
    assert!(
        stderr.contains("text.csv:2") && stderr.contains("abc"),
        "{stderr}"
    );
}

#[test]
fn nan_and_inf_are_refused_by_filter_and_counted_by_inspect() {
    let dir = tempfile::tempdir().unwrap();
    let rows = imu_csv(
        400,
        200.0,
        |c, t| if c == 2 && t == 0.5 { f64::NAN } else { 1.0 },
    );
    let nan = write_file(
        dir.path(),
        "nan.csv",
        &rows.replacen(",1,1,1,1\n", ",1,1,inf,1\n", 1),
    );
    let stderr = filter_fails(dir.path(), &nan, &[], 1);
    assert!(stderr.contains("nan.csv:"), "{stderr}");
    let (status, stdout, stderr) = outcome(&thermonav(&["inspect", arg(&nan), "--json"]));
    assert_eq!(status, 0, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["non_finite_count"], 2);
}

#[test]
fn backwards_and_duplicate_timestamps_are_refused_by_filter() {
    let dir = tempfile::tempdir().unwrap();
    let mut rows = good_rows();
    rows.push_str("2.0,0,0,0,0,0,0\n2.0,0,0,0,0,0,0\n");
    let dup = write_file(dir.path(), "dup.csv", &rows);
    let stderr = filter_fails(dir.path(), &dup, &[], 1);
    assert!(stderr.contains("dup.csv:403"), "{stderr}");
    let mut rows = good_rows();
    rows.push_str("0.5,0,0,0,0,0,0\n");
    let back = write_file(dir.path(), "back.csv", &rows);
    let stderr = filter_fails(dir.path(), &back, &[], 1);
    assert!(stderr.contains("back.csv:402"), "{stderr}");
}

#[test]
fn cutoff_at_or_above_nyquist_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_file(dir.path(), "ok.csv", &good_rows());
    let out = dir.path().join("out.csv");
    let args = [
        "filter",
        arg(&path),
        "--cutoff-hz",
        "100",
        "--out",
        arg(&out),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.to_lowercase().contains("nyquist"), "{stderr}");
    assert!(!out.exists());
    let fir = ["fir", "--fs-hz", "200", "--cutoff-hz", "120"];
    assert_eq!(outcome(&thermonav(&fir)).0, 2);
}

#[test]
fn non_positive_ripple_is_a_usage_error() {
    for ripple in ["0", "-3"] {
        let args = [
            "fir",
            "--fs-hz",
            "200",
            "--cutoff-hz",
            "5",
            "--ripple-db",
            ripple,
        ];
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 2, "ripple {ripple}: {stderr}");
        assert!(stderr.contains("ripple"), "{stderr}");
    }
}

// A tournament takes its candidates from a bank or from a profile, never both (exit 2, both
// options named); neither is refused the same way.
#[test]
fn evaluate_with_bank_and_profile_is_a_usage_error() {
    let files = [
        "--imu",
        "i.csv",
        "--gnss",
        "g.csv",
        "--reference",
        "r.csv",
        "--out",
        "o",
    ];
    let both = [
        &["evaluate"][..],
        &files,
        &["--bank", "b.json", "--profile", "p.toml"],
    ]
    .concat();
    let (status, _, stderr) = outcome(&thermonav(&both));
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--bank") && stderr.contains("--profile"),
        "{stderr}"
    );
    let neither = [&["evaluate"][..], &files].concat();
    let (status, _, stderr) = outcome(&thermonav(&neither));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("--bank"), "{stderr}");
}

#[test]
fn unknown_flag_is_a_usage_error() {
    assert_eq!(outcome(&thermonav(&["inspect", "--frobnicate"])).0, 2);
    assert_eq!(outcome(&thermonav(&["nonsense"])).0, 2);
}

// ---------------------------------------------------------------------------------------------
// The suite: every reader's file spoiled in every way that applies, fed to every subcommand
// that reads it. Each run must exit 1, print nothing on stdout, name the file and the line (or
// say what the whole file lacks) and what was expected, never panic, and leave the folder as it
// was: no output, no temporary file.

/// Binary garbage with a few newlines.
const GARBAGE: &[u8] = b"\x00\x01\x02\xff\xfe\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xc3\x28\n";

/// A spoiled input: what was done, its bytes, and what the message must contain.
struct Spoiled {
    what: &'static str,
    bytes: Vec<u8>,
    needles: Vec<String>,
}

impl Spoiled {
    fn new(what: &'static str, bytes: impl Into<Vec<u8>>, needles: &[String]) -> Self {
        Self {
            what,
            bytes: bytes.into(),
            needles: needles.to_vec(),
        }
    }
}

/// A header and its rows joined into a file.
fn csv_text(header: &str, rows: &[String]) -> String {
    rows.iter()
        .fold(format!("{header}\n"), |text, row| text + row + "\n")
}

/// Rows `0..n` with row `a` moved after row `b` (`a < b`): time goes backwards at `b`'s line.
fn moved_back(rows: &[String], a: usize, b: usize) -> Vec<String> {
    let mut out = rows.to_vec();
    let row = out.remove(a);
    out.insert(b, row);
    out
}

/// Rows with row `k` repeated right after itself.
fn repeated(rows: &[String], k: usize) -> Vec<String> {
    let mut out = rows.to_vec();
    out.insert(k + 1, rows[k].clone());
    out
}

/// Rows with the third field of row `k` replaced by `value`.
fn with_value(rows: &[String], k: usize, value: &str) -> Vec<String> {
    let mut out = rows.to_vec();
    let mut fields: Vec<&str> = rows[k].split(',').collect();
    fields[2] = value;
    out[k] = fields.join(",");
    out
}

/// Every way to spoil a canonical CSV named `name`. Header is line 1, row `k` line `k + 2`.
/// `lenient` keeps only the spoils that a lenient reader (`inspect`) refuses too.
fn spoiled_csvs(name: &str, header: &str, rows: &[String], lenient: bool) -> Vec<Spoiled> {
    let at = |line: usize, what: &str| vec![format!("{name}:{line}:"), what.to_string()];
    let n = rows.len();
    let partial: String = rows[n - 1].chars().take(8).collect();
    let mut cases = vec![
        Spoiled::new(
            "empty",
            "",
            &[format!("{name}: file is empty"), "expected".into()],
        ),
        Spoiled::new("binary", GARBAGE, &at(1, "expected")),
        Spoiled::new(
            "semicolons",
            csv_text(header, rows).replace(',', ";"),
            &at(1, "expected"),
        ),
        Spoiled::new(
            "still being written",
            csv_text(header, rows) + &partial,
            &at(n + 2, "expected"),
        ),
    ];
    if !lenient {
        cases.extend([
            Spoiled::new(
                "backwards",
                csv_text(header, &moved_back(rows, 4, 6)),
                &at(8, "does not increase"),
            ),
            Spoiled::new(
                "duplicate epoch",
                csv_text(header, &repeated(rows, 5)),
                &at(8, "does not increase"),
            ),
            Spoiled::new(
                "NaN",
                csv_text(header, &with_value(rows, 5, "NaN")),
                &at(7, "not finite"),
            ),
            Spoiled::new(
                "inf",
                csv_text(header, &with_value(rows, 5, "-inf")),
                &at(7, "not finite"),
            ),
            // Issue 20: 1e300 made allan print inf and filter write NaN rows; a value no
            // estimator survives is refused at the reader, like NaN.
            Spoiled::new(
                "1e300",
                csv_text(header, &with_value(rows, 5, "1e300")),
                &at(7, "too large (expected a magnitude of at most 1e15"),
            ),
            Spoiled::new(
                "1.79e308",
                csv_text(header, &with_value(rows, 3, "-1.79e308")),
                &at(5, "too large (expected a magnitude of at most 1e15"),
            ),
        ]);
    }
    cases
}

/// A static IMU record in m/s² (`rows` at 100 Hz, small deterministic wiggles, 20 °C).
fn static_imu_rows(rows: usize, scale: f64) -> Vec<String> {
    (0..rows)
        .map(|k| {
            let t = k as f64 / 100.0;
            let w = |c: f64| 1e-3 * (t * (7.0 + c)).sin();
            let a = [w(1.0), w(2.0), -9.80665 + w(3.0)].map(|v| v * scale);
            format!(
                "{t:.9},{},{},{},{},{},{},20",
                w(4.0),
                w(5.0),
                w(6.0),
                a[0],
                a[1],
                a[2]
            )
        })
        .collect()
}

const IMU_T_HEADER: &str = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c";
const GNSS_HEADER: &str = "t_s,lat_deg,lon_deg,h_m";
const REFERENCE_HEADER: &str =
    "t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg";

fn gnss_rows() -> Vec<String> {
    (0..=12)
        .map(|k| {
            format!(
                "{:.9},48.1,11.5,{}",
                k as f64 * 0.5,
                500.0 + k as f64 * 0.01
            )
        })
        .collect()
}

fn reference_rows() -> Vec<String> {
    (0..=60)
        .map(|k| format!("{:.9},48.1,11.5,500,0,0,0,0,0,{}", k as f64 * 0.1, k))
        .collect()
}

/// Good inputs every case can lean on: `imu.csv`, `gnss.csv`, `reference.csv`, `bank.json`
/// (characterised from the IMU) and `profile.toml` (the built-in one).
fn fixtures() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let imu = write_file(
        dir.path(),
        "imu.csv",
        &csv_text(IMU_T_HEADER, &static_imu_rows(6000, 1.0)),
    );
    write_file(dir.path(), "gnss.csv", &csv_text(GNSS_HEADER, &gnss_rows()));
    write_file(
        dir.path(),
        "reference.csv",
        &csv_text(REFERENCE_HEADER, &reference_rows()),
    );
    let bank = dir.path().join("bank.json");
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        arg(&imu),
        "--out",
        arg(&bank),
    ]));
    assert_eq!(status, 0, "{stderr}");
    let profile = dir.path().join("profile.toml");
    let (status, _, stderr) = outcome(&thermonav(&["simulate", "profile", "--out", arg(&profile)]));
    assert_eq!(status, 0, "{stderr}");
    dir
}

/// Runs `command` (words) with `@` replaced by the spoiled file's path (in a fresh folder, as `name`),
/// `@dir` by that folder, `@out*` by outputs in it and `%x` by the fixture `x`; checks the
/// failure's shape.
fn refuses(fixtures: &Path, command: &str, name: &str, spoiled: &Spoiled) {
    let dir = tempfile::tempdir().unwrap();
    let input = write_file(dir.path(), name, "");
    std::fs::write(&input, &spoiled.bytes).unwrap();
    let before = files_in(dir.path());
    let args: Vec<String> = command
        .split_whitespace()
        .map(|a| match a {
            "@" => arg(&input).to_string(),
            "@dir" => arg(dir.path()).to_string(),
            a if a.starts_with("@out") => arg(&dir.path().join(&a[1..])).to_string(),
            a if a.starts_with('%') => arg(&fixtures.join(&a[1..])).to_string(),
            a => a.to_string(),
        })
        .collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    let case = format!("{command} on {name} ({}): {stderr}", spoiled.what);
    assert_eq!(status, 1, "{case}");
    assert!(stdout.is_empty(), "{case}\nstdout: {stdout}");
    assert!(!stderr.contains("panicked"), "{case}");
    for needle in &spoiled.needles {
        assert!(
            stderr.contains(needle.as_str()),
            "{case}\nmissing: {needle}"
        );
    }
    assert_eq!(files_in(dir.path()), before, "{case}: outputs left behind");
}

/// Every subcommand that reads a canonical IMU CSV (strictly), with `@` for it.
const IMU_COMMANDS: &[&str] = &[
    "filter @ --cutoff-hz 5 --out @out.csv",
    "allan @ --json",
    "ar @ --method burg --order 2 --json",
    "characterize @ --out @out.json --json",
    "plot autocorrelation @ --out @out.svg",
    "integrate --imu @ --gnss %gnss.csv --profile %profile.toml --out @out.csv",
    "evaluate --imu @ --gnss %gnss.csv --reference %reference.csv --bank %bank.json --out @out",
];

#[test]
fn every_imu_reader_refuses_every_spoiled_imu_csv() {
    let fixtures = fixtures();
    let mut cases = spoiled_csvs("imu.csv", IMU_T_HEADER, &static_imu_rows(600, 1.0), false);
    cases.push(Spoiled::new(
        "accelerations in g under m/s^2",
        csv_text(IMU_T_HEADER, &static_imu_rows(600, 1.0 / 9.80665)),
        &["imu.csv:1:".into(), "in g".into(), "expected m/s^2".into()],
    ));
    for command in IMU_COMMANDS {
        for spoiled in &cases {
            refuses(fixtures.path(), command, "imu.csv", spoiled);
        }
    }
    for spoiled in spoiled_csvs("imu.csv", IMU_T_HEADER, &static_imu_rows(600, 1.0), true) {
        refuses(fixtures.path(), "inspect @ --json", "imu.csv", &spoiled);
    }
}

#[test]
fn every_gnss_and_reference_reader_refuses_spoiled_files() {
    let fixtures = fixtures();
    let gnss_commands: &[&str] = &[
        "integrate --imu %imu.csv --gnss @ --profile %profile.toml --out @out.csv",
        "evaluate --imu %imu.csv --gnss @ --reference %reference.csv --bank %bank.json --out @out",
    ];
    let reference_commands: &[&str] = &[
        "evaluate --imu %imu.csv --gnss %gnss.csv --reference @ --bank %bank.json --out @out",
        "integrate --imu %imu.csv --gnss %gnss.csv --profile %profile.toml --initial-from @ --out @out.csv",
        "plot trajectory @ --out @out.svg",
    ];
    let inspect = "inspect @ --json";
    for (name, header, rows, commands) in [
        ("gnss.csv", GNSS_HEADER, gnss_rows(), gnss_commands),
        (
            "reference.csv",
            REFERENCE_HEADER,
            reference_rows(),
            reference_commands,
        ),
    ] {
        for command in commands {
            for spoiled in &spoiled_csvs(name, header, &rows, false) {
                refuses(fixtures.path(), command, name, spoiled);
            }
        }
        for spoiled in &spoiled_csvs(name, header, &rows, true) {
            refuses(fixtures.path(), inspect, name, spoiled);
        }
    }
}

/// 1-based line of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset].matches('\n').count() + 1
}

/// Every way to spoil the good bank `text` (JSON), named `bank.json`.
fn spoiled_banks(text: &str) -> Vec<Spoiled> {
    let at = |line: usize, what: &str| vec![format!("bank.json:{line}:"), what.to_string()];
    let half = text.len() / 2;
    let number = text.find(|c: char| c.is_ascii_digit()).unwrap();
    let end = number
        + text[number..]
            .find(|c: char| !c.is_ascii_digit() && c != '.')
            .unwrap();
    let nan = format!("{}NaN{}", &text[..number], &text[end..]);
    vec![
        Spoiled::new("empty", "", &at(1, "not a model bank")),
        Spoiled::new("binary", GARBAGE, &at(1, "not a model bank")),
        Spoiled::new(
            "still being written",
            &text.as_bytes()[..half],
            &at(line_of(text, half), "not a model bank"),
        ),
        Spoiled::new("NaN", nan, &at(line_of(text, number), "not a model bank")),
        Spoiled::new(
            "CSV",
            csv_text(GNSS_HEADER, &gnss_rows()),
            &at(1, "not a model bank"),
        ),
    ]
}

/// Every way to spoil the good profile `text` (TOML), named `profile.toml`.
fn spoiled_profiles(text: &str) -> Vec<Spoiled> {
    let needles = |what: &str| vec!["profile.toml".to_string(), what.to_string()];
    let cut = text.find("correlation_time_s = ").unwrap() + "correlation_time_s = ".len();
    vec![
        Spoiled::new("empty", "", &needles("missing")),
        Spoiled::new("binary", GARBAGE, &needles("line 1")),
        Spoiled::new(
            "still being written",
            &text.as_bytes()[..cut],
            &needles(&format!("line {}", line_of(text, cut))),
        ),
        Spoiled::new(
            "wrong units",
            text.replacen("white_noise_m_s_per_sqrt_h", "white_noise_g_per_sqrt_hz", 1),
            &needles("white_noise_g_per_sqrt_hz"),
        ),
        Spoiled::new(
            "NaN",
            text.replacen("correlation_time_s = 60.0", "correlation_time_s = nan", 1),
            &needles("correlation"),
        ),
    ]
}

#[test]
fn every_bank_and_profile_reader_refuses_spoiled_files() {
    let fixtures = fixtures();
    let bank_commands: &[&str] = &[
        "bank show @ --json",
        "bank export @ --format px4-tc --out @out.params",
        "integrate --imu %imu.csv --gnss %gnss.csv --bank @ --model-temperature-c 20 --out @out.csv",
        "evaluate --imu %imu.csv --gnss %gnss.csv --reference %reference.csv --bank @ --out @out",
        "plot correlation-time @ --out @out.svg",
        "report @dir",
    ];
    let bank = std::fs::read_to_string(fixtures.path().join("bank.json")).unwrap();
    for command in bank_commands {
        for spoiled in &spoiled_banks(&bank) {
            refuses(fixtures.path(), command, "bank.json", spoiled);
        }
    }
    let profile_commands: &[&str] = &[
        "simulate chamber --profile @ --duration-s 10 --out @out",
        "simulate vessel --profile @ --duration-s 60 --out @out",
        "integrate --imu %imu.csv --gnss %gnss.csv --profile @ --out @out.csv",
    ];
    let profile = std::fs::read_to_string(fixtures.path().join("profile.toml")).unwrap();
    for command in profile_commands {
        for spoiled in &spoiled_profiles(&profile) {
            refuses(fixtures.path(), command, "profile.toml", spoiled);
        }
    }
}

#[test]
fn bank_export_refuses_a_bank_without_thermal_a_bad_format_and_its_input_as_output() {
    let fixtures = fixtures();
    let bank = fixtures.path().join("bank.json");
    let before = std::fs::read(&bank).unwrap();
    let out = fixtures.path().join("tc.params");
    let export = |format: &str, out: &Path| {
        outcome(&thermonav(&[
            "bank",
            "export",
            arg(&bank),
            "--format",
            format,
            "--out",
            arg(out),
        ]))
    };
    let (status, stdout, stderr) = export("ardupilot-tcal", &out);
    assert_eq!(status, 1, "{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(
        stderr.contains(arg(&bank)) && stderr.contains("no thermal calibration"),
        "{stderr}"
    );
    assert!(stderr.contains("calibrate the unit first"), "{stderr}");
    // It names the command and options that calibrate, not a library function.
    assert!(
        stderr.contains("thermonav characterize") && stderr.contains("--sweep"),
        "{stderr}"
    );
    assert!(!stderr.contains("thermonav::"), "{stderr}");
    assert!(!out.exists());
    let (status, _, stderr) = export("px4", &out);
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("px4-tc") && stderr.contains("ardupilot-tcal"),
        "{stderr}"
    );
    let (status, _, stderr) = export("px4-tc", &bank);
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("would overwrite the input"), "{stderr}");
    assert_eq!(std::fs::read(&bank).unwrap(), before);
    assert!(!out.exists());
}

#[test]
fn gaps_are_reported_with_their_line_not_refused() {
    // A gap is not an error: the readers keep the actual timestamps, the estimators that
    // need even spacing say so. `inspect` names where the gap starts.
    let dir = tempfile::tempdir().unwrap();
    let mut rows = static_imu_rows(2000, 1.0);
    rows.drain(100..150);
    let path = write_file(dir.path(), "gap.csv", &csv_text(IMU_T_HEADER, &rows));
    let (status, stdout, stderr) = outcome(&thermonav(&["inspect", arg(&path), "--json"]));
    assert_eq!(status, 0, "{stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["gap_count"], 1, "{stdout}");
    // Row 99 (line 101) is the last before the gap; 0.51 s between it and the next sample.
    assert_eq!(json["gaps"][0]["start_line"], 101, "{stdout}");
    let length_s = json["gaps"][0]["length_s"].as_f64().unwrap();
    assert!((length_s - 0.51).abs() < 1e-9, "{stdout}");
    let out = dir.path().join("out.csv");
    let args = ["filter", arg(&path), "--cutoff-hz", "5", "--out", arg(&out)];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    assert!(
        stderr.contains("gap.csv") && stderr.contains("1 gaps"),
        "{stderr}"
    );
}

#[test]
fn plot_inputs_and_motion_files_refuse_spoiled_files() {
    let fixtures = fixtures();
    let name_at =
        |name: &str, line: usize, what: &str| vec![format!("{name}:{line}:"), what.into()];
    for kind in ["allan", "outage-errors", "rms-temperature"] {
        let command = format!("plot {kind} @ --out @out.svg");
        for spoiled in [
            Spoiled::new("empty", "", &name_at("in.json", 1, "not JSON")),
            Spoiled::new(
                "cut",
                "{\"channels\": [1,\n2",
                &name_at("in.json", 2, "not JSON"),
            ),
        ] {
            refuses(fixtures.path(), &command, "in.json", &spoiled);
        }
    }
    let innovations = "plot innovations @ --out @out.svg";
    let header = "t_s,kind,unit,innovation_1,innovation_2,innovation_3,sd_1,sd_2,sd_3,nis,gate_scale,accepted,forced";
    let row = "1.000000000,position,m,0.1,0.2,0.3,1,1,1,0.14,1,1,0";
    for spoiled in [
        Spoiled::new(
            "empty",
            "",
            &name_at("in.csv", 1, "expected the innovations header"),
        ),
        Spoiled::new("binary", GARBAGE, &name_at("in.csv", 1, "expected")),
        Spoiled::new(
            "still being written",
            format!("{header}\n{row}\n1.1,posi"),
            &name_at("in.csv", 3, "expected"),
        ),
        Spoiled::new(
            "NaN",
            format!("{header}\n{}\n", row.replace("0.2", "NaN")),
            &name_at("in.csv", 2, "finite"),
        ),
        Spoiled::new(
            "no accepted update",
            format!("{header}\n{}\n", row.replace(",0.14,1,1,0", ",0.14,1,0,0")),
            &["in.csv".into(), "no accepted update".into()],
        ),
    ] {
        refuses(fixtures.path(), innovations, "in.csv", &spoiled);
    }
    let motion = "simulate vessel --motion @ --out @out";
    for spoiled in [
        Spoiled::new("empty", "", &["motion.toml".into(), "missing field".into()]),
        Spoiled::new(
            "cut",
            "start = {lat_deg = 1\n",
            &["motion.toml".into(), "line 1".into()],
        ),
    ] {
        refuses(fixtures.path(), motion, "motion.toml", &spoiled);
    }
}

/// `--imu-rotation` and `--rate-hz` refused with the reason: a mapping that is no rotation
/// (usage), a rate for a file that has times (data, naming the file), a rotation for a
/// converted file without an IMU (usage), a rate that is not positive (usage).
#[test]
fn bad_rotations_and_rates_are_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let imu = write_file(dir.path(), "imu.csv", &good_rows());
    let refused = |args: &[&str], code: i32, needle: &str| {
        let (status, stdout, stderr) = outcome(&thermonav(args));
        assert_eq!(status, code, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    };
    refused(
        &["allan", arg(&imu), "--imu-rotation", "x,y,-z"],
        2,
        "reflection",
    );
    refused(
        &["allan", arg(&imu), "--imu-rotation", "x,x,z"],
        2,
        "appears twice",
    );
    refused(
        &["allan", arg(&imu), "--imu-rotation", "x,y"],
        2,
        "three comma-separated",
    );
    refused(
        &["allan", arg(&imu), "--imu-rotation", "rpy:0,inf,0"],
        2,
        "finite angle",
    );
    refused(
        &["allan", arg(&imu), "--rate-hz", "100"],
        1,
        "imu.csv:1: the file has a t_s column",
    );
    refused(
        &["allan", arg(&imu), "--rate-hz", "0"],
        2,
        "--rate-hz 0: expected a positive number",
    );
    let untimed = write_file(
        dir.path(),
        "untimed.csv",
        "gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n0,0,0,0,0,-9.8\n",
    );
    refused(
        &["allan", arg(&untimed)],
        1,
        "missing column t_s (or, for a file without times, a sample rate: --rate-hz)",
    );
    let nmea = write_file(
        dir.path(),
        "log.nmea",
        "$GPGGA,000000.00,4436.0000,N,06336.0000,W,1,08,1.0,10.0,M,0.0,M,,*7A\n",
    );
    let out = dir.path().join("out.csv");
    refused(
        &[
            "convert",
            arg(&nmea),
            "--format",
            "nmea",
            "--imu-rotation",
            "-y,x,z",
            "--out",
            arg(&out),
        ],
        2,
        "--imu-rotation goes with an IMU input",
    );
    assert!(!out.exists());
    let bank = dir.path().join("bank.json");
    let manifest = write_file(dir.path(), "lot.toml", "");
    refused(
        &[
            "characterize",
            "--manifest",
            arg(&manifest),
            "--imu-rotation",
            "-y,x,z",
            "--out",
            arg(&bank),
        ],
        2,
        "--imu-rotation and --rate-hz are for records given on the command line",
    );
}

/// A subset of the channels: an rpy rotation (which would mix absent axes in) and streaming
/// (which characterises all six) are refused with the reason.
#[test]
fn a_subset_of_channels_refuses_angles_and_streaming() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("t_s,gz_rad_s\n");
    for k in 0..200 {
        text.push_str(&format!("{},{}\n", k as f64 / 100.0, (k as f64).sin()));
    }
    let gyro = write_file(dir.path(), "gz.csv", &text);
    let (status, _, stderr) = outcome(&thermonav(&[
        "allan",
        arg(&gyro),
        "--imu-rotation",
        "rpy:0,0,90",
    ]));
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("gz.csv:1: channel gz: an rpy rotation mixes"),
        "{stderr}"
    );
    let bank = dir.path().join("bank.json");
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        arg(&gyro),
        "--temperature-c",
        "20",
        "--reading",
        "streaming",
        "--out",
        arg(&bank),
    ]));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("1 of the six channels"), "{stderr}");
    assert!(!bank.exists());
}

/// A ROS test bag of the io crate (tests/data/ros, written by tools/oracles/ros_bags.py).
fn ros_bag(name: &str) -> Vec<u8> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../thermonav-io/tests/data/ros");
    std::fs::read(dir.join(name)).unwrap()
}

/// `convert` of `bytes` saved as `name` (and `--format` when given): exit 1 naming the file,
/// nothing written; returns stderr.
fn bag_fails(name: &str, bytes: &[u8], format: Option<&str>) -> String {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join(name);
    std::fs::write(&input, bytes).unwrap();
    let out = dir.path().join("imu.csv");
    let mut args = vec!["convert", arg(&input), "--out", arg(&out)];
    if let Some(format) = format {
        args.extend(["--format", format]);
    }
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 1, "{name}: {stderr}");
    assert!(
        stdout.is_empty() && !stderr.contains("panicked"),
        "{stderr}"
    );
    assert!(stderr.contains(name), "{stderr}");
    assert_eq!(
        files_in(dir.path()),
        vec![name.to_string()],
        "nothing written"
    );
    stderr
}

#[test]
fn ros_bags_truncated_are_refused_naming_the_byte() {
    let mcap = ros_bag("static_zstd.mcap");
    let stderr = bag_fails("cut.mcap", &mcap[..mcap.len() / 2], None);
    assert!(
        stderr.contains("at byte") && stderr.contains("a truncated file"),
        "{stderr}"
    );
    let bag = ros_bag("static.bag");
    let stderr = bag_fails("cut.bag", &bag[..bag.len() / 3], None);
    assert!(
        stderr.contains("at byte") && stderr.contains("bytes are left"),
        "{stderr}"
    );
    let db = ros_bag("static.db3");
    let stderr = bag_fails("cut.db3", &db[..db.len() / 2], None);
    assert!(
        stderr.contains("at byte 28") && stderr.contains("a truncated file"),
        "{stderr}"
    );
}

#[test]
fn ros_bags_of_the_wrong_magic_are_refused() {
    let mut mcap = ros_bag("static_none.mcap");
    mcap[1] = b'X';
    let stderr = bag_fails("x.mcap", &mcap, Some("ros2-mcap"));
    assert!(
        stderr.contains("at byte 0: expected the MCAP magic bytes"),
        "{stderr}"
    );
    let stderr = bag_fails("x.bag", b"#ROSBAG V1.2\n", Some("ros1-bag"));
    assert!(stderr.contains("#ROSBAG V2.0"), "{stderr}");
    let stderr = bag_fails("x.db3", b"SQLite format 2\0", Some("ros2-db3"));
    assert!(stderr.contains("SQLite header"), "{stderr}");
}

#[test]
fn ros_bags_with_a_huge_length_field_are_refused_without_allocating_it() {
    let mut mcap = ros_bag("static_none.mcap");
    mcap[9..17].copy_from_slice(&u64::MAX.to_le_bytes());
    let stderr = bag_fails("huge.mcap", &mcap, None);
    assert!(
        stderr.contains("expected a record's content of 18446744073709551615 bytes"),
        "{stderr}"
    );
    let mut bag = ros_bag("static.bag");
    bag[13..17].copy_from_slice(&u32::MAX.to_le_bytes());
    let stderr = bag_fails("huge.bag", &bag, None);
    assert!(
        stderr.contains("at byte 17: expected a record header of 4294967295 bytes"),
        "{stderr}"
    );
}

#[test]
fn ros_bags_of_an_unknown_chunk_compression_name_it() {
    let mcap = ros_bag("static_lz4.mcap");
    let at = mcap.windows(3).position(|w| w == b"lz4").unwrap();
    let mut renamed = mcap.clone();
    renamed[at..at + 3].copy_from_slice(b"lzo");
    let stderr = bag_fails("lzo.mcap", &renamed, None);
    assert!(
        stderr.contains("chunk compression \"lzo\" is not supported"),
        "{stderr}"
    );
}

/// A DataFlash test log of the io crate (tests/data/dataflash, written by
/// tools/oracles/dataflash.py).
fn dataflash_log(name: &str) -> Vec<u8> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../thermonav-io/tests/data/dataflash");
    std::fs::read(dir.join(name)).unwrap()
}

/// Offset of the FMT record that defines the IMU message.
fn imu_fmt(log: &[u8]) -> usize {
    (0..log.len() - 89)
        .find(|&i| log[i..i + 3] == [0xA3, 0x95, 128] && log[i + 5..].starts_with(b"IMU\0"))
        .unwrap()
}

#[test]
fn dataflash_logs_truncated_or_out_of_order_are_refused_naming_the_byte() {
    let log = dataflash_log("boot.bin");
    let at = imu_fmt(&log);
    let stderr = bag_fails("cut.bin", &log[..at + 30], Some("dataflash"));
    assert!(
        stderr.contains(&format!(
            "at byte {at}: the file ends inside an FMT record (30 of its 89 bytes"
        )),
        "{stderr}"
    );
    // The IMU's FMT record turned into garbage: its records come before any definition.
    let mut orphan = log.clone();
    orphan[at..at + 89].copy_from_slice(&log[..89]);
    orphan[at + 3] = 129;
    orphan[at + 5..at + 9].copy_from_slice(b"XXX\0");
    let stderr = bag_fails("orphan.bin", &orphan, None);
    assert!(
        stderr.contains("a record of message type 130, which no earlier FMT record defines (expected its FMT first)"),
        "{stderr}"
    );
    let mut garbage = log.clone();
    garbage[at + 89] = 0x00;
    let stderr = bag_fails("garbage.bin", &garbage, None);
    assert!(
        stderr.contains(&format!(
            "at byte {}: expected a record header 0xA3 0x95, found 0x00",
            at + 89
        )),
        "{stderr}"
    );
}

#[test]
fn dataflash_logs_with_an_impossible_or_huge_length_are_refused() {
    let log = dataflash_log("boot.bin");
    let at = imu_fmt(&log);
    // The largest length a record can claim (one byte: 255) for a 54-byte format.
    let mut huge = log.clone();
    huge[at + 4] = 255;
    let stderr = bag_fails("huge.bin", &huge, None);
    assert!(
        stderr.contains("FMT of IMU (type 130): expected a length of 54 bytes (3 header bytes and format \"QBffffffIIfBBHH\"), found 255"),
        "{stderr}"
    );
    // A length shorter than its header.
    let mut short = log.clone();
    short[at + 4] = 2;
    let stderr = bag_fails("short.bin", &short, None);
    assert!(stderr.contains("expected a length of 54 bytes"), "{stderr}");
    // FMT's own definition with a wrong length.
    let mut own = log.clone();
    own[4] = 200;
    let stderr = bag_fails("own.bin", &own, Some("dataflash"));
    assert!(
        stderr.contains("at byte 0: FMT of FMT (type 128): expected a length of 89 bytes"),
        "{stderr}"
    );
}
