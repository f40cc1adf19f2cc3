//! The noise model's source of a run or a tournament, read: a bank or a sensor profile, with the
//! thermal calibration of `--thermal-from` joined to it when given.

use crate::failure::Failure;
use crate::inputs::{load_profile, read_bank, read_thermal_calibration};
use crate::settings::navigation::NoiseSource;
use anyhow::anyhow;
use std::path::Path;
use thermonav::evaluation::experiment::CandidateSource;
use thermonav::imu::{Channel, SampleKind};
use thermonav::nav::run::NoiseModel;
use thermonav::sensor::SensorProfile;
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::thermal::ThermalCalibration;
use thermonav::stoch::thermal::join::{ThermalJoinError, check_join};

/// The noise model's source, read.
pub enum LoadedNoise {
    /// A bank (with the calibration of `--thermal-from`, when given).
    Bank(ModelBank),
    /// A sensor profile.
    Profile(SensorProfile),
    /// A sensor profile with the calibration of `--thermal-from`.
    ProfileWithThermal(SensorProfile, ThermalCalibration),
}

/// Reads the bank or the profile, and joins the thermal calibration of `thermal_from` to it.
pub fn load_noise(
    noise: &NoiseSource,
    thermal_from: Option<&Path>,
) -> Result<LoadedNoise, Failure> {
    let thermal = thermal_from.map(read_thermal_calibration).transpose()?;
    let refused = |e: ThermalJoinError| {
        let (option, path) = match noise {
            NoiseSource::Bank(p) => ("--bank", p),
            NoiseSource::Profile(p) => ("--profile", p),
        };
        let from = thermal_from.map_or_else(String::new, |p| p.display().to_string());
        Failure::Usage(anyhow!(
            "--thermal-from {from} cannot join {option} {}: {e}",
            path.display()
        ))
    };
    match (noise, thermal) {
        (NoiseSource::Bank(path), None) => Ok(LoadedNoise::Bank(read_bank(path)?)),
        (NoiseSource::Bank(path), Some(thermal)) => Ok(LoadedNoise::Bank(
            read_bank(path)?
                .with_thermal_from(thermal)
                .map_err(refused)?,
        )),
        (NoiseSource::Profile(path), None) => Ok(LoadedNoise::Profile(load_profile(Some(path))?)),
        (NoiseSource::Profile(path), Some(thermal)) => {
            let profile = load_profile(Some(path))?;
            let units = Channel::ALL
                .iter()
                .filter(|c| profile.channel(**c).is_some())
                .map(|&c| (c, c.si_unit(SampleKind::Rates).to_string()))
                .collect();
            check_join(&units, &thermal).map_err(refused)?;
            Ok(LoadedNoise::ProfileWithThermal(profile, thermal))
        }
    }
}

impl LoadedNoise {
    /// Where a tournament's candidates come from.
    pub fn source(&self) -> CandidateSource<'_> {
        match self {
            LoadedNoise::Bank(bank) => CandidateSource::Bank(bank),
            LoadedNoise::Profile(profile) | LoadedNoise::ProfileWithThermal(profile, _) => {
                CandidateSource::Profile(profile)
            }
        }
    }

    /// Where a run's noise model comes from.
    pub fn model(&self) -> NoiseModel<'_> {
        match self {
            LoadedNoise::Bank(bank) => NoiseModel::Bank(bank),
            LoadedNoise::Profile(profile) => NoiseModel::Profile(profile),
            LoadedNoise::ProfileWithThermal(profile, thermal) => {
                NoiseModel::ProfileWithThermal(profile, thermal)
            }
        }
    }

    /// The bank's thermal calibration, if any.
    pub fn thermal(&self) -> Option<&ThermalCalibration> {
        self.model().thermal()
    }
}
