//! The stochastic model of the IMU errors that the filters carry, per axis:
//!
//! - white noise of density N (angle random walk, rad/√s; velocity random walk, m/s/√s), from
//!   the bank's Allan fit at τ = 1 s;
//! - a first-order Gauss-Markov bias (Tc, σ) from the bank's Gauss-Markov models;
//! - a first-order Gauss-Markov scale-factor error, which a static record cannot reveal, from
//!   a stated prior ([`ScaleFactorPrior`]).
//!
//! Discretisation over an interval Δt is exact for the Gauss-Markov states:
//! x_{k+1} = e^{−Δt/Tc} x_k + w_k, var(w_k) = σ²(1 − e^{−2Δt/Tc}); the white noise enters the
//! velocity and attitude errors as C_b^n diag(N²) C_n^b Δt, averaged over the interval with the
//! trapezoidal rule ½(Φ Q Φᵀ + Q) (Groves 2013 §3.2.3).

use crate::frames::{Body, Ned, Rotation};
use crate::imu::Channel;
use crate::ins::error_model::{CorrelationTimes, STATES, SystemMatrix, block};
use crate::ins::transition::{NavBlock, ProcessNoise, SensorDiagonal, Transition};
use crate::stoch::bank::{
    BankError, ChannelModel, GaussMarkovSource, ModelBank, Placement, SelectedModel, Selection,
};
use nalgebra::Matrix3;
use serde::Serialize;

/// A first-order Gauss-Markov process: correlation time and steady-state standard deviation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GaussMarkovParameters {
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
    /// Steady-state standard deviation σ, in the state's unit.
    pub sigma: f64,
}

impl GaussMarkovParameters {
    /// The transition factor e^{−Δt/Tc}.
    pub fn transition(&self, dt_s: f64) -> f64 {
        (-dt_s / self.correlation_time_s).exp()
    }

    /// The driving-noise variance over Δt, σ²(1 − e^{−2Δt/Tc}) (computed with `exp_m1` so
    /// that it stays accurate for Δt ≪ Tc).
    pub fn discrete_variance(&self, dt_s: f64) -> f64 {
        -self.sigma * self.sigma * (-2.0 * dt_s / self.correlation_time_s).exp_m1()
    }
}

/// The error model of one sensor axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AxisModel {
    /// White-noise density N: rad/√s for gyros, m/s/√s for accelerometers.
    pub white_noise_density: f64,
    /// Gauss-Markov bias: σ in rad/s or m/s².
    pub bias: GaussMarkovParameters,
    /// Gauss-Markov scale-factor error: σ dimensionless (1e-6 = 1 ppm).
    pub scale_factor: GaussMarkovParameters,
}

/// Scale-factor error priors for both sensor kinds (not observable from static records).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ScaleFactorPrior {
    /// Gyro scale-factor error.
    pub gyro: GaussMarkovParameters,
    /// Accelerometer scale-factor error.
    pub accel: GaussMarkovParameters,
}

impl Default for ScaleFactorPrior {
    /// 1000 ppm with a 1 h correlation time for both: the scale-factor error of a consumer
    /// MEMS unit over temperature (ADIS16364 data sheet: ±1 % initial, 40 ppm/°C).
    fn default() -> Self {
        let prior = GaussMarkovParameters {
            correlation_time_s: 3600.0,
            sigma: 1e-3,
        };
        Self {
            gyro: prior,
            accel: prior,
        }
    }
}

/// Which model to take from a bank.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BankChoice {
    /// Temperature at which to select, °C.
    pub temperature_c: f64,
    /// Nearest entry or linear interpolation.
    pub selection: Selection,
    /// Which of the bank's Gauss-Markov estimates to use.
    pub source: GaussMarkovSource,
}

/// Why an IMU model cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SensorModelError {
    /// The bank cannot give the requested Gauss-Markov model.
    #[error(transparent)]
    Bank(#[from] BankError),
    /// The bank's entry has no white-noise density for a channel.
    #[error(
        "the entry at {temperature_c} °C has no white-noise density (Allan τ = 1 s fit) for channel {channel}"
    )]
    NoWhiteNoise {
        /// Entry temperature.
        temperature_c: f64,
        /// Channel name.
        channel: &'static str,
    },
    /// A parameter is not finite and positive.
    #[error("{what} = {value} must be finite and positive (a sigma may be 0)")]
    Parameter {
        /// Which parameter.
        what: String,
        /// The value.
        value: f64,
    },
}

