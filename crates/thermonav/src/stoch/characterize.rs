//! Characterisation of one static record: every model of the bank for each channel.
//!
//! Per channel (the six in parallel):
//! 1. Allan deviation of the raw rates (never of filtered data: a low-pass filter changes the
//!    white-noise density), its confidence limits and IEEE 952 terms.
//! 2. The paper's conditioning: Kaiser low-pass at `cutoff_hz` (zero-phase), then decimation to
//!    `modelling_rate_hz`, a rate consistent with the cut-off, so the AR fit does not measure
//!    the filter's own correlation. Only the kept samples are filtered
//!    ([`filter_and_decimate`]), taps/factor multiplications per input sample. Or, with
//!    [`Denoiser::Wavelet`], the paper's alternative: wavelet shrinkage of the whole record at
//!    its own rate ([`denoise`]), then every factor-th sample (in memory only).
//! 3. On the conditioned series: the chosen AR model; then each Gauss-Markov family of
//!    [`crate::stoch::gm_family`] fitted by its own module: the AR(1) fit and its AR-based
//!    model (the paper's), and the classical fit to the autocorrelation.
//! 4. On block means of the raw record with their actual times: the exact Gauss-Markov +
//!    white-noise maximum likelihood ([`crate::stoch::noisy_gauss_markov`]), which models the
//!    white noise the other two mistake for decorrelation; with GMWM, the composite fitted to
//!    the raw record's wavelet variance and its bias state.
//!
//! Defaults (state them when reporting): octave Allan grid at 0.683 confidence; Kaiser 60 dB,
//! cut-off 0.4 Hz, transition 0.2 Hz, modelling rate 1 Hz; AR by Burg with the order chosen by
//! BIC up to 4; ACF fit up to the first zero crossing; ML on 0.5 s block means.

use super::allan::{
    AllanCurve, AllanIntervals, DEFAULT_CONFIDENCE, TauGrid, confidence_intervals, overlapping_adev,
};
use super::ar::order::{Criterion, Order, fit_ar_order};
use super::ar::{ArMethod, ArModel};
use super::bank::{
    AllanSummary, ArSummary, ChannelModel, FilterSummary, GmwmSummary, Preprocessing,
    TemperatureEntry, WaveletSummary,
};
use super::gauss_markov::LagWindow;
use super::gm_family::{FitInputs, GaussMarkovEstimate, GaussMarkovModels};
use super::gmwm::{
    ModelSpec, TauBand, auto_candidates, fit_from_first_adequate_scale, map_to_filter_states,
    physical_parameters,
};
use super::noise_terms::{Bound, NoiseTerms, TermReading, fit_noise_terms};
use super::thermal::record_mean;
use super::wavelet_variance::from_allan_curve;
use crate::imu::{Channel, ImuSeries, SampleKind};
use crate::signal::SignalError;
use crate::signal::decimate::{check_anti_alias, decimate, decimation_factor};
use crate::signal::kaiser::{DEFAULT_RIPPLE_DB, FirFilter, KaiserSpec, design_kaiser_lowpass};
use crate::signal::streaming_decimate::filter_and_decimate;
use crate::signal::timestamps::interval_stats;
use crate::signal::wavelet::denoise::{WaveletDenoise, denoise};
use crate::signal::zero_phase::ZeroPhaseMode;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// Settings of the characterisation; [`Default`] gives the documented defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct CharacterizeSettings {
    /// Allan τ grid.
    pub allan_grid: TauGrid,
    /// Confidence level of the Allan limits.
    pub ci_level: f64,
    /// Kaiser pass-band edge, Hz.
    pub cutoff_hz: f64,
    /// Kaiser transition width, Hz.
    pub transition_hz: f64,
    /// Kaiser attenuation, dB.
    pub ripple_db: f64,
    /// Rate of the conditioned series, Hz.
    pub modelling_rate_hz: f64,
    /// AR estimator.
    pub ar_method: ArMethod,
    /// AR order (fixed or selected).
    pub ar_order: Order,
    /// Lags of the classical ACF fit.
    pub acf_window: LagWindow,
    /// Block length of the means fed to the exact likelihood, s.
    pub ml_block_s: f64,
    /// What de-noises the record before the AR and ACF fits.
    pub denoise: Denoiser,
    /// The GMWM composite fitted to the raw record's wavelet variance, or none.
    pub gmwm: Option<GmwmChoice>,
    /// The averaging times the composite is mapped onto the filter's states for.
    pub gmwm_band: TauBand,
}

