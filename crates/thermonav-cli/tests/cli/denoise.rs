//! `filter --method wavelet` and `characterize --denoise wavelet` end to end: the output is the
//! library's de-noising of each column, the sidecar and the bank say what was done, and wrong
//! combinations of options are refused before anything is written.

use crate::modelling::chamber;
use crate::{arg, imu_csv, outcome, thermonav, write_file};
use std::path::Path;
use thermonav::signal::wavelet::denoise::{DecompositionLevel, WaveletDenoise, denoise};
use thermonav::signal::wavelet::threshold::{ThresholdRule, Thresholding};
use thermonav::signal::wavelet::transform::ExtensionMode;

fn json_of(args: &[&str]) -> serde_json::Value {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "stderr: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

/// The rows of a CSV with a header, as numbers.
fn rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// A noisy 100 Hz record of 1001 rows (odd, so the reconstruction's extra sample is dropped).
fn noisy_record(dir: &Path) -> std::path::PathBuf {
    let text = imu_csv(1001, 100.0, |c, t| {
        let wobble = ((t * 1000.0 + c as f64 * 17.0).sin() * 43_758.545).fract() - 0.5;
        (t * (c + 1) as f64).sin() + 0.2 * wobble
    });
    write_file(dir, "in.csv", &text)
}

#[test]
fn wavelet_filter_is_the_library_denoising_of_every_column() {
    let dir = tempfile::tempdir().unwrap();
    let input = noisy_record(dir.path());
    let out = dir.path().join("out.csv");
    let record = json_of(&[
        "filter",
        arg(&input),
        "--method",
        "wavelet",
        "--wavelet",
        "db6",
        "--level",
        "4",
        "--threshold",
        "sure",
        "--thresholding",
        "hard",
        "--extension",
        "periodization",
        "--out",
        arg(&out),
        "--json",
    ]);
    assert_eq!(record["method"], "wavelet");
    assert_eq!(
        (record["wavelet"].as_str(), record["level"].as_u64()),
        (Some("db6"), Some(4))
    );
    assert_eq!(record["threshold"], "sure");
    assert_eq!(record["rows_out"], 1001);
    assert_eq!(record["channels"]["gx"]["unit"], "rad/s");
    assert_eq!(
        record["channels"]["gx"]["thresholds_finest_first"]
            .as_array()
            .unwrap()
            .len(),
        4
    );
    let sidecar: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.csv.json")).unwrap())
            .unwrap();
    assert_eq!(sidecar, record, "the sidecar is the printed record");
    let settings = WaveletDenoise {
        wavelet: "db6".parse().unwrap(),
        level: DecompositionLevel::Fixed(4),
        mode: ExtensionMode::Periodization,
        rule: ThresholdRule::Sure,
        thresholding: Thresholding::Hard,
    };
    let (before, after) = (rows(&input), rows(&out));
    for c in 0..7 {
        let column: Vec<f64> = before.iter().map(|r| r[c]).collect();
        let want = if c == 0 {
            column.clone()
        } else {
            denoise(&column, &settings).unwrap().values
        };
        for (r, w) in after.iter().zip(&want) {
            // The CSV carries each value's shortest round-trip decimal: equal to the bit.
            assert_eq!(r[c], *w, "column {c}");
        }
    }
}

/// Runs `args` (whose output is `dir/out.csv`), expects exit `code` and no output; returns
/// stderr.
fn refused(dir: &Path, args: &[&str], code: i32) -> String {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, code, "{args:?}: {stderr}");
    assert!(
        stdout.is_empty() && !stderr.contains("panicked"),
        "{stderr}"
    );
    assert!(!dir.join("out.csv").exists() && !dir.join("out.csv.json").exists());
    stderr
}

