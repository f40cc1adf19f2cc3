//! Issue 38: the steps where a new user, on real recordings, stopped, guessed or was misled.
//! Each test repeats the user's step; expected values are worked out here from the files, not
//! taken from our own code.

use crate::{IMU_HEADER, Normal, arg, outcome, thermonav, vessel, write_file};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Seconds per hour.
const HOUR_S: f64 = 3600.0;
/// Standard gravity, m/s² per g.
const G: f64 = 9.80665;

/// A static record at 100 Hz: white noise on every channel, plus a Gauss-Markov bias of Tc
/// 5 s and `gm` times the white sd when `gm` > 0, az at −g, columns `columns` of the
/// canonical header (all when `None`).
fn static_imu(rows: usize, gm: f64, columns: Option<&[usize]>) -> String {
    let names: Vec<&str> = IMU_HEADER.split(',').collect();
    let kept: Vec<usize> = columns.map_or((0..6).collect(), <[usize]>::to_vec);
    let header: Vec<&str> = std::iter::once(names[0])
        .chain(kept.iter().map(|&c| names[c + 1]))
        .collect();
    let mut normal = Normal(0x9e37_79b9_7f4a_7c15);
    let mut text = format!("{}\n", header.join(","));
    let decay: f64 = (-0.01_f64 / 5.0).exp();
    let mut bias = [0.0; 6];
    for k in 0..rows {
        let _ = write!(text, "{:.9}", k as f64 / 100.0);
        for &c in &kept {
            let sd = if c < 3 { 2e-3 } else { 2e-2 };
            let mean = if c == 5 { -G } else { 0.0 };
            let drive = gm * sd * (1.0 - decay * decay).sqrt();
            bias[c] = decay * bias[c] + drive * normal.sample();
            let _ = write!(text, ",{}", mean + bias[c] + sd * normal.sample());
        }
        text.push('\n');
    }
    text
}

