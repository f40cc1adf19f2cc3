//! Issue 38: the README's workflows are each one block of commands, run here as written by
//! `sh -e` from a folder laid out as the repository's root (links to its `bench`, `crates`
//! and `examples`, `../shared` beside it), with this build's `thermonav` first on the PATH.
//! The blocks' outputs land in that folder, never in the repository. The RTK workflow's test
//! is `references::readme_rtk_log_to_the_tournament`.

use crate::outcome;
use std::path::{Path, PathBuf};

/// The first `sh` block after `heading` in the README.
pub fn readme_block(heading: &str) -> String {
    let readme = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md");
    let text = std::fs::read_to_string(readme).unwrap();
    let (_, after) = text.split_once(heading).expect("the README's heading");
    let (_, block) = after
        .split_once("```sh\n")
        .expect("a block under the heading");
    let (block, _) = block.split_once("```").expect("the block's end");
    block.to_string()
}

/// A temporary folder `thermonav/` laid out as the repository's root, `shared` beside it.
pub struct Checkout {
    _dir: tempfile::TempDir,
    pub root: PathBuf,
}

/// A new [`Checkout`]: the root links to the repository's folders that the blocks read.
pub fn checkout() -> Checkout {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("thermonav");
    std::fs::create_dir(&root).unwrap();
    let repository = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for folder in ["bench", "crates", "examples"] {
        std::os::unix::fs::symlink(repository.join(folder), root.join(folder)).unwrap();
    }
    let shared = super::convert::shared_data("");
    let shared = shared.parent().unwrap();
    std::os::unix::fs::symlink(shared, dir.path().join("shared")).unwrap();
    Checkout { _dir: dir, root }
}

/// Runs the README's block under `heading` in `root` by `sh -e`, this build first on the
/// PATH; its stdout. Panics, with the block and its output, unless it exits 0.
pub fn run_block(root: &Path, heading: &str) -> String {
    let block = readme_block(heading);
    let binary = Path::new(env!("CARGO_BIN_EXE_thermonav"));
    let path = format!(
        "{}:{}",
        binary.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let run = std::process::Command::new("sh")
        .args(["-e", "-c", &block])
        .current_dir(root)
        .env("PATH", path)
        .output()
        .unwrap();
    let (status, stdout, stderr) = outcome(&run);
    assert_eq!(status, 0, "{block}\n{stdout}\n{stderr}");
    stdout
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The value of `key` in a Kalibr yaml, checked to carry `unit` in its comment.
fn kalibr_value(yaml: &str, key: &str, unit: &str) -> f64 {
    let line = yaml
        .lines()
        .find(|line| line.starts_with(&format!("{key}: ")))
        .unwrap_or_else(|| panic!("{key} in\n{yaml}"));
    assert!(line.contains(&format!("# [{unit}]")), "{line}");
    let value = line[key.len() + 2..].split_whitespace().next().unwrap();
    value.parse().unwrap()
}

/// The largest white-noise density (SI, per √Hz) among `channels` of the bank's only entry.
fn largest_white_noise(bank: &serde_json::Value, channels: [&str; 3]) -> f64 {
    let entry = &bank["entries"][0]["channels"];
    channels
        .map(|c| entry[c]["allan"]["white_noise_density"].as_f64().unwrap())
        .into_iter()
        .fold(f64::NEG_INFINITY, f64::max)
}

/// "A ROS bag to a Kalibr noise file": the io crate's test bag to a bank and a Kalibr
/// `imu.yaml` whose noise densities are the bank's largest per sensor, in Kalibr's units
/// (continuous time, SI per √Hz), with the topic and the bag's 10 Hz rate.
#[test]
fn readme_ros_bag_to_kalibr() {
    let checkout = checkout();
    run_block(&checkout.root, "### A ROS bag to a Kalibr noise file");
    let bank = json(&checkout.root.join("bank.json"));
    let yaml = std::fs::read_to_string(checkout.root.join("imu.yaml")).unwrap();
    let gyro = kalibr_value(&yaml, "gyroscope_noise_density", "rad/s/sqrt(Hz)");
    assert_eq!(gyro, largest_white_noise(&bank, ["gx", "gy", "gz"]));
    let accel = kalibr_value(&yaml, "accelerometer_noise_density", "m/s^2/sqrt(Hz)");
    assert_eq!(accel, largest_white_noise(&bank, ["ax", "ay", "az"]));
    assert!(kalibr_value(&yaml, "gyroscope_random_walk", "rad/s^2/sqrt(Hz)") > 0.0);
    assert!(kalibr_value(&yaml, "accelerometer_random_walk", "m/s^3/sqrt(Hz)") > 0.0);
    assert_eq!(kalibr_value(&yaml, "update_rate", "Hz"), 10.0);
    assert!(yaml.contains("rostopic: \"/imu/data\""), "{yaml}");
}

/// The `TC_*` names of a PX4 parameter file (QGroundControl's tab-separated form).
fn px4_names(params: &str) -> Vec<String> {
    let rows = params.lines().filter(|line| !line.starts_with('#'));
    rows.map(|line| {
        let fields: Vec<&str> = line.split('\t').collect();
        assert_eq!(fields.len(), 5, "{line}");
        fields[3].parse::<f64>().unwrap();
        fields[2].to_string()
    })
    .collect()
}

/// "A PX4 ULog sweep to PX4 thermal parameters": two days of the real CATS record written as
/// ULogs by the committed `bench/thermal_peers/cats_ulog.py`, the sweep's calibration shown,
/// checked against the other day and written as PX4 parameters (every `TC_G0_*` and `TC_A0_*`,
/// with the log's device ids) and as ArduPilot's `INS_TCAL1_*`.
#[test]
fn readme_ulog_sweep_to_px4_parameters() {
    let checkout = checkout();
    let stdout = run_block(
        &checkout.root,
        "### A PX4 ULog sweep to PX4 thermal parameters",
    );
    assert!(
        stdout.contains("bank.json against other_day.ulg"),
        "{stdout}"
    );
    let params = std::fs::read_to_string(checkout.root.join("thermal.params")).unwrap();
    let names = px4_names(&params);
    for sensor in ["G0", "A0"] {
        for suffix in ["ID", "TMIN", "TMAX", "TREF"] {
            assert!(names.contains(&format!("TC_{sensor}_{suffix}")), "{params}");
        }
        for k in 0..4 {
            for axis in 0..3 {
                let name = format!("TC_{sensor}_X{k}_{axis}");
                assert!(names.contains(&name), "{name}: {params}");
            }
        }
    }
    assert!(params.contains("TC_G0_ID\t2293768\t"), "{params}");
    assert!(params.contains("TC_A0_ID\t2293784\t"), "{params}");
    let param = std::fs::read_to_string(checkout.root.join("thermal.param")).unwrap();
    assert!(param.contains("\nINS_TCAL1_ENABLE,1\n"), "{param}");
}
