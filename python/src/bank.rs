//! `characterize` and `load_bank`: a temperature model bank built as `thermonav characterize`
//! builds it (the same library calls, in the same order), written as the same JSON text.

use crate::arrays::{check_finite, check_increasing};
use crate::error;
use crate::records::file_name;
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use std::path::PathBuf;
use thermonav::geo::gravity::normal_gravity_m_s2;
use thermonav::imu::{ImuSeries, SampleKind};
use thermonav::stoch::bank::{ModelBank, TemperatureEntry};
use thermonav::stoch::characterize::{CharacterizeSettings, characterize as characterize_series};
use thermonav::stoch::thermal::{
    DEFAULT_SITE_HEIGHT_M, DEFAULT_SITE_LATITUDE_DEG, bank_power_on, calibrate_level_unit,
};
use thermonav::time::Timestamp;
use thermonav_io::imu::channel_column_names;
use thermonav_io::{Strictness, finite_json_pretty, read_imu_file};

/// A static record to characterise: a canonical IMU CSV, or arrays already in memory.
enum Record {
    /// A file, read strictly as the CLI reads it.
    File(PathBuf),
    /// A series named `source` (the bank's `source`).
    Arrays {
        /// Its name.
        source: String,
        /// Its samples.
        series: ImuSeries,
    },
}

impl Record {
    /// The record, its temperature (given, or the mean of its temp_c) and its entry.
    fn entry(
        &self,
        given: Option<f64>,
        settings: &CharacterizeSettings,
    ) -> Result<TemperatureEntry, String> {
        let (name, series) = match self {
            Record::File(path) => (
                file_name(path),
                read_imu_file(path, Strictness::Strict).map_err(|e| e.to_string())?,
            ),
            Record::Arrays { source, series } => (source.clone(), series.clone()),
        };
        let label = self.label();
        let temperature_c = temperature_of(&label, &series, given)?;
        let (entry, _) = characterize_series(&series, temperature_c, &name, settings)
            .map_err(|e| format!("{label}: {e}"))?;
        Ok(entry)
    }

    /// How errors name the record: its path, or its source.
    fn label(&self) -> String {
        match self {
            Record::File(path) => path.display().to_string(),
            Record::Arrays { source, .. } => source.clone(),
        }
    }
}

/// The temperature of a record: given, or the mean of its temp_c column.
fn temperature_of(label: &str, series: &ImuSeries, given: Option<f64>) -> Result<f64, String> {
    if let Some(t) = given {
        return Ok(t);
    }
    let mean = series.mean_temperature_c().ok_or_else(|| {
        format!("{label}: no temp_c column; give the temperature with temperatures_c")
    })?;
    thermonav_io::check_characterization_temperature(&format!("{label}: the mean of temp_c"), mean)
}

/// A float64 column of a record's mapping.
fn column(record: &Bound<'_, PyDict>, source: &str, name: &str) -> PyResult<Option<Vec<f64>>> {
    let Some(value) = record.get_item(name)? else {
        return Ok(None);
    };
    let values: PyReadonlyArray1<'_, f64> = value.extract().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{source}: {name}: expected a 1-D float64 NumPy array"
        ))
    })?;
    let values = values.as_array().to_vec();
    check_finite(&format!("{source}: {name}"), &values)?;
    Ok(Some(values))
}

/// The times of a record's mapping: `t_ns` (int64, exact) or `t_s` (float64 seconds).
fn times(record: &Bound<'_, PyDict>, source: &str) -> PyResult<Vec<Timestamp>> {
    if let Some(t_ns) = record.get_item("t_ns")? {
        let t_ns: PyReadonlyArray1<'_, i64> = t_ns.extract()?;
        return Ok(t_ns
            .as_array()
            .iter()
            .map(|&t| Timestamp::from_nanos(t))
            .collect());
    }
    let t_s = column(record, source, "t_s")?
        .ok_or_else(|| error(format!("{source}: expected a t_s or t_ns column")))?;
    (t_s.iter())
        .map(|&t| Timestamp::from_seconds(t).map_err(error))
        .collect()
}

/// A series of rates from a mapping of arrays named like the IMU CSV (`read_imu`'s result).
fn series_of(record: &Bound<'_, PyDict>, k: usize) -> PyResult<Record> {
    let source = match record.get_item("source")? {
        Some(s) => s.extract::<String>()?,
        None => format!("record {k}"),
    };
    let mut series = ImuSeries::new(SampleKind::Rates);
    series.time = times(record, &source)?;
    check_increasing(&format!("{source}: time"), &series.time)?;
    for (slot, name) in channel_column_names(SampleKind::Rates)
        .into_iter()
        .enumerate()
    {
        let values = column(record, &source, name)?
            .ok_or_else(|| error(format!("{source}: expected a {name} column (rates in SI)")))?;
        if values.len() != series.time.len() {
            return Err(error(format!(
                "{source}: {name} has {} samples for {} times",
                values.len(),
                series.time.len()
            )));
        }
        series.channels[slot] = values;
    }
    series.temperature_c = column(record, &source, "temp_c")?;
    Ok(Record::Arrays { source, series })
}