/// Which composite `characterize` fits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GmwmChoice {
    /// This one.
    Model(ModelSpec),
    /// The candidate of [`crate::stoch::gmwm::AUTO_CANDIDATES`] with the least asymptotic
    /// WIC ([`crate::stoch::gmwm::rank_by_asymptotic_wic`]; no bootstrap).
    Auto,
}

impl std::fmt::Display for GmwmChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GmwmChoice::Model(spec) => write!(f, "{spec}"),
            GmwmChoice::Auto => write!(f, "auto"),
        }
    }
}

/// The composite `characterize`, `thermonav gmwm` and Python's `gmwm` fit by default: the
/// automatic choice. A fixed `wn+rw+2gm`
/// split one slow process into a 1-3 s process and a random walk on the demo's 30-minute
/// records; the criterion picks `wn+gm` there and the richer composites on the real runs.
pub const DEFAULT_GMWM: GmwmChoice = GmwmChoice::Auto;

/// The de-noising before decimation to the modelling rate (the Allan curve and the exact
/// likelihood always see the raw record).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Denoiser {
    /// The Kaiser low-pass of `cutoff_hz`, `transition_hz`, `ripple_db` (the paper's).
    #[default]
    Kaiser,
    /// Wavelet shrinkage with these settings (needs the whole record in memory).
    Wavelet(WaveletDenoise),
}

impl Default for CharacterizeSettings {
    fn default() -> Self {
        Self {
            allan_grid: TauGrid::Octave,
            ci_level: DEFAULT_CONFIDENCE,
            cutoff_hz: 0.4,
            transition_hz: 0.2,
            ripple_db: DEFAULT_RIPPLE_DB,
            modelling_rate_hz: 1.0,
            ar_method: ArMethod::default(),
            ar_order: Order::Auto {
                criterion: Criterion::Bic,
                max_order: 4,
            },
            acf_window: LagWindow::FirstZeroCrossing,
            ml_block_s: 0.5,
            denoise: Denoiser::Kaiser,
            gmwm: Some(DEFAULT_GMWM),
            gmwm_band: TauBand::default(),
        }
    }
}

/// Why a record cannot be characterised.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CharacterizeError {
    /// The record holds increments, not rates.
    #[error("characterisation needs rates (rad/s, m/s^2), the record holds increments")]
    Increments,
    /// Too short or without a positive interval.
    #[error("the record has {samples} samples; at least {needed} are needed")]
    TooShort {
        /// Samples.
        samples: usize,
        /// Needed.
        needed: usize,
    },
    /// A processing step failed on a channel.
    #[error("channel {channel}: {message}")]
    Channel {
        /// Channel name.
        channel: &'static str,
        /// What failed.
        message: String,
    },
    /// A channel whose every sample is the same value: a stuck sensor (or a column filled
    /// by hand), which no noise model describes.
    #[error(
        "channel {channel} is constant ({value} in every sample): a stuck sensor has no noise to model"
    )]
    ConstantChannel {
        /// Channel name.
        channel: &'static str,
        /// Its one value, SI.
        value: f64,
    },
    /// Bad settings.
    #[error("{0}")]
    Settings(String),
    /// A streamed record whose median sampling interval is not its first part's.
    #[error(
        "the record's median sampling interval gives {record_rate_hz} Hz, its first part {prefix_rate_hz} Hz: the filter and decimation chosen from the first part do not fit (characterise it in memory, or split it where the rate changes)"
    )]
    RateChanged {
        /// Rate from the first part, Hz.
        prefix_rate_hz: f64,
        /// Rate from the whole record, Hz.
        record_rate_hz: f64,
    },
}

/// Everything computed for one channel, beyond what the bank keeps.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelReport {
    /// The bank's model.
    pub model: ChannelModel,
    /// The full Allan curve.
    pub allan: AllanCurve,
    /// Lower and upper Allan limits.
    pub allan_limits: (Vec<f64>, Vec<f64>),
}

/// [`CharacterizeError::ConstantChannel`] for the first channel whose samples are all equal.
pub fn check_no_constant_channel(series: &ImuSeries) -> Result<(), CharacterizeError> {
    for channel in series.present_channels() {
        let column = series.channel(channel);
        if let Some(&first) = column.first()
            && column.len() > 1
            && column.iter().all(|&v| v == first)
        {
            return Err(CharacterizeError::ConstantChannel {
                channel: channel.name(),
                value: first,
            });
        }
    }
    Ok(())
}