/// The error model of a whole IMU: three gyro axes then three accelerometer axes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ImuStochasticModel {
    /// Gyro x, y, z.
    pub gyro: [AxisModel; 3],
    /// Accelerometer x, y, z.
    pub accel: [AxisModel; 3],
}

impl ImuStochasticModel {
    /// The model of every channel selected from `bank` at `choice`, with the scale-factor
    /// priors. White-noise densities are taken from the same entries (interpolated with the
    /// same weight under linear selection).
    ///
    /// # Errors
    /// [`SensorModelError`] when a channel, a Gauss-Markov model or a white-noise density is
    /// missing, or a value is not usable.
    pub fn from_bank(
        bank: &ModelBank,
        choice: &BankChoice,
        scale: &ScaleFactorPrior,
    ) -> Result<Self, SensorModelError> {
        let axis = |channel: Channel, scale_factor: GaussMarkovParameters| {
            let selected: SelectedModel = bank.select(
                choice.temperature_c,
                channel,
                choice.source,
                choice.selection,
            )?;
            let white = white_density(bank, &selected.placement, channel, choice.source)?;
            Ok::<_, SensorModelError>(AxisModel {
                white_noise_density: white,
                bias: GaussMarkovParameters {
                    correlation_time_s: selected.correlation_time_s,
                    sigma: selected.sigma,
                },
                scale_factor,
            })
        };
        Self::from_axes(axis, scale)
    }

    /// The six axes from a per-channel constructor, validated.
    pub fn from_axes(
        axis: impl Fn(Channel, GaussMarkovParameters) -> Result<AxisModel, SensorModelError>,
        scale: &ScaleFactorPrior,
    ) -> Result<Self, SensorModelError> {
        let [gx, gy, gz, ax, ay, az] = Channel::ALL;
        let model = Self {
            gyro: [
                axis(gx, scale.gyro)?,
                axis(gy, scale.gyro)?,
                axis(gz, scale.gyro)?,
            ],
            accel: [
                axis(ax, scale.accel)?,
                axis(ay, scale.accel)?,
                axis(az, scale.accel)?,
            ],
        };
        model.validate()?;
        Ok(model)
    }

    /// Checks that every density and Tc is finite and positive and every σ finite and
    /// non-negative.
    ///
    /// # Errors
    /// [`SensorModelError::Parameter`] naming the first bad value.
    pub fn validate(&self) -> Result<(), SensorModelError> {
        let axes = self.gyro.iter().chain(&self.accel).zip(Channel::ALL);
        for (a, channel) in axes {
            let bad = |what: &str, value: f64| SensorModelError::Parameter {
                what: format!("{} {what}", channel.name()),
                value,
            };
            if !(a.white_noise_density.is_finite() && a.white_noise_density > 0.0) {
                return Err(bad("white-noise density", a.white_noise_density));
            }
            for (name, gm) in [("bias", a.bias), ("scale-factor", a.scale_factor)] {
                if let Some((part, value)) = invalid_part(gm) {
                    return Err(bad(&format!("{name} {part}"), value));
                }
            }
        }
        Ok(())
    }

    /// Multiplies every white-noise density by `factor` (vibration on a vehicle raises the
    /// effective noise above a static record's; a tuning knob navigation engineers expect).
    pub fn scale_white_noise(&mut self, factor: f64) {
        for axis in self.gyro.iter_mut().chain(self.accel.iter_mut()) {
            axis.white_noise_density *= factor;
        }
    }

    /// The correlation times of the four Gauss-Markov groups, for the system matrix.
    pub fn correlation_times(&self) -> CorrelationTimes {
        CorrelationTimes {
            gyro_bias_s: self.gyro.map(|a| a.bias.correlation_time_s),
            accel_bias_s: self.accel.map(|a| a.bias.correlation_time_s),
            gyro_scale_s: self.gyro.map(|a| a.scale_factor.correlation_time_s),
            accel_scale_s: self.accel.map(|a| a.scale_factor.correlation_time_s),
        }
    }

