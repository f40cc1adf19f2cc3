//! `thermonav bank show`: the bank, or the model selected for an operating temperature;
//! `thermonav bank export`: its thermal calibration as autopilot parameters, or its noise
//! model at a temperature as another tool's noise configuration.

use crate::args::{BankExportArgs, BankShowArgs, ExportKind};
use crate::banks::tables::{print_bank_table, significant};
use crate::failure::{Classify, Failure};
use crate::inputs::read_bank;
use crate::report::{print_json, print_rows};
use crate::settings::bank::{ExportSettings, ShowSettings, resolve_export, resolve_show};
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::{Channel, Sensor};
use thermonav::stoch::bank::{GaussMarkovSource, ModelBank, Placement, SelectedModel, Selection};
use thermonav::stoch::thermal::SensorDevices;
use thermonav_io::noise_export::{
    ImuNoise, NoiseExportError, NoiseExportSummary, NoiseFormat, noise_config_text,
    placement_words, write_noise_config,
};
use thermonav_io::thermal_parameters::{
    ExportSummary, ExportTarget, ParameterFile, ParameterTarget, SensorExport,
    ardupilot_parameters, px4_parameters, write_parameter_file,
};
use thermonav_plot::figures::DisplayUnits;

/// Runs `bank export`.
pub fn run_export(args: &BankExportArgs) -> Result<(), Failure> {
    let settings = resolve_export(args)?;
    let bank = read_bank(&args.bank)?;
    match settings.kind {
        ExportKind::Thermal(target) => export_thermal(&bank, target, args),
        ExportKind::Noise(format) => export_noise(&bank, format, &settings, args),
    }
}

fn export_noise(
    bank: &ModelBank,
    format: NoiseFormat,
    settings: &ExportSettings,
    args: &BankExportArgs,
) -> Result<(), Failure> {
    let noise = noise_at_temperature(bank, settings, args)?;
    let text = noise_config_text(format, &noise, &settings.options);
    write_noise_config(&args.out, &text.map_err(|e| noise_failure(e, args))?).data()?;
    if args.json {
        return print_json(&NoiseExportSummary::new(format, &noise));
    }
    print_noise_rows(&noise, args);
    Ok(())
}

/// The bank's noise at the operating temperature.
fn noise_at_temperature(
    bank: &ModelBank,
    settings: &ExportSettings,
    args: &BankExportArgs,
) -> Result<ImuNoise, Failure> {
    let (selection, source) = (settings.selection, settings.source);
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

/// Runs `bank show`.
pub fn run_show(args: &BankShowArgs) -> Result<(), Failure> {
    let ShowSettings {
        at_temperature_c,
        selection,
        source,
    } = resolve_show(args)?;
    let bank = read_bank(&args.bank)?;
    let Some(t) = at_temperature_c else {
        if args.json {
            return print_json(&bank);
        }
        print_bank_table(&bank);
        return Ok(());
    };
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
