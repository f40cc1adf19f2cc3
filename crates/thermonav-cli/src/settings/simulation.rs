//! Settings of `simulate chamber` and `simulate vessel`.

use super::paths::Io;
use crate::args::{ChamberArgs, VesselArgs};
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::path::PathBuf;
use thermonav::sim::chamber::CampaignSettings;
use thermonav::sim::clock::SampleClock;
use thermonav::sim::vessel::SurveySettings;

/// A chamber campaign to simulate and where to write it.
#[derive(Debug, Clone)]
pub struct ChamberSettings {
    /// Output folder.
    pub out: PathBuf,
    /// The campaign.
    pub campaign: CampaignSettings,
    /// Its sampling clock (checked).
    pub clock: SampleClock,
    /// Sensor profile (TOML); none: the built-in one.
    pub profile: Option<PathBuf>,
    /// Seed of every draw.
    pub seed: u64,
}

/// Resolves `simulate chamber`.
pub fn chamber(args: &ChamberArgs) -> Result<ChamberSettings, Failure> {
    let campaign = CampaignSettings {
        temperatures_c: set_points(&args.temperatures_c)?,
        duration_s: args.duration_s,
        rate_hz: args.rate_hz,
        jitter_s: args.jitter_us * 1e-6,
        drop_probability: args.drop_probability,
        ..CampaignSettings::default()
    };
    profile_io(args.profile.as_ref())
        .output_folder("chamber folder", &args.out)
        .check()?;
    chamber_settings(args.out.clone(), campaign, args.profile.clone(), args.seed)
}

/// Checked chamber settings.
pub fn chamber_settings(
    out: PathBuf,
    campaign: CampaignSettings,
    profile: Option<PathBuf>,
    seed: u64,
) -> Result<ChamberSettings, Failure> {
    let clock = SampleClock::new(
        campaign.rate_hz,
        campaign.jitter_s,
        campaign.drop_probability,
    )
    .usage()?;
    Ok(ChamberSettings {
        out,
        campaign,
        clock,
        profile,
        seed,
    })
}

/// Set points: at least one, finite, each once (two records of one temperature would be
/// written to one file).
fn set_points(temperatures_c: &[f64]) -> Result<Vec<f64>, Failure> {
    if temperatures_c.is_empty() || temperatures_c.iter().any(|t| !t.is_finite()) {
        return Err(Failure::Usage(anyhow!(
            "--temperatures-c needs finite temperatures"
        )));
    }
    for (k, t) in temperatures_c.iter().enumerate() {
        if temperatures_c[..k].contains(t) {
            return Err(Failure::Usage(anyhow!(
                "--temperatures-c gives {t} °C twice: each set point is one record"
            )));
        }
    }
    Ok(temperatures_c.to_vec())
}

fn profile_io(profile: Option<&PathBuf>) -> Io {
    match profile {
        Some(p) => Io::new().input("--profile", p),
        None => Io::new(),
    }
}

/// A survey to simulate and where to write it.
#[derive(Debug, Clone)]
pub struct VesselSettings {
    /// Output folder.
    pub out: PathBuf,
    /// Temperature, length and IMU clock.
    pub survey: SurveySettings,
    /// A motion-definition file instead of the harbour survey.
    pub motion: Option<PathBuf>,
    /// Sensor profile (TOML); none: the built-in one.
    pub profile: Option<PathBuf>,
    /// Seed of every draw.
    pub seed: u64,
}

/// Resolves `simulate vessel`.
pub fn vessel(args: &VesselArgs) -> Result<VesselSettings, Failure> {
    let survey = SurveySettings {
        temperature_c: super::finite("--temperature-c", args.temperature_c)?,
        duration_s: args.duration_s,
        ..SurveySettings::default()
    };
    if args.motion.is_none() && !(args.duration_s.is_finite() && args.duration_s >= 60.0) {
        return Err(Failure::Usage(anyhow!(
            "--duration-s {} must be at least 60 s",
            args.duration_s
        )));
    }
    let io = profile_io(args.profile.as_ref()).output_folder("survey folder", &args.out);
    match &args.motion {
        Some(m) => io.input("--motion", m),
        None => io,
    }
    .check()?;
    Ok(VesselSettings {
        out: args.out.clone(),
        survey,
        motion: args.motion.clone(),
        profile: args.profile.clone(),
        seed: args.seed,
    })
}
