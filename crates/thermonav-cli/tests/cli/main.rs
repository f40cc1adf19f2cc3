//! End-to-end tests of the `thermonav` command: exit codes, error messages, outputs.

mod bad_input;
mod bag_folders;
mod bank_and_record;
mod bank_export;
mod commands;
mod convert;
mod convert_dataflash;
mod convert_ros;
mod convert_ulog;
mod denoise;
mod frictions;
mod gmwm_defaults;
mod lot;
mod modelling;
mod navigation;
mod noise_export;
mod oracle;
mod outside;
mod plots;
mod readme;
mod real_data;
mod references;
mod reliability;
mod report_page;
mod run_options;
mod run_parity;
mod runaway;
mod shapes;
mod shards;
mod slow_rover;
mod streaming;
mod streaming_integrate;
mod thermal;
mod thermal_sweeps;
mod thermal_ulog;
#[path = "../../../thermonav-io/tests/it/ulog_writer.rs"]
mod ulog_writer;
mod usage_first;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the binary with `args`, no stdin.
pub fn thermonav(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_thermonav"))
        .args(args)
        .output()
        .expect("the thermonav binary runs")
}

/// Exit code, stdout and stderr of a run.
pub fn outcome(output: &Output) -> (i32, String, String) {
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// Writes `text` to `dir/name` and returns the path.
pub fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("temporary file is writable");
    path
}

/// The canonical IMU header.
pub const IMU_HEADER: &str = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2";

/// A canonical IMU CSV at `rate_hz` whose channels are given by `value(channel, t_s)`.
pub fn imu_csv(rows: usize, rate_hz: f64, value: impl Fn(usize, f64) -> f64) -> String {
    let mut text = format!("{IMU_HEADER}\n");
    for k in 0..rows {
        let t = k as f64 / rate_hz;
        let _ = write!(text, "{t:.9}");
        for c in 0..6 {
            let _ = write!(text, ",{}", value(c, t));
        }
        text.push('\n');
    }
    text
}

/// Path of a string argument.
pub fn arg(path: &Path) -> &str {
    path.to_str().expect("temporary paths are UTF-8")
}

/// Names of the files in `dir`.
pub fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("readable dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A simulated 300 s vessel survey (imu.csv, gnss.csv, reference.csv) in `dir/v`.
pub fn vessel(dir: &Path) -> PathBuf {
    let out = dir.join("v");
    let args = [
        "simulate",
        "vessel",
        "--profile",
        "builtin:temperature-sensitive",
        "--duration-s",
        "300",
        "--out",
        arg(&out),
    ];
    let (status, _, stderr) = outcome(&thermonav(&args));
    assert_eq!(status, 0, "{stderr}");
    out
}

/// A reproducible standard normal stream (xorshift64 and Box-Muller).
pub struct Normal(pub u64);

impl Normal {
    /// A uniform draw in (0, 1).
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// A standard normal draw.
    pub fn sample(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}