/// Characterises a static record measured at `temperature_c`: each of its present channels
/// ([`ImuSeries::present_channels`]; all six but for a record of a subset), which are the
/// entry's channels.
///
/// # Errors
/// [`CharacterizeError`] for increments, a record too short for the conditioning, invalid
/// settings, or a failing step.
pub fn characterize(
    series: &ImuSeries,
    temperature_c: f64,
    source: &str,
    settings: &CharacterizeSettings,
) -> Result<(TemperatureEntry, BTreeMap<Channel, ChannelReport>), CharacterizeError> {
    if series.kind == Some(SampleKind::Increments) {
        return Err(CharacterizeError::Increments);
    }
    let stats = interval_stats(&series.time).ok_or(CharacterizeError::TooShort {
        samples: series.len(),
        needed: 2,
    })?;
    check_no_constant_channel(series)?;
    let conditioning = Conditioning::new(stats.nominal_rate_hz(), settings)?;
    let times_s = series.seconds_from_start();
    let context = Context {
        conditioning: &conditioning,
        times_s: &times_s,
        settings,
    };
    let results: Vec<Result<(Channel, ChannelReport), CharacterizeError>> = series
        .present_channels()
        .par_iter()
        .map(|&channel| {
            context
                .channel(channel, series.channel(channel))
                .map(|r| (channel, r))
        })
        .collect();
    let reports: BTreeMap<Channel, ChannelReport> =
        results.into_iter().collect::<Result<_, _>>()?;
    let mut entry = conditioning.entry(temperature_c, source, settings, &reports);
    entry.record_mean = record_mean(series, series.mean_temperature_c().unwrap_or(temperature_c));
    record_denoiser(&mut entry.preprocessing, settings.denoise, series.len())?;
    Ok((entry, reports))
}

/// With wavelet de-noising, the bank records it in place of the Kaiser filter.
fn record_denoiser(
    preprocessing: &mut Preprocessing,
    denoiser: Denoiser,
    samples: usize,
) -> Result<(), CharacterizeError> {
    if let Denoiser::Wavelet(w) = denoiser {
        let level = w
            .level_for(samples)
            .map_err(|e| CharacterizeError::Settings(e.to_string()))?;
        preprocessing.filter = None;
        preprocessing.wavelet = Some(WaveletSummary {
            wavelet: w.wavelet.to_string(),
            level,
            mode: w.mode.name().into(),
            threshold: w.rule.name().into(),
            thresholding: w.thresholding.name().into(),
        });
    }
    Ok(())
}

/// The conditioning of a record at `rate_hz`: the Kaiser low-pass and the decimation factor.
#[derive(Debug, Clone)]
pub(crate) struct Conditioning {
    pub(crate) rate_hz: f64,
    pub(crate) filter: FirFilter,
    pub(crate) factor: usize,
}

impl Conditioning {
    /// Designs the filter and the decimation for a record at `rate_hz`.
    pub(crate) fn new(
        rate_hz: f64,
        settings: &CharacterizeSettings,
    ) -> Result<Self, CharacterizeError> {
        let spec = KaiserSpec::new(
            rate_hz,
            settings.cutoff_hz,
            settings.transition_hz,
            settings.ripple_db,
        )
        .map_err(|e| CharacterizeError::Settings(e.to_string()))?;
        let filter = design_kaiser_lowpass(&spec)
            .map_err(|e| CharacterizeError::Settings(e.to_string()))?
            .with_odd_taps(&spec);
        let factor = decimation_factor(rate_hz, settings.modelling_rate_hz)
            .map_err(|e| CharacterizeError::Settings(e.to_string()))?;
        check_anti_alias(
            settings.cutoff_hz,
            settings.transition_hz,
            settings.modelling_rate_hz,
        )
        .map_err(|e| CharacterizeError::Settings(e.to_string()))?;
        Ok(Self {
            rate_hz,
            filter,
            factor,
        })
    }

    /// Interval of the conditioned series, s.
    pub(crate) fn modelling_dt_s(&self) -> f64 {
        self.factor as f64 / self.rate_hz
    }

