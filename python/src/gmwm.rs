//! `gmwm`: a composite noise model fitted to the Haar wavelet variance, as one channel of
//! `thermonav gmwm --json` (the same library calls and JSON types).

use crate::allan::sensor_of;
use crate::arrays::{check_finite, samples};
use crate::{error, to_python};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use serde::Serialize;
use thermonav::rng::DEFAULT_SEED;
use thermonav::stoch::characterize::DEFAULT_GMWM;
use thermonav::stoch::gmwm::BootstrapSettings;
use thermonav_io::gmwm::{
    DEFAULT_REPLICATES, GmwmChannelJson, candidates_of, gmwm_channel_json, interval_method,
};

/// The fit with the run's settings, keys as `gmwm --json`'s run and channel.
#[derive(Serialize)]
struct Fit<'a> {
    sample_rate_hz: f64,
    model: &'a str,
    interval_method: &'static str,
    bootstrap_replicates: usize,
    #[serde(flatten)]
    channel: GmwmChannelJson,
}

/// The GMWM fit of rate samples `x` at `rate_hz` (module docs of the Python package:
/// `thermonav.gmwm`).
#[pyfunction]
#[pyo3(signature = (x, rate_hz, model=None, sensor="gyro", replicates=DEFAULT_REPLICATES, seed=DEFAULT_SEED))]
pub fn gmwm<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate_hz: f64,
    model: Option<&str>,
    sensor: &str,
    replicates: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let sensor = sensor_of(sensor)?;
    let model = model.map_or_else(|| DEFAULT_GMWM.to_string(), str::to_string);
    let model = model.as_str();
    let candidates = candidates_of(model).map_err(|e| error(format!("model {model}: {e}")))?;
    let settings = BootstrapSettings {
        replicates,
        seed,
        ..BootstrapSettings::default()
    };
    let y = samples(&x);
    check_finite("x", &y)?;
    let channel = py
        .detach(|| gmwm_channel_json(&y, rate_hz, sensor, (&candidates, settings)))
        .map_err(error)?;
    let fit = Fit {
        sample_rate_hz: rate_hz,
        model,
        interval_method: interval_method(replicates),
        bootstrap_replicates: replicates,
        channel,
    };
    to_python(py, &fit)
}
