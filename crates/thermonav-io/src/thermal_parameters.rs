//! A unit's thermal calibration ([`ThermalCalibration`]) as autopilot parameters: PX4's
//! `TC_*` thermal-compensation parameters in a QGroundControl `.params` file, and ArduPilot's
//! `INS_TCAL1_*` parameters in a Mission Planner / MAVProxy `.param` file; the second and
//! third IMU (instance 1, 2) take `TC_G1`/`TC_A1`, `INS_TCAL2` and so on ([`ExportTarget`]).
//!
//! Each target has its own polynomial, reference temperature and clamping; the curves of the
//! calibration, b(T) = Σ_k b_k (T − T_ref)^k with their own T_ref, are re-expanded about the
//! target's reference exactly (binomial re-expansion, [`reexpanded`]), so nothing is dropped
//! or approximated beyond the targets' 32-bit float storage of each parameter.
//!
//! # PX4 (`TC_G0_*`, `TC_A0_*`)
//! Facts from PX4-Autopilot, `src/modules/temperature_compensation/TemperatureCompensation.cpp`
//! (`calc_thermal_offsets_3D`), `temp_comp_params_gyro_0.yaml`, `temp_comp_params_accel_0.yaml`
//! and `src/lib/sensor_calibration/Gyroscope.hpp`/`Accelerometer.hpp` (`Correct`):
//! - offset_i = X0_i + X1_i·dT + X2_i·dT² + X3_i·dT³ (`TC_G0_Xk_i`: power k, axis i = 0, 1, 2
//!   for x, y, z), dT = clamp(T, TMIN, TMAX) − TREF, T the sensor's temperature, °C;
//! - TREF is the temperature the polynomial is expanded about, free to choose (PX4's own
//!   calibration takes its start temperature plus half the required rise);
//! - the offset is subtracted from the raw reading (`data − thermal_offset − offset`) before
//!   the sensor-to-body rotation, in rad/s (gyro) and m/s² (accelerometer);
//! - `TC_G_ENABLE`/`TC_A_ENABLE` (int32, 1 = on) switch it on, `TC_G0_ID`/`TC_A0_ID` (int32)
//!   name the sensor by its device id; all other values are 32-bit floats.
//!
//! The file is a QGroundControl parameter file (QGroundControl,
//! `docs/en/qgc-dev-guide/file_formats/parameters.md`; written the same way by PX4's
//! `Tools/process_sensor_caldata.py`): `#` comment lines, then one line per parameter with
//! five tab-separated fields, vehicle id, component id, name, value and type
//! (`MAV_PARAM_TYPE`: 6 = INT32, 9 = REAL32). Vehicle and component id are 1 (the
//! autopilot).
//!
//! # ArduPilot (`INS_TCAL1_*`)
//! Facts from ArduPilot, `libraries/AP_InertialSensor/AP_InertialSensor_tempcal.cpp`
//! (`polynomial_eval`, `correct_sensor`) and `AP_InertialSensor_Backend.cpp`
//! (`_rotate_and_correct_gyro`/`_accel`):
//! - a fixed reference of 35 °C (`TEMP_REFERENCE`), not TMIN;
//! - p(T) = 10⁻⁶ (c1·d + c2·d² + c3·d³), d = T − 35 °C, with `ACCk_X/Y/Z` and `GYRk_X/Y/Z`
//!   holding c_k: the stored coefficients are the physical ones times 10⁶ (`SCALE_FACTOR`,
//!   so that values of order 10⁻⁶ are not shown as 0 by parameter editors with few
//!   decimals): units µrad/s/°C^k and µm/s²/°C^k;
//! - there is no constant term: the reading is corrected by p(T) − p(T_cal), T and T_cal both
//!   clamped to [TMIN, TMAX], T_cal being the temperature of the ordinary offset calibration
//!   (`INS_GYR1_CALTEMP`, `INS_ACC1_CALTEMP`), whose offsets (`INS_GYROFFS_*`, measured at
//!   every boot by default, and `INS_ACCOFFS_*`) hold the bias at T_cal. So the curve's
//!   constant is not written: ArduPilot's own offset calibration supplies it, and with that
//!   offset the total correction is our b(T) at every temperature;
//! - the correction is applied after the sensor's mounting rotation and before the board
//!   orientation (`AHRS_ORIENTATION`), in rad/s and m/s²; one TMIN/TMAX for both sensors;
//!   `INS_TCAL1_ENABLE` = 1 (int8) switches it on (after a reboot).
//!
//! The file is a `.param` file of `NAME,VALUE` lines with `#` comments, as Mission Planner
//! saves and loads them; MAVProxy's `param load` (pymavlink `mavparm.py`, `MAVParmDict.load`)
//! reads the same lines (it turns commas into spaces).
//!
//! # Frames and what neither target holds
//! Our channels are the IMU's body axes, x forward, y right, z down (FRD): the same axes PX4
//! and ArduPilot use for the sensor frame in which these corrections apply, so the axes map
//! one to one (x → 0/X, y → 1/Y, z → 2/Z). Neither target has thermal scale-factor
//! parameters; the files say so.

