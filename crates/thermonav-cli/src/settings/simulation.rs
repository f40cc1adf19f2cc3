//! Settings of `simulate chamber` and `simulate vessel`.

use super::paths::Io;
use crate::args::{ChamberArgs, GnssHeadingArg, VesselArgs};
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use std::path::PathBuf;
use thermonav::setting::{finite, positive};
use thermonav::sim::chamber::{CampaignSettings, Ramp};
use thermonav::sim::clock::SampleClock;
use thermonav::sim::temperature_program::TemperatureProgram;
use thermonav::sim::unit::SimulatedUnit;
use thermonav::sim::vessel::{
    GnssHeading, GnssSettings, ImuOffsets, MAX_TIME_OFFSET_S, SurveySettings, SurveyTemperature,
};
use thermonav_io::temperature_table::read_temperature_table;

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
    /// The unit in the chamber.
    pub unit: SimulatedUnit,
    /// Every channel's thermal lag, s, instead of the profile's.
    pub thermal_lag_s: Option<f64>,
}

/// Resolves `simulate chamber`.
pub fn chamber(args: &ChamberArgs) -> Result<ChamberSettings, Failure> {
    profile_io(args.profile.as_ref())
        .optional_inputs([("--temperature-file", args.temperature_file.as_ref())])
        .output_folder("chamber folder", &args.out)
        .check()?;
    let program = args
        .temperature_file
        .as_ref()
        .map(|path| read_temperature_table(path).data())
        .transpose()?
        .map(|table| TemperatureProgram {
            t_s: table.t_s,
            temperature_c: table.temperature_c,
        });
    let campaign = CampaignSettings {
        temperatures_c: match program {
            Some(_) => Vec::new(),
            None => set_points(&args.temperatures_c)?,
        },
        program,
        duration_s: args.duration_s,
        rate_hz: args.rate_hz,
        jitter_s: args.jitter_us * 1e-6,
        drop_probability: args.drop_probability,
        power_ons: power_ons(args.power_ons)?,
        ramp: args.ramp.as_deref().map(ramp).transpose()?,
        ..CampaignSettings::default()
    };
    let mut settings =
        chamber_settings(args.out.clone(), campaign, args.profile.clone(), args.seed)?;
    settings.unit = SimulatedUnit {
        serial: args.unit_serial,
    };
    settings.thermal_lag_s = thermal_lag(args.thermal_lag_s)?;
    Ok(settings)
}

/// Longest thermal lag `--thermal-lag-s` takes, s (a day: far beyond any MEMS package).
pub const MAX_THERMAL_LAG_S: f64 = 86_400.0;

/// `--thermal-lag-s`: 0 to [`MAX_THERMAL_LAG_S`] s.
fn thermal_lag(lag_s: Option<f64>) -> Result<Option<f64>, Failure> {
    match lag_s {
        Some(v) if !(v.is_finite() && (0.0..=MAX_THERMAL_LAG_S).contains(&v)) => {
            Err(Failure::Usage(anyhow!(
                "--thermal-lag-s {v}: give 0 to {MAX_THERMAL_LAG_S} s"
            )))
        }
        _ => Ok(lag_s),
    }
}

/// Most power-ons a campaign repeats (each one repeats every set point).
pub const MAX_POWER_ONS: u32 = 100;

fn power_ons(n: u32) -> Result<u32, Failure> {
    if (1..=MAX_POWER_ONS).contains(&n) {
        return Ok(n);
    }
    Err(Failure::Usage(anyhow!(
        "--power-ons {n}: give 1 to {MAX_POWER_ONS}"
    )))
}