/// Characterizes `imu` at 20 °C into `dir/name`, returning the bank's path and stderr.
fn characterize(dir: &Path, imu: &Path, name: &str, extra: &[&str]) -> (PathBuf, String) {
    let bank = dir.join(name);
    let args = [
        &["characterize", arg(imu), "--temperature-c", "20", "--out"],
        &[arg(&bank)][..],
        extra,
    ]
    .concat();
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    (bank, stderr)
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

/// The number printed just before `unit` in `line` (a leading "<=" dropped).
fn value_before(line: &str, unit: &str) -> f64 {
    let tokens: Vec<&str> = line.split_whitespace().collect();
    let at = tokens
        .iter()
        .position(|t| *t == unit)
        .unwrap_or_else(|| panic!("no {unit} in {line}"));
    tokens[at - 1].trim_start_matches("<=").parse().unwrap()
}

fn close(shown: f64, expected: f64, what: &str) {
    assert!(
        (shown / expected - 1.0).abs() < 1e-3,
        "{what}: shown {shown}, expected {expected}"
    );
}

/// Row 5: `bank show` gives each channel's N, B and K in the edge units, with B's 0.664
/// convention in the table's note, and `--at-temperature-c` gives sigma with its unit.
#[test]
fn bank_show_prints_white_noise_bias_instability_and_random_walk_with_units() {
    let dir = tempfile::tempdir().unwrap();
    let imu = write_file(dir.path(), "imu.csv", &static_imu(20_000, 0.2, None));
    let (bank, _) = characterize(dir.path(), &imu, "bank.json", &[]);
    let doc = json(&std::fs::read_to_string(&bank).unwrap());
    let (status, stdout, stderr) = outcome(&thermonav(&["bank", "show", arg(&bank)]));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("/ 0.664"), "{stdout}");
    let rows: Vec<&str> = stdout
        .lines()
        .filter(|l| l.contains("deg/sqrt(h)") || l.contains("m/s/sqrt(h)"))
        .collect();
    assert_eq!(rows.len(), 6, "{stdout}");
    let deg = 180.0 / PI;
    for (channel, gyro) in [
        ("gx", true),
        ("gy", true),
        ("gz", true),
        ("ax", false),
        ("ay", false),
        ("az", false),
    ] {
        let row = rows
            .iter()
            .find(|l| l.split_whitespace().nth(1) == Some(channel))
            .unwrap();
        let allan = &doc["entries"][0]["channels"][channel]["allan"];
        let n = allan["white_noise_density"]
            .as_f64()
            .expect("white noise identified");
        let b = allan["bias_instability"]
            .as_f64()
            .or(allan["bias_instability_at_most"].as_f64())
            .unwrap();
        if gyro {
            close(
                value_before(row, "deg/sqrt(h)"),
                n * deg * HOUR_S.sqrt(),
                "N",
            );
            close(value_before(row, "deg/h"), b * deg * HOUR_S, "B");
        } else {
            close(value_before(row, "m/s/sqrt(h)"), n * HOUR_S.sqrt(), "N");
            close(value_before(row, "mg"), b / G * 1000.0, "B");
        }
        match allan["rate_random_walk"].as_f64() {
            Some(k) if gyro => close(
                value_before(row, "deg/h/sqrt(h)"),
                k * deg * HOUR_S * HOUR_S.sqrt(),
                "K",
            ),
            Some(k) => close(value_before(row, "m/s^2/sqrt(h)"), k * HOUR_S.sqrt(), "K"),
            None => assert!(row.contains("n/a"), "{row}"),
        }
    }
    // At an operating temperature: sigma in deg/h or mg as text, SI under a suffixed key.
    let show = ["bank", "show", arg(&bank), "--at-temperature-c", "25"];
    let (status, stdout, stderr) = outcome(&thermonav(&show));
    assert_eq!(status, 0, "{stderr}");
    let selected = json(&outcome(&thermonav(&[&show[..], &["--json"]].concat())).1);
    let gx = &selected["channels"]["gx"];
    let sigma = gx["sigma_rad_s"].as_f64().unwrap();
    assert_eq!(gx["sigma"].as_f64(), Some(sigma));
    close(
        gx["sigma_deg_h"].as_f64().unwrap(),
        sigma * deg * HOUR_S,
        "sigma_deg_h",
    );
    let az = &selected["channels"]["az"];
    close(
        az["sigma_mg"].as_f64().unwrap(),
        az["sigma_m_s2"].as_f64().unwrap() / G * 1000.0,
        "sigma_mg",
    );
    let row = stdout.lines().find(|l| l.starts_with("gx ")).unwrap();
    close(value_before(row, "deg/h"), sigma * deg * HOUR_S, "gx sigma");
    let row = stdout.lines().find(|l| l.starts_with("az ")).unwrap();
    close(
        value_before(row, "mg"),
        az["sigma_m_s2"].as_f64().unwrap() / G * 1000.0,
        "az sigma",
    );
}

/// Row 8: an output in a folder that does not exist is refused before any work (the input
/// here does not exist either, and the refusal is about the output), naming the folder, and
/// the system's reason is never said twice.
#[test]
fn an_output_in_a_missing_folder_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing").join("dir");
    let absent_input = dir.path().join("absent.csv");
    let bank = crate::bank_export::plain_bank(dir.path());
    let out = |name: &str| missing.join(name).to_str().unwrap().to_string();
    let runs: Vec<Vec<String>> = vec![
        vec![
            "characterize".into(),
            arg(&absent_input).into(),
            "--out".into(),
            out("bank.json"),
        ],
        vec![
            "filter".into(),
            arg(&absent_input).into(),
            "--cutoff-hz".into(),
            "1".into(),
            "--out".into(),
            out("f.csv"),
        ],
        vec![
            "plot".into(),
            "allan".into(),
            arg(&bank).into(),
            "--out".into(),
            out("a.svg"),
        ],
        vec![
            "simulate".into(),
            "profile".into(),
            "--out".into(),
            out("p.toml"),
        ],
        vec![
            "bank".into(),
            "export".into(),
            arg(&bank).into(),
            "--format".into(),
            "kalibr".into(),
            "--out".into(),
            out("k.yaml"),
        ],
    ];
    for run in &runs {
        let args: Vec<&str> = run.iter().map(String::as_str).collect();
        let (status, stdout, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 2, "{args:?}: {stdout}{stderr}");
        assert!(
            stderr.contains(missing.to_str().unwrap()) && stderr.contains("does not exist"),
            "{args:?}: {stderr}"
        );
        assert!(
            !stderr.contains("absent.csv") && !stderr.contains("os error"),
            "{args:?}: {stderr}"
        );
    }
}