use crate::atomic::write_atomically;
use crate::error::WriteError;
use serde::Serialize;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;
use thermonav::imu::Channel;
use thermonav::stoch::thermal::{MAX_ORDER, ThermalCalibration};

/// ArduPilot's fixed reference temperature, °C (`TEMP_REFERENCE`).
pub const ARDUPILOT_REFERENCE_TEMPERATURE_C: f64 = 35.0;

/// ArduPilot's coefficient scale: stored value = physical coefficient × this (`SCALE_FACTOR`).
pub const ARDUPILOT_COEFFICIENT_SCALE: f64 = 1.0e6;

/// Coefficients of a cubic, power 0..=3.
const TERMS: usize = MAX_ORDER + 1;

/// Which autopilot's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ParameterTarget {
    /// PX4 `TC_*` in a QGroundControl `.params` file.
    Px4Tc,
    /// ArduPilot `INS_TCAL1_*` in a Mission Planner / MAVProxy `.param` file.
    ArdupilotTcal,
}

impl ParameterTarget {
    /// Every target, in the order the command line lists them.
    pub const ALL: [ParameterTarget; 2] = [ParameterTarget::Px4Tc, ParameterTarget::ArdupilotTcal];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ParameterTarget::Px4Tc => "px4-tc",
            ParameterTarget::ArdupilotTcal => "ardupilot-tcal",
        }
    }

    /// What it writes, in a line (the command line's help).
    pub fn help(self) -> &'static str {
        match self {
            ParameterTarget::Px4Tc => {
                "PX4 TC_* thermal compensation, a QGroundControl .params file"
            }
            ParameterTarget::ArdupilotTcal => {
                "ArduPilot INS_TCAL1_* temperature calibration, a Mission Planner/MAVProxy .param file"
            }
        }
    }
}

/// The two sensors of an IMU, each three channels sharing one temperature range.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ImuSensor {
    /// gx, gy, gz (rad/s).
    Gyro,
    /// ax, ay, az (m/s²).
    Accelerometer,
}

impl ImuSensor {
    /// Its channels, x, y, z.
    pub fn channels(self) -> [Channel; 3] {
        match self {
            ImuSensor::Gyro => [Channel::Gx, Channel::Gy, Channel::Gz],
            ImuSensor::Accelerometer => [Channel::Ax, Channel::Ay, Channel::Az],
        }
    }

    /// Its name in tables.
    pub fn name(self) -> &'static str {
        match self {
            ImuSensor::Gyro => "gyro",
            ImuSensor::Accelerometer => "accelerometer",
        }
    }

    /// Unit of the bias.
    pub fn unit(self) -> &'static str {
        match self {
            ImuSensor::Gyro => "rad/s",
            ImuSensor::Accelerometer => "m/s^2",
        }
    }
}