    /// The Gauss-Markov groups in state order (gyro bias, accel bias, gyro scale, accel
    /// scale), each with its first state index.
    pub fn gauss_markov_states(&self) -> [(usize, [GaussMarkovParameters; 3]); 4] {
        [
            (block::GYRO_BIAS, self.gyro.map(|a| a.bias)),
            (block::ACCEL_BIAS, self.accel.map(|a| a.bias)),
            (block::GYRO_SCALE, self.gyro.map(|a| a.scale_factor)),
            (block::ACCEL_SCALE, self.accel.map(|a| a.scale_factor)),
        ]
    }

    /// The sensor states' decay factors e^{−Δt/Tc} over Δt, in state order.
    pub fn decay(&self, dt_s: f64) -> SensorDiagonal {
        self.per_sensor_state(|gm| gm.transition(dt_s))
    }

    /// `value` of each sensor state's Gauss-Markov process, in state order.
    fn per_sensor_state(&self, value: impl Fn(&GaussMarkovParameters) -> f64) -> SensorDiagonal {
        let mut d = SensorDiagonal::zeros();
        for (start, group) in self.gauss_markov_states() {
            for (k, gm) in group.iter().enumerate() {
                d[start - block::GYRO_BIAS + k] = value(gm);
            }
        }
        d
    }

    /// The discrete transition over Δt from the system matrix: Φ = I + FΔt + ½(FΔt)² for the
    /// navigation rows, with the Gauss-Markov diagonal replaced by its exact e^{−Δt/Tc}
    /// (by blocks: [`Transition`]).
    pub fn transition_matrix(&self, f: &SystemMatrix, dt_s: f64) -> Transition {
        Transition::from_system(f, self.decay(dt_s), dt_s)
    }

    /// The discrete process noise over Δt at attitude C_b^n with transition Φ: white noise
    /// averaged with the trapezoidal rule, Gauss-Markov driving noise exact. The white noise
    /// drives velocity and attitude only, so ½(Φ W Φᵀ + W) has only a navigation block.
    pub fn process_noise(
        &self,
        attitude: &Rotation<Body, Ned>,
        phi: &Transition,
        dt_s: f64,
    ) -> ProcessNoise {
        let c = attitude.to_matrix3();
        let squared = |axes: &[AxisModel; 3]| {
            Matrix3::from_diagonal(&nalgebra::Vector3::from(
                axes.map(|a| a.white_noise_density * a.white_noise_density),
            ))
        };
        let mut white = NavBlock::zeros();
        white
            .fixed_view_mut::<3, 3>(block::VELOCITY, block::VELOCITY)
            .copy_from(&(c * squared(&self.accel) * c.transpose() * dt_s));
        white
            .fixed_view_mut::<3, 3>(block::ATTITUDE, block::ATTITUDE)
            .copy_from(&(c * squared(&self.gyro) * c.transpose() * dt_s));
        let driven = phi.nav.fixed_columns::<6>(block::VELOCITY);
        let spread = driven
            * white.fixed_view::<6, 6>(block::VELOCITY, block::VELOCITY)
            * driven.transpose();
        let sensor = self.per_sensor_state(|gm| gm.discrete_variance(dt_s));
        ProcessNoise {
            nav: (spread + white) * 0.5,
            sensor,
        }
    }

    /// Steady-state standard deviations of the 12 sensor states in state order (for the
    /// initial covariance when nothing better is known).
    pub fn steady_state_sd(&self) -> [f64; STATES - block::GYRO_BIAS] {
        self.per_sensor_state(|gm| gm.sigma).into()
    }
}

/// Turn-on bias standard deviations, per axis: the part of a bias that is constant while the
/// unit runs (unit to unit and power-on to power-on), on top of its Gauss-Markov wander.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct TurnOnBias {
    /// Gyro x, y, z, rad/s.
    pub gyro_rad_s: [f64; 3],
    /// Accelerometer x, y, z, m/s².
    pub accel_m_s2: [f64; 3],
}

