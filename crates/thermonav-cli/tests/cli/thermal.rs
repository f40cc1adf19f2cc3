//! The thermal calibration end to end: a simulated chamber campaign with repeated power-ons and
//! a sweep, `characterize` fitting it, `bank show` and `plot thermal-bias` showing it; checked
//! against the simulator's truth (truth.json's repeatable curves), and bad input refused.

use crate::{arg, files_in, outcome, thermonav, write_file};
use std::path::{Path, PathBuf};

/// Where the simulator's chamber stands (sim::chamber's default site, Calgary).
const SITE: [&str; 4] = [
    "--chamber-latitude-deg",
    "51.08",
    "--chamber-height-m",
    "1100",
];

/// Set points of the campaign, °C (the simulator's default).
const SET_POINTS_C: [f64; 6] = [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0];

/// A campaign of three power-ons at the default set points and a −40..60 °C sweep at
/// 2 °C/min, 300 s records at 20 Hz, in `dir/tc`.
pub(crate) fn campaign(dir: &Path) -> PathBuf {
    let out = dir.join("tc");
    let (status, _, stderr) = outcome(&thermonav(&[
        "simulate",
        "chamber",
        "--out",
        arg(&out),
        "--duration-s",
        "300",
        "--rate-hz",
        "20",
        "--power-ons",
        "3",
        "--ramp=-40:60:2",
    ]));
    assert_eq!(status, 0, "{stderr}");
    out
}

/// The CSV files of `dir`, comma-separated (one `--power-on` value).
fn records_of(dir: &Path) -> String {
    let names = files_in(dir).into_iter().filter(|n| n.ends_with(".csv"));
    let paths: Vec<String> = names.map(|n| arg(&dir.join(n)).to_owned()).collect();
    paths.join(",")
}

/// `characterize` of the campaign with both further power-ons and the sweep; its `--json`.
fn characterize(tc: &Path, bank: &Path) -> serde_json::Value {
    characterize_with_sweep(tc, bank, &tc.join("imu_ramp.csv"))
}

