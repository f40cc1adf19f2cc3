//! `thermonav allan`: overlapping Allan deviation of every channel, or another member of the
//! Allan family (`--kind`).

use crate::args::AllanArgs;
use crate::banks::noise_units::{TermsJson, terms_json, terms_line};
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use crate::settings::analysis::{AllanSettings, resolve_allan};
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::{Channel, ImuSeries, SampleKind};
use thermonav::stoch::allan::{
    AllanCurve, DeviationCurve, DeviationKind, channel_deviations, confidence_intervals_with,
    overlapping_adev,
};
use thermonav::stoch::noise_terms::fit_noise_terms;

/// The JSON document of `allan --json`.
#[derive(Debug, Serialize)]
struct AllanJson {
    file: String,
    /// The `--imu-rotation` the record was turned by into body axes, when given.
    #[serde(skip_serializing_if = "Option::is_none")]
    imu_rotation: Option<String>,
    sample_rate_hz: f64,
    confidence: f64,
    channels: BTreeMap<&'static str, ChannelJson>,
}

#[derive(Debug, Serialize)]
/// One channel of `allan --json`.
struct ChannelJson {
    unit: &'static str,
    tau_s: Vec<f64>,
    adev: Vec<f64>,
    n_terms: Vec<usize>,
    ci_low: Vec<f64>,
    ci_high: Vec<f64>,
    noise_type_alpha: Vec<i32>,
    terms: TermsJson,
}

/// Runs `allan`.
pub fn run(args: &AllanArgs) -> Result<(), Failure> {
    let settings = resolve_allan(args)?;
    if settings.kind != DeviationKind::Adev {
        return run_family(args, &settings);
    }
    let read = (&settings.options, &settings.topics);
    let (series, rate_hz) = crate::inputs::read_rates(&args.file, "Allan deviation", read)?;
    let doc = AllanJson {
        file: args.file.display().to_string(),
        imu_rotation: crate::settings::imu::rotation_text(&settings.options),
        sample_rate_hz: rate_hz,
        confidence: settings.ci.level,
        channels: adev_channels(args, &settings, (&series, rate_hz))?,
    };
    if args.json {
        return print_json(&doc);
    }
    print_text(&doc);
    Ok(())
}

/// Every channel's overlapping Allan deviation, limits and terms.
fn adev_channels(
    args: &AllanArgs,
    settings: &AllanSettings,
    (series, rate_hz): (&ImuSeries, f64),
) -> Result<BTreeMap<&'static str, ChannelJson>, Failure> {
    let mut channels = BTreeMap::new();
    for channel in series.present_channels() {
        let y = series.channel(channel);
        let curve = overlapping_adev(y, rate_hz, &settings.grid)
            .map_err(|e| anyhow!("{}: channel {}: {e}", args.file.display(), channel.name()))
            .data()?;
        let json = channel_json(y, curve, channel, settings);
        channels.insert(channel.name(), json);
    }
    Ok(channels)
}

/// One channel's curve with its confidence limits, noise types and fitted noise terms.
fn channel_json(y: &[f64], curve: AllanCurve, channel: Channel, s: &AllanSettings) -> ChannelJson {
    let ci = confidence_intervals_with(y, &curve, &s.ci);
    let terms = terms_json(&fit_noise_terms(&curve, &ci), channel.sensor());
    ChannelJson {
        unit: channel.si_unit(SampleKind::Rates),
        tau_s: curve.tau_s,
        adev: curve.adev,
        n_terms: curve.n_terms,
        ci_low: ci.low,
        ci_high: ci.high,
        noise_type_alpha: ci.alpha,
        terms,
    }
}

/// The text report: a heading line, then each channel's terms and table.
fn print_text(doc: &AllanJson) {
    println!(
        "{}: {:.3} Hz, overlapping Allan deviation ({:.1} % limits)",
        doc.file,
        doc.sample_rate_hz,
        doc.confidence * 100.0
    );
    for (name, c) in &doc.channels {
        print_channel(name, c);
    }
}

/// One channel: its unit and noise terms, then τ, deviation, limits, terms and noise type.
fn print_channel(name: &str, c: &ChannelJson) {
    println!("\n{name} [{}]  {}", c.unit, terms_line(&c.terms));
    println!(
        "{:>12} {:>14} {:>14} {:>14} {:>10} {:>6}",
        "tau_s", "adev", "low", "high", "n_terms", "alpha"
    );
    for i in 0..c.tau_s.len() {
        println!(
            "{:>12.4} {:>14.6e} {:>14.6e} {:>14.6e} {:>10} {:>6}",
            c.tau_s[i], c.adev[i], c.ci_low[i], c.ci_high[i], c.n_terms[i], c.noise_type_alpha[i]
        );
    }
}

