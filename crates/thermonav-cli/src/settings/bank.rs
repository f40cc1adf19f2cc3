//! Settings of `bank show` and `bank export`: the operating temperature (the library's rule),
//! the export's kind with the options its format needs and none of the other kind's, and an
//! output that spares the bank, all checked before the bank is read.

use super::paths::Io;
use crate::args::{BankExportArgs, BankShowArgs, ExportKind};
use crate::failure::{Classify, Failure};
use anyhow::anyhow;
use clap::ValueEnum;
use thermonav::stoch::bank::{GaussMarkovSource, Selection, check_operating_temperature};
use thermonav_io::noise_export::ExportOptions;

/// What `bank show` shows, resolved from its options.
#[derive(Debug, Clone, Copy)]
pub struct ShowSettings {
    /// The operating temperature, °C (finite), or the whole bank without it.
    pub at_temperature_c: Option<f64>,
    /// The selection rule.
    pub selection: Selection,
    /// The Gauss-Markov family.
    pub source: GaussMarkovSource,
}

/// `bank show`: `--at-temperature-c`, when given, a temperature the library accepts.
pub fn resolve_show(args: &BankShowArgs) -> Result<ShowSettings, Failure> {
    operating_temperature("--at-temperature-c", args.at_temperature_c)?;
    Ok(ShowSettings {
        at_temperature_c: args.at_temperature_c,
        selection: args.method.into(),
        source: args.model.into(),
    })
}

/// What `bank export` writes, resolved from its options.
#[derive(Debug, Clone)]
pub struct ExportSettings {
    /// Thermal parameters or a noise configuration, in which format.
    pub kind: ExportKind,
    /// The noise formats' options (checked against the format).
    pub options: ExportOptions,
    /// Noise formats: the selection rule.
    pub selection: Selection,
    /// Noise formats: the Gauss-Markov family.
    pub source: GaussMarkovSource,
}

/// `bank export`: the output spares the bank; a noise format has the options it needs and a
/// temperature the library accepts; no option of the other kind of export is given.
pub fn resolve_export(args: &BankExportArgs) -> Result<ExportSettings, Failure> {
    Io::new()
        .input("BANK", &args.bank)
        .output("exported file", &args.out)
        .check()?;
    let (kind, options) = (ExportKind::from(args.format), export_options(args));
    if let ExportKind::Noise(format) = kind {
        format.check_options(&options).usage()?;
        operating_temperature("--temperature-c", args.temperature_c)?;
    }
    if let Some(option) = misplaced_option(kind, args) {
        return Err(not_applicable(option, args));
    }
    Ok(ExportSettings {
        kind,
        options,
        selection: args.method.into(),
        source: args.model.into(),
    })
}

/// A usage error naming `option` when its temperature is not one the library accepts.
pub fn operating_temperature(option: &str, temperature_c: Option<f64>) -> Result<(), Failure> {
    match temperature_c.map(check_operating_temperature) {
        Some(Err(e)) => Err(Failure::Usage(anyhow!("{option}: {e}"))),
        _ => Ok(()),
    }
}

/// The noise formats' options as given.
fn export_options(args: &BankExportArgs) -> ExportOptions {
    ExportOptions {
        bank_name: args.bank.display().to_string(),
        rostopic: args.rostopic.clone(),
        scale_factor_std_ppm: args.scale_factor_std_ppm,
    }
}

/// An option of the other kind of export, if one was given.
fn misplaced_option(kind: ExportKind, args: &BankExportArgs) -> Option<&'static str> {
    match kind {
        ExportKind::Noise(_) => thermal_option(args),
        ExportKind::Thermal(_) => noise_option(args),
    }
}

fn not_applicable(option: &str, args: &BankExportArgs) -> Failure {
    let format = args.format.to_possible_value();
    let format = format.map_or_else(String::new, |v| v.get_name().to_string());
    Failure::Usage(anyhow!("{option} does not apply to --format {format}"))
}

/// A thermal-export option given, if any.
fn thermal_option(args: &BankExportArgs) -> Option<&'static str> {
    let given = [
        ("--instance", args.instance.is_some()),
        ("--device-id", args.device_id.is_some()),
        ("--gyro-device-id", args.gyro_device_id.is_some()),
        ("--accel-device-id", args.accel_device_id.is_some()),
    ];
    given.into_iter().find(|(_, is)| *is).map(|(name, _)| name)
}

/// A noise-export option without a default given, if any.
fn noise_option(args: &BankExportArgs) -> Option<&'static str> {
    let given = [
        ("--temperature-c", args.temperature_c.is_some()),
        (
            "--scale-factor-std-ppm",
            args.scale_factor_std_ppm.is_some(),
        ),
    ];
    given.into_iter().find(|(_, is)| *is).map(|(name, _)| name)
}
