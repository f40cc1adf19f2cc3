//! NumPy arrays in and out: 1-D float64 samples borrowed when contiguous, checked values and
//! times, results as NumPy arrays.

use crate::error;
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use std::borrow::Cow;
use thermonav::signal::timestamps::check_timestamps;
use thermonav::time::Timestamp;

/// The samples of a 1-D float64 array: borrowed when contiguous, else copied.
pub(crate) fn samples<'a>(x: &'a PyReadonlyArray1<'_, f64>) -> Cow<'a, [f64]> {
    match x.as_slice() {
        Ok(slice) => Cow::Borrowed(slice),
        Err(_) => Cow::Owned(x.as_array().to_vec()),
    }
}

/// `values` as a NumPy array (moved, not copied).
pub(crate) fn array<'py, T: numpy::Element>(
    py: Python<'py>,
    values: Vec<T>,
) -> Bound<'py, PyArray1<T>> {
    PyArray1::from_vec(py, values)
}

/// Refuses an array holding a NaN or an infinity, naming the first.
pub(crate) fn check_finite(name: &str, x: &[f64]) -> PyResult<()> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(error(format!(
            "{name}: sample {index} is {}, not a finite number",
            x[index]
        ))),
        None => Ok(()),
    }
}

/// Refuses arrays of different lengths.
pub(crate) fn check_same_length(names: [&str; 2], lengths: [usize; 2]) -> PyResult<()> {
    if lengths[0] != lengths[1] {
        return Err(error(format!(
            "{} has {} samples and {} has {}: expected one sample per time",
            names[0], lengths[0], names[1], lengths[1]
        )));
    }
    Ok(())
}

/// Times in seconds as integer-nanosecond timestamps, refused unless strictly increasing
/// (a time before or equal to its predecessor is named with its index).
pub(crate) fn timestamps(name: &str, t_s: &[f64]) -> PyResult<Vec<Timestamp>> {
    check_finite(name, t_s)?;
    let times = (t_s.iter())
        .map(|&t| Timestamp::from_seconds(t).map_err(error))
        .collect::<PyResult<Vec<_>>>()?;
    check_increasing(name, &times)?;
    Ok(times)
}

/// Refuses a time axis with a duplicate or a reversal, naming the first of each.
pub(crate) fn check_increasing(name: &str, times: &[Timestamp]) -> PyResult<()> {
    let report = check_timestamps(times);
    let first = [report.reversals.first(), report.duplicates.first()]
        .into_iter()
        .flatten()
        .min_by_key(|fault| fault.index);
    match first {
        Some(fault) => Err(error(format!(
            "{name}: {} times are not after their predecessor ({} go back, {} repeat), the first at sample {}: expected strictly increasing times",
            report.reversal_count + report.duplicate_count,
            report.reversal_count,
            report.duplicate_count,
            fault.index
        ))),
        None => Ok(()),
    }
}

/// The median interval of increasing times, s; refused for fewer than two times.
pub(crate) fn median_interval_s(name: &str, times: &[Timestamp]) -> PyResult<f64> {
    thermonav::signal::timestamps::interval_stats(times)
        .map(|s| s.median.as_seconds())
        .ok_or_else(|| error(format!("{name}: fewer than two samples")))
}
