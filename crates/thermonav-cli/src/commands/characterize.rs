//! `thermonav characterize`: the temperature model bank from static records.

use crate::args::CharacterizeArgs;
use crate::banks::building::build_job_bank;
use crate::banks::production_lot::characterize_lot;
use crate::banks::tables::print_bank_table;
use crate::failure::Failure;
use crate::report::print_json;
use crate::settings::characterization::{CharacterizeJob, characterize};
use crate::thermal::calibration::missing_reason;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::{Channel, Sensor};
use thermonav::stoch::bank::{GaussMarkovEstimate, GaussMarkovSource, ModelBank};
use thermonav::stoch::thermal::sweep_model::ChoiceRule;
use thermonav::stoch::thermal::{CalibrationSummary, ChannelCalibration, ThermalCalibration};

#[derive(Debug, Serialize)]
struct Summary<'a> {
    bank: String,
    temperatures_c: Vec<f64>,
    entries: Vec<EntrySummary<'a>>,
    /// The thermal calibration per channel, or `None` (null) when not fitted.
    thermal: Option<ThermalSummary>,
    /// Why there is no thermal calibration; absent when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    thermal_not_fitted_reason: Option<String>,
    /// Channels of gx..az without a noise model (the records had no such column); absent
    /// when all six are there.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    missing_channels: Vec<&'static str>,
    /// What the missing channels mean for the bank's users; absent with all six.
    #[serde(skip_serializing_if = "Option::is_none")]
    missing_channels_note: Option<String>,
}

/// The thermal calibration in brief.
#[derive(Debug, Serialize)]
struct ThermalSummary {
    /// Legs found in the sweeps (0 without sweeps alone).
    legs: usize,
    power_ons: usize,
    channels: BTreeMap<&'static str, ThermalChannelSummary>,
}

/// One channel's curve in brief; rates in SI, the unit in the key.
#[derive(Debug, Serialize)]
struct ThermalChannelSummary {
    order: usize,
    reference_temperature_c: f64,
    range_c: [f64; 2],
    #[serde(flatten)]
    max_band_half_width: HalfWidth,
    /// From sweeps alone: the model chosen on held-out data.
    #[serde(skip_serializing_if = "Option::is_none")]
    chosen_on_held_out: Option<HeldOutChoice>,
}

/// The model chosen on held-out data (sweeps alone): the curve in T of `order` above, or the
/// lag model; `left_uncompensated` for order 0.
#[derive(Debug, Serialize)]
struct HeldOutChoice {
    rule: ChoiceRule,
    order: usize,
    /// τ of b(T_τ), s; null without a lag.
    thermal_lag_s: Option<f64>,
    /// Its 95 % interval, s (null ends are open).
    thermal_lag_interval_s: Option<[Option<f64>; 2]>,
    left_uncompensated: bool,
    legs: usize,
}

/// The largest band half-width over the fitted range, keyed by its SI unit.
#[derive(Debug, Serialize)]
enum HalfWidth {
    #[serde(rename = "max_band_half_width_rad_s")]
    Gyro(f64),
    #[serde(rename = "max_band_half_width_m_s2")]
    Accelerometer(f64),
}

#[derive(Debug, Serialize)]
struct EntrySummary<'a> {
    temperature_c: f64,
    source: &'a str,
    channels: Vec<ChannelSummary<'a>>,
}

#[derive(Debug, Serialize)]
struct ChannelSummary<'a> {
    channel: &'static str,
    unit: &'a str,
    irregular_ml: &'a GaussMarkovEstimate,
    ar_based: &'a GaussMarkovEstimate,
    acf_fit: &'a GaussMarkovEstimate,
    white_noise_density: Option<f64>,
}

/// Runs `characterize`.
pub fn run(args: &CharacterizeArgs) -> Result<(), Failure> {
    let job = match characterize(args)? {
        CharacterizeJob::Lot(lot) => return characterize_lot(&lot, args.json),
        CharacterizeJob::Bank(job) => job,
    };
    let bank = build_job_bank(&job)?;
    if let Some(note) = missing_channels_note(&bank) {
        eprintln!("note: {note}");
    }
    if args.json {
        return print_json(&summarize(&bank, &job.out));
    }
    print_bank_table(&bank);
    print_missing_thermal(&bank);
    println!("\nbank written to {}", job.out.display());
    Ok(())
}

