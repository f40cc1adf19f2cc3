//! Sensor profiles: the description of an IMU's errors, whose Gauss-Markov bias depends on
//! temperature.
//!
//! A profile is what a data sheet (or a simulation's truth) says about a sensor, and it has
//! three users: the simulator draws errors from it (`sim::errors`, `sim::chamber`,
//! `sim::vessel`), the navigation filter takes its noise model from it
//! ([`SensorProfile::stochastic_model`], for `integrate --profile` and the data-sheet
//! baseline; that conversion lives with the filter's model in `nav::profile_model`, so this
//! module depends on nothing of `nav`), and `thermonav-io` reads and writes it as TOML. So it
//! lives here, at the top level, rather than in `sim` (no core module may depend on `sim`) or
//! in `imu` (which holds samples and series). Drawing the random errors a profile describes
//! stays in `sim::errors`.
//!
//! A profile gives, per channel, the white-noise density, a table of Gauss-Markov bias
//! parameters (Tc, σ) at several temperatures, an optional bias random walk, the turn-on bias
//! spread, deterministic bias and scale-factor temperature coefficients, an optional
//! Gauss-Markov scale-factor error and the quantisation step. Values are SI: gyros in rad/s
//! (densities rad/√s), accelerometers in m/s² (densities m/s/√s).
//!
//! Between table points, ln Tc and ln σ are interpolated with a monotone cubic (Fritsch &
//! Carlson 1980): smooth, never overshooting a neighbour, always positive. Outside the table
//! the end value is held.

use crate::imu::{Channel, Sensor};
use crate::units::{
    arw_deg_per_sqrt_h_to_rad_per_sqrt_s, deg_to_rad, mg_to_m_per_s2,
    vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s,
};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Data-sheet noise figures in the units data sheets use.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DatasheetValues {
    /// Gyro angle random walk, deg/√h.
    pub gyro_arw_deg_sqrt_h: f64,
    /// Gyro in-run bias stability (Allan minimum), deg/s.
    pub gyro_bias_stability_deg_s: f64,
    /// Accelerometer velocity random walk, m/s/√h.
    pub accel_vrw_m_s_sqrt_h: f64,
    /// Accelerometer in-run bias stability (Allan minimum), mg.
    pub accel_bias_stability_mg: f64,
    /// Correlation time assumed for the biases, s.
    pub correlation_time_s: f64,
}

impl DatasheetValues {
    /// Analog Devices ADIS16364 data sheet (Rev. B): 2.0 °/√h, 0.007 °/s, 0.12 m/s/√h,
    /// 0.1 mg; the data sheet gives no correlation time, so 1 h.
    pub fn adis16364() -> Self {
        Self {
            gyro_arw_deg_sqrt_h: 2.0,
            gyro_bias_stability_deg_s: 0.007,
            accel_vrw_m_s_sqrt_h: 0.12,
            accel_bias_stability_mg: 0.1,
            correlation_time_s: 3600.0,
        }
    }
}

/// Gauss-Markov bias parameters measured at one temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GaussMarkovPoint {
    /// Temperature, °C.
    pub temperature_c: f64,
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Standard deviation σ, rad/s or m/s².
    pub sigma: f64,
}

/// A Gauss-Markov scale-factor error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ScaleFactorGaussMarkov {
    /// Correlation time, s.
    pub correlation_time_s: f64,
    /// Standard deviation, ppm.
    pub sigma_ppm: f64,
}