/// Row 7: a record without its az column makes a five-channel bank, and `characterize` says
/// so (stderr and JSON), naming az and what will refuse the bank; the export then does.
#[test]
fn a_bank_without_a_channel_is_announced_when_written() {
    let dir = tempfile::tempdir().unwrap();
    let text = static_imu(20_000, 0.2, Some(&[0, 1, 2, 3, 4]));
    assert!(!text.lines().next().unwrap().contains("az"));
    let imu = write_file(dir.path(), "imu.csv", &text);
    let (bank, stderr) = characterize(dir.path(), &imu, "bank.json", &[]);
    let note = stderr
        .lines()
        .find(|l| l.contains("az has no noise model"))
        .unwrap_or_else(|| panic!("{stderr}"));
    assert!(
        note.contains("5 channels") && note.contains("refuse") && note.contains("bank export"),
        "{note}"
    );
    let args = [
        "characterize",
        arg(&imu),
        "--temperature-c",
        "20",
        "--json",
        "--out",
    ];
    let (status, stdout, stderr) = outcome(&thermonav(
        &[&args[..], &[arg(&dir.path().join("b.json"))]].concat(),
    ));
    assert_eq!(status, 0, "{stderr}");
    assert!(stderr.contains("az has no noise model"), "{stderr}");
    let summary = json(&stdout);
    assert_eq!(summary["missing_channels"], serde_json::json!(["az"]));
    assert!(
        summary["missing_channels_note"]
            .as_str()
            .unwrap()
            .contains("refuse")
    );
    let export = ["bank", "export", arg(&bank), "--format", "kalibr", "--out"];
    let (status, _, stderr) = outcome(&thermonav(
        &[&export[..], &[arg(&dir.path().join("k.yaml"))]].concat(),
    ));
    assert_eq!(status, 1, "{stderr}");
    assert!(stderr.contains("az"), "{stderr}");
    // With all six there is no note.
    let full = write_file(dir.path(), "full.csv", &static_imu(20_000, 0.2, None));
    let (_, stderr) = characterize(dir.path(), &full, "full.json", &[]);
    assert!(!stderr.contains("no noise model"), "{stderr}");
}

