//! Issue 16: outside solutions scored by `evaluate --solution`, `convert --to kf-gins`, and the
//! frictions of `evaluate` and `report` (a reference that starts late, `rel:` outages, errors
//! CSVs relative to evaluation.json, the layout `report` needs).

use crate::navigation::inputs;
use crate::{arg, outcome, thermonav};
use serde_json::Value;
use std::path::{Path, PathBuf};
use thermonav::units::deg_to_rad;

fn run_ok(args: &[String]) -> String {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{args:?}\nstdout: {stdout}\nstderr: {stderr}");
    stdout
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| s.to_string()).collect()
}

const OUTAGES: &str = "60+30,150+30";

/// `integrate` of the vessel run with the bank's 25 °C model on the raw record, started from
/// the reference (as the tournament's candidates are), GNSS withheld in `OUTAGES`.
fn integrate(vessel: &Path, bank: &Path, out: &Path) {
    let (imu, gnss, reference) = vessel_files(vessel);
    run_ok(&strings(&[
        "integrate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--bank",
        arg(bank),
        "--model-temperature-c",
        "25",
        "--no-compensation",
        "--initial-from",
        arg(&reference),
        "--outages",
        OUTAGES,
        "--lever-arm-m",
        "0.3,0,-2.5",
        "--out",
        arg(out),
        "--json",
    ]));
}

fn vessel_files(vessel: &Path) -> (PathBuf, PathBuf, PathBuf) {
    let [imu, gnss, reference] = ["imu.csv", "gnss.csv", "reference.csv"].map(|f| vessel.join(f));
    (imu, gnss, reference)
}

/// `evaluate` of outside solutions alone (no filter runs).
fn score(reference: &Path, solutions: &[&Path], outages: &str, out: &Path) -> Value {
    let mut args = strings(&[
        "evaluate",
        "--reference",
        arg(reference),
        "--outages",
        outages,
    ]);
    for s in solutions {
        args.extend(strings(&["--solution", arg(s)]));
    }
    args.extend(strings(&["--out", arg(out), "--json"]));
    serde_json::from_str(&run_ok(&args)).unwrap()
}

fn model<'a>(json: &'a Value, label: &str) -> &'a Value {
    let models = json["models"].as_array().unwrap();
    models
        .iter()
        .find(|m| m["label"] == label)
        .unwrap_or_else(|| panic!("{label}: {json}"))
}

const PER_OUTAGE_KEYS: [&str; 8] = [
    "rms_north_m",
    "rms_east_m",
    "rms_horizontal_m",
    "rms_heading_deg",
    "max_north_m",
    "max_east_m",
    "max_horizontal_m",
    "max_heading_deg",
];

// Done when: one trajectory of a simulated run written both ways, as our CSV and (by convert
// --to kf-gins) as a KF-GINS .nav, scored by evaluate --solution, gives the same per-outage
// errors (within TOLERANCE: the .nav's yaw is in 0..360°, so its heading errors agree with
// the CSV's after the wrap, to the rounding of one degree-to-radian conversion). The errors CSVs
// are stored relative to evaluation.json and their per-outage RMS is the one reported.
#[test]
fn a_kf_gins_nav_scores_like_the_same_trajectory_as_csv() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let solution = dir.path().join("ours.csv");
    integrate(&vessel, &bank, &solution);
    let nav = dir.path().join("kfgins.nav");
    run_ok(&strings(&[
        "convert",
        arg(&solution),
        "--to",
        "kf-gins",
        "--out",
        arg(&nav),
    ]));
    let text = std::fs::read_to_string(&nav).unwrap();
    let first: Vec<&str> = text.lines().next().unwrap().split_whitespace().collect();
    assert_eq!(first.len(), 11, "{first:?}");
    assert_eq!(
        first[0], "0",
        "times before the GPS epoch are written with week 0"
    );
    let (_, _, reference) = vessel_files(&vessel);
    let out = dir.path().join("ev");
    let json = score(&reference, &[&solution, &nav], OUTAGES, &out);
    assert!(json["filters"].as_array().unwrap().is_empty());
    let (csv, kf) = (model(&json, "ours.csv"), model(&json, "kfgins.nav"));
    assert_eq!(csv["kind"], "outside");
    assert!(csv["filter"].is_null());
    assert_close(csv, kf);
    let b = kf["per_outage"].as_array().unwrap();
    assert_eq!(b.len(), 2);
    let stored = kf["errors_csv"].as_str().unwrap();
    assert_eq!(stored, "errors/outside_kfgins.nav.csv");
    let rows = std::fs::read_to_string(out.join(stored)).unwrap();
    let north: Vec<f64> = rows
        .lines()
        .skip(1)
        .filter(|l| l.starts_with("1,"))
        .map(|l| l.split(',').nth(3).unwrap().parse().unwrap())
        .collect();
    let rms = (north.iter().map(|x| x * x).sum::<f64>() / north.len() as f64).sqrt();
    let reported = b[0]["rms_north_m"].as_f64().unwrap();
    assert!(
        (rms - reported).abs() <= 1e-9 * reported,
        "{rms} vs {reported}"
    );
}

