//! Characterisation of a static record fed in pieces, in memory bounded independently of the
//! record length except where stated: the streaming form of [`characterize`].
//!
//! What each stage of [`characterize`] needs, and how it is kept here (per channel, the six
//! channels updated in parallel on each piece):
//!
//! | stage | input | streaming form | exact? | memory |
//! |---|---|---|---|---|
//! | Allan deviation + limits | raw rates | [`StreamingAllan`] | exact for m ≤ 8192, decimated overlap above (bounded in its docs) | 2·8192 + N/16 values |
//! | Kaiser low-pass + decimation | raw rates | [`StreamingDecimator`] | yes (rounding) | taps + F values, + N/F outputs |
//! | AR, AR-based GM, ACF fit | the decimated series | in memory at the end | yes | N/F values (86 400 for 24 h at 1 Hz) |
//! | exact GM likelihood | 0.5 s block means of the raw rates and of the times | running block sums | bit for bit | N/(0.5 s × rate) values, + as many times shared by the channels |
//! | temperature | mean of temp_c | running sum | bit for bit | — |
//!
//! So the memory grows with the record only through the decimated series, the block means and
//! the strided Allan phase: about 46 MB per channel for 24 h at 1 kHz (43 MB of it the strided
//! phase), against 5.5 GB for the whole record as f64.
//!
//! Two things are fixed by the first `prefix_samples` samples, which are held until then:
//! the nominal rate (the in-memory path takes the median interval of the whole record; the
//! whole record's median is checked at the end, and a record whose median interval differs
//! from its first part's by more than [`RATE_RATIO_TOLERANCE`] is refused, as its filter and
//! decimation would be wrong) and the provisional mean the Allan phase is centred on. A record
//! that ends within the prefix is characterised by [`characterize`] itself.

use super::allan::{ChiSquareQuantile, CiSettings, StreamingAllan, StreamingAllanSettings};
use super::bank::TemperatureEntry;
use super::characterize::{
    ChannelInputs, ChannelReport, CharacterizeError, CharacterizeSettings, Conditioning, Denoiser,
    channel_report, characterize,
};
use super::thermal::RecordSums;
use crate::imu::{Channel, ImuSeries, SampleKind};
use crate::signal::decimate::RATE_RATIO_TOLERANCE;
use crate::signal::streaming_decimate::StreamingDecimator;
use crate::signal::timestamps::interval_stats;
use crate::time::Timestamp;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// How a streaming characterisation runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StreamingSettings {
    /// Where the Allan deviation stops being exact, and its phase stride beyond.
    pub allan: StreamingAllanSettings,
    /// Samples held before streaming starts (they fix the rate and the Allan centring).
    pub prefix_samples: usize,
}

impl Default for StreamingSettings {
    /// The default Allan bounds and a prefix of 2^18 samples (262 s at 1 kHz; at least 30
    /// averages at the largest exact factor, so its noise type comes from the lag-1 method as
    /// in memory).
    fn default() -> Self {
        Self {
            allan: StreamingAllanSettings::default(),
            prefix_samples: 1 << 18,
        }
    }
}

/// Means of consecutive blocks of a fixed number of values fed one by one, each summed in
/// order from zero as the in-memory `chunks_exact(..).map(sum / len)` does.
#[derive(Debug, Clone)]
struct BlockMeans {
    per_block: usize,
    sum: f64,
    count: usize,
    means: Vec<f64>,
}

impl BlockMeans {
    fn new(per_block: usize) -> Self {
        Self {
            per_block,
            sum: 0.0,
            count: 0,
            means: Vec::new(),
        }
    }

    fn push(&mut self, values: impl IntoIterator<Item = f64>) {
        for v in values {
            self.sum += v;
            self.count += 1;
            if self.count == self.per_block {
                self.means.push(self.sum / self.per_block as f64);
                self.sum = 0.0;
                self.count = 0;
            }
        }
    }
}

/// The streaming state of one channel.
#[derive(Debug, Clone)]
struct ChannelStream {
    channel: Channel,
    allan: StreamingAllan,
    decimator: StreamingDecimator,
    blocks: BlockMeans,
}

impl ChannelStream {
    fn push(&mut self, values: &[f64]) -> Result<(), CharacterizeError> {
        let fail = |message: String| CharacterizeError::Channel {
            channel: self.channel.name(),
            message,
        };
        self.allan.push(values).map_err(|e| fail(e.to_string()))?;
        self.decimator
            .push(values)
            .map_err(|e| fail(e.to_string()))?;
        self.blocks.push(values.iter().copied());
        Ok(())
    }
}

/// Positive sampling intervals counted by value (ns), for the whole record's median.
#[derive(Debug, Clone, Default)]
struct IntervalCounts {
    counts: BTreeMap<i64, u64>,
    total: u64,
    last: Option<Timestamp>,
}