/// Error model of one channel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChannelProfile {
    /// White-noise density N (ARW rad/√s, VRW m/s/√s).
    pub white_noise_density: f64,
    /// Gauss-Markov bias table, strictly increasing in temperature.
    pub bias_gauss_markov: Vec<GaussMarkovPoint>,
    /// Bias random-walk density K (rad/s/√s or m/s²/√s); 0 for none.
    pub bias_random_walk_density: f64,
    /// Standard deviation of the unit's fixed bias, drawn once per unit (unit to unit; the
    /// data sheet's initial bias), rad/s or m/s².
    pub turn_on_bias_sigma: f64,
    /// Standard deviation of the offset each power-on adds to the unit's fixed bias (the
    /// turn-on to turn-on repeatability), rad/s or m/s²; 0 for none.
    #[serde(default)]
    pub power_on_offset_sigma: f64,
    /// Deterministic bias change per °C away from the reference temperature.
    pub bias_temperature_coefficient_per_c: f64,
    /// Quadratic term of the deterministic bias, per °C² away from the reference temperature.
    #[serde(default)]
    pub bias_temperature_quadratic_per_c2: f64,
    /// Deterministic scale-factor change per °C away from the reference temperature, ppm/°C.
    pub scale_factor_temperature_coefficient_ppm_per_c: f64,
    /// Gauss-Markov scale-factor error, when modelled.
    pub scale_factor_gauss_markov: Option<ScaleFactorGaussMarkov>,
    /// Quantisation step (one LSB), rad/s or m/s²; 0 for none.
    pub quantization_step: f64,
    /// Thermal lag τ of the MEMS structure behind the temperature sensor, s: the structure's
    /// temperature follows the sensor's through dT_s/dt = (T − T_s)/τ, and every temperature
    /// term of the channel acts at T_s (to first order b(T − τ dT/dt)); 0 for none.
    #[serde(default)]
    pub thermal_lag_s: f64,
}

/// A whole sensor profile.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensorProfile {
    /// Name shown in reports.
    pub name: String,
    /// Temperature at which the deterministic temperature terms vanish, °C.
    pub reference_temperature_c: f64,
    /// One profile per channel; all six are required.
    pub channels: BTreeMap<Channel, ChannelProfile>,
}

/// The Gauss-Markov bias of a channel at one temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BiasAt {
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Standard deviation σ, rad/s or m/s².
    pub sigma: f64,
}

/// Why a profile is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// A channel is missing.
    #[error("sensor profile has no entry for channel {0}")]
    MissingChannel(&'static str),
    /// A channel has no Gauss-Markov point.
    #[error("channel {0}: bias_gauss_markov needs at least one point")]
    EmptyTable(&'static str),
    /// Table temperatures not strictly increasing.
    #[error(
        "channel {channel}: bias_gauss_markov temperatures must increase strictly ({previous_c} °C then {next_c} °C)"
    )]
    TableOrder {
        /// Channel name.
        channel: &'static str,
        /// Earlier temperature.
        previous_c: f64,
        /// Later temperature.
        next_c: f64,
    },
    /// A value that must be finite and positive (or non-negative) is not.
    #[error("channel {channel}: {field} = {value} must be finite and {expected}")]
    Value {
        /// Channel name.
        channel: &'static str,
        /// Field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
}

impl SensorProfile {
    /// Checks every channel: all six present, tables non-empty and increasing, values finite
    /// with the right sign.
    ///
    /// # Errors
    /// The first [`ProfileError`] found.
    pub fn validate(&self) -> Result<(), ProfileError> {
        for channel in Channel::ALL {
            let profile = self
                .channels
                .get(&channel)
                .ok_or(ProfileError::MissingChannel(channel.name()))?;
            profile.validate(channel.name())?;
        }
        Ok(())
    }

    /// The same profile with every channel replaced by `channel` (controlled experiments).
    pub fn with_every_channel(mut self, channel: &ChannelProfile) -> Self {
        for p in self.channels.values_mut() {
            *p = channel.clone();
        }
        self
    }

    /// The profile of one channel (present after [`SensorProfile::validate`]).
    pub fn channel(&self, channel: Channel) -> Option<&ChannelProfile> {
        self.channels.get(&channel)
    }
}

fn check(
    channel: &'static str,
    field: &'static str,
    value: f64,
    positive: bool,
) -> Result<(), ProfileError> {
    let ok = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
    if ok {
        return Ok(());
    }
    let expected = if positive { "positive" } else { "non-negative" };
    Err(ProfileError::Value {
        channel,
        field,
        value,
        expected,
    })
}