// The RTKLIB variant: one trajectory written as an RTKLIB `.pos` (its latitude, longitude and
// height text copied from our CSV, vu the negated vd, GPST calendar times to the nanosecond)
// and as our CSV with the attitude a `.pos` stands for (roll = pitch = 0, yaw the course over
// ground atan2(ve, vn), printed in degrees), scored by evaluate --solution, gives the same
// per-outage errors: positions to the bit (the same decimal text), headings within TOLERANCE
// (one radian-degree-radian round trip of the CSV's yaw).
#[test]
fn an_rtklib_pos_scores_like_the_same_trajectory_as_csv() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let solution = dir.path().join("ours.csv");
    integrate(&vessel, &bank, &solution);
    let (pos, course) = (dir.path().join("rtk.pos"), dir.path().join("course.csv"));
    write_pos_and_course(&solution, &pos, &course);
    let (_, _, reference) = vessel_files(&vessel);
    let json = score(
        &reference,
        &[&course, &pos],
        OUTAGES,
        &dir.path().join("ev"),
    );
    let (csv, rtk) = (model(&json, "course.csv"), model(&json, "rtk.pos"));
    assert_eq!(rtk["kind"], "outside");
    let per_outage = rtk["per_outage"].as_array().unwrap();
    assert_eq!(per_outage.len(), 2);
    assert!(per_outage[0]["epochs"].as_u64().unwrap() > 10);
    assert!(per_outage[0]["rms_horizontal_m"].as_f64().unwrap() > 0.0);
    assert_close(csv, rtk);
}

/// Days since 1970-01-01 as (year, month, day) (Hinnant's civil_from_days).
fn civil_from_days(days: i64) -> (i64, i64, i64) {
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

/// `t_s` text (seconds since 1970 with a fraction) as RTKLIB's `yyyy/mm/dd hh:mm:ss.fff…`.
fn pos_time(t: &str) -> String {
    let (whole, fraction) = t.split_once('.').unwrap_or((t, "0"));
    let seconds: i64 = whole.parse().unwrap();
    let (y, m, d) = civil_from_days(seconds.div_euclid(86_400));
    let s = seconds.rem_euclid(86_400);
    let (hh, mm, ss) = (s / 3600, s / 60 % 60, s % 60);
    format!("{y:04}/{m:02}/{d:02} {hh:02}:{mm:02}:{ss:02}.{fraction}")
}

/// The trajectory CSV `from` as an RTKLIB `.pos` and as a CSV with yaw the course over ground.
fn write_pos_and_course(from: &Path, pos: &Path, course: &Path) {
    let text = std::fs::read_to_string(from).unwrap();
    let mut lines = text.lines();
    let mut csv = vec![lines.next().unwrap().to_string()];
    let mut rtk = vec![
        "% program   : written by the thermonav test from a trajectory CSV".to_string(),
        "%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio    vn(m/s)    ve(m/s)    vu(m/s)".to_string(),
    ];
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let (vn, ve): (f64, f64) = (f[4].parse().unwrap(), f[5].parse().unwrap());
        let vu = match f[6].strip_prefix('-') {
            Some(positive) => positive.to_string(),
            None => format!("-{}", f[6]),
        };
        rtk.push(format!(
            "{} {} {} {} 1 10 0.01 0.01 0.02 0 0 0 0.0 0.0 {} {} {vu}",
            pos_time(f[0]),
            f[1],
            f[2],
            f[3],
            f[4],
            f[5]
        ));
        let yaw = ve.atan2(vn).to_degrees();
        csv.push(format!("{},0,0,{yaw}", f[..7].join(",")));
    }
    std::fs::write(pos, rtk.join("\n") + "\n").unwrap();
    std::fs::write(course, csv.join("\n") + "\n").unwrap();
}