/// `characterize` of the campaign with both further power-ons and `sweep`; its `--json`.
pub(crate) fn characterize_with_sweep(tc: &Path, bank: &Path, sweep: &Path) -> serde_json::Value {
    let own: Vec<String> = SET_POINTS_C
        .iter()
        .map(|t| arg(&tc.join(format!("imu_{t}C.csv"))).to_owned())
        .collect();
    let (second, third) = (
        records_of(&tc.join("power_on_2")),
        records_of(&tc.join("power_on_3")),
    );
    let mut args: Vec<&str> = vec!["characterize"];
    args.extend(own.iter().map(String::as_str));
    args.extend([
        "--power-on",
        &second,
        "--power-on",
        &third,
        "--sweep",
        arg(sweep),
    ]);
    args.extend(SITE);
    args.extend(["--out", arg(bank), "--json"]);
    let (status, stdout, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    serde_json::from_str(&stdout).expect("one JSON document")
}

/// b(T) of truth.json's repeatable curve {reference_temperature_c, coefficients [b, c1, c2]}.
fn true_bias(curve: &serde_json::Value, temperature_c: f64) -> f64 {
    let d = temperature_c - curve["reference_temperature_c"].as_f64().unwrap();
    let c: Vec<f64> = curve["coefficients"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    c.iter().rev().fold(0.0, |acc, b| acc * d + b)
}

pub(crate) fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn characterize_fits_curves_whose_bands_hold_the_true_repeatable_bias() {
    let dir = tempfile::tempdir().unwrap();
    let tc = campaign(dir.path());
    let bank_path = dir.path().join("bank.json");
    let summary = characterize(&tc, &bank_path);
    let truth = read_json(&tc.join("truth.json"));
    let bank: thermonav::stoch::bank::ModelBank =
        serde_json::from_value(read_json(&bank_path)).unwrap();
    let calibration = bank.thermal.expect("the bank has a thermal calibration");
    // Three chamber power-ons and the sweep's own.
    assert_eq!(calibration.power_ons, 4);
    assert_eq!(summary["thermal"]["power_ons"], 4);
    assert!(summary.get("thermal_not_fitted_reason").is_none());
    // az is left out: on a level unit its curve holds b(T) + g·s(T) (scale factor is not
    // identifiable from static records), and the truth's repeatable_bias is b(T) alone.
    let compared = ["gx", "gy", "gz", "ax", "ay"];
    let mut fully_covered = 0;
    for name in compared {
        let channel = thermonav::imu::Channel::ALL
            .into_iter()
            .find(|c| c.name() == name)
            .unwrap();
        let curve = &calibration.channels[&channel].bias;
        let expected = &truth["unit"]["repeatable_bias"][name];
        // The truth's constant is the unit's b; the fit's carries the mean power-on offset,
        // whose uncertainty the band includes.
        let misses: Vec<f64> = SET_POINTS_C
            .iter()
            .map(|&t| {
                let (value, half_width) = curve.band_at(t);
                (value - true_bias(expected, t)).abs() / half_width
            })
            .collect();
        assert!(
            misses.iter().all(|&m| m < 2.0),
            "{name}: |error| / band {misses:?}"
        );
        fully_covered += usize::from(misses.iter().all(|&m| m <= 1.0));
        let json = &summary["thermal"]["channels"][name];
        assert_eq!(json["order"], curve.order);
        let key = if name.starts_with('g') {
            "max_band_half_width_rad_s"
        } else {
            "max_band_half_width_m_s2"
        };
        assert!((json[key].as_f64().unwrap() - curve.max_band_half_width()).abs() < 1e-15);
        assert!(
            json["range_c"][0].as_f64().unwrap() < -39.0
                && json["range_c"][1].as_f64().unwrap() > 59.0
        );
    }
    assert!(
        fully_covered >= 4,
        "the true curve inside the band for most channels: {fully_covered} of 5"
    );
}

#[test]
fn bank_show_prints_the_thermal_table_and_plot_draws_it() {
    let dir = tempfile::tempdir().unwrap();
    let tc = campaign(dir.path());
    let bank = dir.path().join("bank.json");
    characterize(&tc, &bank);
    let (status, stdout, stderr) = outcome(&thermonav(&["bank", "show", arg(&bank)]));
    assert_eq!(status, 0, "{stderr}");
    assert!(stdout.contains("thermal calibration"), "{stdout}");
    assert!(
        stdout.contains("b(Tmin) deg/h") && stdout.contains("max band ± mg"),
        "{stdout}"
    );
    assert!(
        stdout.contains("not identifiable from static level records"),
        "{stdout}"
    );
    assert!(stdout.contains("b(T) + g s(T)"), "{stdout}");
    let rows: Vec<&str> = stdout
        .lines()
        .filter(|l| l.starts_with("gx ") && l.contains(".."))
        .collect();
    assert_eq!(rows.len(), 1, "one gx row: {stdout}");
    // gx row: ch, order, Tref, range, b(Tmin), b(Tref), b(Tmax), max band ±, … in deg/h: the
    // true b at the range's start lies within the largest half-width of the band.
    let cells: Vec<&str> = rows[0].split_whitespace().collect();
    let coldest_c: f64 = cells[3].split("..").next().unwrap().parse().unwrap();
    let (at_coldest, max_band): (f64, f64) = (cells[4].parse().unwrap(), cells[7].parse().unwrap());
    let truth = read_json(&tc.join("truth.json"));
    let expected = thermonav::units::rad_per_s_to_deg_per_h(true_bias(
        &truth["unit"]["repeatable_bias"]["gx"],
        coldest_c,
    ));
    assert!(
        (at_coldest - expected).abs() <= max_band,
        "{at_coldest} against {expected} deg/h, band ± {max_band} deg/h"
    );
    let (status, stdout, _) = outcome(&thermonav(&["bank", "show", arg(&bank), "--json"]));
    assert_eq!(status, 0);
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["thermal"]["channels"].as_object().unwrap().len(), 6);
    let svg = dir.path().join("thermal.svg");
    let (status, _, stderr) = outcome(&thermonav(&[
        "plot",
        "thermal-bias",
        arg(&bank),
        "--out",
        arg(&svg),
    ]));
    assert_eq!(status, 0, "{stderr}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.starts_with("<svg") || text.starts_with("<?xml"),
        "an SVG document"
    );
    assert_eq!(text.matches("class=\"panel\"").count(), 6);
    assert!(text.contains("power-on 4") && text.contains("bias (deg/h)") && text.contains("(mg)"));
    let one = dir.path().join("gx.svg");
    let args = [
        "plot",
        "thermal-bias",
        arg(&bank),
        "--out",
        arg(&one),
        "--channel",
        "gx",
    ];
    assert_eq!(outcome(&thermonav(&args)).0, 0);
    let text = std::fs::read_to_string(&one).unwrap();
    assert_eq!(text.matches("class=\"panel\"").count(), 1);
    // Issue 38 row 18: the band's legend swatch has the band's colour (it was grey).
    let band = ["fill", "fill-opacity"].map(|a| attribute_of(&text, "<polygon class=\"band\"", a));
    let swatch =
        ["fill", "fill-opacity"].map(|a| attribute_of(&text, "<rect class=\"legend-swatch\"", a));
    assert_eq!(swatch, band);
}

/// The value of `attribute` in the first element of `svg` that starts with `start`.
fn attribute_of<'a>(svg: &'a str, start: &str, attribute: &str) -> &'a str {
    let at = svg
        .find(start)
        .unwrap_or_else(|| panic!("{start} in the figure"));
    let element = &svg[at..at + svg[at..].find('>').expect("closed")];
    let needle = format!(" {attribute}=\"");
    let value = &element[element
        .find(&needle)
        .unwrap_or_else(|| panic!("{attribute}"))
        + needle.len()..];
    &value[..value.find('"').expect("quoted")]
}