/// The records of `records`: paths, or mappings of arrays.
fn records_of(records: &Bound<'_, PyAny>) -> PyResult<Vec<Record>> {
    let mut out = Vec::new();
    for (k, item) in records.try_iter()?.enumerate() {
        let item = item?;
        match item.cast::<PyDict>() {
            Ok(mapping) => out.push(series_of(mapping, k)?),
            Err(_) => out.push(Record::File(item.extract::<PathBuf>()?)),
        }
    }
    Ok(out)
}

/// The given temperatures: one per record, each in the characterised range.
fn given_temperatures(given: Option<Vec<f64>>, records: usize) -> Result<Vec<Option<f64>>, String> {
    let Some(given) = given else {
        return Ok(vec![None; records]);
    };
    if given.len() != records {
        return Err(format!(
            "temperatures_c has {} values for {records} records",
            given.len()
        ));
    }
    (given.iter())
        .map(|&t| thermonav_io::check_characterization_temperature("temperatures_c", t).map(Some))
        .collect()
}

/// The bank of `records` (in parallel) with its own thermal calibration, and the notes the CLI
/// prints on stderr.
fn build(
    records: &[Record],
    temperatures: &[Option<f64>],
    settings: &CharacterizeSettings,
    gravity_m_s2: f64,
) -> Result<(ModelBank, Vec<String>), String> {
    let entries: Vec<Result<TemperatureEntry, String>> = (records.par_iter().zip(temperatures))
        .map(|(record, &given)| record.entry(given, settings))
        .collect();
    let entries = entries.into_iter().collect::<Result<Vec<_>, _>>()?;
    let mut bank = ModelBank::new(entries).map_err(|e| e.to_string())?;
    let mut notes = Vec::new();
    bank.thermal = match calibrate_level_unit(vec![bank_power_on(&bank)], gravity_m_s2) {
        Ok(calibration) => calibration,
        Err(e) => {
            notes.push(format!("no thermal calibration: {e}"));
            None
        }
    };
    Ok((bank, notes))
}

/// `bank` as the CLI writes `bank.json`: pretty JSON, every number finite, a final newline.
fn bank_text(bank: &ModelBank) -> PyResult<String> {
    Ok(finite_json_pretty(bank).map_err(error)? + "\n")
}

/// Characterises static records into a model bank: the JSON text of `bank.json` and the notes.
#[pyfunction]
#[allow(clippy::too_many_arguments)] // Python keyword arguments, one per CLI option
#[pyo3(signature = (records, temperatures_c=None, cutoff_hz=None, transition_hz=None, modelling_rate_hz=None, chamber_latitude_deg=DEFAULT_SITE_LATITUDE_DEG, chamber_height_m=DEFAULT_SITE_HEIGHT_M))]
pub fn characterize(
    py: Python<'_>,
    records: &Bound<'_, PyAny>,
    temperatures_c: Option<Vec<f64>>,
    cutoff_hz: Option<f64>,
    transition_hz: Option<f64>,
    modelling_rate_hz: Option<f64>,
    chamber_latitude_deg: f64,
    chamber_height_m: f64,
) -> PyResult<(String, Vec<String>)> {
    let records = records_of(records)?;
    if records.is_empty() {
        return Err(error("records: expected at least one record"));
    }
    let temperatures = given_temperatures(temperatures_c, records.len()).map_err(error)?;
    let defaults = CharacterizeSettings::default();
    let settings = CharacterizeSettings {
        cutoff_hz: cutoff_hz.unwrap_or(defaults.cutoff_hz),
        transition_hz: transition_hz.unwrap_or(defaults.transition_hz),
        modelling_rate_hz: modelling_rate_hz.unwrap_or(defaults.modelling_rate_hz),
        ..defaults
    };
    let (lat, h) = (chamber_latitude_deg, chamber_height_m);
    if !((-90.0..=90.0).contains(&lat) && (-500.0..=10_000.0).contains(&h)) {
        return Err(error(format!(
            "chamber_latitude_deg {lat} / chamber_height_m {h}: expected −90..90° and −500..10000 m"
        )));
    }
    let gravity = normal_gravity_m_s2(lat.to_radians(), h);
    let (bank, notes) = py
        .detach(|| build(&records, &temperatures, &settings, gravity))
        .map_err(error)?;
    Ok((bank_text(&bank)?, notes))
}

/// Reads and checks a bank file; its JSON text as `characterize` gives it.
#[pyfunction]
pub fn load_bank(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    let bank = py
        .detach(|| thermonav_io::bank::read_bank_file(&path))
        .map_err(error)?;
    bank_text(&bank)
}