/// Why a calibration cannot be exported.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// A channel the target needs has no curve.
    #[error("the thermal calibration has no curve for {0}: every channel is needed")]
    MissingChannel(&'static str),
    /// A curve of order above 3.
    #[error("the {channel} curve has {terms} coefficients: the targets hold at most {TERMS}")]
    OrderTooHigh {
        /// The channel.
        channel: &'static str,
        /// Coefficients it has.
        terms: usize,
    },
    /// The channels that share one range have no temperature in common.
    #[error(
        "the fitted temperature ranges of {channels} do not overlap, so one TMIN/TMAX cannot hold them"
    )]
    DisjointRanges {
        /// The channels, named.
        channels: String,
    },
    /// A sensor instance the targets have no parameters for.
    #[error(
        "sensor instance {0}: the targets hold thermal parameters for instances 0 to {MAX_INSTANCE} (PX4 TC_G0..TC_G2, ArduPilot INS_TCAL1..INS_TCAL3)"
    )]
    Instance(u8),
    /// A value that is not finite or overflows a 32-bit float.
    #[error("{name} = {value} cannot be stored as a 32-bit float parameter")]
    NotRepresentable {
        /// The parameter.
        name: String,
        /// Its value.
        value: f64,
    },
}

/// A parameter's value as the autopilot stores it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ParameterValue {
    /// A 32-bit integer (`MAV_PARAM_TYPE_INT32`, or ArduPilot's small integers).
    Integer(i32),
    /// A 32-bit float (`MAV_PARAM_TYPE_REAL32`).
    Real(f32),
}

impl ParameterValue {
    /// `value` as a 32-bit float parameter (a zero, of either sign, as 0); `None` when it is
    /// not finite or overflows a 32-bit float: the one conversion every parameter file's real
    /// values go through (thermal calibration, EKF noise).
    pub fn real(value: f64) -> Option<Self> {
        let stored = if value == 0.0 { 0.0 } else { value as f32 };
        stored.is_finite().then_some(ParameterValue::Real(stored))
    }

    /// The `MAV_PARAM_TYPE` of a QGroundControl file: 6 = INT32, 9 = REAL32.
    pub fn mav_param_type(self) -> u8 {
        match self {
            ParameterValue::Integer(_) => 6,
            ParameterValue::Real(_) => 9,
        }
    }

    /// The value as text that reads back to the same 32-bit value (shortest form, no
    /// exponent, which every ground station parses).
    pub fn text(self) -> String {
        match self {
            ParameterValue::Integer(v) => v.to_string(),
            ParameterValue::Real(v) => v.to_string(),
        }
    }
}

/// One named parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Its name (at most 16 characters, the MAVLink limit).
    pub name: String,
    /// Its value.
    pub value: ParameterValue,
}

/// One sensor's curves as the target holds them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SensorExport {
    /// The sensor.
    pub sensor: ImuSensor,
    /// TMIN and TMAX written, °C: the range the three curves share.
    pub temperature_range_c: [f64; 2],
    /// The target's reference temperature, °C (PX4's TREF, ArduPilot's fixed 35 °C).
    pub reference_temperature_c: f64,
    /// Per axis x, y, z: the curve's coefficients of (T − reference)^k, k = 0..=3, in the
    /// sensor's unit per °C^k, before any target scaling.
    pub coefficients: [[f64; TERMS]; 3],
    /// Channels whose own fitted range is wider than the shared one (their curve is held at
    /// its value at the shared bound beyond it).
    pub narrowed_channels: Vec<&'static str>,
}

/// A parameter file's contents: the parameters, the comments that explain them and what was
/// exported.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterFile {
    /// The target.
    pub target: ParameterTarget,
    /// The parameters, in file order.
    pub parameters: Vec<Parameter>,
    /// Comment lines (without the leading `# `).
    pub comments: Vec<String>,
    /// Per sensor, gyro first.
    pub sensors: Vec<SensorExport>,
}

/// What an export wrote, for `--json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportSummary {
    /// The target.
    pub format: ParameterTarget,
    /// Parameters written.
    pub parameters: usize,
    /// Per sensor.
    pub sensors: Vec<SensorExport>,
}

