//! `thermonav ar`: an AR model per channel and its Gauss-Markov equivalent.

use crate::args::ArArgs;
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use crate::settings::analysis::{ArSettings, resolve_ar};
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;
use thermonav::imu::{Channel, ImuSeries, SampleKind};
use thermonav::signal::timestamps::interval_stats;
use thermonav::stoch::ar::order::{Order, fit_ar_order};
use thermonav::stoch::ar::{ArError, ArMethod, ArModel, fit_ar};
use thermonav::stoch::gauss_markov::{Ar1Estimate, GaussMarkovOutcome, ar_based};
use thermonav_io::{Strictness, read_imu_file};

#[derive(Debug, Serialize)]
struct ArJson {
    file: String,
    method: &'static str,
    sample_interval_s: f64,
    channels: BTreeMap<&'static str, ChannelJson>,
}

#[derive(Debug, Serialize)]
struct ChannelJson {
    unit: &'static str,
    order: usize,
    coefficients: Vec<f64>,
    coefficient_std_errors: Vec<f64>,
    noise_variance: f64,
    /// The Gauss-Markov equivalent of the AR(1) fit by the same method (the paper's eqs 8-10).
    gauss_markov: GaussMarkovJson,
}

#[derive(Debug, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
enum GaussMarkovJson {
    Model {
        correlation_time_s: f64,
        sigma: f64,
        ci95_correlation_time_s: [Option<f64>; 2],
        c1: f64,
    },
    NoEquivalent {
        reason: String,
        c1: f64,
    },
}

/// Runs `ar`.
pub fn run(args: &ArArgs) -> Result<(), Failure> {
    let ArSettings { order, method } = resolve_ar(args)?;
    let series = read_imu_file(&args.file, Strictness::Strict).data()?;
    check_rates(&series, &args.file)?;
    let dt_s = median_interval_s(&series, &args.file)?;
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let fit = ChannelFit {
            file: &args.file,
            channel,
            order,
            method,
            dt_s,
        };
        channels.insert(channel.name(), fit.json(series.channel(channel))?);
    }
    let doc = ArJson {
        file: args.file.display().to_string(),
        method: method.name(),
        sample_interval_s: dt_s,
        channels,
    };
    if args.json {
        return print_json(&doc);
    }
    print_table(&doc);
    Ok(())
}

/// Refuses a file of increments: AR modelling needs rates.
fn check_rates(series: &ImuSeries, file: &Path) -> Result<(), Failure> {
    if series.kind == Some(SampleKind::Increments) {
        return Err(Failure::Data(anyhow!(
            "{}: AR modelling needs rates; the file holds increments",
            file.display()
        )));
    }
    Ok(())
}

/// The median sample interval, s.
fn median_interval_s(series: &ImuSeries, file: &Path) -> Result<f64, Failure> {
    interval_stats(&series.time)
        .map(|s| s.median.as_seconds())
        .ok_or_else(|| Failure::Data(anyhow!("{}: fewer than two samples", file.display())))
}

/// What one channel's fit needs besides its samples.
struct ChannelFit<'a> {
    file: &'a Path,
    channel: Channel,
    order: Order,
    method: ArMethod,
    dt_s: f64,
}

impl ChannelFit<'_> {
    /// The AR model of the chosen order and the Gauss-Markov equivalent of the AR(1) fit.
    fn json(&self, x: &[f64]) -> Result<ChannelJson, Failure> {
        let model = fit_ar_order(x, self.order, self.method)
            .map_err(|e| self.context(e))
            .data()?;
        let ar1 = fit_ar(x, 1, self.method)
            .map_err(|e| self.context(e))
            .data()?;
        Ok(ChannelJson {
            unit: self.channel.si_unit(SampleKind::Rates),
            order: model.order(),
            coefficients: model.coefficients,
            coefficient_std_errors: model.std_errors,
            noise_variance: model.noise_variance,
            gauss_markov: gauss_markov_json(&ar1, self.dt_s),
        })
    }

    /// A fit's error with the file and channel named.
    fn context(&self, e: ArError) -> anyhow::Error {
        anyhow!(
            "{}: channel {}: {e}",
            self.file.display(),
            self.channel.name()
        )
    }
}

/// The Gauss-Markov equivalent of an AR(1) fit (the paper's eqs 8-10).
fn gauss_markov_json(ar1: &ArModel, dt_s: f64) -> GaussMarkovJson {
    let c1 = ar1.coefficients[0];
    match ar_based(&Ar1Estimate {
        c1,
        c1_std_error: ar1.std_errors[0],
        innovation_variance: ar1.noise_variance,
        dt_s,
    }) {
        GaussMarkovOutcome::Model {
            model,
            ci95_correlation_time_s,
        } => GaussMarkovJson::Model {
            correlation_time_s: model.correlation_time_s,
            sigma: model.sigma,
            ci95_correlation_time_s,
            c1,
        },
        GaussMarkovOutcome::NoEquivalent { reason } => GaussMarkovJson::NoEquivalent { reason, c1 },
    }
}

/// The text report: a heading line and one row per channel.
fn print_table(doc: &ArJson) {
    print_header(doc);
    for (name, c) in &doc.channels {
        print_channel_row(name, c);
    }
}

/// The heading line (file, method, interval) and the column names.
fn print_header(doc: &ArJson) {
    println!(
        "{}: AR by {}, dt {:.6} s (median interval)",
        doc.file, doc.method, doc.sample_interval_s
    );
    println!(
        "{:<4} {:>5} {:>34} {:>14} {:>14} {:>26}",
        "ch", "order", "coefficients c_1..c_p", "noise var", "GM Tc s", "95 % interval s"
    );
}

/// One channel's row: order, coefficients, noise variance, correlation time and its interval.
fn print_channel_row(name: &str, c: &ChannelJson) {
    let coefficients = coefficients_text(&c.coefficients);
    let (tc, ci) = correlation_time_cells(&c.gauss_markov);
    println!(
        "{name:<4} {:>5} {coefficients:>34} {:>14.6e} {tc:>14} {ci:>26}",
        c.order, c.noise_variance
    );
}

/// The coefficients to five decimals, space-separated.
fn coefficients_text(coefficients: &[f64]) -> String {
    coefficients
        .iter()
        .map(|v| format!("{v:.5}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The correlation time and its 95 % interval as table cells, or why there is none.
fn correlation_time_cells(gm: &GaussMarkovJson) -> (String, String) {
    match gm {
        GaussMarkovJson::Model {
            correlation_time_s,
            ci95_correlation_time_s: [lo, hi],
            ..
        } => (
            format!("{correlation_time_s:.3}"),
            format!("[{}, {}]", interval_bound(lo), interval_bound(hi)),
        ),
        GaussMarkovJson::NoEquivalent { c1, .. } => (format!("none (c1 {c1:.4})"), String::new()),
    }
}

/// One end of an interval to three decimals, or `unbounded`.
fn interval_bound(v: &Option<f64>) -> String {
    v.map_or("unbounded".to_string(), |v| format!("{v:.3}"))
}
