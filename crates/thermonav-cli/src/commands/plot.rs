//! `thermonav plot`: a figure from a file thermonav wrote, as SVG (or PNG).

use crate::args::{BagTopicArgs, MetricArg, PlotArgs};
use crate::failure::{Classify, Failure};
use crate::html::figure_data::{innovations_of, outage_errors, rms_series};
use crate::inputs::{read_bank, read_imu_input, read_rates, thermal_calibration_of};
use crate::settings::imu::topics;
use crate::settings::plot::{
    Figure, ImageFormat, PlotSettings, bank_entry, outages_over, report_filter, resolve_plot,
};
use anyhow::anyhow;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use thermonav::geo::position::Geodetic;
use thermonav::imu::Channel;
use thermonav::nav::outage::{OutageSpec, Outages};
use thermonav::nav::run::increments_of;
use thermonav::stoch::acf::{Demean, autocovariance};
use thermonav::stoch::allan::DeviationKind;
use thermonav::stoch::gauss_markov::{GaussMarkovOutcome, LagWindow, fit_autocovariance};
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav_io::{ImuOptions, write_atomically};
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::allan::{
    AllanCurve, ConfidenceBand, NoiseTerm, NoiseTermReading, allan_curves_of_entry,
    allan_deviation_figure, deviation_figure, deviation_name,
};
use thermonav_plot::figures::autocorrelation::{
    Autocovariance, GaussMarkovFit, autocorrelation_figure,
};
use thermonav_plot::figures::correlation::{correlation_time_figure, correlation_time_series};
use thermonav_plot::figures::navigation::{
    Trajectory, innovations_figure, outage_errors_figure, rms_versus_temperature_figure,
    trajectory_figure,
};
use thermonav_plot::figures::thermal::{
    ThermalBiasPanel, thermal_bias_figure, thermal_bias_panels,
};
use thermonav_plot::png::svg_to_png;

/// Most lags drawn on an autocovariance figure (the fit uses all of them).
const MAX_DRAWN_LAGS: usize = 2000;

/// Runs `plot`.
pub fn run(args: &PlotArgs) -> Result<(), Failure> {
    let settings = resolve_plot(args)?;
    let svg = figure_svg(args, &settings)?;
    let bytes = image_bytes(svg, settings.format)?;
    write_atomically(&args.out, |file| Ok(file.write_all(&bytes)?)).data()?;
    Ok(())
}

/// The SVG of the chosen figure.
fn figure_svg(args: &PlotArgs, settings: &PlotSettings) -> Result<String, Failure> {
    let units = settings.units;
    match &settings.figure {
        Figure::Allan => allan_svg(args, units),
        Figure::CorrelationTime => correlation_svg(args),
        &Figure::Autocorrelation { channel, max_lag_s } => {
            autocorrelation_svg(args, (channel, max_lag_s), units)
        }
        Figure::Trajectory => trajectory_svg(args),
        Figure::OutageErrors => outage_errors_svg(args),
        Figure::RmsTemperature => rms_temperature_svg(args),
        Figure::Innovations => innovations_svg(args),
        Figure::ThermalBias { channel } => thermal_bias_svg(args, *channel, units),
        Figure::ThermalCheck {
            record,
            block_s,
            channel,
        } => thermal_check_svg(args, (record, *block_s, *channel), units),
    }
}

/// The bytes of the image file: the SVG itself, or rendered to PNG.
fn image_bytes(svg: String, format: ImageFormat) -> Result<Vec<u8>, Failure> {
    match format {
        ImageFormat::Svg => Ok(svg.into_bytes()),
        ImageFormat::Png => svg_to_png(&svg).data(),
    }
}

/// The innovations of a filter with their ±3σ bounds.
fn innovations_svg(args: &PlotArgs) -> Result<String, Failure> {
    Ok(innovations_figure(
        &title_or(args, format!("Innovations, {}", file_name(&args.input))),
        &innovations_of(&args.input)?,
    ))
}

/// `--title`, or the figure's default title.
fn title_or(args: &PlotArgs, default: String) -> String {
    args.title.clone().unwrap_or(default)
}

