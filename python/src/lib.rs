//! The Python extension module `thermonav._native`: thermonav's estimators on NumPy arrays.
//!
//! Every function calls the library functions the command line calls, with the same defaults,
//! so a result equals the CLI's JSON; results leave as dictionaries whose keys are the JSON's
//! snake_case, unit-suffixed names (`tau_s`, `adev`, `correlation_time_s`), arrays as NumPy
//! arrays. The pure-Python package `thermonav` wraps them in attribute dictionaries and
//! documents them (`thermonav/__init__.pyi`). Errors are [`ThermonavError`] (a `ValueError`)
//! with the library's message (file, line and what was expected, for files); a wrong dtype is a
//! `TypeError`. Long calls release the GIL.

mod allan;
mod arrays;
mod bank;
mod gmwm;
mod models;
mod navigation;
mod records;
mod signal;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    _native,
    ThermonavError,
    PyValueError,
    "Bad data or settings: the message names the file, the line and what was expected."
);

/// A [`ThermonavError`] carrying `message`.
pub(crate) fn error(message: impl std::fmt::Display) -> PyErr {
    ThermonavError::new_err(message.to_string())
}

/// `value` serialised as the CLI's JSON writes it, read back by Python's `json` module: the
/// same keys, and floats that read back to the same bits.
pub(crate) fn to_python<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = thermonav_io::finite::finite_json_pretty(value).map_err(error)?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ThermonavError", m.py().get_type::<ThermonavError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(allan::allan, m)?)?;
    m.add_function(wrap_pyfunction!(allan::noise_terms, m)?)?;
    m.add_function(wrap_pyfunction!(models::ar, m)?)?;
    m.add_function(wrap_pyfunction!(models::gauss_markov, m)?)?;
    m.add_function(wrap_pyfunction!(signal::kaiser_fir, m)?)?;
    m.add_function(wrap_pyfunction!(signal::zero_phase, m)?)?;
    m.add_function(wrap_pyfunction!(signal::decimate, m)?)?;
    m.add_function(wrap_pyfunction!(records::read_imu, m)?)?;
    m.add_function(wrap_pyfunction!(records::read_gnss, m)?)?;
    m.add_function(wrap_pyfunction!(bank::characterize, m)?)?;
    m.add_function(wrap_pyfunction!(bank::load_bank, m)?)?;
    m.add_function(wrap_pyfunction!(gmwm::gmwm, m)?)?;
    m.add_function(wrap_pyfunction!(navigation::integrate, m)?)?;
    m.add_function(wrap_pyfunction!(navigation::evaluate, m)?)?;
    Ok(())
}
