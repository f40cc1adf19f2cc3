//! `thermonav bank show`: the bank, or the model selected for an operating temperature;
//! `thermonav bank export`: its thermal calibration as autopilot parameters, or its noise
//! model at a temperature as another tool's noise configuration.

use crate::args::{BankAction, BankArgs, BankExportArgs, BankShowArgs, ExportKind};
use crate::bank_tables::{print_bank_table, significant};
use crate::failure::{Classify, Failure};
use crate::inputs::read_bank;
use crate::report::{print_json, print_rows};
use crate::settings::paths::Io;
use anyhow::anyhow;
use clap::ValueEnum;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::{Channel, Sensor};
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, Placement, SelectedModel, Selection};
use thermonav::stoch::thermal::SensorDevices;
use thermonav_io::noise_export::{
    ExportOptions, ImuNoise, NoiseExportError, NoiseExportSummary, NoiseFormat, noise_config_text,
    placement_words, write_noise_config,
};
use thermonav_io::thermal_parameters::{
    ExportSummary, ExportTarget, ParameterFile, ParameterTarget, SensorExport,
    ardupilot_parameters, px4_parameters, write_parameter_file,
};
use thermonav_plot::figures::DisplayUnits;

/// Runs `bank`.
pub fn run(args: &BankArgs) -> Result<(), Failure> {
    match &args.action {
        BankAction::Show(show) => run_show(show),
        BankAction::Export(export) => run_export(export),
        BankAction::Check(_) => unreachable_check(),
    }
}

/// `bank check` is dispatched to its own command file by `commands::run`.
fn unreachable_check() -> Result<(), Failure> {
    Err(Failure::Usage(anyhow!(
        "bank check is run by its own command"
    )))
}

fn run_export(args: &BankExportArgs) -> Result<(), Failure> {
    export_io(args).check()?;
    let kind = checked_kind(args)?;
    let bank = read_bank(&args.bank)?;
    match kind {
        ExportKind::Thermal(target) => export_thermal(&bank, target, args),
        ExportKind::Noise(format) => export_noise(&bank, format, args),
    }
}