/// The coefficients of Σ_k b_k (T − from_c)^k as coefficients of (T − to_c)^k, exactly:
/// with s = to_c − from_c, (d + s)^k = Σ_m C(k, m) s^(k−m) d^m, so a_m = Σ_{k≥m} C(k, m)
/// s^(k−m) b_k. Missing powers are zero.
///
/// # Example
/// ```
/// use thermonav_io::thermal_parameters::reexpanded;
/// // 1 + 2 (T − 20) = 21 + 2 (T − 30)
/// assert_eq!(reexpanded(&[1.0, 2.0], 20.0, 30.0), [21.0, 2.0, 0.0, 0.0]);
/// ```
pub fn reexpanded(coefficients: &[f64], from_c: f64, to_c: f64) -> [f64; TERMS] {
    let shift_c = to_c - from_c;
    let mut out = [0.0; TERMS];
    for (m, slot) in out.iter_mut().enumerate() {
        *slot = coefficients
            .iter()
            .enumerate()
            .skip(m)
            .map(|(k, b)| binomial(k, m) * shift_c.powi((k - m) as i32) * b)
            .sum();
    }
    out
}

/// C(n, k) for n ≤ 3.
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The range every one of `channels` was fitted over, °C.
fn shared_range_c(
    calibration: &ThermalCalibration,
    channels: &[Channel],
) -> Result<[f64; 2], ExportError> {
    let mut range = [f64::NEG_INFINITY, f64::INFINITY];
    for &channel in channels {
        let [low, high] = curve_of(calibration, channel)?.temperature_range_c;
        range = [range[0].max(low), range[1].min(high)];
    }
    if range[0] > range[1] {
        let names: Vec<&str> = channels.iter().map(|c| c.name()).collect();
        return Err(ExportError::DisjointRanges {
            channels: names.join(", "),
        });
    }
    Ok(range)
}

fn curve_of(
    calibration: &ThermalCalibration,
    channel: Channel,
) -> Result<&thermonav::stoch::thermal::ThermalCurve, ExportError> {
    let curve = &calibration
        .channels
        .get(&channel)
        .ok_or(ExportError::MissingChannel(channel.name()))?
        .bias;
    if curve.coefficients.len() > TERMS {
        return Err(ExportError::OrderTooHigh {
            channel: channel.name(),
            terms: curve.coefficients.len(),
        });
    }
    Ok(curve)
}

/// One sensor's curves over `range_c`, re-expanded about `reference_c`.
fn sensor_export(
    calibration: &ThermalCalibration,
    sensor: ImuSensor,
    range_c: [f64; 2],
    reference_c: f64,
) -> Result<SensorExport, ExportError> {
    let mut coefficients = [[0.0; TERMS]; 3];
    let mut narrowed_channels = Vec::new();
    for (axis, channel) in sensor.channels().into_iter().enumerate() {
        let curve = curve_of(calibration, channel)?;
        coefficients[axis] = reexpanded(
            &curve.coefficients,
            curve.reference_temperature_c,
            reference_c,
        );
        if curve.temperature_range_c != range_c {
            narrowed_channels.push(channel.name());
        }
    }
    Ok(SensorExport {
        sensor,
        temperature_range_c: range_c,
        reference_temperature_c: reference_c,
        coefficients,
        narrowed_channels,
    })
}

/// `value` as a 32-bit float parameter (a zero, of either sign, written as 0).
fn real(name: String, value: f64) -> Result<Parameter, ExportError> {
    match ParameterValue::real(value) {
        Some(value) => Ok(Parameter { name, value }),
        None => Err(ExportError::NotRepresentable { name, value }),
    }
}

fn integer(name: &str, value: i32) -> Parameter {
    Parameter {
        name: name.to_string(),
        value: ParameterValue::Integer(value),
    }
}

/// A temperature as PX4 and ArduPilot store it: the nearest 32-bit float, °C.
fn stored_temperature_c(temperature_c: f64) -> f64 {
    f64::from(temperature_c as f32)
}

/// The highest sensor instance both targets have parameters for: PX4's `TC_G0`..`TC_G2`
/// (`TC_A0`..`TC_A2`) and ArduPilot's `INS_TCAL1`..`INS_TCAL3`.
pub const MAX_INSTANCE: u8 = 2;

/// Which of the autopilot's sensors a parameter file is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExportTarget {
    /// The IMU's instance, 0 for the first (PX4 `TC_G0`, ArduPilot `INS_TCAL1`).
    pub instance: u8,
    /// PX4 device id of its gyro (`TC_Gn_ID`); 0 leaves it for the user to set.
    pub gyro_device_id: u32,
    /// PX4 device id of its accelerometer (`TC_An_ID`).
    pub accel_device_id: u32,
}

