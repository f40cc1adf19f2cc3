//! The error process of one inertial channel, stepped sample by sample with the actual dt.
//!
//! y_k = (1 + s_k·1e-6) u_k + b_c + c₁ ΔT_k + c₂ ΔT_k² + b_GM,k + b_RW,k + n_k, then quantised,
//! where ΔT_k = T_k − T_ref with T_k the temperature of the MEMS structure (the sensor's
//! temperature, or where the profile gives a thermal lag τ its first-order lag, see
//! `StructureLag`), s_k is the scale-factor error in ppm (temperature term plus an
//! optional Gauss-Markov term), b_c the constant bias of this power-on (the unit's fixed bias
//! plus the power-on's offset, `sim::unit`), c₁ and c₂ the bias temperature coefficients, b_GM
//! the Gauss-Markov bias, whose Tc and σ follow the temperature (re-read from the profile when
//! T has moved by more than [`BIAS_PARAMETER_STEP_C`] since they were last read),
//! (exact step φ_k = exp(−dt_k/Tc), driving variance σ²(1 − φ_k²)), b_RW a random walk
//! (variance K² dt_k per step) and n_k white noise of density N averaged over dt_k (variance
//! N²/dt_k). The Gauss-Markov processes start from their stationary distributions.

use crate::sensor::{BiasAt, ChannelProfile};
use crate::stoch::gauss_markov::GaussMarkov;
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

/// Draws a standard normal variate.
pub fn standard_normal(rng: &mut impl Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// One exact Gauss-Markov step ([`GaussMarkov::step`]) for a correlation time and sigma.
pub fn gauss_markov_step(
    previous: f64,
    dt_s: f64,
    correlation_time_s: f64,
    sigma: f64,
    z: f64,
) -> f64 {
    GaussMarkov {
        correlation_time_s,
        sigma,
    }
    .step(previous, dt_s, z)
}

/// Rounds to the nearest multiple of `step` (no change for step 0).
pub fn quantize(value: f64, step: f64) -> f64 {
    if step > 0.0 {
        (value / step).round() * step
    } else {
        value
    }
}

/// Temperature change after which the Gauss-Markov parameters are read again, °C.
pub const BIAS_PARAMETER_STEP_C: f64 = 0.1;

/// The running error state of one channel.
#[derive(Debug, Clone)]
pub struct ChannelErrors<'a> {
    profile: &'a ChannelProfile,
    bias: BiasAt,
    bias_read_at_c: f64,
    reference_temperature_c: f64,
    constant_bias: f64,
    bias_gm: f64,
    bias_rw: f64,
    scale_gm_ppm: f64,
    lag: StructureLag,
    started: bool,
}

/// The temperature of the MEMS structure behind a lagging temperature sensor: a first-order
/// lag dT_s/dt = (T − T_s)/τ, stepped exactly for a temperature linear between samples:
/// T_s,k = T_k − τ s + (T_s,k−1 − T_k−1 + τ s) e^(−dt/τ) with s = (T_k − T_k−1)/dt.
#[derive(Debug, Clone, Copy)]
struct StructureLag {
    tau_s: f64,
    sensor_c: f64,
    structure_c: f64,
}

impl StructureLag {
    /// A structure at the sensor's temperature `temperature_c` (a unit switched on at rest).
    fn settled(tau_s: f64, temperature_c: f64) -> Self {
        Self {
            tau_s,
            sensor_c: temperature_c,
            structure_c: temperature_c,
        }
    }

    /// The structure's temperature after `dt_s` in which the sensor's went linearly to
    /// `temperature_c`, °C.
    fn step(&mut self, dt_s: f64, temperature_c: f64) -> f64 {
        self.structure_c = if self.tau_s > 0.0 && dt_s > 0.0 {
            let slope = (temperature_c - self.sensor_c) / dt_s;
            let offset = self.tau_s * slope;
            let decay = (-dt_s / self.tau_s).exp();
            temperature_c - offset + (self.structure_c - self.sensor_c + offset) * decay
        } else {
            temperature_c
        };
        self.sensor_c = temperature_c;
        self.structure_c
    }
}

