//! The modelling commands end to end: simulate, characterise, read the bank, Allan, AR, FIR.

use crate::{arg, outcome, thermonav, write_file};
use std::path::Path;

fn json_of(args: &[&str]) -> serde_json::Value {
    let (status, stdout, stderr) = outcome(&thermonav(args));
    assert_eq!(status, 0, "stderr: {stderr}");
    serde_json::from_str(&stdout).expect("stdout is one JSON document")
}

/// Two short chamber records (0 and 20 °C, 10 min at 50 Hz) in `dir`.
pub fn chamber(dir: &Path) -> serde_json::Value {
    let out = dir.join("chamber");
    json_of(&[
        "simulate",
        "chamber",
        "--out",
        arg(&out),
        "--temperatures-c",
        "0,20",
        "--duration-s",
        "600",
        "--rate-hz",
        "50",
        "--seed",
        "5",
        "--json",
    ])
}

// The CLI's fir output must be SciPy's design (tools/oracles/kaiser_fir.json, design 0 is the
// README example): same tap count and beta, taps within 1e-12.
#[test]
fn fir_json_is_the_scipy_design() {
    let oracle: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../thermonav/tests/data/kaiser_fir.json"
        ))
        .unwrap(),
    )
    .unwrap();
    let design = &oracle["designs"][0];
    let json = json_of(&[
        "fir",
        "--fs-hz",
        "200",
        "--cutoff-hz",
        "5",
        "--transition-hz",
        "1",
        "--ripple-db",
        "60",
        "--json",
    ]);
    assert_eq!(json["num_taps"], design["num_taps"]);
    assert!((json["beta"].as_f64().unwrap() - design["beta"].as_f64().unwrap()).abs() < 1e-12);
    let ours = json["taps"].as_array().unwrap();
    for (a, b) in ours.iter().zip(design["taps"].as_array().unwrap()) {
        assert!((a.as_f64().unwrap() - b.as_f64().unwrap()).abs() < 1e-12);
    }
    // Group delay (N − 1)/2 samples at 200 Hz.
    assert!(
        (json["group_delay_s"].as_f64().unwrap() - (ours.len() - 1) as f64 / 400.0).abs() < 1e-15
    );
}

