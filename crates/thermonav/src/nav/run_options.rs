//! The options that decide how one filter run goes, beside its data, its noise model and its
//! outages: the Gauss-Markov family, the white-noise scale, the GNSS velocity noise, the
//! innovation gate, the measurements used, the antennas, the longest IMU gap, the covariance
//! step, the Gaussian sum over the z-gyro bias and the static alignment of an aligned start.
//! `thermonav integrate` runs one filter with them and `thermonav evaluate` runs every
//! candidate of its tournament with them, so that a tournament can be tuned as a run is; their
//! defaults are written here once (from [`EngineSettings::default`] and
//! [`DEFAULT_PROCESS_NOISE_SCALE`]). The model's temperature is
//! [`super::run::ModelTemperature::of`]'s, and the IMU-GNSS time-offset search
//! [`super::time_offset::TimeOffsetSearch::with_bracket`]'s, checked there for both commands
//! and the Python package. A refusal is a [`SettingError`] naming the option.

use super::engine::{Aiding, BiasHypotheses, EngineSettings};
use super::measurement::AntennaGeometry;
use super::static_alignment::StaticAlignment;
use crate::setting::{SettingError, positive};
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
    /// Whether a run aligned from GNSS is levelled, and its gyro biases taken, from the
    /// platform standing still at the record's start (a run started from a trajectory takes
    /// its attitude from it).
    pub static_alignment: StaticAlignment,
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

/// The fastest covariance and output rates, Hz: above the fastest MEMS logs (1-4 kHz), a
/// step or an epoch more often than the IMU samples is empty work (an output rate of 1e9 Hz
/// kept a run busy for minutes stepping through empty output times).
pub const MAX_RATE_HZ: f64 = 5000.0;

/// The GNSS velocity sd from one value (every axis) or three (north, east, down), m/s.
///
/// # Errors
/// Another count of values, or one that is not positive.
pub fn velocity_sd_of(values: &[f64]) -> Result<[f64; 3], SettingError> {
    let sd = match values {
        [v] => [*v; 3],
        [n, e, d] => [*n, *e, *d],
        _ => {
            let given: Vec<String> = values.iter().map(f64::to_string).collect();
            return Err(SettingError::new(
                "velocity_sd_m_s",
                given.join(","),
                "expected one value or three (north, east, down)",
            ));
        }
    };
    for v in sd {
        positive("velocity_sd_m_s", v)?;
    }
    Ok(sd)
}

/// The innovation gate of a probability in (0, 1]: `None` (accept every update) at 1.
///
/// # Errors
/// A probability outside (0, 1].
pub fn gate_of(probability: f64) -> Result<Option<f64>, SettingError> {
    match probability {
        1.0 => Ok(None),
        p if p > 0.0 && p < 1.0 => Ok(Some(p)),
        p => Err(SettingError::new(
            "gate_probability",
            p,
            "expected a probability in (0, 1], 1 meaning no gate",
        )),
    }
}

/// The step, s, of a rate in (0, [`MAX_RATE_HZ`]] Hz (`name`: `covariance_rate_hz`,
/// `output_rate_hz`).
///
/// # Errors
/// A rate that is not positive or above [`MAX_RATE_HZ`].
pub fn interval_of_rate(name: &'static str, rate_hz: f64) -> Result<f64, SettingError> {
    match positive(name, rate_hz)? {
        r if r <= MAX_RATE_HZ => Ok(1.0 / r),
        r => Err(SettingError::new(
            name,
            r,
            format!(
                "above {MAX_RATE_HZ} Hz: a filter step or output epoch more often than any IMU samples does nothing"
            ),
        )),
    }
}

/// The Gaussian sum of `members` over the z-gyro bias (1: one filter, `None`).
///
/// # Errors
/// A count that [`BiasHypotheses::split`] refuses.
pub fn bias_hypotheses_of(members: usize) -> Result<Option<BiasHypotheses>, SettingError> {
    if members == 1 {
        return Ok(None);
    }
    let hypotheses = BiasHypotheses {
        members,
        ..BiasHypotheses::default()
    };
    match hypotheses.split() {
        Ok(_) => Ok(Some(hypotheses)),
        Err(e) => Err(SettingError::new("bias_hypotheses", members, e.to_string())),
    }
}

