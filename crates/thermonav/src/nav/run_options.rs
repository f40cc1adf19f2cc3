//! The options that decide how one filter run goes, beside its data, its noise model and its
//! outages: the Gauss-Markov family, the white-noise scale, the GNSS velocity noise, the
//! innovation gate, the measurements used, the antennas, the longest IMU gap, the covariance
//! step and the Gaussian sum over the z-gyro bias. `thermonav integrate` runs one filter with
//! them and `thermonav evaluate` runs every candidate of its tournament with them, so that a
//! tournament can be tuned as a run is; their defaults are written here once (from
//! [`EngineSettings::default`] and [`DEFAULT_PROCESS_NOISE_SCALE`]).

use super::engine::{Aiding, BiasHypotheses, EngineSettings};
use super::measurement::AntennaGeometry;
use crate::stoch::bank::GaussMarkovSource;
use serde::{Deserialize, Serialize};

/// The multiplier of the model's white-noise densities by default: the model as
/// characterised.
pub const DEFAULT_PROCESS_NOISE_SCALE: f64 = 1.0;

/// How one filter run goes (see the module's documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunOptions {
    /// The Gauss-Markov family of a bank that drives the bias states.
    pub gauss_markov: GaussMarkovSource,
    /// Multiplier of the model's white-noise densities (ARW, VRW): vibration on a vehicle
    /// raises the effective noise above a static record's.
    pub process_noise_scale: f64,
    /// Standard deviation of GNSS velocities, north/east/down, m/s.
    pub velocity_sd_m_s: [f64; 3],
    /// Probability of the chi-square innovation gate; `None` accepts every update.
    pub gate_probability: Option<f64>,
    /// Recent updates whose median NIS widens the gate (0: the plain gate).
    pub gate_window: usize,
    /// Measurements used.
    pub aiding: Aiding,
    /// Antennas.
    pub geometry: AntennaGeometry,
    /// Longest IMU interval the filter crosses, s.
    pub max_imu_gap_s: f64,
    /// Longest interval over which the covariance is propagated in one step, s.
    pub covariance_interval_s: f64,
    /// The Gaussian sum over the z-gyro bias prior (`None`: one filter).
    pub bias_hypotheses: Option<BiasHypotheses>,
}

impl Default for RunOptions {
    /// The engine's defaults, the default family and [`DEFAULT_PROCESS_NOISE_SCALE`].
    fn default() -> Self {
        Self::of_engine(
            &EngineSettings::default(),
            GaussMarkovSource::default(),
            DEFAULT_PROCESS_NOISE_SCALE,
        )
    }
}

impl RunOptions {
    /// The options `engine` runs with, with the family and the white-noise scale.
    pub fn of_engine(
        engine: &EngineSettings,
        gauss_markov: GaussMarkovSource,
        process_noise_scale: f64,
    ) -> Self {
        Self {
            gauss_markov,
            process_noise_scale,
            velocity_sd_m_s: engine.velocity_sd_m_s,
            gate_probability: engine.gate_probability,
            gate_window: engine.gate_window,
            aiding: engine.aiding,
            geometry: engine.geometry,
            max_imu_gap_s: engine.max_imu_gap_s,
            covariance_interval_s: engine.covariance_interval_s,
            bias_hypotheses: engine.bias_hypotheses,
        }
    }

    /// `base` with these options' filter settings (the filter kind, outages, output rate,
    /// smoothing and static alignment are `base`'s).
    pub fn engine(&self, base: EngineSettings) -> EngineSettings {
        EngineSettings {
            velocity_sd_m_s: self.velocity_sd_m_s,
            gate_probability: self.gate_probability,
            gate_window: self.gate_window,
            aiding: self.aiding,
            geometry: self.geometry,
            max_imu_gap_s: self.max_imu_gap_s,
            covariance_interval_s: self.covariance_interval_s,
            bias_hypotheses: self.bias_hypotheses,
            ..base
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_give_the_default_engine_back() {
        let options = RunOptions::default();
        assert_eq!(
            options.engine(EngineSettings::default()),
            EngineSettings::default()
        );
        assert_eq!(options.gauss_markov, GaussMarkovSource::IrregularMl);
        assert_eq!(options.process_noise_scale, 1.0);
    }
}