impl ChannelProfile {
    /// A channel with stochastic errors only: white noise of density `white_noise_density`, a
    /// Gauss-Markov bias (one table point, so held at every temperature) and a bias random walk;
    /// no turn-on bias, temperature terms, scale-factor error or quantisation.
    pub fn stochastic_only(
        white_noise_density: f64,
        bias: GaussMarkovPoint,
        bias_random_walk_density: f64,
    ) -> Self {
        Self {
            white_noise_density,
            bias_gauss_markov: vec![bias],
            bias_random_walk_density,
            turn_on_bias_sigma: 0.0,
            power_on_offset_sigma: 0.0,
            bias_temperature_coefficient_per_c: 0.0,
            bias_temperature_quadratic_per_c2: 0.0,
            scale_factor_temperature_coefficient_ppm_per_c: 0.0,
            scale_factor_gauss_markov: None,
            quantization_step: 0.0,
            thermal_lag_s: 0.0,
        }
    }

    fn validate(&self, channel: &'static str) -> Result<(), ProfileError> {
        check(
            channel,
            "white_noise_density",
            self.white_noise_density,
            false,
        )?;
        check(
            channel,
            "bias_random_walk_density",
            self.bias_random_walk_density,
            false,
        )?;
        check(
            channel,
            "turn_on_bias_sigma",
            self.turn_on_bias_sigma,
            false,
        )?;
        check(channel, "quantization_step", self.quantization_step, false)?;
        check(channel, "thermal_lag_s", self.thermal_lag_s, false)?;
        check(
            channel,
            "power_on_offset_sigma",
            self.power_on_offset_sigma,
            false,
        )?;
        check(
            channel,
            "|bias_temperature_quadratic_per_c2|",
            self.bias_temperature_quadratic_per_c2.abs(),
            false,
        )?;
        check(
            channel,
            "|bias_temperature_coefficient_per_c|",
            self.bias_temperature_coefficient_per_c.abs(),
            false,
        )?;
        let sf_tempco = self.scale_factor_temperature_coefficient_ppm_per_c.abs();
        check(
            channel,
            "|scale_factor_temperature_coefficient_ppm_per_c|",
            sf_tempco,
            false,
        )?;
        if let Some(sf) = self.scale_factor_gauss_markov {
            check(
                channel,
                "scale_factor_gauss_markov.correlation_time_s",
                sf.correlation_time_s,
                true,
            )?;
            check(
                channel,
                "scale_factor_gauss_markov.sigma_ppm",
                sf.sigma_ppm,
                false,
            )?;
        }
        self.validate_table(channel)
    }

    fn validate_table(&self, channel: &'static str) -> Result<(), ProfileError> {
        if self.bias_gauss_markov.is_empty() {
            return Err(ProfileError::EmptyTable(channel));
        }
        for point in &self.bias_gauss_markov {
            check(
                channel,
                "bias_gauss_markov.temperature_c",
                point.temperature_c.abs(),
                false,
            )?;
            check(
                channel,
                "bias_gauss_markov.correlation_time_s",
                point.correlation_time_s,
                true,
            )?;
            check(channel, "bias_gauss_markov.sigma", point.sigma, true)?;
        }
        match self
            .bias_gauss_markov
            .windows(2)
            .find(|w| w[0].temperature_c >= w[1].temperature_c)
        {
            Some(w) => Err(ProfileError::TableOrder {
                channel,
                previous_c: w[0].temperature_c,
                next_c: w[1].temperature_c,
            }),
            None => Ok(()),
        }
    }

    /// The deterministic (repeatable) bias change at `delta_c` = T − T_ref:
    /// c₁ ΔT + c₂ ΔT², channel unit.
    pub fn temperature_bias(&self, delta_c: f64) -> f64 {
        (self.bias_temperature_coefficient_per_c + self.bias_temperature_quadratic_per_c2 * delta_c)
            * delta_c
    }