/// `START:END:RATE` in °C, °C and °C/min, within the characterisation range.
fn ramp(text: &str) -> Result<Ramp, Failure> {
    let bad = |why: &str| {
        Failure::Usage(anyhow!(
            "--ramp {text:?}: {why} (expected START:END:RATE in °C, °C and °C/min, e.g. -40:80:1)"
        ))
    };
    let parts: Vec<&str> = text.split(':').collect();
    let [start, end, rate] = parts[..] else {
        return Err(bad("three fields are needed"));
    };
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    let (Some(start_c), Some(end_c), Some(rate)) = (number(start), number(end), number(rate))
    else {
        return Err(bad("each field must be a finite number"));
    };
    ramp_within_range(start_c, end_c, rate).map_err(|why| bad(&why))
}

fn ramp_within_range(start_c: f64, end_c: f64, rate_c_per_min: f64) -> Result<Ramp, String> {
    let [low, high] = thermonav_io::SENSOR_TEMPERATURE_RANGE_C;
    if [start_c, end_c].iter().any(|t| !(low..=high).contains(t)) {
        return Err(format!("the ends must lie within {low}..{high} °C"));
    }
    if start_c == end_c {
        return Err("the start and end must differ".into());
    }
    if !(rate_c_per_min > 0.0 && rate_c_per_min <= 100.0) {
        return Err("the rate must be above 0 and at most 100 °C/min".into());
    }
    Ok(Ramp {
        start_c,
        end_c,
        rate_c_per_min,
    })
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
        unit: SimulatedUnit::default(),
        thermal_lag_s: None,
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
    match profile.filter(|p| !crate::inputs::is_builtin_profile(p)) {
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
    /// The sensor's temperature through the survey.
    pub temperature: SurveyTemperature,
    /// The unit on board.
    pub unit: SimulatedUnit,
    /// A `t_s,temp_c` table of the sensor's temperature instead of `temperature`.
    pub temperature_file: Option<PathBuf>,
    /// A motion-definition file instead of the harbour survey.
    pub motion: Option<PathBuf>,
    /// Every channel's thermal lag, s, instead of the profile's.
    pub thermal_lag_s: Option<f64>,
    /// Sensor profile (TOML); none: the built-in one.
    pub profile: Option<PathBuf>,
    /// Seed of every draw.
    pub seed: u64,
    /// The vehicle's speed, GNSS receiver and IMU offsets.
    pub vehicle: VehicleSettings,
}

/// What `simulate vessel` varies for a slow vehicle; the default is the harbour survey's.
#[derive(Debug, Clone, Default)]
pub struct VehicleSettings {
    /// A slow rover at this speed instead of the harbour survey, m/s.
    pub rover_speed_m_s: Option<f64>,
    /// The GNSS receiver.
    pub gnss: GnssSettings,
    /// The gyro biases and time offset added to the IMU record.
    pub offsets: ImuOffsets,
}

/// Fastest `--speed-m-s`, m/s (a rover, a walk, a car in town: beyond it the harbour survey
/// or a motion file fits better).
pub const MAX_ROVER_SPEED_M_S: f64 = 30.0;

/// `--speed-m-s`, `--gnss-*`, `--gyro-bias-deg-h` and `--time-offset-s`, checked.
fn vehicle(args: &VesselArgs) -> Result<VehicleSettings, Failure> {
    let speed = args.speed_m_s.map(rover_speed_m_s).transpose()?;
    let time_offset_s = finite("time_offset_s", args.time_offset_s)?;
    if time_offset_s.abs() > MAX_TIME_OFFSET_S {
        return Err(Failure::Usage(anyhow!(
            "--time-offset-s {time_offset_s}: give at most {MAX_TIME_OFFSET_S} s either way"
        )));
    }
    let gyro_bias_deg_h = match args.gyro_bias_deg_h.as_slice() {
        [] => [0.0; 3],
        values => super::triple("--gyro-bias-deg-h", values)?,
    };
    Ok(VehicleSettings {
        rover_speed_m_s: speed,
        gnss: gnss_settings(args)?,
        offsets: ImuOffsets {
            gyro_bias_rad_s: gyro_bias_deg_h.map(|b| (b / 3600.0).to_radians()),
            time_offset_s,
        },
    })
}

fn rover_speed_m_s(speed: f64) -> Result<f64, Failure> {
    match speed.is_finite() && speed > 0.0 && speed <= MAX_ROVER_SPEED_M_S {
        true => Ok(speed),
        false => Err(Failure::Usage(anyhow!(
            "--speed-m-s {speed}: give above 0 and at most {MAX_ROVER_SPEED_M_S} m/s"
        ))),
    }
}

/// The receiver of `--gnss-rate-hz`, `--gnss-sd-m` and `--gnss-heading`.
fn gnss_settings(args: &VesselArgs) -> Result<GnssSettings, Failure> {
    let default = GnssSettings::default();
    let rate_hz = args.gnss_rate_hz;
    if !(rate_hz.is_finite() && rate_hz > 0.0 && rate_hz <= 100.0) {
        return Err(Failure::Usage(anyhow!(
            "--gnss-rate-hz {rate_hz}: give above 0 and at most 100 Hz"
        )));
    }
    let position_sd_ned_m = match args.gnss_sd_m.as_slice() {
        [] => default.position_sd_ned_m,
        [horizontal] => [*horizontal, *horizontal, 2.0 * horizontal],
        values => super::triple("--gnss-sd-m", values)?,
    };
    if !position_sd_ned_m
        .iter()
        .all(|sd| sd.is_finite() && *sd > 0.0)
    {
        return Err(Failure::Usage(anyhow!(
            "--gnss-sd-m takes one or three positive sds, m"
        )));
    }
    Ok(GnssSettings {
        rate_hz,
        position_sd_ned_m,
        heading: match args.gnss_heading {
            GnssHeadingArg::DualAntenna => GnssHeading::DualAntenna,
            GnssHeadingArg::None => GnssHeading::None,
        },
        ..default
    })
}

/// Resolves `simulate vessel`.
pub fn vessel(args: &VesselArgs) -> Result<VesselSettings, Failure> {
    let survey = SurveySettings {
        temperature_c: finite("temperature_c", args.temperature_c)?,
        duration_s: args.duration_s,
        ..SurveySettings::default()
    };
    if args.motion.is_none() && !(args.duration_s.is_finite() && args.duration_s >= 60.0) {
        return Err(Failure::Usage(anyhow!(
            "--duration-s {} must be at least 60 s",
            args.duration_s
        )));
    }
    profile_io(args.profile.as_ref())
        .optional_inputs([
            ("--motion", args.motion.as_ref()),
            ("--temperature-file", args.temperature_file.as_ref()),
        ])
        .output_folder("survey folder", &args.out)
        .check()?;
    Ok(VesselSettings {
        out: args.out.clone(),
        temperature: survey_temperature(
            &survey,
            args.warm_up_from_c,
            args.warm_up_time_constant_s,
        )?,
        unit: SimulatedUnit {
            serial: args.unit_serial,
        },
        survey,
        temperature_file: args.temperature_file.clone(),
        motion: args.motion.clone(),
        thermal_lag_s: thermal_lag(args.thermal_lag_s)?,
        profile: args.profile.clone(),
        seed: args.seed,
        vehicle: vehicle(args)?,
    })
}

/// The survey's temperature: held at `--temperature-c`, or warming up to it from
/// `--warm-up-from-c` with the time constant given.
pub fn survey_temperature(
    survey: &SurveySettings,
    warm_up_from_c: Option<f64>,
    time_constant_s: f64,
) -> Result<SurveyTemperature, Failure> {
    let Some(start_c) = warm_up_from_c else {
        return Ok(SurveyTemperature::Constant {
            temperature_c: survey.temperature_c,
        });
    };
    let start_c = finite("warm_up_from_c", start_c)?;
    let time_constant_s = positive("warm_up_time_constant_s", time_constant_s)?;
    Ok(SurveyTemperature::WarmUp {
        start_c,
        settled_c: survey.temperature_c,
        time_constant_s,
    })
}
