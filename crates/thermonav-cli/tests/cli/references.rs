//! Issue 38 row 3: `--reference` takes the reference a user has (our trajectory CSV, a GNSS
//! CSV, an RTKLIB `.pos`, a KF-GINS `.nav`), its kind told by its content. A position-only one
//! scores position and says that heading is not scored, with no heading number anywhere; one
//! on another time scale than the IMU is refused with both time ranges. The fixtures are a
//! simulated survey written in each form here; the README's RTK workflow is run as written.

use crate::{arg, outcome, thermonav, vessel};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// GPST seconds since 1970 of GPS week 0 (1980-01-06).
const GPS_EPOCH_S: i64 = 315_964_800;
/// Seconds in a GPS week.
const WEEK_S: i64 = 604_800;
/// The GPS week and second of week the shifted survey starts at: 2026-01-06 05:33:20 GPST.
const WEEK: i64 = 2400;
const SECOND_OF_WEEK: i64 = 200_000;

/// The shift that puts the survey's t_s (from 0) on the GPST scale, s.
fn gpst_shift_s() -> i64 {
    GPS_EPOCH_S + WEEK * WEEK_S + SECOND_OF_WEEK
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

/// `evaluate` of `imu` and `gnss` against `reference` with the built-in profile, the EKF and
/// two 30 s outages, into `out`, as JSON.
fn evaluate(imu: &Path, gnss: &Path, reference: &Path, out: &Path) -> (i32, String, String) {
    let args = [
        "evaluate",
        "--imu",
        arg(imu),
        "--gnss",
        arg(gnss),
        "--reference",
        arg(reference),
        "--profile",
        "builtin:temperature-sensitive",
        "--filter",
        "ekf",
        "--outages",
        "spread:2,30",
        "--out",
        arg(out),
        "--json",
    ];
    outcome(&thermonav(&args))
}

/// A number of a model's JSON.
fn number(model: &serde_json::Value, key: &str) -> f64 {
    model[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} of {model}"))
}

/// The evaluation against a position-only reference: position scored, heading absent (no key,
/// no number, no error column), the reason said in the JSON, the table and the report.
fn assert_position_only(evaluation: &serde_json::Value, out: &Path) {
    assert_eq!(evaluation["reference"]["content"], "position_only");
    let said = evaluation["reference"]["not_scored"].as_str().unwrap();
    assert!(said.contains("heading"), "{said}");
    let text = std::fs::read_to_string(out.join("evaluation.json")).unwrap();
    assert!(!text.contains("heading_deg"), "a heading figure in {text}");
    assert!(!text.contains("NaN"));
    for model in evaluation["models"].as_array().unwrap() {
        let horizontal = number(model, "rms_horizontal_m");
        assert!(horizontal > 0.0 && horizontal < 1000.0, "{model}");
        let table = out.join(model["errors_csv"].as_str().unwrap());
        let header = std::fs::read_to_string(table).unwrap();
        let header = header.lines().next().unwrap().to_string();
        assert_eq!(
            header,
            "outage,t_s,since_outage_start_s,north_m,east_m,horizontal_m"
        );
    }
}

/// `path`'s canonical CSV with every t_s moved by `shift_s` whole seconds (digits kept).
fn shifted_csv(path: &Path, to: &Path, shift_s: i64) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let (t, rest) = line.split_once(',').unwrap();
        let (whole, fraction) = t.split_once('.').unwrap_or((t, "0"));
        let whole: i64 = whole.parse().unwrap();
        let _ = writeln!(out, "{}.{fraction},{rest}", whole + shift_s);
    }
    std::fs::write(to, out).unwrap();
}

/// Days since 1970-01-01 as (year, month, day), Howard Hinnant's `civil_from_days`.
fn civil(days: i64) -> (i64, i64, i64) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    (yoe + era * 400 + i64::from(month <= 2), month, day)
}

/// How a `.pos` writes its times.
#[derive(Clone, Copy)]
enum PosTime {
    /// `week seconds-of-week`.
    WeekSeconds,
    /// `yyyy/mm/dd hh:mm:ss.fff`.
    Calendar,
}

/// The fixes of the GNSS CSV `gnss` (t_s from 0) as an RTKLIB `.pos` whose GPST times are
/// t_s + [`gpst_shift_s`], in the default latitude/longitude layout, all fixed (Q = 1).
fn pos_of_gnss(gnss: &Path, to: &Path, form: PosTime) {
    let text = std::fs::read_to_string(gnss).unwrap();
    let mut out = String::from(
        "% program   : a test's own writer\n%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio\n",
    );
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (whole, fraction) = f[0].split_once('.').unwrap();
        let whole: i64 = whole.parse().unwrap();
        let time = match form {
            PosTime::WeekSeconds => format!("{WEEK} {}.{fraction}", SECOND_OF_WEEK + whole),
            PosTime::Calendar => {
                let s = gpst_shift_s() + whole;
                let (y, m, d) = civil(s.div_euclid(86_400));
                let of_day = s.rem_euclid(86_400);
                let (h, min, sec) = (of_day / 3600, of_day / 60 % 60, of_day % 60);
                format!("{y}/{m:02}/{d:02} {h:02}:{min:02}:{sec:02}.{fraction}")
            }
        };
        let _ = writeln!(
            out,
            "{time} {} {} {} 1 12 {} {} {} 0.0 0.0 0.0 0.0 0.0",
            f[1], f[2], f[3], f[4], f[5], f[6]
        );
    }
    std::fs::write(to, out).unwrap();
}