    /// The Gauss-Markov bias at `temperature_c` (monotone cubic in ln Tc and ln σ).
    pub fn bias_at(&self, temperature_c: f64) -> BiasAt {
        let temps: Vec<f64> = self
            .bias_gauss_markov
            .iter()
            .map(|p| p.temperature_c)
            .collect();
        let ln_tc: Vec<f64> = self
            .bias_gauss_markov
            .iter()
            .map(|p| p.correlation_time_s.ln())
            .collect();
        let ln_sigma: Vec<f64> = self
            .bias_gauss_markov
            .iter()
            .map(|p| p.sigma.ln())
            .collect();
        BiasAt {
            correlation_time_s: monotone_cubic(&temps, &ln_tc, temperature_c).exp(),
            sigma: monotone_cubic(&temps, &ln_sigma, temperature_c).exp(),
        }
    }
}

/// Fritsch-Carlson monotone cubic Hermite interpolation of (xs, ys) at `x`; the end values are
/// held outside [xs₀, xsₙ]. `xs` strictly increasing and non-empty.
pub fn monotone_cubic(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len();
    if n == 1 || x <= xs[0] {
        return ys[0];
    }
    if x >= xs[n - 1] {
        return ys[n - 1];
    }
    let k = xs.partition_point(|&v| v <= x) - 1;
    let slopes = hermite_slopes(xs, ys);
    let h = xs[k + 1] - xs[k];
    let t = (x - xs[k]) / h;
    let (t2, t3) = (t * t, t * t * t);
    (2.0 * t3 - 3.0 * t2 + 1.0) * ys[k]
        + (t3 - 2.0 * t2 + t) * h * slopes[k]
        + (-2.0 * t3 + 3.0 * t2) * ys[k + 1]
        + (t3 - t2) * h * slopes[k + 1]
}

/// Tangents at the knots: zero at local extrema, the harmonic-mean form elsewhere (Fritsch &
/// Butland 1984, the variant used by PCHIP), one-sided at the ends.
fn hermite_slopes(xs: &[f64], ys: &[f64]) -> Vec<f64> {
    let secants: Vec<f64> = xs
        .windows(2)
        .zip(ys.windows(2))
        .map(|(x, y)| (y[1] - y[0]) / (x[1] - x[0]))
        .collect();
    let n = xs.len();
    let mut slopes = vec![0.0; n];
    slopes[0] = secants[0];
    slopes[n - 1] = secants[n - 2];
    for k in 1..n - 1 {
        let (a, b) = (secants[k - 1], secants[k]);
        if a * b > 0.0 {
            let (h0, h1) = (xs[k] - xs[k - 1], xs[k + 1] - xs[k]);
            let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
            slopes[k] = (w1 + w2) / (w1 / a + w2 / b);
        }
    }
    slopes
}

/// The temperatures of the default chamber campaign, °C.
pub const DEFAULT_TEMPERATURES_C: [f64; 6] = [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0];

/// Gyro bias correlation times at the default temperatures, s (x axis; y ×0.8, z ×1.25).
/// Not monotonic in temperature, spanning tens of seconds to half an hour, as reported for
/// MEMS gyros.
const GYRO_TC_S: [f64; 6] = [40.0, 110.0, 300.0, 150.0, 700.0, 1800.0];
/// Gyro bias σ at the default temperatures, as multiples of the datasheet figure.
const GYRO_SIGMA_SCALE: [f64; 6] = [1.5, 1.2, 0.9, 1.0, 1.25, 1.7];
/// Accelerometer bias correlation times, s (x axis; y ×0.8, z ×1.25).
const ACCEL_TC_S: [f64; 6] = [60.0, 25.0, 180.0, 400.0, 250.0, 900.0];
/// Accelerometer bias σ, multiples of the datasheet figure.
const ACCEL_SIGMA_SCALE: [f64; 6] = [1.4, 1.1, 1.0, 0.9, 1.2, 1.6];
/// Per-axis multipliers of Tc and σ (x, y, z).
const AXIS_TC_SCALE: [f64; 3] = [1.0, 0.8, 1.25];
const AXIS_SIGMA_SCALE: [f64; 3] = [1.0, 1.1, 0.9];

pub use crate::stoch::noise_terms::GAUSS_MARKOV_ADEV_PEAK_RATIO;

