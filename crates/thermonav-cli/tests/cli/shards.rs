//! `evaluate --shard I/N` and `evaluate merge`: three shards merged give the files of one
//! unsharded run byte for byte; the merge refuses a missing shard, a shard twice, and shards
//! of other settings or inputs, naming the files.

use crate::navigation::inputs;
use crate::{arg, files_in, outcome};
use std::path::{Path, PathBuf};
use std::process::Command;

/// `evaluate` on the vessel run (EKF, two 30 s outages, 3 replicates) into `out`, with
/// `extra`.
fn evaluate(vessel: &Path, bank: &Path, out: &Path, extra: &[&str]) -> Command {
    let files = ["imu.csv", "gnss.csv", "reference.csv"].map(|f| vessel.join(f));
    let mut command = Command::new(env!("CARGO_BIN_EXE_thermonav"));
    command
        .args([
            "evaluate",
            "--imu",
            arg(&files[0]),
            "--gnss",
            arg(&files[1]),
        ])
        .args(["--reference", arg(&files[2]), "--bank", arg(bank)])
        .args(["--filter", "ekf", "--outages", "60+30,150+30"])
        .args([
            "--monte-carlo",
            "3",
            "--lever-arm-m",
            "0.3,0,-2.5",
            "--quiet",
        ])
        .args(["--out", arg(out)])
        .args(extra)
        .env_remove("SLURM_ARRAY_TASK_ID");
    command
}

/// Runs `command`, expecting exit 0.
fn succeeds(command: &mut Command) -> String {
    let (status, stdout, stderr) = outcome(&command.output().unwrap());
    assert_eq!(status, 0, "stderr: {stderr}");
    stdout
}

/// `evaluate merge SHARDS... --out OUT`.
fn merge(shards: &[&Path], out: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_thermonav"));
    command.args(["evaluate", "merge"]);
    command.args(shards.iter().map(|p| arg(p)));
    command.args(["--out", arg(out), "--quiet"]);
    command
}

/// Every file under `dir` (evaluation.json and errors/*.csv) with its bytes.
fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files = vec![(
        "evaluation.json".to_string(),
        std::fs::read(dir.join("evaluation.json")).unwrap(),
    )];
    for name in files_in(&dir.join("errors")) {
        let bytes = std::fs::read(dir.join("errors").join(&name)).unwrap();
        files.push((format!("errors/{name}"), bytes));
    }
    files
}

/// The three shards of the vessel tournament under `dir/shards` (shard 2 from
/// $SLURM_ARRAY_TASK_ID with `auto/3`).
fn three_shards(dir: &Path, bank: &Path, vessel: &Path) -> PathBuf {
    let shards = dir.join("shards");
    for shard in ["1/3", "3/3"] {
        succeeds(&mut evaluate(vessel, bank, &shards, &["--shard", shard]));
    }
    let mut auto = evaluate(vessel, bank, &shards, &["--shard", "auto/3", "--json"]);
    let written = succeeds(auto.env("SLURM_ARRAY_TASK_ID", "2"));
    let json: serde_json::Value = serde_json::from_str(&written).unwrap();
    assert_eq!(
        (json["shard_index"].as_u64(), json["shard_count"].as_u64()),
        (Some(2), Some(3))
    );
    // Round robin: shard 2 of 3 holds the runs k = 1, 4, 7, ... of the total.
    let (runs, total) = (
        json["runs"].as_u64().unwrap(),
        json["total_runs"].as_u64().unwrap(),
    );
    assert!(total >= 9 && runs == (total + 1) / 3, "{runs} of {total}");
    shards
}