/// Runs `args` and checks a failure: `code`, nothing on stdout, no panic, stderr naming each
/// of `needles`, and `out` not written.
fn fails(args: &[&str], code: i32, needles: &[&str], out: &Path) {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, code, "{args:?}: {stderr}");
    assert!(stdout.is_empty(), "{args:?}: {stdout}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "{args:?}: {needle} in {stderr}");
    }
    assert!(!out.exists(), "{args:?}: no output after a failure");
}

#[test]
fn simulate_refuses_bad_ramps_power_ons_and_warm_up() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let chamber = |extra: &str| -> Vec<String> {
        let mut args = vec![
            "simulate".into(),
            "chamber".into(),
            "--out".into(),
            arg(&out).into(),
        ];
        args.extend(["--duration-s", "10"].map(String::from));
        args.extend(extra.split(' ').map(String::from));
        args
    };
    let cases = [
        ("--ramp=1:2", vec!["--ramp", "three fields"]),
        ("--ramp=0:0:1", vec!["--ramp", "must differ"]),
        ("--ramp=-200:0:1", vec!["--ramp", "-80..150"]),
        ("--power-ons 0", vec!["--power-ons 0", "1 to 100"]),
        ("--power-ons 101", vec!["--power-ons 101", "1 to 100"]),
    ];
    for (extra, needles) in cases {
        let args = chamber(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        fails(&args, 2, &needles, &out);
    }
    let vessel = [
        "simulate",
        "vessel",
        "--out",
        arg(&out),
        "--warm-up-time-constant-s",
        "-1",
        "--warm-up-from-c",
        "0",
    ];
    fails(&vessel, 2, &["--warm-up-time-constant-s", "positive"], &out);
}

#[test]
fn characterize_refuses_bad_thermal_inputs_naming_the_file_or_option() {
    let dir = tempfile::tempdir().unwrap();
    let tc = campaign(dir.path());
    let own = arg(&tc.join("imu_0C.csv")).to_owned();
    let second = arg(&tc.join("imu_20C.csv")).to_owned();
    let bank = dir.path().join("bank.json");
    let run = |extra: &[&str], code: i32, needles: &[&str]| {
        let mut args = vec![
            "characterize",
            own.as_str(),
            second.as_str(),
            "--out",
            arg(&bank),
        ];
        args.extend_from_slice(extra);
        fails(&args, code, needles, &bank);
    };
    let missing = dir.path().join("missing.csv");
    run(&["--power-on", arg(&missing)], 1, &["missing.csv"]);
    run(&["--power-on", ""], 2, &["--power-on"]);
    let header = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2";
    let rows: String = (0..400)
        .map(|k| format!("{:.3},0,0,0,0,0,-9.8\n", k as f64 * 0.05))
        .collect();
    let no_temp = write_file(
        dir.path(),
        "sweep_no_temp.csv",
        &format!("{header}\n{rows}"),
    );
    run(
        &["--sweep", arg(&no_temp)],
        1,
        &["sweep_no_temp.csv", "temp_c"],
    );
    run(&["--sweep-block-s", "0"], 2, &["--sweep-block-s"]);
    run(
        &["--chamber-latitude-deg", "100"],
        2,
        &["--chamber-latitude-deg 100"],
    );
    let leftovers: Vec<String> = files_in(dir.path())
        .into_iter()
        .filter(|n| n.starts_with("bank"))
        .collect();
    assert!(
        leftovers.is_empty(),
        "no temporary bank left: {leftovers:?}"
    );
}

#[test]
fn plot_thermal_bias_refuses_a_bank_without_thermal_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let bank = crate::bank_export::plain_bank(dir.path());
    let out = dir.path().join("thermal.svg");
    let args = ["plot", "thermal-bias", arg(&bank), "--out", arg(&out)];
    fails(&args, 1, &[arg(&bank), "no thermal calibration"], &out);
}