#[test]
fn characterize_then_select_by_linear_interpolation() {
    let dir = tempfile::tempdir().unwrap();
    let truth = chamber(dir.path());
    assert_eq!(truth["temperatures"].as_array().unwrap().len(), 2);
    let files: Vec<String> = truth["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap().to_string())
        .collect();
    let bank = dir.path().join("bank.json");
    let mut args = vec!["characterize"];
    args.extend(files.iter().map(|f| f.as_str()));
    args.extend(["--out", arg(&bank), "--json"]);
    let summary = json_of(&args);
    // Temperatures come from the temp_c columns: the set points within the 0.05 °C wander.
    let temps: Vec<f64> = summary["temperatures_c"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    assert!(
        (temps[0] - 0.0).abs() < 0.5 && (temps[1] - 20.0).abs() < 0.5,
        "{temps:?}"
    );
    // Select at the midpoint with the AR-based family (always present here): the result is
    // the mean of the two entries' Tc (closed form of linear interpolation at weight ½).
    let mid = (temps[0] + temps[1]) / 2.0;
    let shown = json_of(&[
        "bank",
        "show",
        arg(&bank),
        "--at-temperature-c",
        &mid.to_string(),
        "--method",
        "linear",
        "--model",
        "ar-based",
        "--json",
    ]);
    let full = json_of(&["bank", "show", arg(&bank), "--json"]);
    let tc = |entry: usize| {
        full["entries"][entry]["channels"]["gx"]["gauss_markov"]["ar_based"]["correlation_time_s"]
            .as_f64()
            .unwrap()
    };
    let selected = shown["channels"]["gx"]["correlation_time_s"]
        .as_f64()
        .unwrap();
    assert!(
        (selected - (tc(0) + tc(1)) / 2.0).abs() < 1e-9 * selected,
        "{selected} vs {} and {}",
        tc(0),
        tc(1)
    );
    assert_eq!(full["version"], 2);
    // Issue 16: the same selection as text is a table, not Rust debug text: each channel's
    // row names its Tc in s and the two entries it lies between, with the weight ½.
    let mid_text = mid.to_string();
    let text_args = ["bank", "show", arg(&bank), "--at-temperature-c", &mid_text];
    let (status, stdout, stderr) = outcome(&thermonav(
        &[
            &text_args[..],
            &["--method", "linear", "--model", "ar-based"],
        ]
        .concat(),
    ));
    assert_eq!(status, 0, "{stderr}");
    assert!(
        stdout.contains("selection linear, model ar_based"),
        "{stdout}"
    );
    for debug_text in ["Between {", "ArBased", "Linear", "lower_c"] {
        assert!(!stdout.contains(debug_text), "{debug_text} in {stdout}");
    }
    let gx = stdout.lines().find(|l| l.starts_with("gx ")).unwrap();
    assert!(
        gx.contains("Tc ") && gx.contains("between") && gx.contains("(weight 0.500 on"),
        "{gx}"
    );
}

#[test]
fn allan_and_ar_json_follow_the_contract() {
    let dir = tempfile::tempdir().unwrap();
    let truth = chamber(dir.path());
    let file = truth["files"][0].as_str().unwrap().to_string();
    let allan = json_of(&["allan", &file, "--json"]);
    let gx = &allan["channels"]["gx"];
    assert_eq!(gx["unit"], "rad/s");
    let n_terms = gx["n_terms"].as_array().unwrap();
    let tau = gx["tau_s"].as_array().unwrap();
    assert_eq!(n_terms.len(), tau.len());
    for key in ["adev", "ci_low", "ci_high"] {
        assert!(
            gx[key]
                .as_array()
                .unwrap()
                .iter()
                .all(|v| v.as_f64().unwrap() > 0.0),
            "{key}"
        );
    }
    let arw = &gx["terms"]["random_walk"];
    assert_eq!(arw["unit"], "deg/sqrt(h)");
    assert_eq!(arw["bound"], "estimate");
    let value = arw["value"].as_f64().unwrap();
    assert!(arw["ci_low"].as_f64().unwrap() < value && value < arw["ci_high"].as_f64().unwrap());
    // Every term is either read or absent with its reason, never both, never neither.
    let terms = &gx["terms"];
    for key in [
        "quantization",
        "random_walk",
        "bias_instability",
        "rate_random_walk",
        "rate_ramp",
    ] {
        let reason = &terms["absent"][key];
        assert_ne!(terms[key].is_null(), reason.is_null(), "{key}: {terms}");
        assert!(reason.is_null() || !reason.as_str().unwrap().is_empty());
    }
    let ar = json_of(&[
        "ar",
        &file,
        "--method",
        "yule-walker",
        "--order",
        "2",
        "--json",
    ]);
    let az = &ar["channels"]["az"];
    assert_eq!(az["order"], 2);
    assert_eq!(az["coefficients"].as_array().unwrap().len(), 2);
    assert!(az["gauss_markov"]["status"].is_string());
}

#[test]
fn modelling_commands_refuse_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let not_a_bank = crate::write_file(dir.path(), "bank.json", "{\"hello\": 1}");
    let (status, _, stderr) = outcome(&thermonav(&["bank", "show", arg(&not_a_bank)]));
    assert_eq!(status, 1);
    assert!(
        stderr.contains("bank.json") && stderr.contains("not a model bank"),
        "{stderr}"
    );
    let imu = crate::write_file(
        dir.path(),
        "imu.csv",
        &crate::imu_csv(300, 100.0, |c, t| (c as f64 + t * 37.0).sin()),
    );
    assert_eq!(outcome(&thermonav(&["ar", arg(&imu), "--order", "0"])).0, 2);
    assert_eq!(
        outcome(&thermonav(&["ar", arg(&imu), "--order", "many"])).0,
        2
    );
    assert_eq!(
        outcome(&thermonav(&["allan", arg(&imu), "--confidence", "1.5"])).0,
        2
    );
    let out = dir.path().join("b.json");
    let (status, _, stderr) = outcome(&thermonav(&["characterize", arg(&imu), "--out", arg(&out)]));
    assert_eq!(
        status, 2,
        "no temp_c column and no --temperature-c: {stderr}"
    );
    assert!(!out.exists());
}

// A cold start: the IMU's temp_c follows T(t) = T_settled + (T_start − T_settled) exp(−t/τ)
// from the first sample (closed form, to the 1e-9 °C the CSV prints and more), and
// truth.json gives the true model on a 0.1 °C grid over the samples' temperatures, each
// repeatable bias the unit's curve b + c₁ΔT + c₂ΔT² at that temperature (closed form).
#[test]
fn a_warming_survey_follows_its_time_constant_and_states_its_truth() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v");
    let (status, _, stderr) = outcome(&thermonav(&[
        "simulate",
        "vessel",
        "--out",
        arg(&out),
        "--duration-s",
        "120",
        "--temperature-c",
        "20",
        "--warm-up-from-c",
        "0",
        "--warm-up-time-constant-s",
        "60",
    ]));
    assert_eq!(status, 0, "{stderr}");
    let rows = imu_rows(&out.join("imu.csv"));
    let t0 = rows[0][0];
    for row in rows.iter().step_by(997) {
        let expected = 20.0 - 20.0 * (-(row[0] - t0) / 60.0).exp();
        assert!(
            (row[7] - expected).abs() < 1e-6,
            "{} s: {} vs {expected}",
            row[0],
            row[7]
        );
    }
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("truth.json")).unwrap()).unwrap();
    let models = truth["models"].as_array().unwrap();
    let last_c = rows.last().unwrap()[7];
    assert_eq!(models[0]["temperature_c"].as_f64(), Some(0.0));
    assert!(models.last().unwrap()["temperature_c"].as_f64().unwrap() >= last_c);
    let curve = &truth["unit"]["repeatable_bias"]["gy"];
    let c: Vec<f64> = curve["coefficients"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let reference = curve["reference_temperature_c"].as_f64().unwrap();
    for m in models.iter().step_by(17) {
        let d = m["temperature_c"].as_f64().unwrap() - reference;
        let expected = c[0] + c[1] * d + c[2] * d * d;
        let got = m["channels"]["gy"]["repeatable_bias"].as_f64().unwrap();
        assert!(
            (got - expected).abs() <= 1e-15 * (1.0 + expected.abs()),
            "{got} vs {expected}"
        );
    }
}