impl RunOptions {
    /// Checks every option against its range, as the CLI and Python read them: the one place
    /// these checks are written.
    ///
    /// # Errors
    /// The first option out of range, named.
    pub fn validate(&self) -> Result<(), SettingError> {
        positive("process_noise_scale", self.process_noise_scale)?;
        for v in self.velocity_sd_m_s {
            positive("velocity_sd_m_s", v)?;
        }
        if let Some(p) = self.gate_probability {
            gate_of(p)?;
        }
        positive("max_imu_gap_s", self.max_imu_gap_s)?;
        let covariance_rate_hz =
            1.0 / positive("covariance_interval_s", self.covariance_interval_s)?;
        interval_of_rate("covariance_rate_hz", covariance_rate_hz)?;
        if let Some(h) = &self.bias_hypotheses {
            bias_hypotheses_of(h.members)?;
        }
        Ok(())
    }

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
            static_alignment: engine.static_alignment,
        }
    }

    /// `base` with these options' filter settings (the filter kind, outages, output rate and
    /// smoothing are `base`'s).
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
            static_alignment: self.static_alignment,
            ..base
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_out_of_range_are_refused_naming_the_option() {
        assert!(RunOptions::default().validate().is_ok());
        let refused = |o: RunOptions| o.validate().unwrap_err().name;
        let d = RunOptions::default;
        assert_eq!(
            refused(RunOptions {
                process_noise_scale: 0.0,
                ..d()
            }),
            "process_noise_scale"
        );
        assert_eq!(
            refused(RunOptions {
                velocity_sd_m_s: [0.1, -0.1, 0.1],
                ..d()
            }),
            "velocity_sd_m_s"
        );
        assert_eq!(
            refused(RunOptions {
                gate_probability: Some(1.5),
                ..d()
            }),
            "gate_probability"
        );
        assert_eq!(
            refused(RunOptions {
                max_imu_gap_s: f64::NAN,
                ..d()
            }),
            "max_imu_gap_s"
        );
        assert_eq!(
            refused(RunOptions {
                covariance_interval_s: 1e-9,
                ..d()
            }),
            "covariance_rate_hz"
        );
        let four = BiasHypotheses {
            members: 4,
            ..BiasHypotheses::default()
        };
        assert_eq!(
            refused(RunOptions {
                bias_hypotheses: Some(four),
                ..d()
            }),
            "bias_hypotheses"
        );
        assert_eq!(velocity_sd_of(&[0.2]).unwrap(), [0.2; 3]);
        assert_eq!(
            velocity_sd_of(&[0.1, 0.2]).unwrap_err().as_flag(),
            "--velocity-sd-m-s 0.1,0.2: expected one value or three (north, east, down)"
        );
        assert_eq!(gate_of(1.0).unwrap(), None);
        assert_eq!(interval_of_rate("output_rate_hz", 10.0).unwrap(), 0.1);
        assert!(interval_of_rate("output_rate_hz", 1e9).is_err());
        assert_eq!(bias_hypotheses_of(1).unwrap(), None);
        assert_eq!(
            crate::setting::finite("model_temperature_c", f64::NAN)
                .unwrap_err()
                .as_flag(),
            "--model-temperature-c NaN: expected a finite number"
        );
    }

    #[test]
    fn the_defaults_give_the_default_engine_back() {
        let options = RunOptions::default();
        assert_eq!(
            options.engine(EngineSettings::default()),
            EngineSettings::default()
        );
        assert_eq!(options.gauss_markov, GaussMarkovSource::IRREGULAR_ML);
        assert_eq!(options.process_noise_scale, 1.0);
        assert_eq!(options.static_alignment, StaticAlignment::WhenStill);
        let off = RunOptions {
            static_alignment: StaticAlignment::Off,
            ..RunOptions::default()
        };
        assert_eq!(
            off.engine(EngineSettings::default()).static_alignment,
            StaticAlignment::Off
        );
    }
}
