//! Model banks from static records: each file characterised whole in memory or streamed in
//! pieces (see [`crate::banks::streaming`]), the files in parallel, the bank written atomically.

use crate::args::ReadingArg;
use crate::banks::streaming::{characterize_streaming, streams, temperature_of};
use crate::failure::{Classify, Failure};
use crate::settings::characterization::BankJob;
use crate::thermal::calibration::{ThermalInputs, calibrate_bank};
use anyhow::anyhow;
use std::path::Path;
use thermonav::imu::ImuSeries;
use thermonav::stoch::bank::{ModelBank, TemperatureEntry};
use thermonav::stoch::characterize::{CharacterizeSettings, characterize};
use thermonav_io::ros::extract::TopicNames;
use thermonav_io::{FileSplit, ImuOptions, write_json_atomically};

/// Characterises one file, read as `imu` says (a bag's topics as `topics` choose), whole in
/// memory or streamed as `reading` says; the entry records the mounting.
pub fn characterize_file(
    path: &Path,
    given: Option<f64>,
    settings: &CharacterizeSettings,
    (reading, imu, spares): (ReadingArg, (&ImuOptions, &TopicNames), &SpareSeries),
) -> Result<TemperatureEntry, Failure> {
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let whole = crate::inputs::is_whole_log(path);
    let mut entry = match !whole && streams(path, reading) {
        true => characterize_streaming(path, given, settings, (&name, imu.0, imu.1))?,
        false => characterize_in_memory(path, given, settings, (&name, imu, spares))?,
    };
    entry.imu_rotation = crate::settings::imu::rotation_text(imu.0);
    Ok(entry)
}

/// Characterises one file (a CSV, a bag or a DataFlash log) read whole; `name` is its source label.
fn characterize_in_memory(
    path: &Path,
    given: Option<f64>,
    settings: &CharacterizeSettings,
    (name, imu, spares): (&str, (&ImuOptions, &TopicNames), &SpareSeries),
) -> Result<TemperatureEntry, Failure> {
    let series = crate::inputs::read_imu_input_into(path, imu, spares.take())?;
    let temperature_c = temperature_of(given, series.mean_temperature_c(), path)?;
    let (entry, _) = characterize(&series, temperature_c, name, settings)
        .map_err(|e| anyhow!("{}: {e}", path.display()))
        .data()?;
    spares.give(series);
    Ok(entry)
}

/// The series of records already characterised, kept for the next records to be read into
/// (at most one per record in flight: as many as the pool has threads).
#[derive(Debug, Default)]
pub struct SpareSeries(std::sync::Mutex<Vec<ImuSeries>>);

impl SpareSeries {
    /// A series done with, if any.
    fn take(&self) -> Option<ImuSeries> {
        self.0.lock().ok()?.pop()
    }

    /// Keeps `series` for a later record.
    fn give(&self, series: ImuSeries) {
        if let Ok(mut spares) = self.0.lock() {
            spares.push(series);
        }
    }
}

/// Builds the bank of a job and writes it atomically.
pub fn build_job_bank(job: &BankJob) -> Result<ModelBank, Failure> {
    let files: Vec<&Path> = job.files.iter().map(|p| p.as_path()).collect();
    let inputs = BankInputs {
        files: &files,
        temperatures: &job.temperatures_c,
        thermal: &job.thermal,
    };
    build_bank_reading(&inputs, &job.conditioning, job.reading, &job.out)
}

/// The records a bank is built from, and its thermal calibration's further inputs.
pub struct BankInputs<'a> {
    /// One static record per temperature.
    pub files: &'a [&'a Path],
    /// Their temperatures, °C (empty: each file's mean temp_c).
    pub temperatures: &'a [f64],
    /// Further power-ons and sweeps.
    pub thermal: &'a ThermalInputs,
}

/// Builds the bank of `files` (in parallel) and writes it atomically.
pub fn build_bank(
    files: &[&Path],
    temperatures: &[f64],
    settings: &CharacterizeSettings,
    out: &Path,
) -> Result<ModelBank, Failure> {
    let inputs = BankInputs {
        files,
        temperatures,
        thermal: &ThermalInputs::default(),
    };
    build_bank_reading(&inputs, settings, ReadingArg::Auto, out)
}

/// [`build_bank`] with each file read as `reading` says, and the thermal calibration.
pub fn build_bank_reading(
    inputs: &BankInputs<'_>,
    settings: &CharacterizeSettings,
    reading: ReadingArg,
    out: &Path,
) -> Result<ModelBank, Failure> {
    use rayon::prelude::*;
    let (files, temperatures) = (inputs.files, inputs.temperatures);
    if files.is_empty() {
        let calibration = crate::thermal::sweeps::calibrate_sweeps_alone(inputs.thermal)?;
        let bank = ModelBank::thermal_only(calibration);
        write_json_atomically(out, &bank).data()?;
        return Ok(bank);
    }
    // Several records are read side by side on the pool, each in one pass; one record alone
    // in two halves at once.
    let imu = ImuOptions {
        split: match files.len() {
            0 | 1 => FileSplit::TwoHalves,
            _ => FileSplit::OnePass,
        },
        ..inputs.thermal.imu
    };
    let progress = crate::progress::bar(files.len(), "characterising static records");
    let spares = SpareSeries::default();
    let entries: Vec<Result<TemperatureEntry, Failure>> = files
        .par_iter()
        .enumerate()
        .map(|(k, path)| {
            let given = temperatures.get(k).copied();
            let read = (&imu, &inputs.thermal.topics);
            let entry = characterize_file(path, given, settings, (reading, read, &spares));
            progress.inc(1);
            entry
        })
        .collect();
    progress.finish_and_clear();
    let entries = entries.into_iter().collect::<Result<Vec<_>, _>>()?;
    let mut bank = ModelBank::new(entries).data()?;
    bank.thermal = calibrate_bank(&bank, inputs.thermal)?;
    write_json_atomically(out, &bank).data()?;
    Ok(bank)
}