/// Turn-on to turn-on bias repeatability of the built-in gyros, deg/s: a tenth of the
/// data sheet's ±3 deg/s (3σ) initial bias, which is mostly unit to unit.
const POWER_ON_OFFSET_DEG_S: f64 = 0.1;
/// Turn-on to turn-on repeatability of the built-in accelerometers, mg (a tenth of ±8 mg, 3σ).
const POWER_ON_OFFSET_MG: f64 = 0.27;
/// Curvature of the built-in gyro bias curve, deg/s/°C²: over ±50 °C it bends the linear
/// 0.01 deg/s/°C by a quarter, as MEMS bias curves bend.
const BIAS_CURVATURE_DEG_S_PER_C2: f64 = 5e-5;
/// Curvature of the built-in accelerometer bias curve, mg/°C².
const BIAS_CURVATURE_MG_PER_C2: f64 = 2.5e-4;

/// The built-in ADIS16364-like profile, from the datasheet figures quoted by the paper
/// (method.md): gyro ARW 2 deg/√h, in-run bias stability 0.007 deg/s, initial bias ±3 deg/s
/// (3σ), bias tempco ±0.01 deg/s/°C, LSB 0.05 deg/s; accelerometer VRW 0.12 m/s/√h, in-run
/// bias stability 0.1 mg, initial bias ±8 mg (3σ), bias tempco ±0.05 mg/°C, LSB 1 mg.
/// Correlation times vary with temperature, not monotonically (see the tables above).
pub fn adis16364_like() -> SensorProfile {
    let channels = Channel::ALL
        .iter()
        .map(|&c| (c, default_channel(c)))
        .collect();
    SensorProfile {
        name: "ADIS16364-like (built-in)".into(),
        reference_temperature_c: 25.0,
        channels,
    }
}

/// A profile in which the stochastic model's temperature matters (the demo's second scenario):
/// a quieter sensor than the ADIS16364, so that the bias, not the angle random walk, drives the
/// drift in an outage, with a bias whose instability changes several-fold with temperature.
///
/// - Gyro ARW 0.3 deg/√h (a good consumer MEMS gyro; at 2 deg/√h the white noise alone gives
///   ~130 m per axis after 100 s and hides every bias model) and accelerometer VRW
///   0.05 m/s/√h.
/// - Gauss-Markov σ at −40..+60 °C by 20 °C: gyro 10, 20, 35, 50, 25, 10 deg/h and
///   accelerometer 0.05, 0.1, 0.2, 0.25, 0.12, 0.05 mg: largest near room temperature and
///   5× smaller at the ends (a 5× range, as reported between the ends of MEMS ranges), so a
///   model from a far temperature under-states the drift by 5×.
/// - Correlation times 1000, 600, 200, 100, 300, 800 s: the bias wanders fastest where it is
///   largest.
/// - The deterministic bias curve, fixed bias and power-on offset of the built-in profile
///   halved (±0.5 deg/s unit to unit, 0.05 deg/s per power-on; ±2 mg, 0.2 mg), no scale
///   factor temperature term, fine quantisation (0.001 deg/s, 0.01 mg): nothing else competes
///   with the Gauss-Markov bias.
pub fn temperature_sensitive() -> SensorProfile {
    let channels = Channel::ALL
        .iter()
        .map(|&c| (c, sensitive_channel(c)))
        .collect();
    SensorProfile {
        name: "temperature-sensitive MEMS (built-in)".into(),
        reference_temperature_c: 25.0,
        channels,
    }
}

/// Gyro σ of [`temperature_sensitive`], deg/h.
const SENSITIVE_GYRO_SIGMA_DEG_H: [f64; 6] = [10.0, 20.0, 35.0, 50.0, 25.0, 10.0];
/// Accelerometer σ of [`temperature_sensitive`], mg.
const SENSITIVE_ACCEL_SIGMA_MG: [f64; 6] = [0.05, 0.1, 0.2, 0.25, 0.12, 0.05];
/// Correlation times of [`temperature_sensitive`], s.
const SENSITIVE_TC_S: [f64; 6] = [1000.0, 600.0, 200.0, 100.0, 300.0, 800.0];

