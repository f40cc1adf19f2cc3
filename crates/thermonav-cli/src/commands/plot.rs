//! `thermonav plot`: a figure from a file thermonav wrote, as SVG (or PNG).

use crate::args::{MetricArg, PlotArgs, PlotKind, UnitsArg};
use crate::failure::{Classify, Failure};
use crate::figure_data::{innovations_of, outage_errors, rms_series};
use crate::inputs::{read_bank, read_rates};
use anyhow::anyhow;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::io::Write as _;
use std::path::Path;
use thermonav::geo::position::Geodetic;
use thermonav::imu::Channel;
use thermonav::stoch::acf::{Demean, autocovariance};
use thermonav::stoch::bank::ModelBank;
use thermonav::stoch::gauss_markov::{GaussMarkovOutcome, LagWindow, fit_autocovariance};
use thermonav_io::{Strictness, read_trajectory_file, write_atomically};
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::allan::{
    AllanCurve, ConfidenceBand, NoiseTerm, NoiseTermReading, allan_curves_of_entry,
    allan_deviation_figure,
};
use thermonav_plot::figures::autocorrelation::{
    Autocovariance, GaussMarkovFit, autocorrelation_figure,
};
use thermonav_plot::figures::correlation::{correlation_time_figure, correlation_time_series};
use thermonav_plot::figures::navigation::{
    Trajectory, innovations_figure, outage_errors_figure, rms_versus_temperature_figure,
    trajectory_figure,
};
use thermonav_plot::png::svg_to_png;

/// Most lags drawn on an autocovariance figure (the fit uses all of them).
const MAX_DRAWN_LAGS: usize = 2000;

/// The file format of a figure, from the extension of `--out`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ImageFormat {
    Svg,
    Png,
}

fn image_format(path: &Path) -> Result<ImageFormat, Failure> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("svg") => Ok(ImageFormat::Svg),
        Some("png") => Ok(ImageFormat::Png),
        _ => Err(Failure::Usage(anyhow!(
            "--out {}: the figure file must end in .svg or .png",
            path.display()
        ))),
    }
}

/// Runs `plot`.
pub fn run(args: &PlotArgs) -> Result<(), Failure> {
    let format = image_format(&args.out)?;
    let units = match args.units {
        UnitsArg::Si => DisplayUnits::Si,
        UnitsArg::Navigation => DisplayUnits::Navigation,
    };
    let svg = match args.kind {
        PlotKind::Allan => allan_svg(args, units)?,
        PlotKind::CorrelationTime => correlation_svg(args)?,
        PlotKind::Autocorrelation => autocorrelation_svg(args, units)?,
        PlotKind::Trajectory => trajectory_svg(args)?,
        PlotKind::OutageErrors => outage_errors_svg(args)?,
        PlotKind::RmsTemperature => rms_temperature_svg(args)?,
        PlotKind::Innovations => innovations_figure(
            &title_or(args, format!("Innovations, {}", file_name(&args.input))),
            &innovations_of(&args.input)?,
        ),
    };
    let bytes = match format {
        ImageFormat::Svg => svg.into_bytes(),
        ImageFormat::Png => svg_to_png(&svg).data()?,
    };
    write_atomically(&args.out, |file| Ok(file.write_all(&bytes)?)).data()?;
    Ok(())
}

fn title_or(args: &PlotArgs, default: String) -> String {
    args.title.clone().unwrap_or(default)
}

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

/// One channel of `allan --json`.
#[derive(Debug, Deserialize)]
struct AllanChannelJson {
    tau_s: Vec<f64>,
    adev: Vec<f64>,
    ci_low: Vec<f64>,
    ci_high: Vec<f64>,
    terms: TermsJson,
}

/// The document of `allan --json`.
#[derive(Debug, Deserialize)]
struct AllanJson {
    confidence: f64,
    channels: BTreeMap<Channel, AllanChannelJson>,
}

fn read_json(path: &Path) -> Result<serde_json::Value, Failure> {
    let bytes = std::fs::read(path)
        .map_err(|e| anyhow!("{}: cannot read: {e}", path.display()))
        .data()?;
    serde_json::from_slice(&bytes)
        .map_err(|e| anyhow!("{}:{}: not JSON: {e}", path.display(), e.line()))
        .data()
}