/// The file name of `path` (the whole path when it has none).
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// A term of `allan --json` (SI value and τ range).
#[derive(Debug, Deserialize)]
struct TermJson {
    value_si: f64,
    tau_min_s: f64,
    tau_max_s: f64,
}

/// The terms of one channel in `allan --json`.
#[derive(Debug, Deserialize)]
struct TermsJson {
    quantization: Option<TermJson>,
    random_walk: Option<TermJson>,
    bias_instability: Option<TermJson>,
    rate_random_walk: Option<TermJson>,
    rate_ramp: Option<TermJson>,
}

/// One channel of `allan --json` of any `--kind`: the deviation is under the kind's name, the
/// limits and terms are there for adev only.
#[derive(Debug, Deserialize)]
struct AllanChannelJson {
    tau_s: Vec<f64>,
    ci_low: Option<Vec<f64>>,
    ci_high: Option<Vec<f64>>,
    terms: Option<TermsJson>,
    #[serde(flatten)]
    other: BTreeMap<String, serde_json::Value>,
}

/// The document of `allan --json` (no `kind` means adev, as `allan` wrote it before `--kind`).
#[derive(Debug, Deserialize)]
struct AllanJson {
    #[serde(default)]
    kind: DeviationKind,
    confidence: Option<f64>,
    channels: BTreeMap<Channel, AllanChannelJson>,
}

/// The JSON document at `path`.
fn read_json(path: &Path) -> Result<serde_json::Value, Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))
        .data()?;
    serde_json::from_slice(&bytes)
        .map_err(|e| anyhow!("{}:{}: not JSON: {e}", path.display(), e.line()))
        .data()
}

/// The Allan deviation of a bank entry or of `allan --json` output.
fn allan_svg(args: &PlotArgs, units: DisplayUnits) -> Result<String, Failure> {
    let json = read_json(&args.input)?;
    if json.get("entries").is_some() {
        return bank_allan_svg(args, units);
    }
    let doc = allan_json_of(json, &args.input)?;
    let curves = doc
        .channels
        .into_iter()
        .map(|(channel, c)| allan_curve(channel, c, doc.kind, doc.confidence))
        .collect::<Result<Vec<AllanCurve>, String>>()
        .map_err(|e| anyhow!("{}: {e}", args.input.display()))
        .data()?;
    let title = format!("{}, {}", deviation_name(doc.kind), file_name(&args.input));
    Ok(deviation_figure(
        &title_or(args, title),
        doc.kind,
        &curves,
        units,
    ))
}

/// The Allan deviation of the bank entry chosen by `--temperature-c`.
fn bank_allan_svg(args: &PlotArgs, units: DisplayUnits) -> Result<String, Failure> {
    let bank = read_bank(&args.input)?;
    let entry = &bank.entries[bank_entry(&bank, args.temperature_c, &args.input)?];
    let title = format!(
        "Allan deviation, {} at {} °C",
        file_name(&args.input),
        entry.temperature_c
    );
    Ok(allan_deviation_figure(
        &title_or(args, title),
        &allan_curves_of_entry(entry),
        units,
    ))
}

/// A JSON document read as `allan --json` output.
fn allan_json_of(json: serde_json::Value, path: &Path) -> Result<AllanJson, Failure> {
    serde_json::from_value(json)
        .map_err(|e| {
            anyhow!(
                "{}: neither a model bank nor `allan --json` output: {e}",
                path.display()
            )
        })
        .data()
}

/// One channel of `allan --json` as a curve of `kind` with its confidence band and noise terms
/// when the document has them; an error names the channel whose `kind` values are missing.
fn allan_curve(
    channel: Channel,
    mut c: AllanChannelJson,
    kind: DeviationKind,
    confidence: Option<f64>,
) -> Result<AllanCurve, String> {
    let values = c.other.remove(kind.name()).unwrap_or_default();
    Ok(AllanCurve {
        channel,
        tau_s: c.tau_s,
        deviation: serde_json::from_value(values)
            .map_err(|e| format!("channel {}: `{kind}` values: {e}", channel.name()))?,
        confidence: confidence_band(confidence, c.ci_low, c.ci_high),
        terms: c.terms.map(term_readings).unwrap_or_default(),
        model: None,
    })
}