/// The numbers of every data row of an IMU CSV.
fn imu_rows(path: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// Linear interpolation in a table with the end values held (the temperature file's rule).
fn table_at(table: &[(f64, f64)], t: f64) -> f64 {
    let after = table.partition_point(|&(x, _)| x <= t);
    match after {
        0 => table[0].1,
        n if n == table.len() => table[n - 1].1,
        n => {
            let ((x0, y0), (x1, y1)) = (table[n - 1], table[n]);
            y0 + (t - x0) / (x1 - x0) * (y1 - y0)
        }
    }
}

#[test]
fn a_survey_follows_its_temperature_file_and_refuses_a_bad_one() {
    let dir = tempfile::tempdir().unwrap();
    let table = [(0.0, -5.0), (60.0, 10.0), (100.0, 10.0), (130.0, 0.0)];
    let file = write_file(
        dir.path(),
        "temperature.csv",
        "t_s,temp_c\n0,-5\n60,10\n100,10\n130,0\n",
    );
    let out = dir.path().join("v");
    let simulate = |file: &Path, extra: &[&str]| {
        let mut args = vec![
            "simulate",
            "vessel",
            "--out",
            arg(&out),
            "--duration-s",
            "150",
        ];
        args.extend_from_slice(&["--temperature-file", arg(file)]);
        args.extend_from_slice(extra);
        outcome(&thermonav(&args))
    };
    let (status, _, stderr) = simulate(&file, &[]);
    assert_eq!(status, 0, "{stderr}");
    let rows = imu_rows(&out.join("imu.csv"));
    let t0 = rows[0][0];
    for row in rows.iter().step_by(101) {
        let expected = table_at(&table, row[0] - t0);
        assert!(
            (row[7] - expected).abs() < 1e-9,
            "{} s: {} vs {expected}",
            row[0],
            row[7]
        );
    }
    let truth = std::fs::read_to_string(out.join("truth.json")).unwrap();
    assert!(truth.contains("\"kind\": \"table\""), "{truth}");
    let bad = write_file(dir.path(), "bad.csv", "t_s,temp_c\n0,20\n10,400\n");
    let (status, _, stderr) = simulate(&bad, &[]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("bad.csv:3") && stderr.contains("-80 to 150"),
        "{stderr}"
    );
    let (status, _, stderr) = simulate(&dir.path().join("none.csv"), &[]);
    assert!(status == 1 && stderr.contains("none.csv"), "{stderr}");
    let (status, _, stderr) = simulate(&file, &["--warm-up-from-c", "0"]);
    assert!(
        status == 2 && stderr.contains("--warm-up-from-c"),
        "{stderr}"
    );
}

/// The generated white-FM series of `tools/oracles/allan_family.py` and allantools' curves of
/// it (`crates/thermonav/tests/data/allan_family.json`).
fn allan_family_white_fm() -> serde_json::Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../thermonav/tests/data/allan_family.json"
    ))
    .unwrap();
    serde_json::from_str::<serde_json::Value>(&text).unwrap()["generated"]["white_fm"].take()
}

/// The JSON array `v` as numbers.
fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

