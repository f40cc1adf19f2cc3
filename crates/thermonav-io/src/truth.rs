//! A simulated survey's `truth.json` (written by `thermonav simulate vessel`), read for the
//! oracle candidates of `evaluate --truth`: its `models` list, the true error model of every
//! channel on a fine temperature grid ([`thermonav::evaluation::oracle::TrueModelAt`]), and
//! `thermal_lag_s`, each channel's structure lag (absent in a file written before lags: none);
//! the other fields are kept for people.

use crate::error::{ReadError, ReadErrorKind};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::evaluation::oracle::{TrueModel, TrueModelAt};
use thermonav::imu::Channel;
use thermonav::nav::sensor_model::ScaleFactorPrior;

/// The part of `truth.json` the oracle reads.
#[derive(Debug, Deserialize)]
struct TruthDocument {
    models: Vec<TrueModelAt>,
    #[serde(default)]
    thermal_lag_s: BTreeMap<Channel, f64>,
}

/// Parses and validates a survey truth from the bytes of a JSON file named `input` in errors;
/// `scale` is the scale-factor model of channels for which the truth states none.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] at the line where the JSON is not a survey truth (bad JSON, no
/// `models` list, a field missing or of the wrong type), or without a line when the table
/// parses but is not a usable model (see [`TrueModel::new`]).
pub fn parse_truth(
    bytes: &[u8],
    input: &str,
    scale: &ScaleFactorPrior,
) -> Result<TrueModel, ReadError> {
    let document: TruthDocument = serde_json::from_slice(bytes).map_err(|e| {
        let line = (e.line() > 0).then_some(e.line() as u64);
        let kind = ReadErrorKind::Unusable(format!(
            "not a survey truth (expected the truth.json of `thermonav simulate vessel`): {e}"
        ));
        ReadError::new(input, line, kind)
    })?;
    TrueModel::new(document.models, scale)
        .and_then(|t| t.with_thermal_lags(document.thermal_lag_s))
        .map_err(|e| ReadError::new(input, None, ReadErrorKind::Unusable(e.to_string())))
}

/// Reads and validates the survey truth in `path`.
///
/// # Errors
/// As [`parse_truth`], plus [`ReadErrorKind::Open`] and [`ReadErrorKind::Read`].
pub fn read_truth_file(
    path: impl AsRef<Path>,
    scale: &ScaleFactorPrior,
) -> Result<TrueModel, ReadError> {
    let (bytes, input) = crate::read_named_document(path.as_ref())?;
    parse_truth(&bytes, &input, scale)
}
