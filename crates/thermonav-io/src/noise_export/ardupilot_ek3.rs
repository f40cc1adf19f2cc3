//! ArduPilot EKF3's IMU noise parameters in a `.parm` file.
//!
//! Sources: ArduPilot parameter reference (<https://ardupilot.org/copter/docs/parameters.html>,
//! EK3_ group): `EK3_GYRO_P_NSE` "rate gyro noise", rad/s; `EK3_ACC_P_NSE` "accelerometer
//! noise", m/s²; `EK3_GBIAS_P_NSE` "rate gyro bias stability", rad/s²; `EK3_ABIAS_P_NSE`
//! "accelerometer bias stability", m/s³. ArduPilot `libraries/AP_NavEKF3/AP_NavEKF3_core.cpp`
//! (`CovariancePrediction`): delta-angle variance (dt · EK3_GYRO_P_NSE)², delta-angle bias
//! process noise dt² · EK3_GBIAS_P_NSE as a standard deviation, i.e. the gyro bias variance
//! grows by (dt · EK3_GBIAS_P_NSE)² per step; dt is the EKF step, at least `EKF_TARGET_DT` =
//! 12 ms (`AP_NavEKF3_core.h`). So, as for PX4: value = N / √dt and K / √dt. File layout:
//! `NAME VALUE` lines with `#` comments, as MAVProxy's `param load` (pymavlink `mavparm.py`)
//! and Mission Planner read them.
//!
//! Ours: N and K (or the Gauss-Markov stand-in), the largest of the three axes, dt = 12 ms.

use super::ekf_parameters::{EkfParameters, ekf_parameters_text};
use super::{ExportOptions, ImuNoise, NoiseExportError, NoiseFormat};
use crate::thermal_parameters::ParameterValue;

/// The EKF step the values are computed for, s (`EKF_TARGET_DT`).
pub const EK3_STEP_S: f64 = 0.012;

const ARDUPILOT_EK3: EkfParameters = EkfParameters {
    format: NoiseFormat::ArdupilotEk3,
    step_s: EK3_STEP_S,
    names: [
        "EK3_GYRO_P_NSE",
        "EK3_ACC_P_NSE",
        "EK3_GBIAS_P_NSE",
        "EK3_ABIAS_P_NSE",
    ],
    step_comments: [
        "discrete values for EKF3's step dt = 0.012 s (EKF_TARGET_DT; a vehicle whose loop is slower than 83 Hz steps at its loop interval: multiply every value by sqrt(0.012 / that)):",
        "P_NSE = N / sqrt(dt) from the continuous white-noise density N; BIAS_P_NSE = K / sqrt(dt) from the continuous bias random walk K",
    ],
    header: None,
    line: parm_line,
};

/// The file's text.
///
/// # Errors
/// A missing white-noise density, neither K nor a Gauss-Markov model, or a non-finite value.
pub fn text(noise: &ImuNoise, options: &ExportOptions) -> Result<String, NoiseExportError> {
    ekf_parameters_text(noise, options, &ARDUPILOT_EK3)
}

/// `NAME VALUE`.
fn parm_line(name: &str, value: ParameterValue) -> String {
    format!("{name} {}\n", value.text())
}