impl GaussMarkovParameters {
    /// The process a filter state carries for this Gauss-Markov wander plus a constant of sd
    /// `constant_sd` (one state for both): steady-state variance σ² + c², and the correlation
    /// time stretched to Tc (σ² + c²)/σ² so that the driving noise per unit time,
    /// 2σ²/Tc for Δt ≪ Tc, stays the Gauss-Markov's. Left alone, the state's variance then stays
    /// at σ² + c² (the truth's) instead of decaying to σ² within a few Tc, which would forget
    /// the constant that has not been observed yet; over Δt ≪ Tc the increments are the
    /// Gauss-Markov's. With σ = 0 it is a random constant (Tc infinite).
    pub fn with_constant(&self, constant_sd: f64) -> GaussMarkovParameters {
        let (s2, c2) = (self.sigma * self.sigma, constant_sd * constant_sd);
        if c2 == 0.0 || !c2.is_finite() {
            return *self;
        }
        let correlation_time_s = match s2 > 0.0 {
            true => self.correlation_time_s * (s2 + c2) / s2,
            false => f64::INFINITY,
        };
        GaussMarkovParameters {
            correlation_time_s,
            sigma: (s2 + c2).sqrt(),
        }
    }
}

impl ImuStochasticModel {
    /// The turn-on bias sds an initial covariance `p0` implies for this model: the part of each
    /// initial bias variance above the Gauss-Markov's stationary σ² (a stationary
    /// Gauss-Markov process is never more uncertain than σ, so the excess is a constant the
    /// filter must keep until it is observed; see [`GaussMarkovParameters::with_constant`]).
    pub fn turn_on_bias_in(&self, p0: &SystemMatrix) -> TurnOnBias {
        let excess = |state: usize, gm: &GaussMarkovParameters| {
            (p0[(state, state)] - gm.sigma * gm.sigma).max(0.0).sqrt()
        };
        TurnOnBias {
            gyro_rad_s: std::array::from_fn(|k| excess(block::GYRO_BIAS + k, &self.gyro[k].bias)),
            accel_m_s2: std::array::from_fn(|k| excess(block::ACCEL_BIAS + k, &self.accel[k].bias)),
        }
    }

    /// The model whose bias states also carry the constant turn-on biases `turn_on`
    /// ([`GaussMarkovParameters::with_constant`], axis by axis).
    pub fn keeping_turn_on_bias(&self, turn_on: &TurnOnBias) -> ImuStochasticModel {
        let mut model = *self;
        for (axis, sd) in model.gyro.iter_mut().zip(turn_on.gyro_rad_s) {
            axis.bias = axis.bias.with_constant(sd);
        }
        for (axis, sd) in model.accel.iter_mut().zip(turn_on.accel_m_s2) {
            axis.bias = axis.bias.with_constant(sd);
        }
        model
    }
}

/// The first parameter of `gm` out of range: ("correlation time", Tc) unless finite and
/// positive, ("sigma", σ) unless finite and non-negative.
fn invalid_part(gm: GaussMarkovParameters) -> Option<(&'static str, f64)> {
    let tc = gm.correlation_time_s;
    if !(tc.is_finite() && tc > 0.0) {
        return Some(("correlation time", tc));
    }
    (!(gm.sigma.is_finite() && gm.sigma >= 0.0)).then_some(("sigma", gm.sigma))
}