/// The export's kind, with its options checked (usage errors, before any file is read): what
/// a noise format needs, and no option of the other kind of export.
fn checked_kind(args: &BankExportArgs) -> Result<ExportKind, Failure> {
    let kind = ExportKind::from(args.format);
    if let ExportKind::Noise(format) = kind {
        format.check_options(&export_options(args)).usage()?;
    }
    match misplaced_option(kind, args) {
        Some(option) => Err(not_applicable(option, args)),
        None => Ok(kind),
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

fn export_noise(
    bank: &ModelBank,
    format: NoiseFormat,
    args: &BankExportArgs,
) -> Result<(), Failure> {
    let noise = noise_at_temperature(bank, args)?;
    let text = noise_config_text(format, &noise, &export_options(args));
    write_noise_config(&args.out, &text.map_err(|e| noise_failure(e, args))?).data()?;
    if args.json {
        return print_json(&NoiseExportSummary::new(format, &noise));
    }
    print_noise_rows(&noise, args);
    Ok(())
}

/// The bank's noise at the operating temperature.
fn noise_at_temperature(bank: &ModelBank, args: &BankExportArgs) -> Result<ImuNoise, Failure> {
    let (selection, source) = (args.method.into(), args.model.into());
    ImuNoise::at_temperature(bank, args.temperature_c, selection, source)
        .map_err(|e| anyhow!("{}: {e}", args.bank.display()))
        .data()
}

fn print_noise_rows(noise: &ImuNoise, args: &BankExportArgs) {
    let at = format!(
        "{} °C, {}",
        noise.temperature_c,
        placement_words(noise.placement)
    );
    print_rows(&[("written", args.out.display().to_string()), ("at", at)]);
}

fn export_options(args: &BankExportArgs) -> ExportOptions {
    ExportOptions {
        bank_name: args.bank.display().to_string(),
        rostopic: args.rostopic.clone(),
        scale_factor_std_ppm: args.scale_factor_std_ppm,
    }
}

fn noise_failure(error: NoiseExportError, args: &BankExportArgs) -> Failure {
    Failure::Data(anyhow!("{}: {error}", args.bank.display()))
}

fn export_thermal(
    bank: &ModelBank,
    target: ParameterTarget,
    args: &BankExportArgs,
) -> Result<(), Failure> {
    let file = parameter_file(bank, target, args)?;
    write_parameter_file(&args.out, &file).data()?;
    if args.json {
        return print_json(&file.summary());
    }
    print_export_rows(&file.summary(), args);
    Ok(())
}

fn export_io(args: &BankExportArgs) -> Io {
    Io::new()
        .input("BANK", &args.bank)
        .output("exported file", &args.out)
}

/// The bank's thermal calibration in the chosen target's parameters.
fn parameter_file(
    bank: &ModelBank,
    target_format: ParameterTarget,
    args: &BankExportArgs,
) -> Result<ParameterFile, Failure> {
    let calibration = bank
        .thermal
        .as_ref()
        .ok_or_else(|| no_thermal_calibration(&args.bank))?;
    let target = export_target(calibration.devices.as_ref(), args);
    let file = match target_format {
        ParameterTarget::Px4Tc => px4_parameters(calibration, target),
        ParameterTarget::ArdupilotTcal => ardupilot_parameters(calibration, target),
    };
    file.map_err(|e| anyhow!("{}: {e}", args.bank.display()))
        .data()
}

/// The instance and device ids: as given, else the calibration's sensors, else 0.
fn export_target(devices: Option<&SensorDevices>, args: &BankExportArgs) -> ExportTarget {
    let of = |pick: fn(&SensorDevices) -> Option<u32>| devices.and_then(pick).unwrap_or(0);
    ExportTarget {
        instance: args.instance.or(devices.map(|d| d.instance)).unwrap_or(0),
        gyro_device_id: args
            .device_id
            .or(args.gyro_device_id)
            .unwrap_or(of(|d| d.gyro_device_id)),
        accel_device_id: args
            .device_id
            .or(args.accel_device_id)
            .unwrap_or(of(|d| d.accel_device_id)),
    }
}

fn no_thermal_calibration(path: &Path) -> Failure {
    Failure::Data(anyhow!(
        "{}: the bank has no thermal calibration (no 'thermal' field): calibrate the unit first with `thermonav characterize`, from sweeps alone (`--sweep LOG`: a warm-up or chamber log, CSV, ULog, DataFlash or bag, at any rate), from static records at two or more temperatures (`--temperature-c`), or with further power-ons (`--power-on`), then export that bank",
        path.display()
    ))
}

fn print_export_rows(summary: &ExportSummary, args: &BankExportArgs) {
    let mut rows = vec![
        ("written", args.out.display().to_string()),
        ("parameters", summary.parameters.to_string()),
    ];
    rows.extend(summary.sensors.iter().map(sensor_row));
    print_rows(&rows);
}

fn sensor_row(export: &SensorExport) -> (&'static str, String) {
    let [low, high] = export.temperature_range_c;
    let reference = export.reference_temperature_c;
    let range = format!("TMIN..TMAX {low}..{high} °C, reference {reference} °C");
    (export.sensor.name(), range)
}

#[derive(Debug, Serialize)]
struct SelectionJson {
    operating_temperature_c: f64,
    selection: Selection,
    model: GaussMarkovSource,
    channels: BTreeMap<&'static str, SelectedChannel>,
}

/// A selected model with its sigma also under a unit-suffixed key, SI and edge unit:
/// `sigma_rad_s` and `sigma_deg_h` for a gyro, `sigma_m_s2` and `sigma_mg` for an
/// accelerometer (`sigma` stays, in the channel's SI unit).
#[derive(Debug, Serialize)]
struct SelectedChannel {
    #[serde(flatten)]
    model: SelectedModel,
    #[serde(skip_serializing_if = "Option::is_none")]
    sigma_rad_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sigma_deg_h: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sigma_m_s2: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sigma_mg: Option<f64>,
    #[serde(skip)]
    sensor: Sensor,
}

impl SelectedChannel {
    fn new(channel: Channel, model: SelectedModel) -> Self {
        let (sigma, sensor) = (model.sigma, channel.sensor());
        let gyro = sensor == Sensor::Gyro;
        let edge = DisplayUnits::Navigation.rate(sensor, sigma);
        Self {
            model,
            sigma_rad_s: gyro.then_some(sigma),
            sigma_deg_h: gyro.then_some(edge),
            sigma_m_s2: (!gyro).then_some(sigma),
            sigma_mg: (!gyro).then_some(edge),
            sensor,
        }
    }
}

fn run_show(args: &BankShowArgs) -> Result<(), Failure> {
    let bank = read_bank(&args.bank)?;
    let Some(t) = args.at_temperature_c else {
        if args.json {
            return print_json(&bank);
        }
        print_bank_table(&bank);
        return Ok(());
    };
    let (selection, source): (Selection, GaussMarkovSource) =
        (args.method.into(), args.model.into());
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let model = bank
            .select(t, channel, source, selection)
            .map_err(|e| anyhow!("{}: {e}", args.bank.display()))
            .data()?;
        channels.insert(channel.name(), SelectedChannel::new(channel, model));
    }
    let doc = SelectionJson {
        operating_temperature_c: t,
        selection,
        model: source,
        channels,
    };
    if args.json {
        return print_json(&doc);
    }
    print_selection(&doc);
    Ok(())
}

/// The selected models as a table: one row per channel, Tc in s, sigma in the channel's unit
/// and the bank entries each came from.
fn print_selection(doc: &SelectionJson) {
    let (selection, model) = (serde_name(&doc.selection), serde_name(&doc.model));
    let t = doc.operating_temperature_c;
    println!("model for {t} °C (selection {selection}, model {model}):");
    let rows: Vec<(&str, String)> = doc.channels.iter().map(selected_row).collect();
    print_rows(&rows);
}

fn selected_row((name, c): (&&'static str, &SelectedChannel)) -> (&'static str, String) {
    let m = &c.model;
    let tc_s = m.correlation_time_s;
    let units = DisplayUnits::Navigation;
    let sigma = significant(units.rate(c.sensor, m.sigma));
    let text = format!(
        "Tc {tc_s:>10.2} s  sigma {sigma:>10} {:<5}  {}",
        units.rate_unit(c.sensor),
        placement_text(&m.placement)
    );
    (name, text)
}

/// Where a selected model came from, in words with its temperatures in °C.
fn placement_text(placement: &Placement) -> String {
    match *placement {
        Placement::Entry { temperature_c } => format!("entry at {temperature_c} °C"),
        Placement::Between {
            lower_c,
            upper_c,
            weight,
        } => {
            format!("between {lower_c} and {upper_c} °C (weight {weight:.3} on {upper_c} °C)")
        }
        Placement::Clamped { temperature_c } => format!("held at the end entry {temperature_c} °C"),
    }
}

/// The name a value has in the JSON output (its serde name).
fn serde_name(value: &impl Serialize) -> String {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(name)) => name,
        _ => String::new(),
    }
}