impl ExportTarget {
    fn checked(self) -> Result<Self, ExportError> {
        match self.instance <= MAX_INSTANCE {
            true => Ok(self),
            false => Err(ExportError::Instance(self.instance)),
        }
    }
}

/// PX4's parameters for the gyro and accelerometer of `target`: TREF is the middle of each
/// sensor's shared range (as stored, a 32-bit float, so that the re-expansion is about the
/// very value PX4 reads).
///
/// # Errors
/// A missing channel, a curve above order 3, channels without a common temperature, a value
/// beyond 32-bit float range, or an instance above [`MAX_INSTANCE`].
pub fn px4_parameters(
    calibration: &ThermalCalibration,
    target: ExportTarget,
) -> Result<ParameterFile, ExportError> {
    let target = target.checked()?;
    let mut parameters = vec![integer("TC_G_ENABLE", 1), integer("TC_A_ENABLE", 1)];
    let mut sensors = Vec::new();
    for sensor in [ImuSensor::Gyro, ImuSensor::Accelerometer] {
        let range_c = shared_range_c(calibration, &sensor.channels())?;
        let reference_c = stored_temperature_c(0.5 * (range_c[0] + range_c[1]));
        let export = sensor_export(calibration, sensor, range_c, reference_c)?;
        parameters.extend(px4_sensor_parameters(&export, target)?);
        sensors.push(export);
    }
    let mut comments = px4_comments(&sensors, target);
    let at = comments.len() - 2;
    comments.splice(at..at, held_out_comments(calibration));
    Ok(ParameterFile {
        target: ParameterTarget::Px4Tc,
        parameters,
        comments,
        sensors,
    })
}

/// `TC_Gn_*` or `TC_An_*` of one sensor.
fn px4_sensor_parameters(
    export: &SensorExport,
    target: ExportTarget,
) -> Result<Vec<Parameter>, ExportError> {
    let (prefix, device_id) = match export.sensor {
        ImuSensor::Gyro => (format!("TC_G{}", target.instance), target.gyro_device_id),
        ImuSensor::Accelerometer => (format!("TC_A{}", target.instance), target.accel_device_id),
    };
    // PX4 stores the id as int32 and compares it as uint32: the same 32 bits.
    let mut out = vec![integer(&format!("{prefix}_ID"), device_id as i32)];
    let [low_c, high_c] = export.temperature_range_c;
    out.push(real(format!("{prefix}_TMIN"), low_c)?);
    out.push(real(format!("{prefix}_TMAX"), high_c)?);
    out.push(real(
        format!("{prefix}_TREF"),
        export.reference_temperature_c,
    )?);
    for power in 0..TERMS {
        for (axis, coefficients) in export.coefficients.iter().enumerate() {
            out.push(real(
                format!("{prefix}_X{power}_{axis}"),
                coefficients[power],
            )?);
        }
    }
    Ok(out)
}

fn px4_comments(sensors: &[SensorExport], target: ExportTarget) -> Vec<String> {
    let mut lines = vec![
        "PX4 thermal compensation parameters (sensors/temperature_compensation) from a thermonav model bank".to_string(),
        "offset = X3*dT^3 + X2*dT^2 + X1*dT + X0, dT = clamp(T, TMIN, TMAX) - TREF (degC); subtracted from the raw reading".to_string(),
        "units: gyro rad/s per degC^k, accelerometer m/s^2 per degC^k; axes 0,1,2 = x fwd, y right, z down (FRD) of the sensor frame".to_string(),
        "no thermal scale-factor parameters exist in PX4: only the bias is compensated".to_string(),
    ];
    let n = target.instance;
    if target.gyro_device_id == 0 || target.accel_device_id == 0 {
        lines.push(format!("TC_G{n}_ID or TC_A{n}_ID is 0: set them to the IMU's device ids (calibrate from a ULog sweep, or export with --gyro-device-id/--accel-device-id), else PX4 applies nothing"));
    }
    lines.extend(narrowing_comments(sensors));
    lines.push(String::new());
    lines.push("Vehicle-Id Component-Id Name Value Type".to_string());
    lines
}