/// The stand-in of an Allan curve worked out here: σ = the minimum / 0.664 and Tc its τ when
/// the minimum is inside the curve, else the bound at the longest τ and that τ.
fn stand_in_of(allan: &serde_json::Value) -> (f64, f64) {
    let column = |key: &str| -> Vec<f64> {
        allan[key]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    let (tau, adev) = (column("tau_s"), column("adev"));
    let mut k = 0;
    for i in 1..adev.len() {
        if adev[i] < adev[k] {
            k = i;
        }
    }
    if k == 0 || k + 1 == adev.len() {
        k = adev.len() - 1;
    }
    (adev[k] / 0.664, tau[k])
}

/// The numbers of `key`'s line in a YAML or Python export: `key: [a, b, c]` or
/// `'key': np.array([a, b, c])`.
fn numbers_of(text: &str, key: &str) -> Vec<f64> {
    let line = text
        .lines()
        .find(|l| {
            !l.trim_start().starts_with('#')
                && (l.trim_start().starts_with(&format!("{key}:"))
                    || l.contains(&format!("'{key}'")))
        })
        .unwrap_or_else(|| panic!("no {key} in {text}"));
    let body = line.split('#').next().unwrap();
    let body = body.split_once(':').unwrap().1;
    body.split(|c: char| !(c.is_ascii_digit() || "+-.e".contains(c)))
        .filter(|t| !t.is_empty() && t.chars().any(|c| c.is_ascii_digit()))
        .map(|t| t.parse().unwrap())
        .collect()
}

/// Row 11: a bank whose Gauss-Markov part is not significant (white noise alone) exports to
/// KF-GINS, OB_GINS and gnss-ins-sim with the documented stand-in, said so in the file.
#[test]
fn exports_needing_a_gauss_markov_bias_write_the_allan_stand_in() {
    let dir = tempfile::tempdir().unwrap();
    let imu = write_file(dir.path(), "imu.csv", &static_imu(20_000, 0.0, None));
    let (bank, _) = characterize(dir.path(), &imu, "bank.json", &[]);
    let doc = json(&std::fs::read_to_string(&bank).unwrap());
    let channels = &doc["entries"][0]["channels"];
    assert_eq!(
        channels["gx"]["gauss_markov"]["irregular_ml"]["status"], "no_equivalent",
        "{}",
        channels["gx"]["gauss_markov"]
    );
    let names = ["gx", "gy", "gz", "ax", "ay", "az"];
    let stand_ins: Vec<(f64, f64)> = names
        .iter()
        .map(|c| stand_in_of(&channels[*c]["allan"]))
        .collect();
    let export = |format: &str, extra: &[&str]| -> String {
        let out = dir.path().join(format!("{format}.out"));
        let args = [
            &[
                "bank",
                "export",
                arg(&bank),
                "--format",
                format,
                "--out",
                arg(&out),
            ][..],
            extra,
        ]
        .concat();
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, 0, "{format}: {stderr}");
        std::fs::read_to_string(out).unwrap()
    };
    // gnss-ins-sim: per axis, σ in deg/h and m/s², Tc in s.
    let sim = export("gnss-ins-sim", &[]);
    assert!(sim.contains("stand-in") && sim.contains("0.664"), "{sim}");
    let deg_h = 180.0 / PI * HOUR_S;
    for (k, (sigma, tc)) in numbers_of(&sim, "gyro_b_stability")
        .iter()
        .zip(numbers_of(&sim, "gyro_b_corr"))
        .enumerate()
    {
        close(*sigma, stand_ins[k].0 * deg_h, "gyro_b_stability");
        close(tc, stand_ins[k].1, "gyro_b_corr");
    }
    for (k, (sigma, tc)) in numbers_of(&sim, "accel_b_stability")
        .iter()
        .zip(numbers_of(&sim, "accel_b_corr"))
        .enumerate()
    {
        close(*sigma, stand_ins[3 + k].0, "accel_b_stability");
        close(tc, stand_ins[3 + k].1, "accel_b_corr");
    }
    // KF-GINS: σ per axis in deg/h and mGal, one Tc in hours (the geometric mean of the six).
    let kf = export("kf-gins", &["--scale-factor-std-ppm", "100"]);
    assert!(kf.contains("stand-in"), "{kf}");
    for (k, v) in numbers_of(&kf, "gbstd").iter().enumerate() {
        close(*v, stand_ins[k].0 * deg_h, "gbstd");
    }
    for (k, v) in numbers_of(&kf, "abstd").iter().enumerate() {
        close(*v, stand_ins[3 + k].0 / 1e-5, "abstd");
    }
    let mean_tc = (stand_ins.iter().map(|s| s.1.ln()).sum::<f64>() / 6.0).exp();
    close(numbers_of(&kf, "corrtime")[0], mean_tc / HOUR_S, "corrtime");
    // OB_GINS: the largest axis.
    let ob = export("ob-gins", &[]);
    assert!(ob.contains("stand-in"), "{ob}");
    let largest = stand_ins[..3].iter().map(|s| s.0).fold(0.0, f64::max);
    close(numbers_of(&ob, "gbstd")[0], largest * deg_h, "ob gbstd");
}