// The oracle is the unsharded run itself: the merge of its three shards must write the same
// bytes (evaluation.json names its own path, so both are written to the same --out).
#[test]
fn three_shards_merged_write_the_unsharded_files_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("out");
    succeeds(&mut evaluate(&vessel, &bank, &out, &[]));
    let single = tree(&out);
    std::fs::rename(&out, dir.path().join("single")).unwrap();
    let shards = three_shards(dir.path(), &bank, &vessel);
    assert_eq!(
        files_in(&shards),
        [
            "shard-1-of-3.json",
            "shard-2-of-3.json",
            "shard-3-of-3.json"
        ]
    );
    succeeds(&mut merge(&[&shards], &out));
    let merged = tree(&out);
    assert!(single.len() > 3, "{} files", single.len());
    assert_eq!(
        single.iter().map(|f| &f.0).collect::<Vec<_>>(),
        merged.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    for ((name, a), (_, b)) in single.iter().zip(&merged) {
        assert!(
            a == b,
            "{name} differs between the unsharded run and the merge"
        );
    }
    let report: serde_json::Value = serde_json::from_slice(&merged[0].1).unwrap();
    assert_eq!(report["significance"]["replicates"], 3);
}

/// `merge` fails with exit 1, `needles` in its message, and writes nothing.
fn merge_fails(shards: &[&Path], out: &Path, needles: &[&str]) {
    let (status, _, stderr) = outcome(&merge(shards, out).output().unwrap());
    assert_eq!(status, 1, "stderr: {stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "{needle:?} not in: {stderr}");
    }
    assert!(!out.join("evaluation.json").exists());
}

#[test]
fn merge_refuses_missing_duplicate_and_foreign_shards() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let shards = three_shards(dir.path(), &bank, &vessel);
    let [one, two, three] = [1, 2, 3].map(|i| shards.join(format!("shard-{i}-of-3.json")));
    let out = dir.path().join("merged");
    merge_fails(&[&one, &three], &out, &["shard 2/3 is missing"]);
    let again = dir.path().join("again");
    std::fs::create_dir(&again).unwrap();
    let copy = again.join("shard-1-of-3.json");
    std::fs::copy(&one, &copy).unwrap();
    let copy_name = copy.display().to_string();
    let needles = [
        "shard 1/3 is given twice",
        &one.display().to_string(),
        &copy_name,
    ];
    merge_fails(&[&shards, &again], &out, &needles);
    // Another seed: other settings.
    let seeded = dir.path().join("seeded");
    succeeds(&mut evaluate(
        &vessel,
        &bank,
        &seeded,
        &["--shard", "2/3", "--seed", "9"],
    ));
    let other = seeded.join("shard-2-of-3.json");
    let other_name = other.display().to_string();
    merge_fails(
        &[&one, &other, &three],
        &out,
        &["different settings", &other_name],
    );
    // The same bank with one more byte: other inputs.
    let changed = dir.path().join("bank-copy.json");
    let mut text = std::fs::read(&bank).unwrap();
    text.push(b'\n');
    std::fs::write(&changed, text).unwrap();
    let foreign = dir.path().join("foreign");
    succeeds(&mut evaluate(
        &vessel,
        &changed,
        &foreign,
        &["--shard", "3/3"],
    ));
    let foreign_file = foreign.join("shard-3-of-3.json");
    let needles = [
        "different --bank (file contents)",
        &foreign_file.display().to_string(),
    ];
    merge_fails(&[&one, &two, &foreign_file], &out, &needles);
    // Not a shard file: named, with serde's line and column.
    let bad = dir.path().join("bad");
    std::fs::create_dir(&bad).unwrap();
    std::fs::write(bad.join("shard-1-of-1.json"), "{\n\"tournament\": 3}\n").unwrap();
    merge_fails(
        &[&bad],
        &out,
        &["shard-1-of-1.json: not a shard file", "line 2"],
    );
}

