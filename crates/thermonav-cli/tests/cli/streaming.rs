//! `characterize --reading streaming` against `--reading in-memory` on the same file, and its
//! bad-input behaviour.

use crate::{arg, imu_csv, outcome, thermonav, write_file};
use serde_json::Value;
use std::path::Path;

/// A uniform value in [−1, 1) from a counter (SplitMix64): reproducible noise for a CSV.
fn noise(counter: u64) -> f64 {
    let mut z = counter.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// 300 000 rows at 100 Hz (beyond the 2^18-sample prefix, so the record really streams):
/// a bias, a slow oscillation and white noise per channel.
fn long_record() -> String {
    imu_csv(300_000, 100.0, |c, t| {
        let k = (t * 100.0).round() as u64;
        0.01 * c as f64 + 1e-3 * (t / 90.0 + c as f64).sin() + 1e-3 * noise(6 * k + c as u64)
    })
}

fn bank(args: &[&str]) -> Value {
    let (status, _, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "{stderr}");
    let out = args[args.iter().position(|a| *a == "--out").unwrap() + 1];
    serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap()
}

/// `characterize IMU --out OUT --temperature-c 20 --reading READING`: status, stdout, stderr.
fn characterize_at_20c(imu: &Path, out: &Path, reading: &str) -> (i32, String, String) {
    outcome(&thermonav(&[
        "characterize",
        arg(imu),
        "--out",
        arg(out),
        "--temperature-c",
        "20",
        "--reading",
        reading,
    ]))
}

fn number(v: &Value) -> f64 {
    v.as_f64().expect("a number")
}

// Oracle: the in-memory path on the same file. The block-mean likelihood must agree bit for
// bit (same sums in the same order), and so must the AR fits and the AR-based and ACF-fitted
// Gauss-Markov models (both paths filter only the kept samples by the same direct sums,
// `filter_and_decimate` equals the piecewise decimator bit for bit), the Allan deviation to 1e-9 up to
// m = 8192 (exact) and within 1 % above (the decimated-overlap points; the library tests
// bound them against the confidence interval).
#[test]
fn streaming_gives_the_in_memory_bank() {
    let dir = tempfile::tempdir().unwrap();
    let imu = write_file(dir.path(), "long.csv", &long_record());
    let (memory, streamed) = (dir.path().join("m.json"), dir.path().join("s.json"));
    let common = ["--temperature-c", "20"];
    let mut args = vec!["characterize", arg(&imu), "--out", arg(&memory)];
    args.extend(common);
    let memory = bank(&[args.as_slice(), &["--reading", "in-memory"]].concat());
    let mut args = vec!["characterize", arg(&imu), "--out", arg(&streamed)];
    args.extend(common);
    let streamed = bank(&[args.as_slice(), &["--reading", "streaming"]].concat());
    let (m, s) = (&memory["entries"][0], &streamed["entries"][0]);
    assert_eq!(m["preprocessing"], s["preprocessing"]);
    for channel in ["gx", "gy", "gz", "ax", "ay", "az"] {
        let (mc, sc) = (&m["channels"][channel], &s["channels"][channel]);
        assert_eq!(
            mc["gauss_markov"]["irregular_ml"],
            sc["gauss_markov"]["irregular_ml"]
        );
        assert!(mc["ar"]["coefficients"].is_array(), "{channel}: {mc}");
        assert_eq!(mc["ar"], sc["ar"], "{channel}");
        for family in ["ar_based", "acf_fit"] {
            assert!(mc["gauss_markov"][family].is_object(), "{channel} {family}");
            assert_eq!(
                mc["gauss_markov"][family], sc["gauss_markov"][family],
                "{channel} {family}"
            );
        }
        let tau = mc["allan"]["tau_s"].as_array().unwrap();
        let (ma, sa) = (&mc["allan"]["adev"], &sc["allan"]["adev"]);
        for (i, t) in tau.iter().enumerate() {
            let tolerance = if number(t) * 100.0 <= 8192.5 {
                1e-9
            } else {
                1e-2
            };
            let r = (number(&sa[i]) / number(&ma[i]) - 1.0).abs();
            assert!(r < tolerance, "{channel} tau {t}: {r}");
        }
    }
}

#[test]
fn a_bad_row_deep_in_a_streamed_file_names_its_line_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = long_record();
    let at = text.match_indices('\n').nth(280_000).unwrap().0;
    text.insert_str(at + 1, "12.5,not-a-number,0,0,0,0,0\n");
    let imu = write_file(dir.path(), "bad.csv", &text);
    let out = dir.path().join("b.json");
    let (status, _, stderr) = characterize_at_20c(&imu, &out, "streaming");
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("bad.csv") && stderr.contains("280002"),
        "{stderr}"
    );
    assert!(!out.exists());
}

// The streamed record is checked for accelerations in g like one read whole: 300 000 rows
// (beyond the in-memory prefix) whose z acceleration is 1 ± 1e-3 under an m/s^2 name are
// refused at the header line, on both paths, and no bank is written.
#[test]
fn a_streamed_record_in_g_is_refused_like_one_read_whole() {
    let dir = tempfile::tempdir().unwrap();
    let text = imu_csv(300_000, 100.0, |c, t| {
        let k = (t * 100.0).round() as u64;
        let level = if c == 5 { 1.0 } else { 0.0 };
        level + 1e-3 * noise(6 * k + c as u64)
    });
    let imu = write_file(dir.path(), "in_g.csv", &text);
    let out = dir.path().join("b.json");
    for reading in ["streaming", "in-memory"] {
        let (status, _, stderr) = characterize_at_20c(&imu, &out, reading);
        assert_eq!(status, 1, "{reading}: {stderr}");
        assert!(
            stderr.contains("in_g.csv:1:") && stderr.contains("in g"),
            "{reading}: {stderr}"
        );
        assert!(!out.exists(), "{reading}");
    }
}
