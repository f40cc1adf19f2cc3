//! Settings of `plot`: the image format from `--out`, the units, the channel, and the options
//! of the chosen figure, checked before any file is read; and the choices that can only be
//! checked against the input once it is read (a bank's entry, a report's filter, outages
//! over the record's span), each still a usage error naming its option.

use super::paths::Io;
use crate::args::{PlotArgs, PlotKind, UnitsArg};
use crate::failure::Failure;
use anyhow::anyhow;
use std::path::{Path, PathBuf};
use thermonav::imu::Channel;
use thermonav::nav::outage::{OutageSpec, Outages};
use thermonav::setting::positive;
use thermonav::stoch::bank::ModelBank;
use thermonav::time::Timestamp;
use thermonav_plot::figures::DisplayUnits;

/// The file format of a figure, from the extension of `--out`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// SVG, as drawn.
    Svg,
    /// PNG, rasterised from the SVG.
    Png,
}

/// What `plot` draws and how, resolved from its options.
#[derive(Debug, Clone)]
pub struct PlotSettings {
    /// The figure with its own options.
    pub figure: Figure,
    /// The image format.
    pub format: ImageFormat,
    /// The units of rates and deviations.
    pub units: DisplayUnits,
}

/// The figure, with the options it uses resolved.
#[derive(Debug, Clone)]
pub enum Figure {
    /// Allan deviation (`--temperature-c` picks a bank's entry).
    Allan,
    /// Correlation time against temperature.
    CorrelationTime,
    /// The autocovariance of one channel up to the longest lag, s.
    Autocorrelation {
        /// `--channel` (default gx).
        channel: Channel,
        /// `--max-lag-s`, positive.
        max_lag_s: f64,
    },
    /// A trajectory with its outages.
    Trajectory,
    /// Errors in the first outage.
    OutageErrors,
    /// RMS error against temperature.
    RmsTemperature,
    /// Innovations.
    Innovations,
    /// Bias against temperature of `--channel`, or of every calibrated channel.
    ThermalBias {
        /// `--channel`, if given.
        channel: Option<Channel>,
    },
    /// A calibration against `--record` in blocks of `--block-s`.
    ThermalCheck {
        /// `--record`.
        record: PathBuf,
        /// `--block-s`, positive.
        block_s: f64,
        /// `--channel`, if given.
        channel: Option<Channel>,
    },
}

/// `plot`: the output spares the inputs and ends in .svg or .png; `--channel` names a channel;
/// autocorrelation has a positive `--max-lag-s`; thermal-check has `--record` and a positive
/// `--block-s`; allan's `--temperature-c` is a temperature the library accepts.
pub fn resolve_plot(args: &PlotArgs) -> Result<PlotSettings, Failure> {
    Io::new()
        .input("INPUT", &args.input)
        .optional_inputs([
            ("--record", args.record.as_ref()),
            ("--imu", args.imu.as_ref()),
        ])
        .output("figure", &args.out)
        .check()?;
    Ok(PlotSettings {
        format: image_format(&args.out)?,
        figure: figure(args)?,
        units: display_units(args.units),
    })
}

/// The chosen figure with its options.
fn figure(args: &PlotArgs) -> Result<Figure, Failure> {
    let channel = args.channel.as_deref().map(channel_of).transpose()?;
    Ok(match args.kind {
        PlotKind::Allan => {
            super::bank::operating_temperature("--temperature-c", args.temperature_c)?;
            Figure::Allan
        }
        PlotKind::CorrelationTime => Figure::CorrelationTime,
        PlotKind::Autocorrelation => Figure::Autocorrelation {
            channel: channel.unwrap_or(Channel::Gx),
            max_lag_s: positive("max_lag_s", args.max_lag_s)?,
        },
        PlotKind::Trajectory => Figure::Trajectory,
        PlotKind::OutageErrors => Figure::OutageErrors,
        PlotKind::RmsTemperature => Figure::RmsTemperature,
        PlotKind::Innovations => Figure::Innovations,
        PlotKind::ThermalBias => Figure::ThermalBias { channel },
        PlotKind::ThermalCheck => Figure::ThermalCheck {
            record: thermal_check_record(args)?,
            block_s: positive("block_s", args.block_s)?,
            channel,
        },
    })
}

/// thermal-check's `--record`, which it needs.
fn thermal_check_record(args: &PlotArgs) -> Result<PathBuf, Failure> {
    args.record.clone().ok_or_else(|| {
        Failure::Usage(anyhow!(
            "plot thermal-check needs --record RECORD (the record checked)"
        ))
    })
}

/// The image format told by the extension of `--out`.
fn image_format(path: &Path) -> Result<ImageFormat, Failure> {
    let extension = path.extension().and_then(|e| e.to_str());
    match extension.map(str::to_ascii_lowercase).as_deref() {
        Some("svg") => Ok(ImageFormat::Svg),
        Some("png") => Ok(ImageFormat::Png),
        _ => Err(Failure::Usage(anyhow!(
            "--out {}: the figure file must end in .svg or .png",
            path.display()
        ))),
    }
}

/// `--units` as the figures' display units.
fn display_units(units: UnitsArg) -> DisplayUnits {
    match units {
        UnitsArg::Si => DisplayUnits::Si,
        UnitsArg::Navigation => DisplayUnits::Navigation,
    }
}

/// The channel named by `--channel`.
fn channel_of(name: &str) -> Result<Channel, Failure> {
    Channel::from_name(name)
        .ok_or_else(|| Failure::Usage(anyhow!("--channel {name}: not one of gx gy gz ax ay az")))
}

/// The bank entry for `--temperature-c` (the nearest); without it the bank read from `path`
/// must have one entry only.
pub fn bank_entry(
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

/// `--filter`, which must be one of the report's `filters`, or the report's primary filter.
pub fn report_filter(chosen: Option<&String>, filters: &[String]) -> Result<String, Failure> {
    let filter = chosen.cloned().unwrap_or_else(|| filters[0].clone());
    if !filters.contains(&filter) {
        return Err(Failure::Usage(anyhow!(
            "--filter {filter}: the report has {}",
            filters.join(", ")
        )));
    }
    Ok(filter)
}

/// `--outages` laid over `span`, the record's first and last time.
pub fn outages_over(spec: &OutageSpec, span: (Timestamp, Timestamp)) -> Result<Outages, Failure> {
    spec.resolve(span)
        .map_err(|e| Failure::Usage(anyhow!("--outages: {e}")))
}