impl IntervalCounts {
    fn push(&mut self, times: &[Timestamp]) {
        for &t in times {
            if let Some(previous) = self.last {
                let dt = t.since(previous).as_nanos();
                if dt > 0 {
                    *self.counts.entry(dt).or_insert(0) += 1;
                    self.total += 1;
                }
            }
            self.last = Some(t);
        }
    }

    /// The lower middle interval (as `interval_stats`), s.
    fn median_s(&self) -> Option<f64> {
        let middle = self.total.checked_sub(1)? / 2;
        let mut seen = 0;
        self.counts.iter().find_map(|(&dt, &count)| {
            seen += count;
            (seen > middle).then_some(dt as f64 * 1e-9)
        })
    }
}

/// Everything kept once streaming has started.
#[derive(Debug, Clone)]
struct Running {
    conditioning: Conditioning,
    start: Timestamp,
    channels: Vec<ChannelStream>,
    times: BlockMeans,
    intervals: IntervalCounts,
}

impl Running {
    fn push(&mut self, piece: &ImuSeries) -> Result<(), CharacterizeError> {
        let start = self.start;
        self.times
            .push(piece.time.iter().map(|t| t.since(start).as_seconds()));
        self.intervals.push(&piece.time);
        self.channels
            .par_iter_mut()
            .try_for_each(|c| c.push(piece.channel(c.channel)))
    }
}

#[derive(Debug, Clone)]
enum Stage {
    Prefix(ImuSeries),
    Running(Box<Running>),
}

/// Running mean of the temperature column, kept only while every sample has one.
#[derive(Debug, Clone, Copy)]
struct TemperatureSum {
    sum: f64,
    count: usize,
    complete: bool,
}

/// A characterisation fed with successive pieces of one static record.
///
/// # Example
/// ```
/// use thermonav::stoch::characterize::CharacterizeSettings;
/// use thermonav::stoch::streaming::{StreamingCharacterizer, StreamingSettings};
/// let stream = StreamingCharacterizer::new(CharacterizeSettings::default(), StreamingSettings::default());
/// assert_eq!(stream.samples(), 0);
/// ```
#[derive(Debug, Clone)]
pub struct StreamingCharacterizer {
    settings: CharacterizeSettings,
    streaming: StreamingSettings,
    stage: Stage,
    samples: usize,
    temperature: TemperatureSum,
    sums: RecordSums,
}

impl StreamingCharacterizer {
    /// A characterisation with the given settings.
    pub fn new(settings: CharacterizeSettings, streaming: StreamingSettings) -> Self {
        Self {
            settings,
            streaming,
            stage: Stage::Prefix(ImuSeries::new(SampleKind::Rates)),
            samples: 0,
            temperature: TemperatureSum {
                sum: 0.0,
                count: 0,
                complete: true,
            },
            sums: RecordSums::default(),
        }
    }

    /// Samples fed so far.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Mean of the temp_c column so far, °C (`None` when a sample had none, or no sample).
    pub fn mean_temperature_c(&self) -> Option<f64> {
        let t = self.temperature;
        (t.complete && t.count > 0).then(|| t.sum / t.count as f64)
    }

    /// Adds the next piece of the record.
    ///
    /// # Errors
    /// [`CharacterizeError`] for increments, a first part without a positive interval, invalid
    /// settings, or a non-finite sample.
    pub fn push(&mut self, piece: &ImuSeries) -> Result<(), CharacterizeError> {
        if piece.kind == Some(SampleKind::Increments) {
            return Err(CharacterizeError::Increments);
        }
        self.add_temperatures(piece);
        self.sums.add(piece);
        self.samples += piece.len();
        match &mut self.stage {
            Stage::Running(running) => running.push(piece),
            Stage::Prefix(prefix) => {
                append(prefix, piece);
                if prefix.len() >= self.streaming.prefix_samples {
                    let prefix = std::mem::take(prefix);
                    let mut running = self.start_running(&prefix)?;
                    running.push(&prefix)?;
                    self.stage = Stage::Running(Box::new(running));
                }
                Ok(())
            }
        }
    }

    fn add_temperatures(&mut self, piece: &ImuSeries) {
        match &piece.temperature_c {
            Some(column) if column.len() == piece.len() => {
                for &t in column {
                    self.temperature.sum += t;
                }
                self.temperature.count += column.len();
            }
            _ if piece.is_empty() => {}
            _ => self.temperature.complete = false,
        }
    }