fn allan_svg(args: &PlotArgs, units: DisplayUnits) -> Result<String, Failure> {
    let json = read_json(&args.input)?;
    let name = file_name(&args.input);
    if json.get("entries").is_some() {
        let bank = read_bank(&args.input)?;
        let entry = &bank.entries[entry_index(&bank, args.temperature_c, &args.input)?];
        let title = format!("Allan deviation, {name} at {} °C", entry.temperature_c);
        return Ok(allan_deviation_figure(
            &title_or(args, title),
            &allan_curves_of_entry(entry),
            units,
        ));
    }
    let doc: AllanJson = serde_json::from_value(json)
        .map_err(|e| {
            anyhow!(
                "{}: neither a model bank nor `allan --json` output: {e}",
                args.input.display()
            )
        })
        .data()?;
    let curves: Vec<AllanCurve> = doc
        .channels
        .into_iter()
        .map(|(channel, c)| allan_curve(channel, c, doc.confidence))
        .collect();
    let title = format!("Allan deviation, {name}");
    Ok(allan_deviation_figure(
        &title_or(args, title),
        &curves,
        units,
    ))
}

/// The bank entry for `--temperature-c`; without it the bank must have one entry only.
fn entry_index(
    bank: &ModelBank,
    temperature_c: Option<f64>,
    path: &Path,
) -> Result<usize, Failure> {
    match (temperature_c, bank.entries.len()) {
        (Some(t), _) => Ok(bank.nearest_index(t)),
        (None, 1) => Ok(0),
        (None, _) => Err(Failure::Usage(anyhow!(
            "{}: the bank has entries at {:?} °C; choose one with --temperature-c",
            path.display(),
            bank.temperatures_c()
        ))),
    }
}

