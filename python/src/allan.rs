//! `allan` and `noise_terms`: the Allan family of deviations and the IEEE 952 terms read off
//! the overlapping Allan curve, as `thermonav allan` computes them.

use crate::arrays::{array, samples};
use crate::{error, to_python};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use thermonav::imu::{Channel, Sensor};
use thermonav::stoch::allan::{
    AllanCurve, AllanIntervals, CiSettings, DEFAULT_CONFIDENCE, DeviationKind, TauGrid,
    confidence_intervals, deviation, overlapping_adev,
};
use thermonav::stoch::noise_terms::fit_noise_terms;
use thermonav_io::noise_terms::terms_json;

/// Points per decade of `taus="dense"`, as `thermonav allan --taus dense`.
const DENSE_PER_DECADE: usize = 20;

/// The τ grid of `taus`: "octave", "decade", "dense", or a sequence of averaging factors m.
fn tau_grid(taus: Option<&Bound<'_, PyAny>>) -> PyResult<TauGrid> {
    let Some(taus) = taus else {
        return Ok(TauGrid::Octave);
    };
    if let Ok(name) = taus.cast::<PyString>() {
        return match name.to_str()? {
            "octave" => Ok(TauGrid::Octave),
            "decade" => Ok(TauGrid::Decade),
            "dense" => Ok(TauGrid::Dense {
                per_decade: DENSE_PER_DECADE,
            }),
            other => Err(error(format!(
                "taus {other:?}: expected \"octave\", \"decade\", \"dense\" or a sequence of averaging factors"
            ))),
        };
    }
    Ok(TauGrid::Explicit(taus.extract::<Vec<usize>>()?))
}

/// Refuses a confidence level the library refuses (outside (0, 1)).
fn check_confidence(confidence: f64) -> PyResult<()> {
    let settings = CiSettings {
        level: confidence,
        ..CiSettings::default()
    };
    (settings.validate()).map_err(|e| error(format!("confidence {confidence}: {e}")))
}

/// The overlapping Allan curve of `y` and its confidence limits.
fn adev_with_limits(
    y: &[f64],
    rate_hz: f64,
    grid: &TauGrid,
    confidence: f64,
) -> PyResult<(AllanCurve, AllanIntervals)> {
    let curve = overlapping_adev(y, rate_hz, grid).map_err(error)?;
    let limits = confidence_intervals(y, &curve, confidence);
    Ok((curve, limits))
}

/// Allan deviation of rate samples `x` taken at `rate_hz` (module docs of the Python package:
/// `thermonav.allan`).
#[pyfunction]
#[pyo3(signature = (x, rate_hz, taus=None, kind=DeviationKind::default().name(), confidence=DEFAULT_CONFIDENCE, limits=true))]
pub fn allan<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate_hz: f64,
    taus: Option<&Bound<'py, PyAny>>,
    kind: &str,
    confidence: f64,
    limits: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let kind: DeviationKind = kind.parse().map_err(error)?;
    let grid = tau_grid(taus)?;
    let y = samples(&x);
    let out = PyDict::new(py);
    out.set_item("kind", kind.name())?;
    out.set_item("sample_rate_hz", rate_hz)?;
    if kind != DeviationKind::Adev || !limits {
        let curve = py
            .detach(|| deviation(kind, &y, rate_hz, &grid))
            .map_err(error)?;
        out.set_item("tau_s", array(py, curve.tau_s))?;
        out.set_item("averaging_factor", array(py, curve.averaging_factor))?;
        out.set_item(kind.name(), array(py, curve.deviation))?;
        out.set_item("n_terms", array(py, curve.n_terms))?;
        return Ok(out);
    }
    check_confidence(confidence)?;
    let (curve, limits) = py.detach(|| adev_with_limits(&y, rate_hz, &grid, confidence))?;
    out.set_item("confidence", confidence)?;
    out.set_item("tau_s", array(py, curve.tau_s))?;
    out.set_item("averaging_factor", array(py, curve.averaging_factor))?;
    out.set_item("adev", array(py, curve.adev))?;
    out.set_item("n_terms", array(py, curve.n_terms))?;
    out.set_item("ci_low", array(py, limits.low))?;
    out.set_item("ci_high", array(py, limits.high))?;
    out.set_item("noise_type_alpha", array(py, limits.alpha))?;
    out.set_item("edf", array(py, limits.edf))?;
    Ok(out)
}

/// The sensor of `sensor`: "gyro", "accelerometer", or a channel name (gx .. az).
pub(crate) fn sensor_of(sensor: &str) -> PyResult<Sensor> {
    match sensor {
        "gyro" => Ok(Sensor::Gyro),
        "accelerometer" => Ok(Sensor::Accelerometer),
        name => Channel::ALL
            .into_iter()
            .find(|c| c.name() == name)
            .map(Channel::sensor)
            .ok_or_else(|| {
                error(format!(
                    "sensor {name:?}: expected \"gyro\", \"accelerometer\" or a channel name (gx, gy, gz, ax, ay, az)"
                ))
            }),
    }
}

/// The IEEE 952 noise terms of rate samples `x` at `rate_hz`, as `thermonav allan --json`'s
/// `terms`.
#[pyfunction]
#[pyo3(signature = (x, rate_hz, sensor, taus=None, confidence=DEFAULT_CONFIDENCE))]
pub fn noise_terms<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate_hz: f64,
    sensor: &str,
    taus: Option<&Bound<'py, PyAny>>,
    confidence: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let sensor = sensor_of(sensor)?;
    let grid = tau_grid(taus)?;
    check_confidence(confidence)?;
    let y = samples(&x);
    let terms = py.detach(|| {
        let (curve, limits) = adev_with_limits(&y, rate_hz, &grid, confidence)?;
        Ok::<_, PyErr>(terms_json(&fit_noise_terms(&curve, &limits), sensor))
    })?;
    to_python(py, &terms)
}