/// The white-noise density of `channel` at the entries a placement refers to: the GMWM
/// composite's mapped density with the GMWM bias state, the Allan curve's N otherwise.
fn white_density(
    bank: &ModelBank,
    placement: &Placement,
    channel: Channel,
    source: GaussMarkovSource,
) -> Result<f64, SensorModelError> {
    let density = |m: &ChannelModel| m.white_noise_density(source);
    let at = |temperature_c: f64| {
        bank.entries
            .iter()
            .find(|e| e.temperature_c == temperature_c)
            .and_then(|e| e.channels.get(&channel))
            .and_then(density)
            .ok_or(SensorModelError::NoWhiteNoise {
                temperature_c,
                channel: channel.name(),
            })
    };
    match *placement {
        Placement::Entry { temperature_c } | Placement::Clamped { temperature_c } => {
            at(temperature_c)
        }
        Placement::Between {
            lower_c,
            upper_c,
            weight,
        } => Ok(at(lower_c)? * (1.0 - weight) + at(upper_c)? * weight),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // The exact discretisation must reproduce the stationary variance: with x₀ ~ N(0, σ²),
    // var(x₁) = φ²σ² + q = σ² for every Δt (a closed form), and it must match the Euler
    // form 2σ²Δt/Tc when Δt ≪ Tc.
    #[test]
    fn exact_discretisation_keeps_the_stationary_variance() {
        let gm = GaussMarkovParameters {
            correlation_time_s: 120.0,
            sigma: 3e-4,
        };
        for dt in [1e-3, 0.1, 1.0, 60.0, 1e4] {
            let phi = gm.transition(dt);
            let total = phi * phi * gm.sigma.powi(2) + gm.discrete_variance(dt);
            assert!((total / gm.sigma.powi(2) - 1.0).abs() < 1e-12, "dt {dt}");
        }
        let dt = 1e-4;
        let euler = 2.0 * gm.sigma.powi(2) * dt / gm.correlation_time_s;
        assert!((gm.discrete_variance(dt) / euler - 1.0).abs() < 1e-5);
    }
}

#[cfg(test)]
mod discretisation_tests {
    use super::*;
    use crate::filter::ekf::propagate_covariance;
    use crate::frames::Vector;
    use crate::geo::position::Geodetic;
    use crate::ins::error_model::system_matrix;
    use crate::ins::state::NavState;
    use crate::sensor::adis16364_like;

    // The block forms against the dense formulas they replace (slow and obviously correct):
    // Φ = I + FΔt + ½(FΔt)² with the exact decay on the Gauss-Markov diagonal,
    // Q = ½(Φ W Φᵀ + W) + diag(σ²(1 − e^{−2Δt/Tc})) and P ← Φ P Φᵀ + Q, at a turning,
    // accelerating state with every model term non-zero.
    fn assert_covariances_agree(a: &SystemMatrix, b: &SystemMatrix) {
        for i in 0..STATES {
            for j in 0..STATES {
                let scale = (b[(i, i)] * b[(j, j)]).sqrt();
                let (x, y) = (a[(i, j)], b[(i, j)]);
                assert!(
                    (x - y).abs() <= 1e-12 * scale,
                    "({i}, {j}): {x} against {y}"
                );
            }
        }
    }

    #[test]
    fn block_discretisation_equals_the_dense_one() {
        let model = adis16364_like()
            .stochastic_model(17.0, &ScaleFactorPrior::default())
            .unwrap();
        let state = NavState {
            time: crate::time::Timestamp::from_seconds(0.0).unwrap(),
            position: Geodetic {
                latitude_rad: 0.9,
                longitude_rad: -1.2,
                height_m: 120.0,
            },
            velocity: Vector::new(8.0, -3.0, 0.4),
            attitude: Rotation::from_euler_zyx(1.1, 0.05, -0.03),
        };
        let rate = Vector::<Body>::new(0.02, -0.01, 0.3);
        let force = Vector::<Body>::new(0.8, 0.3, -9.7);
        let f = system_matrix(&state, &rate, &force, &model.correlation_times());
        let dt = 0.1;
        let fdt = f * dt;
        let mut phi = SystemMatrix::identity() + fdt + fdt * fdt * 0.5;
        let mut q_sensor = SystemMatrix::zeros();
        for (start, group) in model.gauss_markov_states() {
            for (k, gm) in group.iter().enumerate() {
                phi[(start + k, start + k)] = gm.transition(dt);
                q_sensor[(start + k, start + k)] = gm.discrete_variance(dt);
            }
        }
        let blocks = model.transition_matrix(&f, dt);
        assert!((blocks.to_matrix() - phi).amax() < 1e-15);

        let c = state.attitude.to_matrix3();
        let density = |axes: &[AxisModel; 3], i: usize| axes[i].white_noise_density.powi(2);
        let mut white = SystemMatrix::zeros();
        for i in 0..3 {
            white[(3 + i, 3 + i)] = density(&model.accel, i);
            white[(6 + i, 6 + i)] = density(&model.gyro, i);
        }
        let mut rotate = SystemMatrix::identity();
        rotate.fixed_view_mut::<3, 3>(3, 3).copy_from(&c);
        rotate.fixed_view_mut::<3, 3>(6, 6).copy_from(&c);
        let white = rotate * white * rotate.transpose() * dt;
        let q = (phi * white * phi.transpose() + white) * 0.5 + q_sensor;
        let q_blocks = model
            .process_noise(&state.attitude, &blocks, dt)
            .to_matrix();
        // A covariance entry is bounded by √(q_ii q_jj), which is its natural scale (entries
        // span 1e-20 to 1e-6, and off-diagonal ones come from cancelling sums): rounding of
        // sums of 21 terms in another order stays below 1e-12 of it.
        assert_covariances_agree(&q_blocks, &q);
        let p = crate::nav::alignment::InitialUncertainty::default().covariance();
        let propagated = blocks.propagate(&p, &model.process_noise(&state.attitude, &blocks, dt));
        let dense = propagate_covariance(&p, &phi, &q);
        assert_covariances_agree(&propagated, &dense);
    }
}

#[cfg(test)]
mod turn_on_tests {
    use super::*;

    // Closed forms of the carried process: its stationary variance is σ² + c² (φ²(σ² + c²) + q
    // = σ² + c² for every Δt), and for Δt ≪ Tc its driving noise per second is the
    // Gauss-Markov's 2σ²/Tc (the relative difference is O(Δt/Tc), 1e-4 here at most).
    #[test]
    fn a_constant_keeps_the_variance_and_the_short_term_driving_noise() {
        let gm = GaussMarkovParameters {
            correlation_time_s: 215.0,
            sigma: 1.6e-4,
        };
        let c = 1f64.to_radians();
        let carried = gm.with_constant(c);
        let total = gm.sigma.powi(2) + c * c;
        assert!((carried.sigma.powi(2) / total - 1.0).abs() < 1e-12);
        for dt in [1e-3, 0.1, 1.0, 600.0] {
            let phi = carried.transition(dt);
            let after = phi * phi * total + carried.discrete_variance(dt);
            assert!((after / total - 1.0).abs() < 1e-12, "dt {dt}");
        }
        let dt = 0.01;
        let rate = |g: &GaussMarkovParameters| g.discrete_variance(dt) / dt;
        assert!((rate(&carried) / rate(&gm) - 1.0).abs() < 1e-4);
        assert_eq!(gm.with_constant(0.0), gm);
    }

    // With no Gauss-Markov part the carried state is a random constant: Φ = 1, no noise.
    #[test]
    fn a_constant_alone_is_a_random_constant() {
        let gm = GaussMarkovParameters {
            correlation_time_s: 100.0,
            sigma: 0.0,
        };
        let carried = gm.with_constant(0.02);
        assert_eq!(carried.transition(10.0), 1.0);
        assert_eq!(carried.discrete_variance(10.0), 0.0);
        assert!((carried.sigma - 0.02).abs() < 1e-15);
    }

    // The turn-on part is the initial variance above σ²; none where P0 is at or below it.
    #[test]
    fn the_turn_on_part_is_the_initial_variance_above_the_gauss_markov() {
        let model = crate::sensor::adis16364_like()
            .stochastic_model(17.0, &ScaleFactorPrior::default())
            .unwrap();
        let mut p0 = SystemMatrix::identity() * 1e-12;
        let sigma = model.gyro[2].bias.sigma;
        p0[(block::GYRO_BIAS + 2, block::GYRO_BIAS + 2)] = sigma * sigma + 0.01f64.powi(2);
        let turn_on = model.turn_on_bias_in(&p0);
        assert!((turn_on.gyro_rad_s[2] / 0.01 - 1.0).abs() < 1e-9);
        assert_eq!(turn_on.gyro_rad_s[0], 0.0);
        assert_eq!(turn_on.accel_m_s2, [0.0; 3]);
        let carried = model.keeping_turn_on_bias(&turn_on);
        assert_eq!(carried.gyro[0], model.gyro[0]);
        assert!((carried.gyro[2].bias.sigma.powi(2) / p0[(11, 11)] - 1.0).abs() < 1e-12);
    }
}

#[cfg(test)]
mod validation_tests {
    use super::*;
    use crate::sensor::adis16364_like;

    #[test]
    fn a_negative_sigma_is_named_as_a_sigma() {
        // It used to be reported as a bad correlation time, with the correlation time's value.
        let mut model = adis16364_like()
            .stochastic_model(20.0, &ScaleFactorPrior::default())
            .unwrap();
        model.gyro[1].bias.sigma = -1e-4;
        let message = model.validate().unwrap_err().to_string();
        assert!(message.starts_with("gy bias sigma = -0.0001"), "{message}");
        model.gyro[1].bias.sigma = 1e-4;
        model.accel[2].scale_factor.correlation_time_s = f64::NAN;
        let message = model.validate().unwrap_err().to_string();
        assert!(
            message.starts_with("az scale-factor correlation time = NaN"),
            "{message}"
        );
    }
}