impl<'a> ChannelErrors<'a> {
    /// A channel starting at temperature `temperature_c` (which sets Tc and σ of the bias),
    /// with the constant bias of this power-on and the initial Gauss-Markov states drawn from
    /// `rng`.
    pub fn new(
        profile: &'a ChannelProfile,
        reference_temperature_c: f64,
        temperature_c: f64,
        constant_bias: f64,
        rng: &mut impl Rng,
    ) -> Self {
        let bias = profile.bias_at(temperature_c);
        // The draw that was the turn-on bias before the unit's identity moved to `sim::unit`:
        // kept and discarded, so that every later draw of the stream is the one earlier
        // versions made and their results stay comparable.
        let _ = standard_normal(rng);
        let bias_gm = bias.sigma * standard_normal(rng);
        let scale_gm_ppm = profile
            .scale_factor_gauss_markov
            .map_or(0.0, |s| s.sigma_ppm * standard_normal(rng));
        Self {
            profile,
            bias,
            bias_read_at_c: temperature_c,
            reference_temperature_c,
            constant_bias,
            bias_gm,
            bias_rw: 0.0,
            scale_gm_ppm,
            lag: StructureLag::settled(profile.thermal_lag_s, temperature_c),
            started: false,
        }
    }

    /// The Gauss-Markov bias parameters in force.
    pub fn bias_parameters(&self) -> BiasAt {
        self.bias
    }

    /// The constant bias of this power-on.
    pub fn constant_bias(&self) -> f64 {
        self.constant_bias
    }

    /// The measurement of true value `u` over an interval of `dt_s` at the sensor's
    /// temperature `sensor_c` (the channel's temperature terms act at its structure's, which
    /// lags by the profile's `thermal_lag_s`); the processes step first (except for the very
    /// first sample).
    pub fn measure(&mut self, u: f64, dt_s: f64, sensor_c: f64, rng: &mut impl Rng) -> f64 {
        let p = self.profile;
        let temperature_c = if self.started {
            self.lag.step(dt_s, sensor_c)
        } else {
            self.lag.structure_c
        };
        if (temperature_c - self.bias_read_at_c).abs() > BIAS_PARAMETER_STEP_C {
            self.bias = p.bias_at(temperature_c);
            self.bias_read_at_c = temperature_c;
        }
        if self.started {
            self.step(dt_s, rng);
        }
        self.started = true;
        let delta_t = temperature_c - self.reference_temperature_c;
        let scale_ppm =
            p.scale_factor_temperature_coefficient_ppm_per_c * delta_t + self.scale_gm_ppm;
        let bias = self.constant_bias + p.temperature_bias(delta_t) + self.bias_gm + self.bias_rw;
        let white = p.white_noise_density / dt_s.sqrt() * standard_normal(rng);
        quantize(
            (1.0 + scale_ppm * 1e-6) * u + bias + white,
            p.quantization_step,
        )
    }

    fn step(&mut self, dt_s: f64, rng: &mut impl Rng) {
        let p = self.profile;
        self.bias_gm = gauss_markov_step(
            self.bias_gm,
            dt_s,
            self.bias.correlation_time_s,
            self.bias.sigma,
            standard_normal(rng),
        );
        if p.bias_random_walk_density > 0.0 {
            self.bias_rw += p.bias_random_walk_density * dt_s.sqrt() * standard_normal(rng);
        }
        if let Some(s) = p.scale_factor_gauss_markov {
            self.scale_gm_ppm = gauss_markov_step(
                self.scale_gm_ppm,
                dt_s,
                s.correlation_time_s,
                s.sigma_ppm,
                standard_normal(rng),
            );
        }
    }
}