/// `evaluate` of the survey in `v` with the built-in profile, the EKF and two outages.
fn evaluate(v: &Path, out: &Path, extra: &[&str]) -> (i32, String, String) {
    let files = ["imu.csv", "gnss.csv", "reference.csv"].map(|f| v.join(f));
    let args = [
        "evaluate",
        "--imu",
        arg(&files[0]),
        "--gnss",
        arg(&files[1]),
        "--reference",
        arg(&files[2]),
        "--profile",
        "builtin:temperature-sensitive",
        "--filter",
        "ekf",
        "--outages",
        "spread:2,30",
        "--out",
        arg(out),
    ];
    outcome(&thermonav(&[&args[..], extra].concat()))
}

/// Row 12: `report DIR` on the folder `evaluate` wrote makes the tournament's report, without
/// the bank's sections; a folder with neither names both layouts.
#[test]
fn report_of_a_folder_evaluate_wrote_is_the_tournament() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let out = dir.path().join("ev");
    let (status, _, stderr) = evaluate(&v, &out, &["--json"]);
    assert_eq!(status, 0, "{stderr}");
    let (status, stdout, stderr) = outcome(&thermonav(&["report", arg(&out)]));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("report.html"), "{stdout}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let evaluation = json(&std::fs::read_to_string(out.join("evaluation.json")).unwrap());
    for model in evaluation["models"].as_array().unwrap() {
        let label = model["label"].as_str().unwrap().replace('&', "&amp;");
        assert!(html.contains(&label), "{label} not in the report");
    }
    assert!(html.contains("tournament alone") && !html.contains("Allan deviation at"));
    // Row 19: this report too opens with its answer, the ranking's verdict.
    let summary = html.find("<section id=\"summary\"").expect("a summary");
    assert!(summary < html.find("<figure").unwrap());
    assert!(html[summary..].contains(">The tournament</a>") && html.contains("class=\"verdict"));
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let (status, _, stderr) = outcome(&thermonav(&["report", arg(&empty)]));
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("bank.json: missing") && stderr.contains("evaluate --out DIR"),
        "{stderr}"
    );
}

/// Row 15: files given to the wrong options are named as what they look like, with the
/// option they were probably meant for, by integrate and evaluate.
#[test]
fn swapped_files_are_recognised_and_the_option_suggested() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let [imu, gnss, reference] = ["imu.csv", "gnss.csv", "reference.csv"].map(|f| v.join(f));
    let profile = ["--profile", "builtin:temperature-sensitive"];
    let solution = dir.path().join("s.csv");
    let integrate = |imu: &Path, gnss: &Path| {
        let args = [
            "integrate",
            "--imu",
            arg(imu),
            "--gnss",
            arg(gnss),
            "--out",
            arg(&solution),
        ];
        outcome(&thermonav(&[&args[..], &profile].concat()))
    };
    let evaluate = |imu: &Path, gnss: &Path, reference: &Path| {
        let out = dir.path().join("e");
        let args = [
            "evaluate",
            "--imu",
            arg(imu),
            "--gnss",
            arg(gnss),
            "--reference",
            arg(reference),
            "--out",
            arg(&out),
        ];
        outcome(&thermonav(&[&args[..], &profile].concat()))
    };
    let cases = [
        (
            integrate(&gnss, &imu),
            "gnss.csv:1: unknown column \"lat_deg\"",
            "looks like a GNSS CSV: was it meant for --gnss?",
        ),
        (
            integrate(&imu, &reference),
            "reference.csv:1: unknown column \"roll_deg\"",
            "looks like a trajectory CSV (a reference or a solution): was it meant for --reference?",
        ),
        (
            evaluate(&gnss, &imu, &reference),
            "gnss.csv:1: unknown column \"lat_deg\"",
            "was it meant for --gnss?",
        ),
        (
            evaluate(&reference, &gnss, &imu),
            "reference.csv:1",
            "was it meant for --reference?",
        ),
        (
            evaluate(&imu, &gnss, &imu),
            "imu.csv:1: unknown column \"gx_rad_s\"",
            "looks like an IMU CSV: was it meant for --imu?",
        ),
    ];
    for ((status, _, stderr), place, hint) in cases {
        assert_eq!(status, 1, "{stderr}");
        assert!(stderr.contains(place) && stderr.contains(hint), "{stderr}");
    }
    assert!(!solution.exists());
}