/// The survey's IMU and GNSS CSVs with t_s on the GPST scale (as `convert` puts a receiver's
/// logs), in `dir`.
fn gpst_survey(v: &Path, dir: &Path) -> (PathBuf, PathBuf) {
    let (imu, gnss) = (dir.join("imu_gpst.csv"), dir.join("gnss_gpst.csv"));
    shifted_csv(&v.join("imu.csv"), &imu, gpst_shift_s());
    shifted_csv(&v.join("gnss.csv"), &gnss, gpst_shift_s());
    (imu, gnss)
}

/// The survey's reference.csv as KF-GINS `.nav` (`convert --to kf-gins`), in `dir`.
fn nav_of_reference(v: &Path, dir: &Path) -> PathBuf {
    let (csv, nav) = (v.join("reference.csv"), dir.join("ref.nav"));
    let args = ["convert", arg(&csv), "--to", "kf-gins", "--out", arg(&nav)];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    nav
}

/// `evaluate --reference gnss.csv`: the GNSS CSV `--gnss` reads is the reference; position is
/// scored and heading is said not to be, in the JSON, the printed table and the report.
#[test]
fn evaluate_takes_the_gnss_csv_as_a_position_only_reference() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let (imu, gnss) = (v.join("imu.csv"), v.join("gnss.csv"));
    let out = dir.path().join("ev");
    let (status, stdout, stderr) = evaluate(&imu, &gnss, &gnss, &out);
    assert_eq!(status, 0, "{stderr}");
    assert_position_only(&json(&stdout), &out);
    // The table says it too, in the heading column and under the table.
    let mut args: Vec<&str> = vec!["evaluate", "--imu", arg(&imu), "--gnss", arg(&gnss)];
    let table_out = dir.path().join("ev-table");
    args.extend(["--reference", arg(&gnss), "--profile"]);
    args.extend(["builtin:temperature-sensitive", "--filter", "ekf"]);
    args.extend(["--outages", "spread:2,30", "--out", arg(&table_out)]);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("not scored: heading"), "{stdout}");
    assert!(
        !stdout.contains("NaN") && !stdout.contains("diverged"),
        "{stdout}"
    );
    // The report of the folder says it beside the ranking.
    let (status, _, stderr) = outcome(&thermonav(&["report", arg(&out)]));
    assert_eq!(status, 0, "{stderr}");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        html.contains("Not scored: heading"),
        "the report says nothing"
    );
    assert!(html.contains("not scored"), "the ranking's heading cells");
}

/// `evaluate --reference sol.pos`: an RTK solution in GPST week/seconds, beside an IMU and GNSS
/// on the GPST scale, scores like the same fixes as a GNSS CSV (the same run, the same
/// positions); the same solution in calendar time gives the same numbers.
#[test]
fn evaluate_takes_an_rtklib_pos_in_week_seconds_or_calendar_time() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let (imu, gnss) = gpst_survey(&v, dir.path());
    let runs = [
        ("gnss", gnss.clone()),
        ("week", dir.path().join("week.pos")),
        ("calendar", dir.path().join("calendar.pos")),
    ];
    pos_of_gnss(&v.join("gnss.csv"), &runs[1].1, PosTime::WeekSeconds);
    pos_of_gnss(&v.join("gnss.csv"), &runs[2].1, PosTime::Calendar);
    let mut horizontal = Vec::new();
    for (name, reference) in &runs {
        let out = dir.path().join(format!("ev-{name}"));
        let (status, stdout, stderr) = evaluate(&imu, &gnss, reference, &out);
        assert_eq!(status, 0, "{name}: {stderr}");
        let evaluation = json(&stdout);
        assert_position_only(&evaluation, &out);
        let models = evaluation["models"].as_array().unwrap().clone();
        horizontal.push(
            models
                .iter()
                .map(|m| number(m, "rms_horizontal_m"))
                .collect::<Vec<_>>(),
        );
    }
    // The .pos holds the CSV's fixes to the digits written (1e-9 deg is 0.1 mm): the same
    // scores to 1 mm.
    for other in &horizontal[1..] {
        for (a, b) in horizontal[0].iter().zip(other) {
            assert!((a - b).abs() < 1e-3, "{horizontal:?}");
        }
    }
}