    /// Samples per block mean of the exact likelihood.
    pub(crate) fn samples_per_ml_block(&self, settings: &CharacterizeSettings) -> usize {
        ((settings.ml_block_s * self.rate_hz).round() as usize).max(1)
    }

    /// The bank entry of a record from its channel reports.
    pub(crate) fn entry(
        &self,
        temperature_c: f64,
        source: &str,
        settings: &CharacterizeSettings,
        reports: &BTreeMap<Channel, ChannelReport>,
    ) -> TemperatureEntry {
        TemperatureEntry {
            temperature_c,
            source: source.to_string(),
            preprocessing: Preprocessing {
                input_rate_hz: self.rate_hz,
                filter: Some(FilterSummary {
                    cutoff_hz: settings.cutoff_hz,
                    transition_hz: settings.transition_hz,
                    ripple_db: settings.ripple_db,
                    num_taps: self.filter.num_taps(),
                    beta: self.filter.beta(),
                    mode: ZeroPhaseMode::DelayCompensated.name().into(),
                }),
                wavelet: None,
                decimation_factor: self.factor,
                modelling_rate_hz: self.rate_hz / self.factor as f64,
            },
            channels: reports.iter().map(|(c, r)| (*c, r.model.clone())).collect(),
            record_mean: None,
            imu_rotation: None,
        }
    }
}

/// What the models of one channel are computed from: the Allan curve and its limits of the raw
/// rates, the conditioned series, and the block means (with their times) for the likelihood.
#[derive(Debug, Clone)]
pub(crate) struct ChannelInputs {
    pub(crate) allan: AllanCurve,
    pub(crate) limits: AllanIntervals,
    pub(crate) conditioned: Vec<f64>,
    pub(crate) block_times_s: Vec<f64>,
    pub(crate) block_means: Vec<f64>,
}

/// Every model of one channel from its inputs.
pub(crate) fn channel_report(
    channel: Channel,
    inputs: ChannelInputs,
    dt_s: f64,
    settings: &CharacterizeSettings,
) -> Result<ChannelReport, CharacterizeError> {
    let fail = |message: String| CharacterizeError::Channel {
        channel: channel.name(),
        message,
    };
    let ChannelInputs {
        allan,
        limits,
        conditioned,
        block_times_s,
        block_means,
    } = inputs;
    let terms = fit_noise_terms(&allan, &limits);
    let chosen = fit_ar_order(&conditioned, settings.ar_order, settings.ar_method)
        .map_err(|e| fail(e.to_string()))?;
    let gmwm = settings
        .gmwm
        .and_then(|spec| gmwm_summary(&allan, spec, settings.gmwm_band));
    let gauss_markov = GaussMarkovModels::fit(&FitInputs {
        conditioned: &conditioned,
        dt_s,
        ar_method: settings.ar_method,
        acf_window: settings.acf_window,
        block_times_s: &block_times_s,
        block_means: &block_means,
        gmwm_bias: gmwm.as_ref().map(|(_, bias)| bias),
    })
    .map_err(fail)?;
    let model = ChannelModel {
        unit: channel.si_unit(SampleKind::Rates).to_string(),
        allan: allan_summary(&allan, &terms),
        ar: ar_summary(&chosen, dt_s),
        gauss_markov,
        gmwm: gmwm.map(|(summary, _)| summary),
    };
    Ok(ChannelReport {
        model,
        allan,
        allan_limits: (limits.low, limits.high),
    })
}

/// The composite `choice` fitted to the wavelet variance read off the raw octave Allan curve,
/// and its bias state for the filter; `None` when the curve has too few octaves for the
/// model or the fit fails (a constant stretch: zero variance at a scale).
fn gmwm_summary(
    allan: &AllanCurve,
    choice: GmwmChoice,
    band: TauBand,
) -> Option<(GmwmSummary, GaussMarkovEstimate)> {
    let wv = from_allan_curve(allan, DEFAULT_CONFIDENCE)?;
    let candidates = match choice {
        GmwmChoice::Model(spec) => vec![spec],
        GmwmChoice::Auto => auto_candidates(),
    };
    let (fit, skipped) = fit_from_first_adequate_scale(&wv, &candidates).ok()?;
    let spec = fit.model;
    let record_s = allan.n_samples as f64 * allan.tau0_s;
    let mapped = map_to_filter_states(&fit.terms, fit.dt_s, record_s, band);
    let parameters = physical_parameters(&fit.terms, fit.dt_s)
        .iter()
        .map(|p| (p.kind.name(), p.value))
        .collect();
    let summary = GmwmSummary {
        model: spec.to_string(),
        parameters,
        objective: fit.objective,
        scales: fit.scale_samples.len(),
        first_scale_s: wv.scale_s[skipped],
        band_tau_s: [band.shortest_s, band.longest_s],
        white_noise_density: mapped.white_noise_density,
        folds: mapped.folds,
    };
    let bias = GaussMarkovEstimate::Model {
        correlation_time_s: mapped.bias_correlation_time_s,
        sigma: mapped.bias_sigma,
        ci95_correlation_time_s: [None, None],
    };
    Some((summary, bias))
}

