//! `thermonav gmwm`: a composite noise model per channel fitted to the Haar wavelet variance.

use crate::args::GmwmArgs;
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::{Channel, ImuSeries, Sensor};
use thermonav::stoch::gmwm::{BootstrapSettings, ModelSpec};
use thermonav_io::gmwm::{
    AbsentJson, CandidateJson, GmwmChannelJson as ChannelJson, MergedJson, ParameterJson,
    WaveletVarianceJson, gmwm_channel_json, interval_method,
};
use thermonav_io::noise_terms::term_units;

#[derive(Debug, Serialize)]
struct GmwmJson {
    #[serde(flatten)]
    run: RunJson,
    channels: Channels,
}

#[derive(Debug, Serialize)]
struct RunJson {
    file: String,
    sample_rate_hz: f64,
    model: String,
    interval_method: &'static str,
    bootstrap_replicates: usize,
}

type Channels = BTreeMap<&'static str, ChannelJson>;

/// What every channel is fitted with: the rate (Hz), the candidates, the bootstrap.
struct Job(f64, Vec<ModelSpec>, BootstrapSettings);

/// Runs `gmwm`.
pub fn run(args: &GmwmArgs) -> Result<(), Failure> {
    let settings = crate::settings::gmwm::resolve(args)?;
    let read = (
        &Default::default(),
        &crate::settings::imu::topics(&args.topics),
    );
    let (series, rate_hz) = crate::inputs::read_rates(&args.file, "GMWM", read)?;
    let doc = document(
        args,
        &series,
        Job(rate_hz, settings.candidates, settings.bootstrap),
    )?;
    if args.json {
        return print_json(&doc);
    }
    print_text(&doc);
    Ok(())
}

fn channels(args: &GmwmArgs, series: &ImuSeries, job: &Job) -> Result<Channels, Failure> {
    let Job(rate_hz, candidates, settings) = job;
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let y = series.channel(channel);
        let json = gmwm_channel_json(y, *rate_hz, channel.sensor(), (candidates, *settings));
        let in_channel = |e| anyhow!("{}: channel {}: {e}", args.file.display(), channel.name());
        channels.insert(channel.name(), json.map_err(in_channel).data()?);
    }
    Ok(channels)
}

fn document(args: &GmwmArgs, series: &ImuSeries, job: Job) -> Result<GmwmJson, Failure> {
    let run = run_json(args, job.0);
    let channels = channels(args, series, &job)?;
    Ok(GmwmJson { run, channels })
}

fn run_json(args: &GmwmArgs, rate_hz: f64) -> RunJson {
    RunJson {
        file: args.file.display().to_string(),
        sample_rate_hz: rate_hz,
        model: args.model.clone(),
        interval_method: interval_method(args.replicates),
        bootstrap_replicates: args.replicates,
    }
}

/// The text report: a heading, then each channel.
fn print_text(doc: &GmwmJson) {
    let r = &doc.run;
    let heading = format!("{}: {:.3} Hz, GMWM", r.file, r.sample_rate_hz);
    let (method, replicates) = (r.interval_method, r.bootstrap_replicates);
    let tail = format!("{method}, {replicates} replicates");
    println!("{heading} ({tail})");
    for (name, c) in &doc.channels {
        print_channel(name, c);
    }
}

fn print_channel(name: &str, c: &ChannelJson) {
    let s = &c.selected;
    let title = format!("{name} [{}]  model {}", s.unit, s.selected_model);
    let reported = match c.reported_model == s.selected_model {
        true => String::new(),
        false => format!("  reported as {}", c.reported_model),
    };
    println!("\n{title}  WIC {:.3}{reported}", s.wic);
    print_wavelet_variance(&c.wavelet_variance);
    print_parameters(&c.parameters);
    let sensor = Channel::ALL
        .iter()
        .find(|ch| ch.name() == name)
        .map(|ch| ch.sensor());
    if let Some(line) = sensor.and_then(|s| white_noise_line(s, &c.parameters)) {
        println!("{line}");
    }
    c.merged.iter().for_each(|m| println!("{}", merged_line(m)));
    c.absent.iter().for_each(|a| println!("{}", absent_line(a)));
    if c.candidates.len() > 1 {
        print_candidates(&c.candidates);
    }
    for left_out in &c.not_fitted {
        println!("not fitted: {}", left_out.reason);
    }
}

/// Right-aligned labels, 14 wide.
fn labels(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("{n:>14}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Right-aligned numbers, 14 wide, 6 digits after the point in exponent form.
fn cells(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| format!("{v:>14.6e}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn print_parameters(parameters: &BTreeMap<String, ParameterJson>) {
    println!("{:>40} {}", "parameter", labels(&["value", "low", "high"]));
    for (key, p) in parameters {
        let limits = match (p.ci_low, p.ci_high) {
            (Some(low), Some(high)) => cells(&[low, high]),
            _ => labels(&["-", "-"]),
        };
        println!("{key:>40} {} {limits}", cells(&[p.value]));
    }
}

/// A merged process in one line: what it was and where it went, values with their units.
fn merged_line(m: &MergedJson) -> String {
    let values: Vec<String> = (m.values.iter())
        .map(|(key, value)| format!("{key} {value:.4e}"))
        .collect();
    let into = serde_json::to_value(m.into).map_or_else(|_| String::new(), |v| v.to_string());
    format!(
        "merged into the {}: {} of {} (Tc {:.4e} s = {:.2} sample periods, {}): {}",
        into.trim_matches('"').replace('_', " "),
        m.process,
        m.fitted_in,
        m.correlation_time_s,
        m.correlation_time_sample_periods,
        values.join(", "),
        m.reason
    )
}

/// The reported white-noise density in the unit navigation engineers quote (deg/sqrt(h),
/// m/s/sqrt(h)), as the Allan report gives it.
fn white_noise_line(
    sensor: Sensor,
    parameters: &BTreeMap<String, ParameterJson>,
) -> Option<String> {
    let (_, white) = parameters
        .iter()
        .find(|(key, _)| key.starts_with("white_noise_density"))?;
    let (si, edge, to_edge) = term_units(sensor)[1];
    Some(format!(
        "white noise N {:.4e} {si} = {:.4} {edge}",
        white.value,
        to_edge(white.value)
    ))
}

/// An absent process in one line.
fn absent_line(a: &AbsentJson) -> String {
    format!("absent: {}: {}", a.process, a.reason)
}

fn print_wavelet_variance(w: &WaveletVarianceJson) {
    let header = labels(&["wv", "low", "high", "model"]);
    println!("{:>12} {header}", "scale_s");
    for j in 0..w.scale_s.len() {
        println!("{:>12.4} {}", w.scale_s[j], cells(&w.row(j)));
    }
}

fn print_candidates(candidates: &[CandidateJson]) {
    println!("{:>16} {}", "candidate", labels(&["wic", "objective"]));
    for c in candidates {
        println!("{:>16} {}", c.model, cells(&[c.wic, c.objective]));
    }
}
