//! The noise model's source of a run or a tournament, read: a bank or a sensor profile, with the
//! thermal calibration of `--thermal-from` joined to it when given; and the notes on how the
//! bank's records differ from the IMU record it is used on ([`LoadedNoise::notes_on_record`]).

use crate::failure::Failure;
use crate::inputs::{load_profile, read_bank, read_thermal_calibration};
use crate::settings::navigation::NoiseSource;
use anyhow::anyhow;
use serde::Serialize;
use std::path::Path;
use thermonav::evaluation::experiment::CandidateSource;
use thermonav::imu::{Channel, SampleKind};
use thermonav::nav::run::NoiseModel;
use thermonav::sensor::SensorProfile;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::thermal::ThermalCalibration;
use thermonav::stoch::thermal::join::{ThermalJoinError, check_join};
use thermonav_io::imu::ImuOptions;
use thermonav_io::{ImuReader, Strictness};

/// The noise model's source, read.
pub enum LoadedNoise {
    /// A bank (with the calibration of `--thermal-from`, when given).
    Bank(ModelBank),
    /// A sensor profile.
    Profile(SensorProfile),
    /// A sensor profile with the calibration of `--thermal-from`.
    ProfileWithThermal(SensorProfile, ThermalCalibration),
}

/// Reads the bank or the profile, and joins the thermal calibration of `thermal_from` to it.
pub fn load_noise(
    noise: &NoiseSource,
    thermal_from: Option<&Path>,
) -> Result<LoadedNoise, Failure> {
    let thermal = thermal_from.map(read_thermal_calibration).transpose()?;
    let refused = |e: ThermalJoinError| {
        let (option, path) = match noise {
            NoiseSource::Bank(p) => ("--bank", p),
            NoiseSource::Profile(p) => ("--profile", p),
        };
        let from = thermal_from.map_or_else(String::new, |p| p.display().to_string());
        Failure::Usage(anyhow!(
            "--thermal-from {from} cannot join {option} {}: {e}",
            path.display()
        ))
    };
    match (noise, thermal) {
        (NoiseSource::Bank(path), None) => Ok(LoadedNoise::Bank(read_bank(path)?)),
        (NoiseSource::Bank(path), Some(thermal)) => Ok(LoadedNoise::Bank(
            read_bank(path)?
                .with_thermal_from(thermal)
                .map_err(refused)?,
        )),
        (NoiseSource::Profile(path), None) => Ok(LoadedNoise::Profile(load_profile(Some(path))?)),
        (NoiseSource::Profile(path), Some(thermal)) => {
            let profile = load_profile(Some(path))?;
            let units = Channel::ALL
                .iter()
                .filter(|c| profile.channel(**c).is_some())
                .map(|&c| (c, c.si_unit(SampleKind::Rates).to_string()))
                .collect();
            check_join(&units, &thermal).map_err(refused)?;
            Ok(LoadedNoise::ProfileWithThermal(profile, thermal))
        }
    }
}

impl LoadedNoise {
    /// Where a tournament's candidates come from.
    pub fn source(&self) -> CandidateSource<'_> {
        match self {
            LoadedNoise::Bank(bank) => CandidateSource::Bank(bank),
            LoadedNoise::Profile(profile) | LoadedNoise::ProfileWithThermal(profile, _) => {
                CandidateSource::Profile(profile)
            }
        }
    }

    /// Where a run's noise model comes from.
    pub fn model(&self) -> NoiseModel<'_> {
        match self {
            LoadedNoise::Bank(bank) => NoiseModel::Bank(bank),
            LoadedNoise::Profile(profile) => NoiseModel::Profile(profile),
            LoadedNoise::ProfileWithThermal(profile, thermal) => {
                NoiseModel::ProfileWithThermal(profile, thermal)
            }
        }
    }

    /// The bank's thermal calibration, if any.
    pub fn thermal(&self) -> Option<&ThermalCalibration> {
        self.model().thermal()
    }
}