#[test]
fn evaluate_refuses_a_bad_shard() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("out");
    for (shard, needle) in [
        ("0/3", "1..=3"),
        ("4/3", "1..=3"),
        ("x/3", "not a whole number"),
        ("3", "expected I/N"),
        ("auto/3", "SLURM_ARRAY_TASK_ID is not set"),
    ] {
        let output = evaluate(&vessel, &bank, &out, &["--shard", shard]).output();
        let (status, _, stderr) = outcome(&output.unwrap());
        assert_eq!(status, 2, "--shard {shard}: {stderr}");
        assert!(stderr.contains(needle), "--shard {shard}: {stderr}");
        assert!(!out.exists());
    }
}

/// The shard file at `path` with `edit` applied to its JSON, written to `to`.
fn edited_shard(path: &Path, to: &Path, edit: impl Fn(&mut serde_json::Value)) -> PathBuf {
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    edit(&mut json);
    std::fs::create_dir_all(to.parent().unwrap()).unwrap();
    std::fs::write(to, serde_json::to_vec(&json).unwrap()).unwrap();
    to.to_path_buf()
}

/// Every run's stored metrics of a shard's JSON.
fn each_metrics(json: &mut serde_json::Value, set: impl Fn(&mut serde_json::Value)) {
    for run in json["tournament"]["runs"].as_array_mut().unwrap() {
        if let Some(metrics) = run["outcome"]["Ok"].get_mut("metrics") {
            set(metrics);
        }
    }
}

// Issue 37 rows 12 and 13, and the minor point on negative RMS: shards edited to absurd
// counts or figures are refused before anything is allocated or written.
#[test]
fn merge_refuses_edited_shards_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let shards = three_shards(dir.path(), &bank, &vessel);
    let [one, two, three] = [1, 2, 3].map(|i| shards.join(format!("shard-{i}-of-3.json")));
    let out = dir.path().join("merged");
    let edits = dir.path().join("edits");
    // A count of 2^63: it panicked with "capacity overflow".
    let huge = edited_shard(&one, &edits.join("huge/shard-1-of-3.json"), |j| {
        j["tournament"]["shard"]["count"] = serde_json::json!(1_u64 << 63);
    });
    merge_fails(&[&huge], &out, &["shard 2/9223372036854775808 is missing"]);
    // A frame that stands for more runs than the shard holds.
    let frame = edited_shard(&one, &edits.join("frame/shard-1-of-1.json"), |j| {
        j["tournament"]["shard"]["count"] = serde_json::json!(1);
        j["tournament"]["frame"]["replicates"] = serde_json::json!(1_u64 << 62);
    });
    merge_fails(&[&frame], &out, &["but their frame stands for"]);
    // A negative RMS.
    let negative = edited_shard(&one, &edits.join("negative/shard-1-of-3.json"), |j| {
        each_metrics(j, |m| m["rms_north_m"] = serde_json::json!(-1.0));
    });
    merge_fails(&[&negative, &two, &three], &out, &["rms_north_m is -1"]);
    // 1.7e308 is finite, but the summaries over replicates overflow: refused before any
    // error table is written (it left five errors/*.csv without evaluation.json).
    let overflowing = edited_shard(&one, &edits.join("overflow/shard-1-of-3.json"), |j| {
        each_metrics(j, |m| m["rms_horizontal_m"] = serde_json::json!(1.7e308));
    });
    merge_fails(&[&overflowing, &two, &three], &out, &["NaN or infinity"]);
    assert!(!out.join("errors").exists() || files_in(&out.join("errors")).is_empty());
}

#[test]
fn evaluate_refuses_more_shards_than_runs() {
    let dir = tempfile::tempdir().unwrap();
    let (bank, vessel) = inputs(dir.path());
    let out = dir.path().join("out");
    let output = evaluate(&vessel, &bank, &out, &["--shard", "1/1000000000"]).output();
    let (status, _, stderr) = outcome(&output.unwrap());
    assert_ne!(status, 0, "{stderr}");
    assert!(
        stderr.contains("shard count 1000000000") && stderr.contains("at most"),
        "{stderr}"
    );
    assert!(!out.join("shard-1-of-1000000000.json").exists());
}