// Done when: a tournament with --solution pointing at one of our own integrate outputs (the
// 25 °C bank model on the raw record, started from the reference, the same outages) scores
// it with that candidate's per-outage errors (to the last bits of the CSV's degrees, see
// TOLERANCE: the epochs, their times and the maxima agree exactly), as an unranked outside row.
#[test]
fn our_own_integrate_output_scores_as_its_candidate() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let solution = dir.path().join("integrated.csv");
    integrate(&vessel, &bank, &solution);
    let (imu, gnss, reference) = vessel_files(&vessel);
    let out = dir.path().join("ev");
    let stdout = run_ok(&strings(&[
        "evaluate",
        "--imu",
        arg(&imu),
        "--gnss",
        arg(&gnss),
        "--reference",
        arg(&reference),
        "--bank",
        arg(&bank),
        "--filter",
        "ekf",
        "--no-schedule",
        "--no-compensation",
        "--lever-arm-m",
        "0.3,0,-2.5",
        "--outages",
        OUTAGES,
        "--solution",
        arg(&solution),
        "--solution-label",
        "integrate 25 °C",
        "--out",
        arg(&out),
        "--json",
    ]));
    let json: Value = serde_json::from_str(&stdout).unwrap();
    let (ours, outside) = (
        model(&json, "bank 25.0 °C"),
        model(&json, "integrate 25 °C"),
    );
    assert_eq!(ours["filter"], "ekf");
    assert_eq!(outside["kind"], "outside");
    assert_close(ours, outside);
    for (_, best) in json["best"].as_object().unwrap() {
        assert_ne!(best, "integrate 25 °C", "outside rows are not ranked");
    }
    let rows = |m: &Value| -> Vec<Vec<f64>> {
        let text = std::fs::read_to_string(out.join(m["errors_csv"].as_str().unwrap())).unwrap();
        let numbers = |l: &str| l.split(',').map(|x| x.parse().unwrap()).collect();
        text.lines().skip(1).map(numbers).collect()
    };
    let (a, b) = (rows(ours), rows(outside));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(
            x[..3],
            y[..3],
            "outage, time and time since its start are exact"
        );
        let close = x.iter().zip(y).all(|(p, q)| (p - q).abs() <= TOLERANCE);
        assert!(close, "{x:?} vs {y:?}");
    }
}

/// Agreement of two trajectories' errors, m and deg: the trajectory CSV prints the degrees that
/// read back to the same radians when one lies within two units in the last place, otherwise
/// the nearest, a few units off (one unit of latitude in radians is ~7e-10 m on the Earth; the
/// largest difference seen is 1.4e-9 m). 1e-8 covers that and is five orders of magnitude below
/// any difference a filter's arithmetic would make (mm and more).
const TOLERANCE: f64 = 1e-8;

/// The per-outage figures of two report rows agree within [`TOLERANCE`], epoch counts exactly.
fn assert_close(a: &Value, b: &Value) {
    let (a, b) = (
        a["per_outage"].as_array().unwrap(),
        b["per_outage"].as_array().unwrap(),
    );
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert_eq!((&x["epochs"], &x["start_s"]), (&y["epochs"], &y["start_s"]));
        for key in PER_OUTAGE_KEYS {
            let (x, y) = (x[key].as_f64().unwrap(), y[key].as_f64().unwrap());
            assert!((x - y).abs() <= TOLERANCE, "{key}: {x} vs {y}");
        }
    }
}

/// The vessel's reference without its first `from_s` seconds.
fn late_reference(vessel: &Path, from_s: f64, path: &Path) {
    let text = std::fs::read_to_string(vessel.join("reference.csv")).unwrap();
    let mut lines = text.lines();
    let mut kept = vec![lines.next().unwrap()];
    kept.extend(lines.filter(|l| l.split(',').next().unwrap().parse::<f64>().unwrap() >= from_s));
    std::fs::write(path, kept.join("\n") + "\n").unwrap();
}