/// The JSON document of `allan --kind K --json` for a kind other than adev.
#[derive(Debug, Serialize)]
struct FamilyJson {
    file: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    imu_rotation: Option<String>,
    sample_rate_hz: f64,
    kind: DeviationKind,
    channels: BTreeMap<&'static str, FamilyChannelJson>,
}

/// One channel of [`FamilyJson`]: the deviation under the kind's name, in `unit`.
#[derive(Debug, Serialize)]
struct FamilyChannelJson {
    unit: &'static str,
    tau_s: Vec<f64>,
    #[serde(flatten)]
    deviation: BTreeMap<&'static str, Vec<f64>>,
    n_terms: Vec<usize>,
}

/// `allan --kind K` for a kind other than adev: each channel's curve, without confidence limits
/// or noise terms (those are the overlapping Allan deviation's).
fn run_family(args: &AllanArgs, settings: &AllanSettings) -> Result<(), Failure> {
    let doc = family_doc(args, settings)?;
    if args.json {
        return print_json(&doc);
    }
    print_family_text(&doc);
    Ok(())
}

/// Every channel's curve of `args.kind`.
fn family_doc(args: &AllanArgs, settings: &AllanSettings) -> Result<FamilyJson, Failure> {
    let read = (&settings.options, &settings.topics);
    let (series, rate_hz) = crate::inputs::read_rates(&args.file, "Allan deviation", read)?;
    let curves = family_curves(args, settings, (&series, rate_hz))?;
    Ok(FamilyJson {
        file: args.file.display().to_string(),
        imu_rotation: crate::settings::imu::rotation_text(&settings.options),
        sample_rate_hz: rate_hz,
        kind: settings.kind,
        channels: curves.into_iter().map(family_channel).collect(),
    })
}

/// Each channel with its curve.
type Curves = Vec<(Channel, DeviationCurve)>;

/// The curve of the chosen kind of every channel of `series`, or the first channel's error.
fn family_curves(
    args: &AllanArgs,
    settings: &AllanSettings,
    (series, rate_hz): (&ImuSeries, f64),
) -> Result<Curves, Failure> {
    let (kind, grid) = (settings.kind, &settings.grid);
    channel_deviations(kind, series, rate_hz, grid)
        .map_err(|(c, e)| anyhow!("{}: channel {}: {e}", args.file.display(), c.name()))
        .data()
}

/// A channel's name and its part of [`FamilyJson`].
type NamedChannel = (&'static str, FamilyChannelJson);

/// A channel's name and its curve in its unit: the rate's, or the rate's times seconds (tdev).
fn family_channel((channel, curve): (Channel, DeviationCurve)) -> NamedChannel {
    let json = FamilyChannelJson {
        unit: deviation_unit(curve.kind, channel),
        tau_s: curve.tau_s,
        deviation: BTreeMap::from([(curve.kind.name(), curve.deviation)]),
        n_terms: curve.n_terms,
    };
    (channel.name(), json)
}

/// The SI unit of `kind` on a rate `channel`: rad/s or m/s^2, times seconds (rad, m/s) for tdev.
fn deviation_unit(kind: DeviationKind, channel: Channel) -> &'static str {
    let scaled = kind.is_time_scaled();
    channel.si_unit(if scaled {
        SampleKind::Increments
    } else {
        SampleKind::Rates
    })
}

/// The text report of a kind other than adev: a heading line, then each channel's table.
fn print_family_text(doc: &FamilyJson) {
    let (kind, rate_hz, title) = (doc.kind, doc.sample_rate_hz, doc.kind.title());
    println!(
        "{}: {rate_hz:.3} Hz, {title} ({kind}; no limits or noise terms)",
        doc.file
    );
    for (name, c) in &doc.channels {
        print_family_channel(name, kind, c);
    }
}

/// One channel of a kind other than adev: its unit, then τ, deviation and terms.
fn print_family_channel(name: &str, kind: DeviationKind, c: &FamilyChannelJson) {
    let header = format!("{kind} ({})", c.unit);
    println!(
        "\n{name} [{}]\n{:>12} {header:>16} {:>10}",
        c.unit, "tau_s", "n_terms"
    );
    for (i, sigma) in c.deviation[kind.name()].iter().enumerate() {
        println!("{:>12.4} {sigma:>16.6e} {:>10}", c.tau_s[i], c.n_terms[i]);
    }
}