/// A walk: still for 12 s, then 1.4 m/s to the north-east for 60 s, simulated in `dir/NAME`.
fn still_then_walk(dir: &Path, name: &str) -> PathBuf {
    let motion = write_file(
        dir,
        "walk.toml",
        "initial_speed_m_s = 0.0\ninitial_heading_deg = 30.0\n[start]\nlat_deg = 45.0\nlon_deg = 7.0\nh_m = 300.0\n[[segment]]\nduration_s = 12.0\n[[segment]]\nduration_s = 1.0\nacceleration_m_s2 = 1.4\n[[segment]]\nduration_s = 60.0\n",
    );
    let out = dir.join(name);
    let args = [
        "simulate",
        "vessel",
        "--motion",
        arg(&motion),
        "--profile",
        "builtin:temperature-sensitive",
        "--out",
        arg(&out),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    out
}

/// The GNSS CSV at `from` with only its first `columns` columns, written to `to`; its rows.
fn gnss_columns(from: &Path, to: &Path, columns: usize) -> usize {
    let text = std::fs::read_to_string(from).unwrap();
    let cut: Vec<String> = text
        .lines()
        .map(|l| l.split(',').take(columns).collect::<Vec<_>>().join(","))
        .collect();
    std::fs::write(to, cut.join("\n") + "\n").unwrap();
    cut.len() - 1
}

/// `integrate --json` of `imu` and `gnss` with the built-in profile: the summary and the text.
fn integrate_both(dir: &Path, imu: &Path, gnss: &Path) -> (serde_json::Value, String) {
    let out = dir.join("sol.csv");
    let args = [
        "integrate",
        "--imu",
        arg(imu),
        "--gnss",
        arg(gnss),
        "--profile",
        "builtin:temperature-sensitive",
        "--out",
        arg(&out),
    ];
    let (status, text, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    let (_, doc, _) = outcome(&thermonav(&[&args[..], &["--json"]].concat()));
    (json(&doc), text)
}

/// Rows 9 and 10: a walk that starts still, with and without dual-antenna headings and sd
/// columns: the static alignment's decision with its reason, and the GNSS sds used, are
/// printed and in --json.
#[test]
fn the_still_start_decision_and_the_gnss_sd_used_are_reported() {
    let dir = tempfile::tempdir().unwrap();
    let walk = still_then_walk(dir.path(), "walk");
    let imu = walk.join("imu.csv");
    // With headings the alignment takes the first fix: the still span is cut there.
    let (doc, text) = integrate_both(dir.path(), &imu, &walk.join("gnss.csv"));
    let decision = &doc["static_alignment"];
    assert_eq!(decision["decision"], "too_short", "{decision}");
    assert_eq!(decision["ended_by"], "alignment_fix", "{decision}");
    let row = text
        .lines()
        .find(|l| l.starts_with("static alignment"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        row.contains("not used")
            && row.contains("at least 5 s needed")
            && row.contains("came first"),
        "{row}"
    );
    assert_eq!(doc["gnss_sd"]["source"], "file");
    // Positions alone (course over ground): the still span is not cut by the alignment; the
    // decision is used, or not with the reason that ended the span (here the IMU's 1 s
    // windows of the warming sensor depart from each other: the text says so).
    let positions = dir.path().join("positions.csv");
    let fixes = gnss_columns(&walk.join("gnss.csv"), &positions, 7);
    let (doc, text) = integrate_both(dir.path(), &imu, &positions);
    let decision = &doc["static_alignment"];
    let row = text
        .lines()
        .find(|l| l.starts_with("static alignment"))
        .unwrap_or_else(|| panic!("{text}"));
    let still_s = decision["still_s"].as_f64().unwrap();
    assert!(still_s <= 12.0, "{decision}");
    match decision["decision"].as_str().unwrap() {
        "used" => assert!(
            still_s >= 5.0 && row.contains("used: the platform stood still"),
            "{row}"
        ),
        "too_short" => {
            let reason = match decision["ended_by"].as_str().unwrap() {
                "imu_changed" => "departed from the earlier ones",
                "fixes_moved" => "the fixes left",
                other => panic!("{other}: {decision}"),
            };
            assert!(
                still_s < 5.0 && row.contains("not used") && row.contains(reason),
                "{row}"
            );
            let fixes_still_s = decision["fixes_still_s"].as_f64().unwrap();
            assert!((10.0..=14.0).contains(&fixes_still_s), "{decision}");
        }
        other => panic!("{other}: {decision}"),
    }
    // Row 9: no sd columns: the default is used on every fix, and said so with its values.
    let bare = dir.path().join("bare.csv");
    assert_eq!(gnss_columns(&walk.join("gnss.csv"), &bare, 4), fixes);
    let (doc, text) = integrate_both(dir.path(), &imu, &bare);
    let sd = &doc["gnss_sd"];
    assert_eq!(sd["source"], "default", "{sd}");
    assert_eq!(sd["fixes"].as_u64(), Some(fixes as u64));
    assert_eq!(sd["fixes_with_default_sd"].as_u64(), Some(fixes as u64));
    let default = thermonav::nav::engine::EngineSettings::default().default_position_sd_m;
    assert_eq!(sd["default_position_sd_ned_m"], serde_json::json!(default));
    let row = text
        .lines()
        .find(|l| l.starts_with("GNSS position sd"))
        .unwrap_or_else(|| panic!("{text}"));
    let [n, e, d] = default;
    assert!(
        row.contains(&format!(
            "default {n} m north, {e} m east, {d} m down on {fixes} of {fixes} fixes"
        )),
        "{row}"
    );
}

/// Row 9, evaluate: a GNSS CSV without sd columns is run with the default sd, said on stderr
/// with its values and the number of fixes (counted here); with sd columns nothing is said.
#[test]
fn evaluate_says_when_the_default_gnss_sd_is_used() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let bare = dir.path().join("bare");
    std::fs::create_dir(&bare).unwrap();
    let fixes = gnss_columns(&v.join("gnss.csv"), &bare.join("gnss.csv"), 4);
    for f in ["imu.csv", "reference.csv"] {
        std::fs::copy(v.join(f), bare.join(f)).unwrap();
    }
    let (status, _, stderr) = evaluate(&bare, &dir.path().join("e1"), &["--json"]);
    assert_eq!(status, 0, "{stderr}");
    let [n, e, d] = thermonav::nav::engine::EngineSettings::default().default_position_sd_m;
    let said = format!(
        "GNSS position sd: default {n} m north, {e} m east, {d} m down on {fixes} of {fixes} fixes"
    );
    assert!(stderr.contains(&said), "{stderr}");
    let (status, _, stderr) = evaluate(&v, &dir.path().join("e2"), &[]);
    assert_eq!(status, 0, "{stderr}");
    assert!(!stderr.contains("GNSS position sd"), "{stderr}");
}

/// Row 4: `plot trajectory --outages rel:...` of an integrate solution counts from the IMU's
/// first increment with `--imu`, as integrate did; without it, it says what it counts from.
#[test]
fn plot_trajectory_counts_rel_outages_as_integrate_with_imu() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let solution = dir.path().join("sol.csv");
    let outages = "rel:100+30";
    let (imu, gnss) = (v.join("imu.csv"), v.join("gnss.csv"));
    let args = [
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--profile",
        "builtin:temperature-sensitive",
        "--outages",
        outages,
        "--out",
        arg(&solution),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    let first_solution_s: f64 = std::fs::read_to_string(&solution)
        .unwrap()
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let plot = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let args = [
            "plot",
            "trajectory",
            arg(&solution),
            "--outages",
            outages,
            "--out",
            arg(&out),
        ];
        let (status, _, stderr) = outcome(&thermonav(&[&args[..], extra].concat()));
        assert_eq!(status, 0, "{stderr}");
        (std::fs::read_to_string(out).unwrap(), stderr)
    };
    let (alone, stderr) = plot("alone.svg", &[]);
    assert!(
        stderr.contains("rel: counts here from the solution's first point")
            && stderr.contains("--imu"),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!("{first_solution_s:.3}")),
        "{stderr}"
    );
    let (with_imu, stderr) = plot("imu.svg", &["--imu", arg(&imu)]);
    assert!(!stderr.contains("note"), "{stderr}");
    // The solution starts after the IMU (alignment), so the windows move with the origin.
    assert!(first_solution_s > 0.5, "{first_solution_s}");
    assert_ne!(alone, with_imu);
}

