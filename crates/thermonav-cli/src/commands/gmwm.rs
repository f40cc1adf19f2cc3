//! `thermonav gmwm`: a composite noise model per channel fitted to the Haar wavelet variance.

use crate::args::GmwmArgs;
use crate::failure::{Classify, Failure};
use crate::report::print_json;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::imu::{Channel, ImuSeries, SampleKind, Sensor};
use thermonav::stoch::gmwm::{
    BootstrapSettings, GmwmEstimate, ModelSpec, ParameterEstimate, auto_candidates, select_model,
};
use thermonav::stoch::wavelet_variance::{WaveletVariance, haar_wavelet_variance};

/// How the parameter intervals are made, in words (for the JSON and the heading).
const INTERVALS: &str =
    "95 % parametric bootstrap: Wald on the log scale, spread from the interquartile range";

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

#[derive(Debug, Serialize)]
struct ChannelJson {
    #[serde(flatten)]
    selected: SelectedJson,
    wavelet_variance: WaveletVarianceJson,
    parameters: BTreeMap<String, ParameterJson>,
    candidates: Vec<CandidateJson>,
}

#[derive(Debug, Serialize)]
struct SelectedJson {
    unit: &'static str,
    selected_model: String,
    wic: f64,
}

#[derive(Debug, Serialize)]
struct WaveletVarianceJson {
    scale_s: Vec<f64>,
    variance_unit2: Vec<f64>,
    ci_low_unit2: Vec<f64>,
    ci_high_unit2: Vec<f64>,
    implied_unit2: Vec<f64>,
}

impl WaveletVarianceJson {
    /// Estimate, limits and the model's value at scale j.
    fn row(&self, j: usize) -> [f64; 4] {
        [
            self.variance_unit2[j],
            self.ci_low_unit2[j],
            self.ci_high_unit2[j],
            self.implied_unit2[j],
        ]
    }
}

#[derive(Debug, Serialize)]
struct ParameterJson {
    value: f64,
    ci_low: f64,
    ci_high: f64,
}

#[derive(Debug, Serialize)]
struct CandidateJson {
    model: String,
    wic: f64,
    objective: f64,
}

/// What every channel is fitted with: the rate (Hz), the candidates, the bootstrap.
struct Job(f64, Vec<ModelSpec>, BootstrapSettings);

/// Runs `gmwm`.
pub fn run(args: &GmwmArgs) -> Result<(), Failure> {
    let candidates = candidates(&args.model)?;
    let (series, rate_hz) = crate::inputs::read_rates(&args.file, "GMWM")?;
    let doc = document(args, &series, Job(rate_hz, candidates, settings(args)))?;
    if args.json {
        return print_json(&doc);
    }
    print_text(&doc);
    Ok(())
}

fn settings(args: &GmwmArgs) -> BootstrapSettings {
    let mut settings = BootstrapSettings::default();
    (settings.replicates, settings.seed) = (args.replicates, args.seed);
    settings
}

/// The candidates of `--model`: the automatic list or the one model given.
fn candidates(model: &str) -> Result<Vec<ModelSpec>, Failure> {
    if model.eq_ignore_ascii_case("auto") {
        return Ok(auto_candidates());
    }
    let spec = model.parse::<ModelSpec>();
    spec.map(|s| vec![s])
        .map_err(|e| Failure::Usage(anyhow!("--model {model}: {e}")))
}

fn channels(args: &GmwmArgs, series: &ImuSeries, job: &Job) -> Result<Channels, Failure> {
    let mut channels = BTreeMap::new();
    for channel in Channel::ALL {
        let json = channel_json(series.channel(channel), channel, job);
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
        interval_method: INTERVALS,
        bootstrap_replicates: args.replicates,
    }
}

/// One channel: its wavelet variance, the candidates ranked by WIC, the selected fit.
fn channel_json(y: &[f64], channel: Channel, job: &Job) -> Result<ChannelJson, anyhow::Error> {
    let Job(rate_hz, candidates, settings) = job;
    let wv = haar_wavelet_variance(y, *rate_hz, None, settings.confidence)?;
    let ranked = select_model(&wv, candidates, *settings)?;
    Ok(ranked_json(&wv, &ranked, channel))
}

fn ranked_json(wv: &WaveletVariance, ranked: &[GmwmEstimate], channel: Channel) -> ChannelJson {
    let best = &ranked[0];
    ChannelJson {
        selected: selected_json(best, channel),
        wavelet_variance: wavelet_variance_json(wv, best),
        parameters: parameters_json(best, channel.sensor()),
        candidates: ranked.iter().map(candidate_json).collect(),
    }
}

fn selected_json(best: &GmwmEstimate, channel: Channel) -> SelectedJson {
    SelectedJson {
        unit: channel.si_unit(SampleKind::Rates),
        selected_model: best.fit.model.to_string(),
        wic: best.wic,
    }
}

fn wavelet_variance_json(wv: &WaveletVariance, best: &GmwmEstimate) -> WaveletVarianceJson {
    WaveletVarianceJson {
        scale_s: wv.scale_s.clone(),
        variance_unit2: wv.variance.clone(),
        ci_low_unit2: wv.ci_low.clone(),
        ci_high_unit2: wv.ci_high.clone(),
        implied_unit2: best.fit.implied_variance.clone(),
    }
}

/// The parameters keyed by name, the library's `unit` replaced by the channel's unit.
fn parameters_json(best: &GmwmEstimate, sensor: Sensor) -> BTreeMap<String, ParameterJson> {
    let unit = match sensor {
        Sensor::Gyro => "rad_per_s",
        Sensor::Accelerometer => "m_per_s2",
    };
    let entry = |p: &ParameterEstimate| (p.kind.name().replace("unit", unit), parameter_json(p));
    best.parameters.iter().map(entry).collect()
}

fn parameter_json(p: &ParameterEstimate) -> ParameterJson {
    ParameterJson {
        value: p.value,
        ci_low: p.ci_low,
        ci_high: p.ci_high,
    }
}

fn candidate_json(e: &GmwmEstimate) -> CandidateJson {
    let (model, objective) = (e.fit.model.to_string(), e.fit.objective);
    CandidateJson {
        model,
        wic: e.wic,
        objective,
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
    println!("\n{title}  WIC {:.3}", s.wic);
    print_wavelet_variance(&c.wavelet_variance);
    print_parameters(&c.parameters);
    if c.candidates.len() > 1 {
        print_candidates(&c.candidates);
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
        println!("{key:>40} {}", cells(&[p.value, p.ci_low, p.ci_high]));
    }
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