// Issue 16: evaluate accepts a reference that starts after the first GNSS fix (the runs start
// at its first point, as integrate --initial-from does): an outage inside its span is scored,
// one before it is refused naming the reference and both spans; and outages given with rel:
// count from the first sample (here, without an IMU, the reference's first point t0):
// rel:10+30 is the outage starting at t0 + 10 s and scores as that absolute outage does.
#[test]
fn a_late_reference_is_accepted_and_rel_outages_count_from_its_start() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let late = dir.path().join("late.csv");
    late_reference(&vessel, 50.0, &late);
    let (imu, gnss, _) = vessel_files(&vessel);
    let tournament = |outages: &str, out: &Path| {
        strings(&[
            "evaluate",
            "--imu",
            arg(&imu),
            "--gnss",
            arg(&gnss),
            "--reference",
            arg(&late),
            "--bank",
            arg(&bank),
            "--filter",
            "ekf",
            "--lever-arm-m",
            "0.3,0,-2.5",
            "--outages",
            outages,
            "--out",
            arg(out),
            "--json",
        ])
    };
    let json: Value =
        serde_json::from_str(&run_ok(&tournament("60+30", &dir.path().join("a")))).unwrap();
    assert_eq!(json["outages"][0]["start_s"], 60.0);
    assert!(json["models"][0]["rms_north_m"].is_number(), "{json}");
    let bad_out = dir.path().join("b");
    let args = tournament("20+10", &bad_out);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 1, "{stderr}");
    assert!(stderr.contains(arg(&late)), "{stderr}");
    assert!(
        stderr.contains("does not cover the outage 20.000-30.000 s"),
        "{stderr}"
    );
    assert!(!bad_out.join("evaluation.json").exists());
    let first_s: f64 = std::fs::read_to_string(&late)
        .unwrap()
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let solution = vessel.join("reference.csv");
    let relative = score(&late, &[&solution], "rel:10+30", &dir.path().join("rel"));
    let start_s = relative["outages"][0]["start_s"].as_f64().unwrap();
    assert!(
        (start_s - (first_s + 10.0)).abs() < 1e-9,
        "{start_s} vs {first_s} + 10"
    );
    let absolute = format!("{:.9}+30", first_s + 10.0);
    let absolute = score(&late, &[&solution], &absolute, &dir.path().join("abs"));
    assert_close(&absolute["models"][0], &relative["models"][0]);
}

// Outside solutions need their outages stated; a solution on another time scale is refused
// naming the file and both spans; nothing is written.
#[test]
fn outside_solutions_are_refused_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("reference.csv");
    let mut text =
        String::from("t_s,lat_deg,lon_deg,h_m,vn_m_s,ve_m_s,vd_m_s,roll_deg,pitch_deg,yaw_deg\n");
    for k in 0..=100 {
        text.push_str(&format!("{k}.0,30.5,114.25,20,0,0,0,0,0,10\n"));
    }
    std::fs::write(&reference, &text).unwrap();
    let shifted = dir.path().join("gpst.csv");
    let late: String = text
        .lines()
        .enumerate()
        .map(|(k, l)| match k {
            0 => format!("{l}\n"),
            _ => format!("{}{}\n", 1_400_000_000 + k, &l[l.find('.').unwrap()..]),
        })
        .collect();
    std::fs::write(&shifted, late).unwrap();
    let out = dir.path().join("ev");
    let fails = |extra: &[&str], code: i32, needle: &str| {
        let mut args = vec![
            "evaluate",
            "--reference",
            arg(&reference),
            "--out",
            arg(&out),
        ];
        args.extend(extra);
        let (status, _, stderr) = outcome(&thermonav(&args));
        assert_eq!(status, code, "{extra:?}: {stderr}");
        assert!(stderr.contains(needle), "{extra:?}: {stderr}");
        assert!(!out.exists());
    };
    fails(
        &["--solution", arg(&reference)],
        2,
        "--solution needs --outages",
    );
    fails(
        &["--solution", arg(&shifted), "--outages", "10+5"],
        1,
        "same time scale",
    );
    fails(
        &["--solution", arg(&shifted), "--outages", "10+5"],
        1,
        arg(&shifted),
    );
    fails(&["--outages", "10+5"], 2, "--imu");
}