fn sensitive_channel(channel: Channel) -> ChannelProfile {
    let axis = channel.index() % 3;
    let (scale, sign) = ([1.0, 0.9, 1.1][axis], [1.0, -0.6, 0.8][axis]);
    let table = |sigma: [f64; 6], to_si: fn(f64) -> f64| {
        (0..6)
            .map(|k| GaussMarkovPoint {
                temperature_c: DEFAULT_TEMPERATURES_C[k],
                correlation_time_s: SENSITIVE_TC_S[k] * scale,
                sigma: to_si(sigma[k]) * scale,
            })
            .collect()
    };
    let base = ChannelProfile {
        scale_factor_temperature_coefficient_ppm_per_c: 0.0,
        ..default_channel(channel)
    };
    match channel.sensor() {
        Sensor::Gyro => ChannelProfile {
            white_noise_density: arw_deg_per_sqrt_h_to_rad_per_sqrt_s(0.3),
            bias_gauss_markov: table(
                SENSITIVE_GYRO_SIGMA_DEG_H,
                crate::units::deg_per_h_to_rad_per_s,
            ),
            turn_on_bias_sigma: deg_to_rad(0.5),
            power_on_offset_sigma: deg_to_rad(0.05),
            bias_temperature_coefficient_per_c: sign * deg_to_rad(0.005),
            bias_temperature_quadratic_per_c2: -sign
                * deg_to_rad(BIAS_CURVATURE_DEG_S_PER_C2 / 2.0),
            quantization_step: deg_to_rad(0.001),
            ..base
        },
        Sensor::Accelerometer => ChannelProfile {
            white_noise_density: vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s(0.05),
            bias_gauss_markov: table(SENSITIVE_ACCEL_SIGMA_MG, mg_to_m_per_s2),
            turn_on_bias_sigma: mg_to_m_per_s2(2.0),
            power_on_offset_sigma: mg_to_m_per_s2(0.2),
            bias_temperature_coefficient_per_c: sign * mg_to_m_per_s2(0.025),
            bias_temperature_quadratic_per_c2: -sign
                * mg_to_m_per_s2(BIAS_CURVATURE_MG_PER_C2 / 2.0),
            quantization_step: mg_to_m_per_s2(0.01),
            ..base
        },
    }
}

fn default_channel(channel: Channel) -> ChannelProfile {
    let sheet = DatasheetValues::adis16364();
    let axis = channel.index() % 3;
    let tempco_sign = [1.0, -0.6, 0.8][axis];
    match channel.sensor() {
        Sensor::Gyro => ChannelProfile {
            white_noise_density: arw_deg_per_sqrt_h_to_rad_per_sqrt_s(sheet.gyro_arw_deg_sqrt_h),
            bias_gauss_markov: table(
                &GYRO_TC_S,
                &GYRO_SIGMA_SCALE,
                deg_to_rad(sheet.gyro_bias_stability_deg_s),
                axis,
            ),
            bias_random_walk_density: 0.0,
            turn_on_bias_sigma: deg_to_rad(1.0),
            power_on_offset_sigma: deg_to_rad(POWER_ON_OFFSET_DEG_S),
            bias_temperature_coefficient_per_c: tempco_sign * deg_to_rad(0.01),
            bias_temperature_quadratic_per_c2: -tempco_sign
                * deg_to_rad(BIAS_CURVATURE_DEG_S_PER_C2),
            scale_factor_temperature_coefficient_ppm_per_c: tempco_sign * 40.0,
            scale_factor_gauss_markov: None,
            quantization_step: deg_to_rad(0.05),
            thermal_lag_s: 0.0,
        },
        Sensor::Accelerometer => ChannelProfile {
            white_noise_density: vrw_m_per_s_per_sqrt_h_to_m_per_s_per_sqrt_s(
                sheet.accel_vrw_m_s_sqrt_h,
            ),
            bias_gauss_markov: table(
                &ACCEL_TC_S,
                &ACCEL_SIGMA_SCALE,
                mg_to_m_per_s2(sheet.accel_bias_stability_mg),
                axis,
            ),
            bias_random_walk_density: 0.0,
            turn_on_bias_sigma: mg_to_m_per_s2(8.0 / 3.0),
            power_on_offset_sigma: mg_to_m_per_s2(POWER_ON_OFFSET_MG),
            bias_temperature_coefficient_per_c: tempco_sign * mg_to_m_per_s2(0.05),
            bias_temperature_quadratic_per_c2: -tempco_sign
                * mg_to_m_per_s2(BIAS_CURVATURE_MG_PER_C2),
            scale_factor_temperature_coefficient_ppm_per_c: tempco_sign * 25.0,
            scale_factor_gauss_markov: None,
            quantization_step: mg_to_m_per_s2(1.0),
            thermal_lag_s: 0.0,
        },
    }
}