fn allan_curve(channel: Channel, c: AllanChannelJson, confidence: f64) -> AllanCurve {
    let t = c.terms;
    let terms = [
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
    .collect();
    AllanCurve {
        channel,
        tau_s: c.tau_s,
        adev: c.adev,
        confidence: Some(ConfidenceBand {
            level: confidence,
            low: c.ci_low,
            high: c.ci_high,
        }),
        terms,
    }
}

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

fn autocorrelation_svg(args: &PlotArgs, units: DisplayUnits) -> Result<String, Failure> {
    let channel = Channel::ALL
        .into_iter()
        .find(|c| c.name() == args.channel)
        .ok_or_else(|| {
            Failure::Usage(anyhow!(
                "--channel {}: not one of gx gy gz ax ay az",
                args.channel
            ))
        })?;
    if !(args.max_lag_s.is_finite() && args.max_lag_s > 0.0) {
        return Err(Failure::Usage(anyhow!(
            "--max-lag-s {} must be positive",
            args.max_lag_s
        )));
    }
    let (series, rate_hz) = read_rates(&args.input, "the autocovariance")?;
    let y = series.channel(channel);
    let max_lag = ((args.max_lag_s * rate_hz).round() as usize)
        .min(y.len().saturating_sub(1))
        .max(1);
    let gamma = autocovariance(y, max_lag, Demean::Subtract)
        .map_err(|e| anyhow!("{}: channel {}: {e}", args.input.display(), channel.name()))
        .data()?;
    let dt_s = 1.0 / rate_hz;
    let fit = match fit_autocovariance(&gamma, dt_s, LagWindow::FirstZeroCrossing) {
        GaussMarkovOutcome::Model { model, .. } => Some(GaussMarkovFit {
            sigma: model.sigma,
            correlation_time_s: model.correlation_time_s,
        }),
        GaussMarkovOutcome::NoEquivalent { .. } => None,
    };
    // Every stride-th lag: a figure needs no more than MAX_DRAWN_LAGS points.
    let stride = gamma.len().div_ceil(MAX_DRAWN_LAGS).max(1);
    let data = Autocovariance {
        channel,
        lag_s: (0..gamma.len())
            .step_by(stride)
            .map(|k| k as f64 * dt_s)
            .collect(),
        value: gamma.iter().step_by(stride).copied().collect(),
        fit,
    };
    let title = format!(
        "Autocovariance, {} {}",
        file_name(&args.input),
        channel.name()
    );
    Ok(autocorrelation_figure(&title_or(args, title), &data, units))
}

fn trajectory_svg(args: &PlotArgs) -> Result<String, Failure> {
    let points = read_trajectory_file(&args.input, Strictness::Strict).data()?;
    let (Some(first), Some(last)) = (points.first(), points.last()) else {
        return Err(Failure::Data(anyhow!(
            "{}: no trajectory point",
            args.input.display()
        )));
    };
    let outages = args
        .outages
        .resolve((first.time, last.time))
        .map_err(|e| anyhow!("--outages: {e}"))
        .usage()?;
    let position = |i: usize| Geodetic {
        latitude_rad: points[i].latitude_rad,
        longitude_rad: points[i].longitude_rad,
        height_m: points[i].height_m,
    };
    let origin = position(0);
    let local: Vec<[f64; 3]> = (0..points.len())
        .map(|i| position(i).ned_from(&origin).to_array())
        .collect();
    let trajectory = Trajectory {
        time_s: points.iter().map(|p| p.time.as_seconds()).collect(),
        north_m: local.iter().map(|ned| ned[0]).collect(),
        east_m: local.iter().map(|ned| ned[1]).collect(),
    };
    let windows: Vec<(f64, f64)> = outages
        .windows()
        .iter()
        .map(|w| (w.start.as_seconds(), w.end.as_seconds()))
        .collect();
    let title = format!("Trajectory, {}", file_name(&args.input));
    Ok(trajectory_figure(
        &title_or(args, title),
        &trajectory,
        &windows,
    ))
}

/// The evaluation report and its filters (first = the report's primary one).
fn evaluation(args: &PlotArgs) -> Result<(serde_json::Value, Vec<String>), Failure> {
    let text = std::fs::read_to_string(&args.input)
        .map_err(|e| anyhow!("{}: cannot read: {e}", args.input.display()))
        .data()?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| anyhow!("{}:{}: not JSON: {e}", args.input.display(), e.line()))
        .data()?;
    let filters: Vec<String> = json
        .get("filters")
        .and_then(serde_json::Value::as_array)
        .map(|f| {
            f.iter()
                .filter_map(|x| x.as_str().map(str::to_string))
                .collect()
        })
        .unwrap_or_default();
    if json.get("models").is_none() || filters.is_empty() {
        return Err(Failure::Data(anyhow!(
            "{}: not an evaluation report (expected \"models\" and \"filters\" keys)",
            args.input.display()
        )));
    }
    Ok((json, filters))
}

fn outage_errors_svg(args: &PlotArgs) -> Result<String, Failure> {
    let (json, filters) = evaluation(args)?;
    let filter = args.filter.clone().unwrap_or_else(|| filters[0].clone());
    if !filters.contains(&filter) {
        return Err(Failure::Usage(anyhow!(
            "--filter {filter}: the report has {}",
            filters.join(", ")
        )));
    }
    let models = json["models"].as_array().cloned().unwrap_or_default();
    let errors = outage_errors(&models, &filter)?;
    let title = format!(
        "INS-only errors in the first outage ({})",
        filter.to_uppercase()
    );
    Ok(outage_errors_figure(&title_or(args, title), &errors, None))
}

fn rms_temperature_svg(args: &PlotArgs) -> Result<String, Failure> {
    let (json, filters) = evaluation(args)?;
    let models = json["models"].as_array().cloned().unwrap_or_default();
    let (key, quantity, unit) = match args.metric {
        MetricArg::North => ("rms_north_m", "north RMS error", "m"),
        MetricArg::East => ("rms_east_m", "east RMS error", "m"),
        MetricArg::Heading => ("rms_heading_deg", "heading RMS error", "deg"),
    };
    let series = rms_series(&models, &filters, key);
    let title = format!("{quantity} per model");
    Ok(rms_versus_temperature_figure(
        &title_or(args, title),
        quantity,
        unit,
        &series,
    ))
}
