//! Readers for the oracle files in `shared/data` and the generated `tests/data/allan.json`.

use std::io::{BufRead, BufReader, Read};
use std::path::PathBuf;

use flate2::read::GzDecoder;

/// Path of a file under `shared/data` (the repository and `shared/` are siblings).
pub fn shared(relative: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data")).join(relative)
}

fn open_text(relative: &str) -> Box<dyn BufRead> {
    let path = shared(relative);
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    if relative.ends_with(".gz") {
        Box::new(BufReader::with_capacity(1 << 20, GzDecoder::new(file)))
    } else {
        Box::new(BufReader::new(file))
    }
}

/// All lines of a (possibly gzipped) text file.
pub fn lines(relative: &str) -> Vec<String> {
    open_text(relative).lines().map(|l| l.unwrap()).collect()
}

/// A one-column data file: `#` comment lines and blank lines skipped.
pub fn column(relative: &str) -> Vec<f64> {
    lines(relative)
        .iter()
        .map(|l| l.trim())
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect()
}

/// Frequency differences of a phase series: y_i = (x_{i+1} - x_i) / tau0.
pub fn phase_to_frequency(x: &[f64], tau0_s: f64) -> Vec<f64> {
    x.windows(2).map(|w| (w[1] - w[0]) / tau0_s).collect()
}

/// The Stable32 data sets used below: result file, series as fractional frequency, tau0.
pub struct Stable32Set {
    pub name: &'static str,
    pub result_file: &'static str,
    pub y: Vec<f64>,
    pub tau0_s: f64,
}

fn ocxo_fractional_frequency() -> Vec<f64> {
    // Stable32 analysed f / 1e7 - 1 (allantools' frequency2fractional, mean_frequency = 1e7).
    column("allantools/ocxo/ocxo_frequency.txt")
        .iter()
        .map(|f| f / 1e7 - 1.0)
        .collect()
}

/// The six runs with Stable32 OADEV confidence limits (octave, or decade for the Cs clock).
pub fn stable32_ci_sets() -> Vec<Stable32Set> {
    let phase = |f: &str| phase_to_frequency(&column(f), 1.0);
    vec![
        Stable32Set {
            name: "ocxo",
            result_file: "allantools/ocxo/oadev_octave.txt",
            y: ocxo_fractional_frequency(),
            tau0_s: 1.0,
        },
        Stable32Set {
            name: "pink",
            result_file: "allantools/pink_frequency/s32_oadev_octave.txt",
            y: column("allantools/pink_frequency/pink_frequency.txt"),
            tau0_s: 1.0,
        },
        Stable32Set {
            name: "phasedat",
            result_file: "allantools/phasedat/phase_dat_oadev_octave.txt",
            y: phase("allantools/phasedat/PHASE.DAT"),
            tau0_s: 1.0,
        },
        Stable32Set {
            name: "tic",
            result_file: "allantools/Keysight53230A_ti_noise_floor/tic_oadev.txt",
            y: phase("allantools/Keysight53230A_ti_noise_floor/tic_phase.txt"),
            tau0_s: 1.0,
        },
        Stable32Set {
            name: "gps",
            result_file: "allantools/gps/stable32_OADEV_octave.txt",
            y: phase("allantools/gps/gps_1pps_phase_data.txt.gz"),
            tau0_s: 1.0,
        },
        Stable32Set {
            name: "cs5071a",
            result_file: "allantools/Cs5071A/oadev_decade.txt",
            y: phase("allantools/Cs5071A/5071A_phase.txt.gz"),
            tau0_s: 1.0,
        },
    ]
}

/// Runs with Stable32 OADEV values (no limits) at every tau or octave, for the deviation itself.
pub fn stable32_value_sets() -> Vec<Stable32Set> {
    let phase = |f: &str| phase_to_frequency(&column(f), 1.0);
    vec![
        Stable32Set {
            name: "ocxo all tau",
            result_file: "allantools/ocxo/stable32_oadev_alltau.txt",
            y: ocxo_fractional_frequency(),
            tau0_s: 1.0,
        },
        Stable32Set {
            // tau0 = 42 s; Stable32 prints Tau with 5 digits, so tau is checked as AF * tau0.
            name: "pink all tau",
            result_file: "allantools/pink_frequency/oadev.txt",
            y: column("allantools/pink_frequency/pink_frequency.txt"),
            tau0_s: 42.0,
        },
        Stable32Set {
            name: "PHASE.DAT all tau",
            result_file: "allantools/phasedat/phase_dat_oadev.txt",
            y: phase("allantools/phasedat/PHASE.DAT"),
            tau0_s: 1.0,
        },
        Stable32Set {
            name: "Cs 5071A all tau",
            result_file: "allantools/Cs5071A/oadev_all.txt",
            y: phase("allantools/Cs5071A/5071A_phase.txt.gz"),
            tau0_s: 1.0,
        },
    ]
}

/// One data row of a Stable32 result file: `AF Tau # Alpha MinSigma Sigma MaxSigma`.
#[derive(Debug, Clone, Copy)]
pub struct Stable32Row {
    pub m: usize,
    pub tau_s: f64,
    pub n_terms: usize,
    pub alpha: i32,
    pub min_sigma: f64,
    pub sigma: f64,
    pub max_sigma: f64,
}

pub fn stable32_rows(relative: &str) -> Vec<Stable32Row> {
    lines(relative)
        .iter()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            Stable32Row {
                m: f[0].parse().unwrap(),
                tau_s: f[1].parse().unwrap(),
                n_terms: f[2].parse().unwrap(),
                alpha: f[3].parse().unwrap(),
                min_sigma: f[4].parse().unwrap(),
                sigma: f[5].parse().unwrap(),
                max_sigma: f[6].parse().unwrap(),
            }
        })
        .collect()
}

/// The JSON written by `tools/oracles/allan.py`.
pub fn oracle_json() -> serde_json::Value {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/allan.json");
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The six columns of the ADIS16405 static run 1 (deg/s and g), 1 000 000 rows at 100 Hz.
pub fn adis16405_run1() -> (Vec<String>, Vec<Vec<f64>>) {
    let mut reader = open_text("smac-imudata/adis_16405_imu1.csv.gz");
    let mut text = String::new();
    reader.read_to_string(&mut text).unwrap();
    let mut rows = text.lines();
    let names: Vec<String> = rows.next().unwrap().split(',').map(String::from).collect();
    let mut columns = vec![Vec::with_capacity(1_000_000); names.len()];
    for row in rows {
        for (column, field) in columns.iter_mut().zip(row.split(',')) {
            column.push(field.parse::<f64>().unwrap());
        }
    }
    (names, columns)
}
