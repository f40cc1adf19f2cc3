//! `kaiser_fir`, `zero_phase` and `decimate`: the Kaiser low-pass of `thermonav fir` and the
//! filtering and decimation of `thermonav filter`, on one array.

use crate::arrays::{array, samples};
use crate::error;
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use thermonav::signal::decimate::{check_anti_alias, decimate_valid, decimation_factor};
use thermonav::signal::kaiser::{
    DEFAULT_RIPPLE_DB, DEFAULT_TRANSITION_HZ, FirFilter, KaiserSpec, design_kaiser_lowpass,
};
use thermonav::signal::zero_phase::{
    ZeroPhaseMode, decimation_edge_samples, filter_for_mode, filter_zero_phase,
};

/// The Kaiser design of a specification; a bad one is named as the library says.
fn design(
    fs_hz: f64,
    cutoff_hz: f64,
    transition_hz: f64,
    ripple_db: f64,
) -> PyResult<(KaiserSpec, FirFilter)> {
    let spec = KaiserSpec::new(fs_hz, cutoff_hz, transition_hz, ripple_db).map_err(error)?;
    let filter = design_kaiser_lowpass(&spec).map_err(error)?;
    Ok((spec, filter))
}

/// The mode called `name`: "zero-phase" (one pass, delay removed) or "filtfilt".
fn mode_of(name: &str) -> PyResult<ZeroPhaseMode> {
    ZeroPhaseMode::from_name(name).ok_or_else(|| {
        error(format!(
            "mode {name:?}: expected \"zero-phase\" or \"filtfilt\""
        ))
    })
}

/// A Kaiser-window low-pass design, tap for tap SciPy's `kaiserord` + `firwin`.
#[pyfunction]
#[pyo3(signature = (fs_hz, cutoff_hz, transition_hz=DEFAULT_TRANSITION_HZ, ripple_db=DEFAULT_RIPPLE_DB))]
pub fn kaiser_fir(
    py: Python<'_>,
    fs_hz: f64,
    cutoff_hz: f64,
    transition_hz: f64,
    ripple_db: f64,
) -> PyResult<Bound<'_, PyDict>> {
    let (_, filter) = design(fs_hz, cutoff_hz, transition_hz, ripple_db)?;
    let out = PyDict::new(py);
    out.set_item("sample_rate_hz", filter.sample_rate_hz())?;
    out.set_item("cutoff_hz", cutoff_hz)?;
    out.set_item("transition_hz", transition_hz)?;
    out.set_item("ripple_db", ripple_db)?;
    out.set_item("num_taps", filter.num_taps())?;
    out.set_item("beta", filter.beta())?;
    out.set_item("group_delay_s", filter.group_delay_s())?;
    out.set_item("taps", array(py, filter.taps().to_vec()))?;
    Ok(out)
}

/// The filter `thermonav filter` runs for a specification and mode.
fn mode_filter(
    rate_hz: f64,
    (cutoff_hz, transition_hz, ripple_db): (f64, f64, f64),
    mode: ZeroPhaseMode,
) -> PyResult<FirFilter> {
    let (spec, designed) = design(rate_hz, cutoff_hz, transition_hz, ripple_db)?;
    Ok(filter_for_mode(designed, &spec, mode))
}

/// `x` low-passed without phase shift (same length; SciPy's `filtfilt` with `mode="filtfilt"`).
#[pyfunction]
#[pyo3(signature = (x, rate_hz, cutoff_hz, transition_hz=DEFAULT_TRANSITION_HZ, ripple_db=DEFAULT_RIPPLE_DB, mode=ZeroPhaseMode::default().name()))]
pub fn zero_phase<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate_hz: f64,
    cutoff_hz: f64,
    transition_hz: f64,
    ripple_db: f64,
    mode: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let mode = mode_of(mode)?;
    let filter = mode_filter(rate_hz, (cutoff_hz, transition_hz, ripple_db), mode)?;
    let x = samples(&x);
    let y = py
        .detach(|| filter_zero_phase(&filter, &x, mode))
        .map_err(error)?;
    Ok(array(py, y))
}

/// `x` low-passed and decimated to `to_hz`, as `thermonav filter --decimate-to-hz`.
#[pyfunction]
#[pyo3(signature = (x, rate_hz, to_hz, cutoff_hz, transition_hz=DEFAULT_TRANSITION_HZ, ripple_db=DEFAULT_RIPPLE_DB, mode=ZeroPhaseMode::default().name()))]
#[allow(clippy::too_many_arguments)] // Python keyword arguments, one per CLI option
pub fn decimate<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate_hz: f64,
    to_hz: f64,
    cutoff_hz: f64,
    transition_hz: f64,
    ripple_db: f64,
    mode: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let mode = mode_of(mode)?;
    check_anti_alias(cutoff_hz, transition_hz, to_hz)
        .map_err(|e| error(format!("to_hz {to_hz}: {e}")))?;
    let filter = mode_filter(rate_hz, (cutoff_hz, transition_hz, ripple_db), mode)?;
    let factor = decimation_factor(rate_hz, to_hz).map_err(error)?;
    let edge = decimation_edge_samples(&filter, mode, factor);
    let x = samples(&x);
    let y = py
        .detach(|| filter_zero_phase(&filter, &x, mode).map(|y| decimate_valid(&y, edge, factor)))
        .map_err(error)?;
    let out = PyDict::new(py);
    out.set_item("samples", array(py, y))?;
    out.set_item("decimation_factor", factor)?;
    out.set_item("output_rate_hz", rate_hz / factor as f64)?;
    out.set_item("edge_samples_dropped", edge)?;
    out.set_item("num_taps", filter.num_taps())?;
    Ok(out)
}