/// The band of `allan --json` when it has a level and both limits.
fn confidence_band(
    level: Option<f64>,
    low: Option<Vec<f64>>,
    high: Option<Vec<f64>>,
) -> Option<ConfidenceBand> {
    let (level, low, high) = (level?, low?, high?);
    Some(ConfidenceBand { level, low, high })
}

/// The noise terms `allan --json` gives, each with its τ range.
fn term_readings(t: TermsJson) -> Vec<NoiseTermReading> {
    [
        (NoiseTerm::Quantization, t.quantization),
        (NoiseTerm::RandomWalk, t.random_walk),
        (NoiseTerm::BiasInstability, t.bias_instability),
        (NoiseTerm::RateRandomWalk, t.rate_random_walk),
        (NoiseTerm::RateRamp, t.rate_ramp),
    ]
    .into_iter()
    .filter_map(|(term, json)| {
        json.map(|j| NoiseTermReading {
            term,
            value_si: j.value_si,
            tau_range_s: Some((j.tau_min_s, j.tau_max_s)),
        })
    })
    .collect()
}

/// The correlation time against temperature of the chosen `--families`.
fn correlation_svg(args: &PlotArgs) -> Result<String, Failure> {
    let bank = read_bank(&args.input)?;
    let families: Vec<_> = args.families.iter().map(|&f| f.into()).collect();
    let series = correlation_time_series(&bank, &families);
    if series.is_empty() {
        return Err(Failure::Data(anyhow!(
            "{}: no Gauss-Markov model of the chosen families at any temperature",
            args.input.display()
        )));
    }
    let title = format!(
        "Correlation time versus temperature, {}",
        file_name(&args.input)
    );
    Ok(correlation_time_figure(&title_or(args, title), &series))
}

/// Bias against temperature of the bank's thermal calibration.
fn thermal_bias_svg(
    args: &PlotArgs,
    channel: Option<Channel>,
    units: DisplayUnits,
) -> Result<String, Failure> {
    let panels = thermal_panels(args, channel)?;
    let title = format!("Bias against temperature, {}", file_name(&args.input));
    Ok(thermal_bias_figure(&title_or(args, title), &panels, units))
}

/// The record, block length (s) and channel of a thermal check.
type CheckOptions<'a> = (&'a Path, f64, Option<Channel>);

/// The bank's calibration checked against `--record`, for `--channel` or every channel.
fn thermal_check_svg(
    args: &PlotArgs,
    (record, block_s, channel): CheckOptions,
    units: DisplayUnits,
) -> Result<String, Failure> {
    let calibration = crate::inputs::read_thermal_calibration(&args.input)?;
    let read = (&ImuOptions::default(), &topics(&args.topics));
    let series = crate::thermal::calibration::sweep_series(record, 0, read)?.series;
    let checks =
        thermonav::stoch::thermal::check::check_record(&calibration, &series, block_s, None)
            .map_err(|e| anyhow!("{}: {e}", record.display()))
            .data()?;
    let chosen: Vec<_> = (checks.iter())
        .filter(|(c, _)| channel.is_none_or(|k| k == **c))
        .map(|(&c, k)| (c, k))
        .collect();
    if chosen.is_empty() {
        return Err(not_calibrated(&args.input));
    }
    let title = format!("{} against {}", file_name(&args.input), file_name(record));
    Ok(
        thermonav_plot::figures::thermal_check::thermal_check_figure(
            &title_or(args, title),
            &chosen,
            units,
        ),
    )
}

/// The panels of `--channel`, or of every calibrated channel, of the bank's calibration.
fn thermal_panels(
    args: &PlotArgs,
    channel: Option<Channel>,
) -> Result<Vec<ThermalBiasPanel>, Failure> {
    let bank = read_bank(&args.input)?;
    let calibration = thermal_calibration_of(&bank, &args.input)?;
    Some(thermal_bias_panels(calibration, channel.as_slice()))
        .filter(|panels| !panels.is_empty())
        .ok_or_else(|| not_calibrated(&args.input))
}

/// `--channel` names a channel the calibration lacks.
fn not_calibrated(path: &Path) -> Failure {
    Failure::Data(anyhow!(
        "{}: the thermal calibration has no such channel",
        path.display()
    ))
}