#[test]
fn options_of_the_other_method_and_impossible_levels_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let input = noisy_record(dir.path());
    let out = dir.path().join("out.csv");
    let (i, o) = (arg(&input), arg(&out));
    let wavelet_with_kaiser = refused(
        dir.path(),
        &[
            "filter",
            i,
            "--cutoff-hz",
            "5",
            "--wavelet",
            "db2",
            "--level",
            "2",
            "--out",
            o,
        ],
        2,
    );
    assert!(
        wavelet_with_kaiser.contains("--wavelet, --level")
            && wavelet_with_kaiser.contains("--method kaiser"),
        "{wavelet_with_kaiser}"
    );
    let kaiser_with_wavelet = refused(
        dir.path(),
        &[
            "filter",
            i,
            "--method",
            "wavelet",
            "--decimate-to-hz",
            "10",
            "--out",
            o,
        ],
        2,
    );
    assert!(
        kaiser_with_wavelet.contains("--decimate-to-hz") && kaiser_with_wavelet.contains("Kaiser"),
        "{kaiser_with_wavelet}"
    );
    // 1001 rows with db4 (8 taps): dwt_max_level = floor(log2(1001 / 7)) = 7.
    let too_deep = refused(
        dir.path(),
        &[
            "filter", i, "--method", "wavelet", "--level", "8", "--out", o,
        ],
        2,
    );
    assert!(
        too_deep.contains("--level 8") && too_deep.contains("1..=7") && too_deep.contains("in.csv"),
        "{too_deep}"
    );
    let zero = refused(
        dir.path(),
        &[
            "filter", i, "--method", "wavelet", "--level", "0", "--out", o,
        ],
        2,
    );
    assert!(zero.contains("--level 0"), "{zero}");
    let unknown = refused(
        dir.path(),
        &[
            "filter",
            i,
            "--method",
            "wavelet",
            "--wavelet",
            "sym4",
            "--out",
            o,
        ],
        2,
    );
    assert!(unknown.contains("db1..db10"), "{unknown}");
    let no_cutoff = refused(dir.path(), &["filter", i, "--out", o], 2);
    assert!(no_cutoff.contains("--cutoff-hz"), "{no_cutoff}");
}

#[test]
fn a_record_too_short_for_one_level_is_a_data_error() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_file(dir.path(), "short.csv", &imu_csv(6, 100.0, |_, t| t));
    let out = dir.path().join("out.csv");
    let stderr = refused(
        dir.path(),
        &[
            "filter",
            arg(&input),
            "--method",
            "wavelet",
            "--out",
            arg(&out),
        ],
        1,
    );
    assert!(
        stderr.contains("short.csv") && stderr.contains("at least 7"),
        "{stderr}"
    );
}

#[test]
fn characterize_records_the_wavelet_denoiser_in_the_bank() {
    let dir = tempfile::tempdir().unwrap();
    let truth = chamber(dir.path());
    let file = truth["files"][0].as_str().unwrap().to_string();
    let bank_path = dir.path().join("bank.json");
    let args = [
        "characterize",
        &file,
        "--denoise",
        "wavelet",
        "--out",
        arg(&bank_path),
        "--json",
    ];
    json_of(&args);
    let bank: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&bank_path).unwrap()).unwrap();
    let preprocessing = &bank["entries"][0]["preprocessing"];
    assert!(preprocessing["filter"].is_null(), "{preprocessing}");
    assert_eq!(preprocessing["wavelet"]["wavelet"], "db4");
    assert_eq!(preprocessing["wavelet"]["threshold"], "universal");
    // 600 s at 50 Hz = 30 000 samples: floor(log2(30000 / 7)) = 12.
    assert_eq!(preprocessing["wavelet"]["level"], 12);
    assert_eq!(preprocessing["decimation_factor"], 50);
    let streamed = dir.path().join("streamed.json");
    let (status, _, stderr) = outcome(&thermonav(&[
        "characterize",
        &file,
        "--denoise",
        "wavelet",
        "--reading",
        "streaming",
        "--out",
        arg(&streamed),
    ]));
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--reading streaming") && !streamed.exists(),
        "{stderr}"
    );
}