/// The curve and the terms the bank keeps: N, B (an estimate, or its bound at an end of the
/// curve) and K, with the white-noise region and the reason for each missing term.
fn allan_summary(allan: &AllanCurve, terms: &NoiseTerms) -> AllanSummary {
    let estimate = |t: &TermReading| {
        t.as_ref()
            .ok()
            .filter(|t| t.bound == Bound::Estimate)
            .map(|t| t.value)
    };
    let b = terms.bias_instability.as_ref().ok();
    AllanSummary {
        tau_s: allan.tau_s.clone(),
        adev: allan.adev.clone(),
        white_noise_density: estimate(&terms.random_walk),
        bias_instability: estimate(&terms.bias_instability),
        rate_random_walk: estimate(&terms.rate_random_walk),
        bias_instability_at_most: b.filter(|t| t.bound == Bound::AtMost).map(|t| t.value),
        white_noise_tau_range_s: (terms.random_walk.as_ref().ok())
            .map(|t| [t.tau_min_s, t.tau_max_s]),
        absent_terms: absent_terms(terms),
    }
}

/// Term name → reason, for the terms the bank keeps that the curve does not support.
fn absent_terms(terms: &NoiseTerms) -> BTreeMap<String, String> {
    [
        ("white_noise_density", &terms.random_walk),
        ("bias_instability", &terms.bias_instability),
        ("rate_random_walk", &terms.rate_random_walk),
    ]
    .into_iter()
    .filter_map(|(name, t)| {
        t.as_ref()
            .err()
            .map(|a| (name.to_string(), a.reason.clone()))
    })
    .collect()
}

struct Context<'a> {
    conditioning: &'a Conditioning,
    times_s: &'a [f64],
    settings: &'a CharacterizeSettings,
}

impl Context<'_> {
    fn channel(
        &self,
        channel: Channel,
        values: &[f64],
    ) -> Result<ChannelReport, CharacterizeError> {
        let fail = |message: String| CharacterizeError::Channel {
            channel: channel.name(),
            message,
        };
        let c = self.conditioning;
        let allan = overlapping_adev(values, c.rate_hz, &self.settings.allan_grid)
            .map_err(|e| fail(e.to_string()))?;
        let limits = confidence_intervals(values, &allan, self.settings.ci_level);
        let conditioned = self.conditioned(values).map_err(|e| fail(e.to_string()))?;
        let per_block = c.samples_per_ml_block(self.settings);
        let inputs = ChannelInputs {
            allan,
            limits,
            conditioned,
            block_times_s: block_means(self.times_s, per_block),
            block_means: block_means(values, per_block),
        };
        channel_report(channel, inputs, c.modelling_dt_s(), self.settings)
    }
}

impl Context<'_> {
    /// The record de-noised and decimated to the modelling rate.
    fn conditioned(&self, values: &[f64]) -> Result<Vec<f64>, SignalError> {
        let c = self.conditioning;
        match &self.settings.denoise {
            Denoiser::Kaiser => filter_and_decimate(&c.filter, values, c.factor),
            Denoiser::Wavelet(w) => Ok(decimate(&denoise(values, w)?.values, c.factor)),
        }
    }
}

/// Means of consecutive whole blocks of `per_block` values (a partial last block is dropped).
fn block_means(values: &[f64], per_block: usize) -> Vec<f64> {
    values
        .chunks_exact(per_block)
        .map(|c| c.iter().sum::<f64>() / c.len() as f64)
        .collect()
}

fn ar_summary(model: &ArModel, dt_s: f64) -> ArSummary {
    ArSummary {
        method: model.method.name().to_string(),
        coefficients: model.coefficients.clone(),
        noise_variance: model.noise_variance,
        dt_s,
    }
}