/// `path`'s CSV with `shift_s` added to every t_s, written to `to`.
fn shifted(path: &Path, to: &Path, shift_s: f64) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let (t, rest) = line.split_once(',').unwrap();
        let _ = writeln!(out, "{:.9},{rest}", t.parse::<f64>().unwrap() + shift_s);
    }
    std::fs::write(to, out).unwrap();
}

/// Row 4, integrate: windows before data on Unix time suggest rel:, which then works.
#[test]
fn outages_before_clock_time_data_suggest_rel() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let (imu, gnss) = (dir.path().join("imu.csv"), dir.path().join("gnss.csv"));
    shifted(&v.join("imu.csv"), &imu, 1.7e9);
    shifted(&v.join("gnss.csv"), &gnss, 1.7e9);
    let out = dir.path().join("sol.csv");
    let run = |outages: &str| {
        let args = [
            "integrate",
            "--imu",
            arg(&imu),
            "--gnss",
            arg(&gnss),
            "--profile",
            "builtin:temperature-sensitive",
            "--outages",
            outages,
            "--out",
            arg(&out),
        ];
        outcome(&thermonav(&args))
    };
    let (status, _, stderr) = run("every:40,10,30,3");
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("outage 40-50 s is not inside the data")
            && stderr.contains("put rel: before the specification"),
        "{stderr}"
    );
    let (status, _, stderr) = run("rel:every:40,10,30,3");
    assert_eq!(status, 0, "{stderr}");
}