/// The autocovariance of one channel with its first-order Gauss-Markov fit.
fn autocorrelation_svg(
    args: &PlotArgs,
    (channel, max_lag_s): (Channel, f64),
    units: DisplayUnits,
) -> Result<String, Failure> {
    let read = (&ImuOptions::default(), &topics(&args.topics));
    let (series, rate_hz) = read_rates(&args.input, "the autocovariance", read)?;
    let y = series.channel(channel);
    let max_lag = ((max_lag_s * rate_hz).round() as usize)
        .min(y.len().saturating_sub(1))
        .max(1);
    let gamma = autocovariance(y, max_lag, Demean::Subtract)
        .map_err(|e| anyhow!("{}: channel {}: {e}", args.input.display(), channel.name()))
        .data()?;
    let data = drawn_autocovariance(channel, &gamma, 1.0 / rate_hz);
    let title = format!(
        "Autocovariance, {} {}",
        file_name(&args.input),
        channel.name()
    );
    Ok(autocorrelation_figure(&title_or(args, title), &data, units))
}

/// The Gauss-Markov fit to the autocovariance up to its first zero crossing, when there is one.
fn gauss_markov_fit(gamma: &[f64], dt_s: f64) -> Option<GaussMarkovFit> {
    match fit_autocovariance(gamma, dt_s, LagWindow::FirstZeroCrossing) {
        GaussMarkovOutcome::Model { model, .. } => Some(GaussMarkovFit {
            sigma: model.sigma,
            correlation_time_s: model.correlation_time_s,
        }),
        GaussMarkovOutcome::NoEquivalent { .. } => None,
    }
}

/// The autocovariance as drawn: every stride-th lag, at most [`MAX_DRAWN_LAGS`] points, and the
/// fit to all lags.
fn drawn_autocovariance(channel: Channel, gamma: &[f64], dt_s: f64) -> Autocovariance {
    let fit = gauss_markov_fit(gamma, dt_s);
    let stride = gamma.len().div_ceil(MAX_DRAWN_LAGS).max(1);
    Autocovariance {
        channel,
        lag_s: (0..gamma.len())
            .step_by(stride)
            .map(|k| k as f64 * dt_s)
            .collect(),
        value: gamma.iter().step_by(stride).copied().collect(),
        fit,
    }
}

/// The trajectory in north/east metres from its first point, with the `--outages` windows.
fn trajectory_svg(args: &PlotArgs) -> Result<String, Failure> {
    let points = crate::navigation::reference_input::read_reference(&args.input)?.points;
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return Err(Failure::Data(anyhow!(
            "{}: no trajectory point",
            args.input.display()
        )));
    };
    let span = match &args.imu {
        Some(imu) => imu_span(imu, &args.topics)?,
        None => {
            note_origin(&args.outages, first.time);
            (first.time, last.time)
        }
    };
    let outages = outages_over(&args.outages, span)?;
    let title = format!("Trajectory, {}", file_name(&args.input));
    Ok(trajectory_figure(
        &title_or(args, title),
        &local_trajectory(&points),
        &outage_windows(&outages),
    ))
}

/// The span `integrate` lays its outages over: the IMU record's first increment to its last.
fn imu_span(imu: &Path, choice: &BagTopicArgs) -> Result<(Timestamp, Timestamp), Failure> {
    let series = read_imu_input(imu, &ImuOptions::default(), &topics(choice))?;
    let increments = increments_of(&series)
        .map_err(|e| anyhow!("{}: {e}", imu.display()))
        .data()?;
    match (increments.first(), increments.last()) {
        (Some(first), Some(last)) => Ok((first.time, last.time)),
        _ => Err(anyhow!("{}: no IMU interval", imu.display())).data(),
    }
}

/// Without `--imu`, says what `rel:` counts from here and how to count as integrate did.
fn note_origin(outages: &OutageSpec, first: Timestamp) {
    if matches!(outages, OutageSpec::FromStart(_)) {
        eprintln!(
            "note: --outages rel: counts here from the solution's first point (t_s {:.3}); integrate counts from the first IMU increment: give --imu IMU.csv to draw the windows where integrate laid them",
            first.as_seconds()
        );
    }
}