/// For a calibration from sweeps: which channels were left at order 0 by their held-out
/// legs, and what each chosen lag term would have added beyond the curve in T alone that the
/// file holds (the largest difference over the fitted blocks, in the channel's SI unit).
fn held_out_comments(calibration: &ThermalCalibration) -> Vec<String> {
    let mut lines = Vec::new();
    for (channel, cal) in &calibration.channels {
        let Some(selection) = &cal.selection else {
            continue;
        };
        let unit = channel.si_unit(thermonav::imu::SampleKind::Rates);
        if cal.bias.order == 0 {
            lines.push(format!(
                "{}: order 0 on held-out data (no thermal curve predicted unseen data better): its coefficients beyond the constant are 0",
                channel.name()
            ));
        }
        let Some(lagged) = &cal.lagged else {
            continue;
        };
        let added = calibration
            .sweep_blocks
            .iter()
            .map(|b| {
                let with_lag = cal
                    .bias_at_effective(b.effective_temperature_c(cal.lag_s()))
                    .0;
                let [low, high] = cal.bias.temperature_range_c;
                (with_lag - cal.bias.value_at(b.temperature_c.clamp(low, high))).abs()
            })
            .fold(0.0_f64, f64::max);
        lines.push(format!(
            "{}: the model chosen on held-out legs is b(T + tau dT/dt) of order {} with tau {:.1} s; this file holds the best curve in T alone (order {}), which differs from it by up to {added:.3e} {unit} on the sweeps",
            channel.name(),
            selection.chosen.order,
            lagged.lag.tau_s,
            cal.bias.order
        ));
    }
    lines
}

fn narrowing_comments(sensors: &[SensorExport]) -> Vec<String> {
    sensors
        .iter()
        .filter(|s| !s.narrowed_channels.is_empty())
        .map(|s| {
            format!(
                "{} fitted over a wider range than the shared TMIN..TMAX {}..{} degC: held at the shared bound beyond it",
                s.narrowed_channels.join(", "),
                s.temperature_range_c[0],
                s.temperature_range_c[1]
            )
        })
        .collect()
}

/// ArduPilot's parameters for the IMU of `target` (`INS_TCALn_*`, n = instance + 1): one
/// TMIN/TMAX, the range all six
/// curves share; the curves re-expanded about 35 °C, their constants left to ArduPilot's
/// offset calibration (module docs).
///
/// # Errors
/// As [`px4_parameters`].
pub fn ardupilot_parameters(
    calibration: &ThermalCalibration,
    target: ExportTarget,
) -> Result<ParameterFile, ExportError> {
    let prefix = format!("INS_TCAL{}", target.checked()?.instance + 1);
    let range_c = shared_range_c(calibration, &Channel::ALL)?;
    let mut parameters = vec![
        integer(&format!("{prefix}_ENABLE"), 1),
        real(format!("{prefix}_TMIN"), range_c[0])?,
        real(format!("{prefix}_TMAX"), range_c[1])?,
    ];
    let mut sensors = Vec::new();
    for sensor in [ImuSensor::Accelerometer, ImuSensor::Gyro] {
        let export = sensor_export(
            calibration,
            sensor,
            range_c,
            ARDUPILOT_REFERENCE_TEMPERATURE_C,
        )?;
        parameters.extend(ardupilot_sensor_parameters(&export, &prefix)?);
        sensors.push(export);
    }
    sensors.reverse();
    let mut comments = ardupilot_comments(&sensors, &prefix);
    comments.extend(held_out_comments(calibration));
    Ok(ParameterFile {
        target: ParameterTarget::ArdupilotTcal,
        parameters,
        comments,
        sensors,
    })
}