// Issue 38 row 18: `integrate` without a noise model listed `--bank` alone as required, though
// `--profile` serves as well; the usage error now names both as the one choice, and giving
// both is refused.
#[test]
fn integrate_without_a_noise_model_asks_for_a_bank_or_a_profile() {
    let (status, _, stderr) = outcome(&thermonav(&["integrate"]));
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("<--bank <BANK>|--profile <PROFILE>>"),
        "{stderr}"
    );
    let both = [
        "integrate",
        "--imu",
        "a.csv",
        "--gnss",
        "b.csv",
        "--out",
        "c.csv",
        "--bank",
        "x.json",
        "--profile",
        "y.toml",
    ];
    let (status, _, stderr) = outcome(&thermonav(&both));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("cannot be used with"), "{stderr}");
}

// Issue 38 row 18: `inspect --help` called its file "the IMU CSV", though inspect reads GNSS
// and reference CSVs too (chosen by the header), and says so in its own description.
#[test]
fn inspect_help_names_every_csv_it_reads() {
    let (status, stdout, stderr) = outcome(&thermonav(&["inspect", "--help"]));
    assert_eq!(status, 0, "{stderr}");
    let file = (stdout.lines())
        .find(|l| l.trim_start().starts_with("<FILE>"))
        .unwrap_or_else(|| panic!("{stdout}"));
    for kind in ["IMU", "GNSS", "reference"] {
        assert!(file.contains(kind), "{file}");
    }
}