/// The position of a trajectory point.
fn geodetic(p: &TrajectoryPoint) -> Geodetic {
    Geodetic {
        latitude_rad: p.latitude_rad,
        longitude_rad: p.longitude_rad,
        height_m: p.height_m,
    }
}

/// North and east of every point from the first one, m.
fn local_trajectory(points: &[TrajectoryPoint]) -> Trajectory {
    let origin = geodetic(&points[0]);
    let local: Vec<[f64; 3]> = points
        .iter()
        .map(|p| geodetic(p).ned_from(&origin).to_array())
        .collect();
    Trajectory {
        time_s: points.iter().map(|p| p.time.as_seconds()).collect(),
        north_m: local.iter().map(|ned| ned[0]).collect(),
        east_m: local.iter().map(|ned| ned[1]).collect(),
    }
}

/// The outage windows as (start, end) in seconds.
fn outage_windows(outages: &Outages) -> Vec<(f64, f64)> {
    outages
        .windows()
        .iter()
        .map(|w| (w.start.as_seconds(), w.end.as_seconds()))
        .collect()
}

/// The evaluation report and its filters (first = the report's primary one).
fn evaluation(args: &PlotArgs) -> Result<(serde_json::Value, Vec<String>), Failure> {
    let text = std::fs::read_to_string(&args.input)
        .map_err(|e| anyhow!("{}: cannot read: {e}", args.input.display()))
        .data()?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| anyhow!("{}:{}: not JSON: {e}", args.input.display(), e.line()))
        .data()?;
    let filters = filters_of(&json);
    check_evaluation(&json, &filters, &args.input)?;
    Ok((json, filters))
}

/// The error for a document without models or filters.
fn check_evaluation(
    json: &serde_json::Value,
    filters: &[String],
    path: &Path,
) -> Result<(), Failure> {
    if json.get("models").is_none() || filters.is_empty() {
        return Err(Failure::Data(anyhow!(
            "{}: not an evaluation report (expected \"models\" and \"filters\" keys)",
            path.display()
        )));
    }
    Ok(())
}

/// The filters an evaluation report names, in its order.
fn filters_of(json: &serde_json::Value) -> Vec<String> {
    json.get("filters")
        .and_then(serde_json::Value::as_array)
        .map(|f| {
            f.iter()
                .filter_map(|x| x.as_str().map(str::to_string))
                .collect()
        })
        .unwrap_or_default()
}

/// The models of an evaluation report.
fn models_of(json: &serde_json::Value) -> Vec<serde_json::Value> {
    json["models"].as_array().cloned().unwrap_or_default()
}

/// The INS-only errors of every model in the first outage with the chosen filter.
fn outage_errors_svg(args: &PlotArgs) -> Result<String, Failure> {
    let (json, filters) = evaluation(args)?;
    let filter = report_filter(args.filter.as_ref(), &filters)?;
    let errors = outage_errors(&models_of(&json), &filter, &folder_of(&args.input))?;
    let title = format!(
        "INS-only errors in the first outage ({})",
        filter.to_uppercase()
    );
    Ok(outage_errors_figure(&title_or(args, title), &errors, None))
}

/// The folder a file is in (`.` for a bare file name).
fn folder_of(file: &Path) -> PathBuf {
    match file.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// The RMS error of the chosen `--metric` per model against the model's temperature.
fn rms_temperature_svg(args: &PlotArgs) -> Result<String, Failure> {
    let (json, filters) = evaluation(args)?;
    let (key, quantity, unit) = metric_columns(args.metric);
    let series = rms_series(&models_of(&json), &filters, key);
    let title = format!("RMS {quantity} error per model");
    Ok(rms_versus_temperature_figure(
        &title_or(args, title),
        quantity,
        unit,
        &series,
    ))
}

/// The report key, the quantity's name and its unit of a `--metric`.
fn metric_columns(metric: MetricArg) -> (&'static str, &'static str, &'static str) {
    match metric {
        MetricArg::North => ("rms_north_m", "north", "m"),
        MetricArg::East => ("rms_east_m", "east", "m"),
        MetricArg::Heading => ("rms_heading_deg", "heading", "deg"),
    }
}
