//! gnss-ins-sim's custom IMU error model, the `imu_err` dictionary of a Python script.
//!
//! Source: Aceinna/gnss-ins-sim, `gnss_ins_sim/sim/imu_model.py` (`IMU.__init__` docstring:
//! `gyro_b` deg/hr, `gyro_arw` deg/rt-hr, `gyro_b_stability` deg/hr, `gyro_b_corr` s,
//! `accel_b` m/s², `accel_vrw` m/s/rt-hr, `accel_b_stability` m/s², `accel_b_corr` s, each a
//! 3-vector `np.array`) and `gnss_ins_sim/pathgen/pathgen.py` (`bias_drift`: a first-order
//! Gauss-Markov drift with stationary std `*_b_stability` and correlation time `*_b_corr`;
//! white noise of std arw/√dt per sample, so `*_arw`/`*_vrw` are continuous densities).
//!
//! Ours: N → `*_arw`/`*_vrw`, the Gauss-Markov σ and Tc → `*_b_stability`/`*_b_corr`, per
//! axis. The constant biases `gyro_b`/`accel_b` are not noise: written as zeros (the thermal
//! calibration, not the noise model, holds a unit's bias).

use super::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseFormat, Term, bias_stand_in_comments,
    commented, finite_axes, provenance, vector_text,
};
use thermonav::imu::Sensor;
use thermonav::nav::sensor_model::GaussMarkovParameters;
use thermonav::units::{
    arw_rad_per_sqrt_s_to_deg_per_sqrt_h, rad_per_s_to_deg_per_h,
    vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h,
};

/// The script's text: `import numpy as np` and `imu_err = {...}`.
///
/// # Errors
/// A missing white-noise density or Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    let gyro = noise.bias_model_axes(Sensor::Gyro)?;
    let accel = noise.bias_model_axes(Sensor::Accelerometer)?;
    let sigma = |gm: [GaussMarkovParameters; 3]| gm.map(|m| m.sigma);
    let tc = |gm: [GaussMarkovParameters; 3]| gm.map(|m| m.correlation_time_s);
    let entries = [
        (
            "gyro_b",
            [0.0; 3],
            "[deg/hr] constant bias: not part of the noise model, zero",
        ),
        (
            "gyro_arw",
            noise
                .axes(Sensor::Gyro, Term::WhiteNoiseDensity)?
                .map(arw_rad_per_sqrt_s_to_deg_per_sqrt_h),
            "[deg/rt-hr] angle random walk, continuous",
        ),
        (
            "gyro_b_stability",
            sigma(gyro).map(rad_per_s_to_deg_per_h),
            "[deg/hr] Gauss-Markov bias drift std (stationary)",
        ),
        ("gyro_b_corr", tc(gyro), "[s] Gauss-Markov correlation time"),
        (
            "accel_b",
            [0.0; 3],
            "[m/s^2] constant bias: not part of the noise model, zero",
        ),
        (
            "accel_vrw",
            noise
                .axes(Sensor::Accelerometer, Term::WhiteNoiseDensity)?
                .map(vrw_m_per_s_per_sqrt_s_to_m_per_s_per_sqrt_h),
            "[m/s/rt-hr] velocity random walk, continuous",
        ),
        (
            "accel_b_stability",
            sigma(accel),
            "[m/s^2] Gauss-Markov bias drift std (stationary)",
        ),
        (
            "accel_b_corr",
            tc(accel),
            "[s] Gauss-Markov correlation time",
        ),
    ];
    let mut comments = provenance(NoiseFormat::GnssInsSim, noise, options);
    comments.extend([
        "pass it as imu_model.IMU(accuracy=imu_err, axis=6); axes x forward, y right, z down".to_string(),
        "arw, vrw: continuous densities (gnss-ins-sim draws arw/sqrt(dt) per sample); b_stability, b_corr: first-order Gauss-Markov drift".to_string(),
    ]);
    comments.extend(bias_stand_in_comments(noise)?);
    let mut body = String::from("import numpy as np\n\nimu_err = {\n");
    for (key, values, note) in entries {
        let values = finite_axes(key, values)?;
        body.push_str(&format!(
            "    '{key}': np.array({}),  # {note}\n",
            vector_text(&values)
        ));
    }
    body.push_str("}\n");
    Ok(commented("#", &comments) + &body)
}
