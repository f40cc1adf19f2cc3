//! A bad option is refused (exit 2) before any file is read: each command below is given an
//! input that does not exist, and must name the option, not the missing file, and write
//! nothing.

use crate::{arg, outcome, thermonav};
use std::path::Path;

/// Runs `args` in a folder whose `missing.*` inputs do not exist; asserts exit 2, a message
/// naming `option`, no word of the missing file, and an empty folder afterwards.
fn refused_before_reading(dir: &Path, args: &[impl AsRef<str>], option: &str) {
    let args: Vec<&str> = args.iter().map(AsRef::as_ref).collect();
    let (code, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(code, 2, "{args:?}: {stderr}");
    assert!(
        stderr.contains(option),
        "{args:?} should name {option}: {stderr}"
    );
    assert!(
        !stderr.contains("missing") && !stderr.contains("No such file"),
        "{args:?} read (or looked for) its input first: {stderr}"
    );
    let left: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
    assert!(left.is_empty(), "{args:?} wrote {left:?}");
}

#[test]
fn allan_refuses_a_confidence_outside_0_1_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("missing.csv");
    for level in ["1.5", "0", "NaN"] {
        let args = ["allan", arg(&input), "--confidence", level];
        refused_before_reading(dir.path(), &args, "--confidence");
    }
}

#[test]
fn ar_refuses_an_order_out_of_range_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("missing.csv");
    let d = dir.path();
    refused_before_reading(d, &["ar", arg(&input), "--order", "0"], "--order");
    refused_before_reading(d, &["ar", arg(&input), "--order", "101"], "--order");
    refused_before_reading(d, &["ar", arg(&input), "--order", "x"], "--order");
    let auto = ["ar", arg(&input), "--order", "auto", "--max-order", "0"];
    refused_before_reading(d, &auto, "--max-order");
}

#[test]
fn filter_refuses_bad_options_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let (input, out) = (dir.path().join("missing.csv"), dir.path().join("out.csv"));
    let d = dir.path();
    let filter = |extra: &[&'static str]| {
        let mut args = vec!["filter", arg(&input), "--out", arg(&out)];
        args.extend_from_slice(extra);
        args.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let cases: [(&[&str], &str); 4] = [
        (&[], "--cutoff-hz"),
        (&["--method", "wavelet", "--level", "0"], "--level"),
        (&["--cutoff-hz", "10", "--level", "2"], "--level"),
        // With --fs-hz the design and the decimation are checked before reading: 100 Hz
        // does not decimate to 30 Hz by an integer factor.
        (
            &[
                "--cutoff-hz",
                "5",
                "--fs-hz",
                "100",
                "--decimate-to-hz",
                "30",
            ],
            "--decimate-to-hz",
        ),
    ];
    for (extra, option) in cases {
        refused_before_reading(d, &filter(extra), option);
    }
    // Without --fs-hz, the band's checks that need no rate: a negative cut-off.
    refused_before_reading(d, &filter(&["--cutoff-hz=-5"]), "cut-off -5 Hz");
    // A cut-off above the --fs-hz Nyquist frequency: the design's own message.
    let args = filter(&["--cutoff-hz", "60", "--fs-hz", "100"]);
    refused_before_reading(d, &args, "60");
}

#[test]
fn plot_refuses_bad_options_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (input, svg) = (d.join("missing.json"), d.join("figure.svg"));
    let pdf = d.join("figure.pdf");
    let plot = |kind: &'static str, extra: &[&'static str]| {
        let mut args = vec!["plot", kind, arg(&input)];
        args.extend_from_slice(extra);
        args.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let svg_arg = arg(&svg).to_string();
    let with_out = |mut args: Vec<String>, out: &str| {
        args.extend(["--out".to_string(), out.to_string()]);
        args
    };
    let cases = [
        (with_out(plot("allan", &[]), arg(&pdf)), "--out"),
        (
            with_out(plot("thermal-bias", &["--channel", "gw"]), &svg_arg),
            "--channel",
        ),
        (
            with_out(plot("autocorrelation", &["--max-lag-s", "0"]), &svg_arg),
            "--max-lag-s",
        ),
        (with_out(plot("thermal-check", &[]), &svg_arg), "--record"),
        (
            with_out(plot("allan", &["--temperature-c", "NaN"]), &svg_arg),
            "--temperature-c",
        ),
    ];
    for (args, option) in cases {
        refused_before_reading(d, &args, option);
    }
}

#[test]
fn bank_refuses_bad_options_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (bank, out) = (d.join("missing.json"), d.join("out.yaml"));
    let show = ["bank", "show", arg(&bank), "--at-temperature-c", "inf"];
    refused_before_reading(d, &show, "--at-temperature-c");
    let export = |extra: &[&'static str]| {
        let mut args = vec!["bank", "export", arg(&bank), "--out", arg(&out)];
        args.extend_from_slice(extra);
        args.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let cases: [(&[&str], &str); 3] = [
        (&["--format", "kalibr", "--instance", "1"], "--instance"),
        (
            &["--format", "px4-tc", "--temperature-c", "20"],
            "--temperature-c",
        ),
        (
            &["--format", "kalibr", "--temperature-c", "NaN"],
            "--temperature-c",
        ),
    ];
    for (extra, option) in cases {
        refused_before_reading(d, &export(extra), option);
    }
}

#[test]
fn gmwm_refuses_an_unknown_model_before_reading() {
    // Its --replicates: tests/cli/runaway.rs.
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("missing.csv");
    let d = dir.path();
    refused_before_reading(d, &["gmwm", arg(&input), "--model", "wn+xx"], "--model");
}

/// A value out of the range the library's one check ([`thermonav::setting`]) allows is
/// refused in the command line's words, naming the option and the value, whichever command
/// reads it.
#[test]
fn settings_out_of_range_are_refused_naming_the_option_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let missing = |name: &str| arg(&d.join(name)).to_string();
    let (imu, bank, out) = (
        missing("missing.csv"),
        missing("missing.json"),
        missing("o"),
    );
    let (positive, finite) = ("expected a positive number", "expected a finite number");
    let characterize = ["characterize", &imu, "--temperature-c", "20", "--out", &out];
    let sweep = ["characterize", "--sweep", &imu, "--out", &out];
    let nmea = ["convert", &imu, "--format", "nmea", "--out", &out];
    let vessel = ["simulate", "vessel", "--out", &out];
    let warm_up = [&vessel[..], &["--warm-up-from-c", "0"]].concat();
    let cases: [(&[&str], &str, &str, &str); 10] = [
        (&["allan", &imu], "--rate-hz", "0", positive),
        (&characterize, "--cutoff-hz", "0", positive),
        (&characterize, "--transition-hz", "-1", positive),
        (&characterize, "--modelling-rate-hz", "inf", positive),
        (&sweep, "--sweep-block-s", "0", positive),
        (&["bank", "check", &bank, &imu], "--block-s", "0", positive),
        (&nmea, "--heading-sd-deg", "0", positive),
        (&warm_up, "--warm-up-time-constant-s", "0", positive),
        (&vessel, "--warm-up-from-c", "NaN", finite),
        (&vessel, "--time-offset-s", "inf", finite),
    ];
    for (command, option, value, expected) in cases {
        let setting = format!("{option}={value}");
        let args = [command, &[setting.as_str()]].concat();
        refused_before_reading(d, &args, &format!("{option} {value}: {expected}"));
    }
}