// Issue 16: `report DIR` on a folder without bank.json names the missing file and the layout
// it reads, and writes nothing.
#[test]
fn report_names_the_missing_file_and_its_layout() {
    let dir = tempfile::tempdir().unwrap();
    let (status, _, stderr) = outcome(&thermonav(&["report", arg(dir.path())]));
    assert_eq!(status, 1, "{stderr}");
    let missing = dir.path().join("bank.json");
    assert!(
        stderr.contains(&format!("{}: missing", missing.display())),
        "{stderr}"
    );
    assert!(stderr.contains("evaluation/evaluation.json"), "{stderr}");
    assert!(!dir.path().join("report.html").exists());
    let (_, help, _) = outcome(&thermonav(&["report", "--help"]));
    assert!(
        help.contains("DIR/bank.json") && help.contains("DIR/vessel/reference.csv"),
        "{help}"
    );
    let (_, help, _) = outcome(&thermonav(&["evaluate", "--help"]));
    assert!(help.contains("rel:"), "{help}");
}

// convert --to kf-gins: the vessel's GNSS CSV becomes the README's 7-column file, which
// convert reads back (--format kf-gins-gnss) to the same fixes' positions and STDs, times
// and all; an IMU CSV of rates becomes one fewer increment rows.
#[test]
fn convert_to_kf_gins_round_trips_through_the_readers() {
    let dir = tempfile::tempdir().unwrap();
    let gnss = dir.path().join("gnss.csv");
    std::fs::write(&gnss, "t_s,lat_deg,lon_deg,h_m,sd_n_m,sd_e_m,sd_u_m\n1.5,30.5,114.25,20.125,0.5,0.25,1\n2.5,30.50001,114.25002,20.5,0.5,0.25,1\n").unwrap();
    let txt = dir.path().join("gnss.txt");
    run_ok(&strings(&[
        "convert",
        arg(&gnss),
        "--to",
        "kf-gins",
        "--out",
        arg(&txt),
    ]));
    // The README's columns: seconds of week, lat, lon (deg), h (m), STD n e d (m); degrees are
    // printed so that they read back to the same radians (30.5 may print as 30.499999999999996).
    let text = std::fs::read_to_string(&txt).unwrap();
    let expected = [
        [1.5, 30.5, 114.25, 20.125, 0.5, 0.25, 1.0],
        [2.5, 30.50001, 114.25002, 20.5, 0.5, 0.25, 1.0],
    ];
    assert_eq!(text.lines().count(), 2);
    for (line, want) in text.lines().zip(expected) {
        let got: Vec<f64> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        assert_eq!(got.len(), 7, "{line}");
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            match k {
                1 | 2 => assert_eq!(deg_to_rad(*g).to_bits(), deg_to_rad(w).to_bits(), "{line}"),
                _ => assert_eq!(*g, w, "{line}"),
            }
        }
    }
    let back = dir.path().join("back.csv");
    run_ok(&strings(&[
        "convert",
        arg(&txt),
        "--format",
        "kf-gins-gnss",
        "--out",
        arg(&back),
    ]));
    let back = std::fs::read_to_string(&back).unwrap();
    let rows: Vec<Vec<f64>> = (back.lines().skip(1))
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2, "{back}");
    for (got, want) in rows.iter().zip(expected) {
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            match k {
                1 | 2 => assert_eq!(deg_to_rad(*g).to_bits(), deg_to_rad(w).to_bits(), "{back}"),
                _ => assert_eq!(*g, w, "{back}"),
            }
        }
    }
    let imu = dir.path().join("imu.csv");
    std::fs::write(&imu, crate::imu_csv(5, 100.0, |c, _| c as f64)).unwrap();
    let imu_txt = dir.path().join("imu.txt");
    let stdout = run_ok(&strings(&[
        "convert",
        arg(&imu),
        "--to",
        "kf-gins",
        "--out",
        arg(&imu_txt),
    ]));
    assert!(stdout.contains("4 KF-GINS IMU increments"), "{stdout}");
    let rows = std::fs::read_to_string(&imu_txt).unwrap();
    // Channel 1 (gy) is 1 rad/s: held for 0.01 s it is 0.01 rad.
    let first: Vec<f64> = rows
        .lines()
        .next()
        .unwrap()
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(first.len(), 7);
    assert!(
        (first[0] - 0.01).abs() < 1e-12 && (first[2] - 0.01).abs() < 1e-12,
        "{first:?}"
    );
}