/// `evaluate --reference ref.nav`: the survey's reference written as KF-GINS `.nav` by
/// `convert --to kf-gins` (week 0: seconds of week, the IMU's own scale) holds attitude, so
/// heading is scored, and every figure equals the reference CSV's.
#[test]
fn evaluate_takes_a_kf_gins_nav_with_its_attitude() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let nav = nav_of_reference(&v, dir.path());
    let (imu, gnss) = (v.join("imu.csv"), v.join("gnss.csv"));
    let mut results = Vec::new();
    for (name, reference) in [("csv", v.join("reference.csv")), ("nav", nav)] {
        let out = dir.path().join(format!("ev-{name}"));
        let (status, stdout, stderr) = evaluate(&imu, &gnss, &reference, &out);
        assert_eq!(status, 0, "{name}: {stderr}");
        let evaluation = json(&stdout);
        assert_eq!(evaluation["reference"]["content"], "full");
        assert!(evaluation["reference"].get("not_scored").is_none());
        results.push(evaluation["models"].as_array().unwrap().clone());
    }
    for (a, b) in results[0].iter().zip(&results[1]) {
        for key in ["rms_horizontal_m", "rms_heading_deg"] {
            let (x, y) = (number(a, key), number(b, key));
            // The .nav's degrees are written to 1e-9 deg: 0.1 mm and far below 1e-3 deg.
            assert!((x - y).abs() < 1e-3, "{key}: {x} against {y}");
        }
    }
}

/// A reference on another time scale than the IMU (an RTK solution in GPST against a record
/// timed from 0) is refused, naming the file, its kind, both time ranges and the cure.
#[test]
fn a_reference_that_misses_the_imu_record_is_refused_with_both_ranges() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let pos = dir.path().join("sol.pos");
    pos_of_gnss(&v.join("gnss.csv"), &pos, PosTime::Calendar);
    let (imu, gnss) = (v.join("imu.csv"), v.join("gnss.csv"));
    let (status, _, stderr) = evaluate(&imu, &gnss, &pos, &dir.path().join("ev"));
    assert_eq!(status, 1, "{stderr}");
    let first_fix_s = gpst_shift_s() + 1;
    for said in [
        arg(&pos),
        "RTKLIB .pos",
        &format!("t = {first_fix_s}.000"),
        "the IMU record",
        "t = 0.",
        "do not overlap",
        "GPST",
    ] {
        assert!(stderr.contains(said), "{said:?} not in {stderr}");
    }
    assert!(!dir.path().join("ev").exists());
}

/// `integrate --initial-from` takes a `.nav` as its start, and refuses a position-only
/// reference (nothing to take the attitude from) with what to do instead; `plot trajectory`
/// draws a `.pos` as it draws a trajectory CSV.
#[test]
fn integrate_starts_from_a_nav_refuses_fixes_and_plot_draws_a_pos() {
    let dir = tempfile::tempdir().unwrap();
    let v = vessel(dir.path());
    let nav = nav_of_reference(&v, dir.path());
    let (imu, gnss) = (v.join("imu.csv"), v.join("gnss.csv"));
    let sol = dir.path().join("sol.csv");
    let integrate = |start: &Path| {
        let args = [
            "integrate",
            "--imu",
            arg(&imu),
            "--gnss",
            arg(&gnss),
            "--profile",
            "builtin:temperature-sensitive",
            "--initial-from",
            arg(start),
            "--out",
            arg(&sol),
        ];
        outcome(&thermonav(&args))
    };
    let (status, _, stderr) = integrate(&nav);
    assert_eq!(status, 0, "{stderr}");
    let (status, _, stderr) = integrate(&gnss);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains(arg(&gnss)) && stderr.contains("positions only"),
        "{stderr}"
    );
    assert!(stderr.contains("leave out --initial-from"), "{stderr}");
    let pos = dir.path().join("sol.pos");
    pos_of_gnss(&gnss, &pos, PosTime::WeekSeconds);
    let svg = dir.path().join("track.svg");
    let args = ["plot", "trajectory", arg(&pos), "--out", arg(&svg)];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
}

/// The README's "GNSS + IMU (an RTK log) to the tournament" block, run as written by `sh -e`
/// from a folder laid out as the repository's root (its `examples/`, and `../shared` beside
/// it), with this build's `thermonav` first on the PATH: the RTK solution is the reference,
/// position is scored in every outage, heading is said not to be, and the report is written.
#[test]
fn readme_rtk_log_to_the_tournament() {
    let checkout = crate::readme::checkout();
    let heading = "### GNSS + IMU (an RTK log) to the tournament";
    let stdout = crate::readme::run_block(&checkout.root, heading);
    assert!(stdout.contains("not scored: heading"), "{stdout}");
    let ev = checkout.root.join("ev-rtk");
    let evaluation = json(&std::fs::read_to_string(ev.join("evaluation.json")).unwrap());
    assert_position_only(&evaluation, &ev);
    assert_eq!(evaluation["outages"].as_array().unwrap().len(), 6);
    let html = std::fs::read_to_string(ev.join("report.html")).unwrap();
    assert!(html.contains("Not scored: heading"));
}
