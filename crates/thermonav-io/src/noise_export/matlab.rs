//! A MATLAB script building the Navigation / Sensor Fusion Toolbox's IMU model.
//!
//! Source: MathWorks documentation of `gyroparams` and `accelparams`
//! (<https://www.mathworks.com/help/nav/ref/gyroparams.html>,
//! <https://www.mathworks.com/help/nav/ref/accelparams.html>) and `imuSensor`
//! (<https://www.mathworks.com/help/nav/ref/imusensor-system-object.html>): properties
//! `NoiseDensity` ((rad/s)/√Hz, (m/s²)/√Hz), `BiasInstability` (rad/s, m/s²) and `RandomWalk`
//! ((rad/s)·√Hz, (m/s²)·√Hz), scalars or 1-by-3 vectors, continuous-time (the System object
//! discretises with its `SampleRate`); `imuSensor('accel-gyro', 'SampleRate', fs, ...)`.
//! MATLAB's own Allan-variance example ("Inertial Sensor Noise Analysis Using Allan Variance")
//! reads `NoiseDensity` as N, `RandomWalk` as K and `BiasInstability` as B (the flat part of
//! the curve divided by sqrt(2 ln 2 / π)), the IEEE Std 952 terms the bank holds.
//!
//! Ours: N, B, K per axis. A B or K the Allan curve does not show is written as 0 (MATLAB's
//! default, the term off: a simulator should add no noise the record did not show), and a
//! comment says so; N is required.

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, Term, commented, finite, finite_axes,
    float_text, provenance, sensor_channels, vector_text,
};
use thermonav::imu::Sensor;

/// The script's text.
///
/// # Errors
/// A missing white-noise density, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let mut comments = provenance(NoiseFormat::Matlab, noise, options);
    comments.extend([
        "continuous-time values; imuSensor discretises them with SampleRate".to_string(),
        "1-by-3 vectors: axes x forward, y right, z down, as recorded".to_string(),
    ]);
    let gyro = sensor_block(noise, Sensor::Gyro, &mut comments)?;
    let accel = sensor_block(noise, Sensor::Accelerometer, &mut comments)?;
    let rate = finite("SampleRate", noise.sample_rate_hz)?;
    let imu = format!(
        "imu = imuSensor('accel-gyro', 'SampleRate', {}, 'Gyroscope', gyro, 'Accelerometer', accel); % SampleRate [Hz]\n",
        float_text(rate)
    );
    Ok(commented("%", &comments) + &gyro + &accel + &imu)
}

/// `gyro = gyroparams(...)` or `accel = accelparams(...)`.
fn sensor_block(
    noise: &ImuNoise,
    sensor: Sensor,
    comments: &mut Vec<String>,
) -> Result<String, NoiseExportError> {
    let (variable, function, unit) = match sensor {
        Sensor::Gyro => ("gyro", "gyroparams", "rad/s"),
        Sensor::Accelerometer => ("accel", "accelparams", "m/s^2"),
    };
    let density = noise.axes(sensor, Term::WhiteNoiseDensity)?;
    let instability = term_or_zero(
        noise,
        (sensor, Term::BiasInstability),
        "BiasInstability",
        comments,
    );
    let walk = term_or_zero(
        noise,
        (sensor, Term::RateRandomWalk),
        "RandomWalk",
        comments,
    );
    let properties = [
        ("NoiseDensity", density, format!("({unit})/sqrt(Hz)")),
        ("BiasInstability", instability, unit.to_string()),
        ("RandomWalk", walk, format!("({unit})*sqrt(Hz)")),
    ];
    let mut block = format!("{variable} = {function}( ...\n");
    for (k, (property, values, unit)) in properties.into_iter().enumerate() {
        let row = matlab_row(&finite_axes(property, values)?);
        let end = if k == 2 { ");" } else { ", ..." };
        block.push_str(&format!("    '{property}', {row}{end} % [{unit}]\n"));
    }
    Ok(block)
}

/// `term` per axis, 0 where the Allan curve shows none (a comment line says which).
fn term_or_zero(
    noise: &ImuNoise,
    (sensor, term): (Sensor, Term),
    property: &str,
    comments: &mut Vec<String>,
) -> [f64; 3] {
    sensor_channels(sensor).map(|channel| {
        noise.require(channel, term).unwrap_or_else(|_| {
            comments.push(format!(
                "{}: no {} on the Allan curve: {property} 0 (MATLAB's default, the term off)",
                channel.name(),
                term.words()
            ));
            0.0
        })
    })
}

/// `[x y z]`, a MATLAB row vector.
fn matlab_row(values: &[f64]) -> String {
    vector_text(values).replace(',', "")
}