/// The channels of gx..az that some entry of the bank has no model for.
fn missing_channels(bank: &ModelBank) -> Vec<&'static str> {
    let lacking = |c: &&Channel| bank.entries.iter().any(|e| !e.channels.contains_key(*c));
    Channel::ALL
        .iter()
        .filter(lacking)
        .map(|c| c.name())
        .collect()
}

/// What a bank without some channels cannot be used for, naming them; `None` with all six.
fn missing_channels_note(bank: &ModelBank) -> Option<String> {
    let missing = missing_channels(bank);
    if missing.is_empty() {
        return None;
    }
    let (list, verb) = (
        missing.join(", "),
        if missing.len() == 1 { "has" } else { "have" },
    );
    Some(format!(
        "{list} {verb} no noise model in this bank (the records have no such column): a bank of {} channels; what needs all six (`bank export` of a noise configuration such as kalibr or kf-gins, `bank show --at-temperature-c`, `integrate` and `evaluate` with --bank) will refuse it",
        Channel::ALL.len() - missing.len()
    ))
}

/// Why the bank has no thermal calibration, when it has none.
fn print_missing_thermal(bank: &ModelBank) {
    if bank.thermal.is_none() {
        println!("\nno thermal calibration: {}", missing_reason(bank));
    }
}

impl HalfWidth {
    /// The half-width `si` of a channel of `sensor` (rad/s or m/s²).
    fn of(sensor: Sensor, si: f64) -> Self {
        match sensor {
            Sensor::Gyro => HalfWidth::Gyro(si),
            Sensor::Accelerometer => HalfWidth::Accelerometer(si),
        }
    }
}

/// The thermal calibration of `bank` in brief, or why there is none.
fn thermal_summary(bank: &ModelBank) -> (Option<ThermalSummary>, Option<String>) {
    match &bank.thermal {
        Some(c) => (Some(thermal_summary_of(c)), None),
        None => (None, Some(missing_reason(bank))),
    }
}

fn thermal_summary_of(calibration: &ThermalCalibration) -> ThermalSummary {
    let channels = Channel::ALL.into_iter().filter_map(|channel| {
        let summary = calibration.summary(channel)?;
        let mut brief = thermal_channel_summary(channel, &summary);
        brief.chosen_on_held_out = calibration.channels.get(&channel).and_then(held_out_choice);
        Some((channel.name(), brief))
    });
    ThermalSummary {
        legs: calibration.legs.len(),
        power_ons: calibration.power_ons,
        channels: channels.collect(),
    }
}

fn thermal_channel_summary(channel: Channel, s: &CalibrationSummary) -> ThermalChannelSummary {
    ThermalChannelSummary {
        order: s.order,
        reference_temperature_c: s.reference_temperature_c,
        range_c: s.temperature_range_c,
        max_band_half_width: HalfWidth::of(channel.sensor(), s.max_band_half_width),
        chosen_on_held_out: None,
    }
}

fn held_out_choice(c: &ChannelCalibration) -> Option<HeldOutChoice> {
    let selection = c.selection.as_ref()?;
    let lag = c.lagged.as_ref().map(|l| &l.lag);
    Some(HeldOutChoice {
        rule: selection.rule,
        order: selection.chosen.order,
        thermal_lag_s: lag.map(|l| l.tau_s),
        thermal_lag_interval_s: lag.map(|l| l.tau_interval_s),
        left_uncompensated: selection.chosen.order == 0,
        legs: selection.spread.legs,
    })
}

fn summarize<'a>(bank: &'a ModelBank, out: &Path) -> Summary<'a> {
    let (thermal, thermal_not_fitted_reason) = thermal_summary(bank);
    Summary {
        thermal,
        thermal_not_fitted_reason,
        missing_channels: missing_channels(bank),
        missing_channels_note: missing_channels_note(bank),
        bank: out.display().to_string(),
        temperatures_c: bank.temperatures_c(),
        entries: bank
            .entries
            .iter()
            .map(|e| EntrySummary {
                temperature_c: e.temperature_c,
                source: &e.source,
                channels: e
                    .channels
                    .iter()
                    .map(|(c, m)| ChannelSummary {
                        channel: c.name(),
                        unit: &m.unit,
                        irregular_ml: m.gauss_markov.get(GaussMarkovSource::IRREGULAR_ML),
                        ar_based: m.gauss_markov.get(GaussMarkovSource::AR_BASED),
                        acf_fit: m.gauss_markov.get(GaussMarkovSource::ACF_FIT),
                        white_noise_density: m.allan.white_noise_density,
                    })
                    .collect(),
            })
            .collect(),
    }
}