// `allan --kind mdev --json` on a record whose six channels are the white-FM series (5000
// samples at 10 Hz, written with Rust's shortest round-trip decimals, so read back bit for
// bit) must give allantools' mdev on the octave grid: same factors and term counts, values to
// 1e-9 relative (the library's tolerance; see tests/it/allan_family.rs). tdev carries the
// rate's unit times seconds: rad and m/s.
#[test]
fn allan_kind_mdev_json_is_allantools_mdev() {
    let fixture = allan_family_white_fm();
    let y = numbers(&fixture["y"]);
    let dir = tempfile::tempdir().unwrap();
    let file = write_file(
        dir.path(),
        "white.csv",
        &crate::imu_csv(y.len(), 10.0, |_, t| y[(t * 10.0).round() as usize]),
    );
    let doc = json_of(&["allan", arg(&file), "--kind", "mdev", "--json"]);
    assert_eq!(doc["kind"], "mdev");
    assert!(doc.get("confidence").is_none());
    let expected = &fixture["octave"]["mdev"];
    for channel in ["gx", "ay"] {
        let c = &doc["channels"][channel];
        assert_eq!(c["n_terms"], expected["n_terms"], "{channel}");
        let pairs = numbers(&c["mdev"])
            .into_iter()
            .zip(numbers(&expected["deviation"]));
        for (got, want) in pairs {
            assert!(
                (got / want - 1.0).abs() < 1e-9,
                "{channel}: {got} vs {want}"
            );
        }
        for (tau_s, m) in numbers(&c["tau_s"]).iter().zip(numbers(&expected["m"])) {
            assert!(
                (tau_s - m / 10.0).abs() < 1e-9 * tau_s,
                "{tau_s} s vs m = {m}"
            );
        }
    }
    let tdev = json_of(&["allan", arg(&file), "--kind", "tdev", "--json"]);
    assert_eq!(tdev["channels"]["gx"]["unit"], "rad");
    assert_eq!(tdev["channels"]["ax"]["unit"], "m/s");
    let got = numbers(&tdev["channels"]["gz"]["tdev"]);
    for (got, want) in got
        .iter()
        .zip(numbers(&fixture["octave"]["tdev"]["deviation"]))
    {
        assert!((got / want - 1.0).abs() < 1e-9, "tdev: {got} vs {want}");
    }
}

// Issue 15: `thermonav gmwm` on a simulated chamber record whose truth is known. Fitting
// WN + GM to the whole Haar wavelet variance recovers the simulated white-noise density of
// every channel within 5 % (the target the issue sets for the bank; the Allan slope method
// was 1.29-1.66x off on the demo's 0 °C record), the interval brackets it, and the implied
// wavelet variance has one value per scale. A bad --model is a usage error.
#[test]
fn gmwm_recovers_the_simulated_white_noise_density() {
    let dir = tempfile::tempdir().unwrap();
    let chamber = chamber(dir.path());
    let file = chamber["files"][1].as_str().unwrap().to_string();
    let truth_path = dir.path().join("chamber").join("truth.json");
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(truth_path).unwrap()).unwrap();
    let at_20 = &truth["temperatures"][1]["channels"];
    let args = [
        "gmwm",
        &file,
        "--model",
        "wn+gm",
        "--replicates",
        "20",
        "--json",
    ];
    let doc = json_of(&args);
    assert_eq!(doc["model"], "wn+gm");
    for (name, channel) in doc["channels"].as_object().unwrap() {
        let wv = &channel["wavelet_variance"];
        let scales = wv["scale_s"].as_array().unwrap().len();
        assert_eq!(wv["implied_unit2"].as_array().unwrap().len(), scales);
        let (key, p) = channel["parameters"]
            .as_object()
            .unwrap()
            .iter()
            .find(|(k, _)| k.starts_with("white_noise_density"))
            .unwrap();
        let value = p["value"].as_f64().unwrap();
        let simulated = at_20[name]["white_noise_density"].as_f64().unwrap();
        let ratio = value / simulated;
        assert!(
            (0.95..1.05).contains(&ratio),
            "{name} {key}: {value} vs {simulated}"
        );
        let (low, high) = (
            p["ci_low"].as_f64().unwrap(),
            p["ci_high"].as_f64().unwrap(),
        );
        assert!(
            low <= value && value <= high,
            "{name}: {low} {value} {high}"
        );
    }
    let (status, _, stderr) = outcome(&thermonav(&["gmwm", &file, "--model", "wn+xx"]));
    assert_eq!(status, 2, "{stderr}");
    assert!(stderr.contains("--model wn+xx"), "{stderr}");
}
