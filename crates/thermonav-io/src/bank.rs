//! Model bank files (`bank.json`, written by `thermonav characterize`).

use crate::error::{ReadError, ReadErrorKind};
use std::path::Path;
use thermonav::stoch::bank::ModelBank;

/// Parses and validates a model bank from the bytes of a JSON file named `input` in errors.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] at the line where the JSON is not a model bank (bad JSON, a
/// missing or unknown field, a value of the wrong type), or without a line when the bank
/// parses but fails [`ModelBank::validate`]; [`ReadErrorKind::OutOfRange`] for an entry
/// outside [`crate::SENSOR_TEMPERATURE_RANGE_C`].
pub fn parse_bank(bytes: &[u8], input: &str) -> Result<ModelBank, ReadError> {
    let bank: ModelBank = serde_json::from_slice(bytes).map_err(|e| {
        let line = (e.line() > 0).then_some(e.line() as u64);
        let kind = ReadErrorKind::Unusable(format!("not a model bank: {e}"));
        ReadError::new(input, line, kind)
    })?;
    bank.validate()
        .map_err(|e| ReadError::new(input, None, ReadErrorKind::Unusable(e.to_string())))?;
    let outside = bank.entries.iter().map(|e| e.temperature_c);
    match outside
        .into_iter()
        .find(|&t| !crate::is_sensor_temperature(t))
    {
        Some(t) => Err(ReadError::new(
            input,
            None,
            crate::temperature_out_of_range("temperature_c", t),
        )),
        None => Ok(bank),
    }
}

/// Reads and validates the model bank in `path`.
///
/// # Errors
/// As [`parse_bank`], plus [`ReadErrorKind::Open`] and [`ReadErrorKind::Read`].
pub fn read_bank_file(path: impl AsRef<Path>) -> Result<ModelBank, ReadError> {
    let (bytes, input) = crate::read_named_document(path.as_ref())?;
    parse_bank(&bytes, &input)
}