    /// The rate, conditioning and per-channel states from the first part of the record.
    fn start_running(&self, prefix: &ImuSeries) -> Result<Running, CharacterizeError> {
        let stats = interval_stats(&prefix.time).ok_or(CharacterizeError::TooShort {
            samples: prefix.len(),
            needed: 2,
        })?;
        if self.settings.denoise != Denoiser::Kaiser {
            return Err(CharacterizeError::Settings(
                "wavelet de-noising needs the whole record: characterise it in memory".into(),
            ));
        }
        let conditioning = Conditioning::new(stats.nominal_rate_hz(), &self.settings)?;
        let per_block = conditioning.samples_per_ml_block(&self.settings);
        let channels = Channel::ALL
            .iter()
            .map(|&channel| {
                let values = prefix.channel(channel);
                let offset = values.iter().sum::<f64>() / values.len() as f64;
                let fail = |message: String| CharacterizeError::Channel {
                    channel: channel.name(),
                    message,
                };
                Ok(ChannelStream {
                    channel,
                    allan: StreamingAllan::new(
                        self.settings.allan_grid.clone(),
                        if offset.is_finite() { offset } else { 0.0 },
                        self.streaming.allan,
                    )
                    .map_err(|e| fail(e.to_string()))?,
                    decimator: StreamingDecimator::new(&conditioning.filter, conditioning.factor)
                        .map_err(|e| fail(e.to_string()))?,
                    blocks: BlockMeans::new(per_block),
                })
            })
            .collect::<Result<Vec<_>, CharacterizeError>>()?;
        Ok(Running {
            start: prefix.time[0],
            times: BlockMeans::new(per_block),
            intervals: IntervalCounts::default(),
            channels,
            conditioning,
        })
    }

    /// The bank entry and the channel reports of the whole record measured at `temperature_c`.
    ///
    /// # Errors
    /// As [`characterize`], and [`CharacterizeError::RateChanged`] when the rate of the whole
    /// record's median interval is off its first part's by more than [`RATE_RATIO_TOLERANCE`].
    pub fn finish(
        self,
        temperature_c: f64,
        source: &str,
    ) -> Result<(TemperatureEntry, BTreeMap<Channel, ChannelReport>), CharacterizeError> {
        let mean = self
            .sums
            .mean(self.mean_temperature_c().unwrap_or(temperature_c));
        let running = match self.stage {
            Stage::Prefix(prefix) => {
                return characterize(&prefix, temperature_c, source, &self.settings);
            }
            Stage::Running(running) => running,
        };
        let Running {
            conditioning,
            channels,
            times,
            intervals,
            ..
        } = *running;
        check_rate(conditioning.rate_hz, &intervals)?;
        let settings = &self.settings;
        let ci = CiSettings {
            level: settings.ci_level,
            quantile: ChiSquareQuantile::Exact,
        };
        let results: Vec<Result<(Channel, ChannelReport), CharacterizeError>> = channels
            .into_par_iter()
            .map(|c| {
                let fail = |message: String| CharacterizeError::Channel {
                    channel: c.channel.name(),
                    message,
                };
                let (allan, limits) = c
                    .allan
                    .finish(conditioning.rate_hz, &ci)
                    .map_err(|e| fail(e.to_string()))?;
                let conditioned = c.decimator.finish().map_err(|e| fail(e.to_string()))?;
                let inputs = ChannelInputs {
                    allan,
                    limits,
                    conditioned,
                    block_times_s: times.means.clone(),
                    block_means: c.blocks.means,
                };
                let report =
                    channel_report(c.channel, inputs, conditioning.modelling_dt_s(), settings)?;
                Ok((c.channel, report))
            })
            .collect();
        let reports: BTreeMap<Channel, ChannelReport> =
            results.into_iter().collect::<Result<_, _>>()?;
        let mut entry = conditioning.entry(temperature_c, source, settings, &reports);
        entry.record_mean = mean;
        Ok((entry, reports))
    }
}

/// Refuses a record whose whole median interval is off the rate its first part gave.
fn check_rate(prefix_rate_hz: f64, intervals: &IntervalCounts) -> Result<(), CharacterizeError> {
    let Some(median_s) = intervals.median_s() else {
        return Ok(());
    };
    let record_rate_hz = 1.0 / median_s;
    if (record_rate_hz / prefix_rate_hz - 1.0).abs() > RATE_RATIO_TOLERANCE {
        return Err(CharacterizeError::RateChanged {
            prefix_rate_hz,
            record_rate_hz,
        });
    }
    Ok(())
}

/// Appends the samples of `piece` to `series` (a temperature column only while both have one).
fn append(series: &mut ImuSeries, piece: &ImuSeries) {
    let had_temperature = series.is_empty() || series.temperature_c.is_some();
    series.time.extend_from_slice(&piece.time);
    for channel in Channel::ALL {
        series.channels[channel.index()].extend_from_slice(piece.channel(channel));
    }
    series.temperature_c = match (
        had_temperature,
        series.temperature_c.take(),
        &piece.temperature_c,
    ) {
        (true, Some(mut column), Some(more)) => {
            column.extend_from_slice(more);
            Some(column)
        }
        (true, None, Some(more)) => Some(more.clone()),
        _ => None,
    };
    if series.kind.is_none() {
        series.kind = piece.kind;
    }
}