/// `INS_TCALn_ACCk_*` or `INS_TCALn_GYRk_*` (`prefix` = `INS_TCALn`), k = 1..=3, scaled by
/// 10⁶.
fn ardupilot_sensor_parameters(
    export: &SensorExport,
    prefix: &str,
) -> Result<Vec<Parameter>, ExportError> {
    let stem = match export.sensor {
        ImuSensor::Gyro => "GYR",
        ImuSensor::Accelerometer => "ACC",
    };
    let mut out = Vec::new();
    for power in 1..TERMS {
        for (axis, coefficients) in ["X", "Y", "Z"].iter().zip(&export.coefficients) {
            out.push(real(
                format!("{prefix}_{stem}{power}_{axis}"),
                coefficients[power] * ARDUPILOT_COEFFICIENT_SCALE,
            )?);
        }
    }
    Ok(out)
}

fn ardupilot_comments(sensors: &[SensorExport], prefix: &str) -> Vec<String> {
    let mut lines = vec![
        format!("ArduPilot IMU temperature calibration (AP_InertialSensor_tempcal) of the IMU of {prefix}_*, from a thermonav model bank"),
        "correction = p(clamp(T)) - p(clamp(T_cal)), p(T) = 1e-6 * (c1*d + c2*d^2 + c3*d^3), d = T - 35 degC, clamp to TMIN..TMAX".to_string(),
        "ACCk_*/GYRk_* hold c_k = 1e6 x the coefficient of d^k: micro-m/s^2 and micro-rad/s per degC^k; X, Y, Z = x fwd, y right, z down (FRD)".to_string(),
        "no constant term: the bias at 35 degC below is not a parameter; ArduPilot's offset calibration (INS_GYROFFS_* at boot, INS_ACCOFFS_*) measures the bias at T_cal (INS_GYR1_CALTEMP, INS_ACC1_CALTEMP), and with it the total correction is the bank's curve".to_string(),
        format!("no thermal scale-factor parameters exist in ArduPilot: only the bias is compensated; {prefix}_ENABLE = 1 takes effect after a reboot"),
    ];
    for sensor in sensors {
        for (channel, coefficients) in sensor.sensor.channels().iter().zip(&sensor.coefficients) {
            lines.push(format!(
                "{} bias at 35 degC (not a parameter): {:e} {}",
                channel.name(),
                coefficients[0],
                sensor.sensor.unit()
            ));
        }
    }
    lines.extend(narrowing_comments(sensors));
    lines
}

impl ParameterFile {
    /// The file's text: comments, then one line per parameter in the target's format.
    pub fn text(&self) -> String {
        let mut text = String::new();
        for comment in &self.comments {
            match comment.is_empty() {
                true => text.push_str("#\n"),
                false => {
                    let _ = writeln!(text, "# {comment}");
                }
            }
        }
        for parameter in &self.parameters {
            let _ = match self.target {
                ParameterTarget::Px4Tc => writeln!(
                    text,
                    "1\t1\t{}\t{}\t{}",
                    parameter.name,
                    parameter.value.text(),
                    parameter.value.mav_param_type()
                ),
                ParameterTarget::ArdupilotTcal => {
                    writeln!(text, "{},{}", parameter.name, parameter.value.text())
                }
            };
        }
        text
    }

    /// What the file holds, for `--json`.
    pub fn summary(&self) -> ExportSummary {
        ExportSummary {
            format: self.target,
            parameters: self.parameters.len(),
            sensors: self.sensors.clone(),
        }
    }
}

/// Writes `file` to `path` atomically.
///
/// # Errors
/// As [`write_atomically`]; a parameter that is not a finite number ([`crate::finite`]), and
/// nothing is written.
pub fn write_parameter_file(path: &Path, file: &ParameterFile) -> Result<(), WriteError> {
    write_atomically(path, |out| {
        check_parameters_finite(file)?;
        Ok(out.write_all(file.text().as_bytes())?)
    })
}

/// The first real parameter that is not finite, refused as [`crate::finite`] refuses.
fn check_parameters_finite(file: &ParameterFile) -> std::io::Result<()> {
    let bad = file.parameters.iter().find_map(|p| match p.value {
        ParameterValue::Real(v) if !v.is_finite() => Some((p, f64::from(v))),
        _ => None,
    });
    match bad {
        Some((p, value)) => {
            let path = format!("parameter {}", p.name);
            let e = crate::finite::NonFinite { path, value };
            Err(std::io::Error::new(std::io::ErrorKind::InvalidData, e))
        }
        None => Ok(()),
    }
}