fn table(
    tc_s: &[f64; 6],
    sigma_scale: &[f64; 6],
    stability: f64,
    axis: usize,
) -> Vec<GaussMarkovPoint> {
    let sigma = stability / GAUSS_MARKOV_ADEV_PEAK_RATIO;
    (0..6)
        .map(|k| GaussMarkovPoint {
            temperature_c: DEFAULT_TEMPERATURES_C[k],
            correlation_time_s: tc_s[k] * AXIS_TC_SCALE[axis],
            sigma: sigma * sigma_scale[k] * AXIS_SIGMA_SCALE[axis],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_profile_is_valid_and_hits_its_table_points() {
        let profile = adis16364_like();
        profile.validate().unwrap();
        let gy = profile.channel(Channel::Gy).unwrap();
        let at = gy.bias_at(20.0);
        assert!((at.correlation_time_s - 150.0 * 0.8).abs() < 1e-9);
        let sigma = deg_to_rad(0.007) / 0.62 * 1.1;
        assert!((at.sigma - sigma).abs() < 1e-15);
    }

    #[test]
    fn interpolation_stays_between_neighbours_and_is_continuous() {
        let gx = adis16364_like().channels[&Channel::Gx].clone();
        for k in 0..5 {
            let (a, b) = (gx.bias_gauss_markov[k], gx.bias_gauss_markov[k + 1]);
            let (lo, hi) = (
                a.correlation_time_s.min(b.correlation_time_s),
                a.correlation_time_s.max(b.correlation_time_s),
            );
            for step in 0..=20 {
                let t = a.temperature_c + (b.temperature_c - a.temperature_c) * step as f64 / 20.0;
                let tc = gx.bias_at(t).correlation_time_s;
                assert!(
                    tc >= lo * (1.0 - 1e-12) && tc <= hi * (1.0 + 1e-12),
                    "{t} °C: {tc}"
                );
            }
        }
        // Continuity across a knot (Hermite pieces share the knot value).
        let left = gx.bias_at(20.0 - 1e-9).correlation_time_s;
        let right = gx.bias_at(20.0 + 1e-9).correlation_time_s;
        assert!((left - right).abs() < 1e-6);
        // End values held outside the table.
        assert_eq!(gx.bias_at(-60.0).correlation_time_s, 40.0);
    }

    #[test]
    fn monotone_cubic_reproduces_a_straight_line_exactly() {
        // On collinear data all secants equal the slope, so the Hermite cubic is that line.
        let xs = [0.0, 1.0, 3.0, 4.0];
        let ys: Vec<f64> = xs.iter().map(|x| 2.0 * x - 1.0).collect();
        for x in [0.5, 1.7, 2.9, 3.3] {
            assert!((monotone_cubic(&xs, &ys, x) - (2.0 * x - 1.0)).abs() < 1e-12);
        }
    }

    #[test]
    fn invalid_profiles_are_named() {
        let mut profile = adis16364_like();
        profile.channels.remove(&Channel::Az);
        assert_eq!(profile.validate(), Err(ProfileError::MissingChannel("az")));
        let mut profile = adis16364_like();
        profile
            .channels
            .get_mut(&Channel::Gx)
            .unwrap()
            .bias_gauss_markov[1]
            .correlation_time_s = -1.0;
        assert!(matches!(
            profile.validate(),
            Err(ProfileError::Value { channel: "gx", .. })
        ));
    }
}
