//! Settings of `characterize` (files or a production lot).

use super::paths::Io;
use crate::args::{CharacterizeArgs, DenoiseArg, ReadingArg};
use crate::failure::Failure;
use crate::thermal::calibration::ThermalInputs;
use anyhow::anyhow;
use std::path::PathBuf;
use thermonav::setting::positive;
use thermonav::signal::wavelet::denoise::WaveletDenoise;
use thermonav::sim::chamber::Site;
use thermonav::stoch::characterize::{CharacterizeSettings, Denoiser, GmwmChoice};
use thermonav::stoch::gmwm::ModelSpec;
use thermonav_io::ImuOptions;

/// Which units of a lot a run characterises.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum UnitChoice {
    /// Every unit of the manifest.
    All,
    /// The unit with this serial.
    Serial(String),
    /// The unit at this 0-based position.
    Index(usize),
}

/// A bank from files, one per temperature.
#[derive(Debug, Clone)]
pub struct BankJob {
    /// Static records.
    pub files: Vec<PathBuf>,
    /// Their temperatures, °C (empty: each file's mean temp_c).
    pub temperatures_c: Vec<f64>,
    /// Conditioning and estimators.
    pub conditioning: CharacterizeSettings,
    /// How each record is read.
    pub reading: ReadingArg,
    /// The bank written.
    pub out: PathBuf,
    /// Further inputs of the thermal calibration (with how every record is read: its
    /// mounting and rate, `thermal.imu`).
    pub thermal: ThermalInputs,
}

/// A production lot from its manifest.
#[derive(Debug, Clone)]
pub struct LotJob {
    /// The manifest (TOML).
    pub manifest: PathBuf,
    /// Which units.
    pub units: UnitChoice,
    /// Conditioning (the manifest's `[defaults]` take precedence).
    pub conditioning: CharacterizeSettings,
    /// How each record is read.
    pub reading: ReadingArg,
    /// The output folder.
    pub out: PathBuf,
}

/// What `characterize` does.
#[derive(Debug, Clone)]
pub enum CharacterizeJob {
    /// One bank.
    Bank(Box<BankJob>),
    /// A lot.
    Lot(Box<LotJob>),
}

/// Resolves `characterize`.
pub fn characterize(args: &CharacterizeArgs) -> Result<CharacterizeJob, Failure> {
    let conditioning = conditioning(args)?;
    let imu = super::imu::options(&args.rotation, &args.rate)?;
    let given = imu.mounting.is_some() || imu.rate_hz.is_some();
    if args.manifest.is_some() && given {
        return Err(Failure::Usage(anyhow!(
            "--imu-rotation and --rate-hz are for records given on the command line; a lot's records are read as its manifest says"
        )));
    }
    match &args.manifest {
        Some(manifest) => Ok(CharacterizeJob::Lot(Box::new(LotJob {
            manifest: manifest.clone(),
            units: unit_choice(args),
            conditioning,
            reading: reading(args)?,
            out: args.out.clone(),
        }))),
        None => bank_job(args, conditioning, imu).map(|job| CharacterizeJob::Bank(Box::new(job))),
    }
}

fn bank_job(
    args: &CharacterizeArgs,
    conditioning: CharacterizeSettings,
    imu: ImuOptions,
) -> Result<BankJob, Failure> {
    if args.files.is_empty() && !args.temperature_c.is_empty() {
        return Err(Failure::Usage(anyhow!(
            "--temperature-c gives the temperatures of static records, and none is given (a sweep's temperatures are its temp_c column)"
        )));
    }
    if args.files.is_empty() && !args.power_on.is_empty() {
        return Err(Failure::Usage(anyhow!(
            "--power-on adds power-ons of static records to a bank of static records, and none is given: give each sweep its own --sweep (comma-separated files are pieces of one power-on)"
        )));
    }
    if !args.temperature_c.is_empty() && args.temperature_c.len() != args.files.len() {
        return Err(Failure::Usage(anyhow!(
            "--temperature-c has {} values for {} files",
            args.temperature_c.len(),
            args.files.len()
        )));
    }
    for &t in &args.temperature_c {
        check_temperature("--temperature-c", t)?;
    }
    let thermal = ThermalInputs {
        imu,
        ..thermal_inputs(args)?
    };
    let further: Vec<PathBuf> = thermal.power_ons.iter().flatten().cloned().collect();
    let sweeps: Vec<PathBuf> = thermal.sweeps.iter().flatten().cloned().collect();
    Io::new()
        .inputs("a record", &args.files)
        .inputs("a --power-on record", &further)
        .inputs("a --sweep record", &sweeps)
        .output("bank", &args.out)
        .check()?;
    Ok(BankJob {
        files: args.files.clone(),
        temperatures_c: args.temperature_c.clone(),
        conditioning,
        reading: reading(args)?,
        out: args.out.clone(),
        thermal,
    })
}