/// How far the IMU record's sample rate may be from that of the records the bank was made from
/// before a note says so: 5 %. Clock errors and timestamp jitter move a nominal rate by well
/// under 1 %; another output-rate setting moves it by 20 % or more (100 to 125 Hz is the
/// smallest common step; the case, 100 to 152 Hz, is 52 %).
pub const RATE_TOLERANCE: f64 = 0.05;

/// Samples read from the start of the IMU record for its nominal rate (the median interval).
const RATE_SAMPLES: usize = 4096;

/// A note on the bank against the IMU record it is used on: a run goes on, the user is told.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordNote {
    /// What differs: `sample_rate`.
    pub differs: &'static str,
    /// The nominal rate of the bank's records, Hz (the farthest from the IMU's when its entries
    /// differ).
    pub bank_rate_hz: f64,
    /// The IMU record's nominal rate (median interval of its first samples), Hz.
    pub record_rate_hz: f64,
    /// The relative difference allowed without a note.
    pub tolerance: f64,
    /// The records the bank was made from (each entry's source).
    pub bank_sources: Vec<String>,
    /// The note in words.
    pub note: String,
}

impl LoadedNoise {
    /// Notes on how the bank's records differ from the IMU record at `imu` (read with
    /// `options`): its sample rate beyond [`RATE_TOLERANCE`]. None for a profile (it has no
    /// rate), nor when the record's first samples cannot be read (the run says why). Neither
    /// side carries a sensor's identity to compare (an IMU CSV has none; a bank has its
    /// records' file names), so the note names the bank's records.
    pub fn notes_on_record(&self, imu: &Path, options: &ImuOptions) -> Vec<RecordNote> {
        let LoadedNoise::Bank(bank) = self else {
            return vec![];
        };
        let Some(record_rate_hz) = record_rate_hz(imu, options) else {
            return vec![];
        };
        let farthest = (bank.entries.iter())
            .map(|e| e.preprocessing.input_rate_hz)
            .max_by(|a, b| relative(*a, record_rate_hz).total_cmp(&relative(*b, record_rate_hz)));
        match farthest {
            Some(bank_rate_hz) if relative(bank_rate_hz, record_rate_hz) > RATE_TOLERANCE => {
                let bank_sources = bank.entries.iter().map(|e| e.source.clone()).collect();
                vec![rate_note(bank_rate_hz, record_rate_hz, bank_sources)]
            }
            _ => vec![],
        }
    }
}

/// |a − b| / b.
fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b
}

/// The nominal rate of the first [`RATE_SAMPLES`] samples of the IMU record, Hz.
fn record_rate_hz(imu: &Path, options: &ImuOptions) -> Option<f64> {
    let reader = ImuReader::open_with(imu, Strictness::Strict, options).ok()?;
    let times: Vec<_> = (reader.take(RATE_SAMPLES))
        .map_while(Result::ok)
        .map(|s| s.time)
        .collect();
    let stats = thermonav::signal::timestamps::interval_stats(&times)?;
    Some(stats.nominal_rate_hz())
}

/// The note of a bank made at `bank_rate_hz` used on a record at `record_rate_hz`.
fn rate_note(bank_rate_hz: f64, record_rate_hz: f64, bank_sources: Vec<String>) -> RecordNote {
    let note = format!(
        "the bank was made from records at {bank_rate_hz:.1} Hz ({}), this IMU record runs at \
         {record_rate_hz:.1} Hz ({:+.0} %, beyond the {:.0} % tolerance): another output rate, and \
         perhaps another sensor or internal low-pass. The bank's noise model is in densities and \
         continuous time (white-noise densities in rad/sqrt(s) and m/s/sqrt(s), Gauss-Markov Tc \
         in s and sigma in rad/s or m/s^2), which the filter discretises at this record's own \
         intervals, so it carries over to {record_rate_hz:.1} Hz if the sensor and its filter are \
         the same; if they are not, characterize a static record of this one",
        bank_sources.join(", "),
        100.0 * (record_rate_hz / bank_rate_hz - 1.0),
        100.0 * RATE_TOLERANCE
    );
    RecordNote {
        differs: "sample_rate",
        bank_rate_hz,
        record_rate_hz,
        tolerance: RATE_TOLERANCE,
        bank_sources,
        note,
    }
}