/// The further power-ons and sweeps of the thermal calibration.
fn thermal_inputs(args: &CharacterizeArgs) -> Result<ThermalInputs, Failure> {
    Ok(ThermalInputs {
        power_ons: args.power_on.iter().map(|p| p.0.clone()).collect(),
        sweeps: args.sweep.iter().map(|s| s.0.clone()).collect(),
        sweep_block_s: args
            .sweep_block_s
            .map(|b| positive("sweep_block_s", b))
            .transpose()?,
        sweep_instance: args.sweep_instance,
        site: chamber_site(args)?,
        imu: ImuOptions::default(),
        topics: super::imu::topics(&args.topics),
    })
}

/// The chamber's site: a latitude within ±90° and a height within −500..10 000 m.
fn chamber_site(args: &CharacterizeArgs) -> Result<Site, Failure> {
    let (lat, h) = (args.chamber_latitude_deg, args.chamber_height_m);
    if !((-90.0..=90.0).contains(&lat) && (-500.0..=10_000.0).contains(&h)) {
        return Err(Failure::Usage(anyhow!(
            "--chamber-latitude-deg {lat} / --chamber-height-m {h}: expected −90..90° and −500..10000 m"
        )));
    }
    Ok(Site {
        latitude_rad: lat.to_radians(),
        height_m: h,
    })
}

/// `t` when it lies in the sensor temperature range, else a usage error naming where it came
/// from.
pub fn check_temperature(source: &str, t: f64) -> Result<f64, Failure> {
    thermonav_io::check_characterization_temperature(source, t)
        .map_err(|message| Failure::Usage(anyhow!(message)))
}

fn unit_choice(args: &CharacterizeArgs) -> UnitChoice {
    match (&args.unit, args.unit_index) {
        (Some(serial), _) => UnitChoice::Serial(serial.clone()),
        (None, Some(index)) => UnitChoice::Index(index),
        (None, None) => UnitChoice::All,
    }
}

fn conditioning(args: &CharacterizeArgs) -> Result<CharacterizeSettings, Failure> {
    Ok(CharacterizeSettings {
        cutoff_hz: positive("cutoff_hz", args.cutoff_hz)?,
        transition_hz: positive("transition_hz", args.transition_hz)?,
        modelling_rate_hz: positive("modelling_rate_hz", args.modelling_rate_hz)?,
        denoise: denoiser(args.denoise),
        gmwm: gmwm_model(&args.gmwm)?,
        ..CharacterizeSettings::default()
    })
}

/// `--gmwm`: a composite, `auto` or `off`.
fn gmwm_model(text: &str) -> Result<Option<GmwmChoice>, Failure> {
    match text.to_ascii_lowercase().as_str() {
        "off" => Ok(None),
        "auto" => Ok(Some(GmwmChoice::Auto)),
        _ => text
            .parse::<ModelSpec>()
            .map(|spec| Some(GmwmChoice::Model(spec)))
            .map_err(|e| Failure::Usage(anyhow!("--gmwm {text}: {e} (or auto, or off)"))),
    }
}

/// `--denoise`: the wavelet de-noiser takes the library's wavelet defaults.
fn denoiser(denoise: DenoiseArg) -> Denoiser {
    match denoise {
        DenoiseArg::Kaiser => Denoiser::Kaiser,
        DenoiseArg::Wavelet => Denoiser::Wavelet(WaveletDenoise::default()),
    }
}

/// `--reading`: the wavelet transform needs the whole record, so it reads in memory (auto) and
/// refuses streaming.
fn reading(args: &CharacterizeArgs) -> Result<ReadingArg, Failure> {
    match (args.denoise, args.reading) {
        (DenoiseArg::Wavelet, ReadingArg::Streaming) => Err(Failure::Usage(anyhow!(
            "--denoise wavelet needs the whole record in memory: --reading streaming cannot be used with it"
        ))),
        (DenoiseArg::Wavelet, _) => Ok(ReadingArg::InMemory),
        (DenoiseArg::Kaiser, reading) => Ok(reading),
    }
}
