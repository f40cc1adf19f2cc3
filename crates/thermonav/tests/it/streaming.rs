//! The streaming characterisation against the in-memory one and against allantools: exact
//! where it claims to be, within a small fraction of the confidence interval where it is not.

use crate::allan::{adis_16405_allantools, adis_16405_columns, assert_matches_allantools};
use thermonav::imu::{Channel, ImuSeries};
use thermonav::sensor::adis16364_like;
use thermonav::sim::chamber::{ChamberRun, ChamberWander, calgary, simulate_chamber_run};
use thermonav::sim::clock::SampleClock;
use thermonav::stoch::allan::{
    CiSettings, StreamingAllan, StreamingAllanSettings, TauGrid, confidence_intervals,
    overlapping_adev,
};
use thermonav::stoch::bank::{GaussMarkovEstimate, GaussMarkovSource};
use thermonav::stoch::characterize::{CharacterizeSettings, characterize};
use thermonav::stoch::streaming::{StreamingCharacterizer, StreamingSettings};

/// Feeds `y` in pieces of `piece` samples, centred on the mean of its first 4096 samples.
fn streamed(y: &[f64], piece: usize, settings: StreamingAllanSettings) -> StreamingAllan {
    let offset = y[..4096].iter().sum::<f64>() / 4096.0;
    let mut stream = StreamingAllan::new(TauGrid::Octave, offset, settings).unwrap();
    for chunk in y.chunks(piece) {
        stream.push(chunk).unwrap();
    }
    stream
}

// Oracle: allantools 2024.6 oadev (10 significant digits) on real data. With the exact bound
// above every factor the streaming curve is the overlapping estimator itself: 1e-9 relative
// (the printed precision), same term counts.
#[test]
fn streaming_allan_with_every_factor_exact_matches_allantools() {
    let (columns, peer) = (adis_16405_columns(), adis_16405_allantools());
    let settings = StreamingAllanSettings {
        exact_max_factor: 1 << 18,
        stride: 16,
    };
    for (y, rows) in columns.iter().zip(&peer) {
        let (curve, _) = streamed(y, 65_521, settings)
            .finish(100.0, &CiSettings::default())
            .unwrap();
        assert_matches_allantools(&curve, rows, usize::MAX);
    }
}

// With the default bounds (exact to m = 8192, stride 16 beyond): the exact factors equal
// allantools to 1e-9 and their noise types and limits equal the in-memory ones (same
// decisions, limits to 1e-9); the decimated-overlap factors (16384 ... 262144, 1024 ... 16384
// starting points per period of m) stay within 2 % of the in-memory 68 % confidence half-width
// (measured: at most 0.04 % on these six channels), and their noise types agree.
#[test]
fn streaming_allan_with_default_bounds_is_exact_below_and_close_above() {
    let (columns, peer) = (adis_16405_columns(), adis_16405_allantools());
    let settings = StreamingAllanSettings::default();
    let ci = CiSettings {
        level: 0.683,
        ..CiSettings::default()
    };
    let mut worst_fraction: f64 = 0.0;
    for (y, rows) in columns.iter().zip(&peer) {
        let (curve, limits) = streamed(y, 10_007, settings).finish(100.0, &ci).unwrap();
        let memory = overlapping_adev(y, 100.0, &TauGrid::Octave).unwrap();
        let memory_limits = confidence_intervals(y, &memory, 0.683);
        assert_eq!(limits.alpha, memory_limits.alpha);
        assert_matches_allantools(&curve, rows, settings.exact_max_factor);
        for (i, &(m, _, _)) in rows.iter().enumerate() {
            if m <= settings.exact_max_factor {
                assert!((limits.low[i] / memory_limits.low[i] - 1.0).abs() < 1e-9);
                assert!((limits.high[i] / memory_limits.high[i] - 1.0).abs() < 1e-9);
            } else {
                let half_width = (memory_limits.high[i] - memory_limits.low[i]) / 2.0;
                let fraction = (curve.adev[i] - memory.adev[i]).abs() / half_width;
                worst_fraction = worst_fraction.max(fraction);
                assert!(fraction < 0.02, "m {m}: {fraction} of the half-width");
            }
        }
    }
    eprintln!("worst decimated-overlap difference: {worst_fraction} of the half-width");
}

/// A simulated static 50 Hz chamber record of `seconds` at 10 °C (the ADIS16364-like unit).
pub(crate) fn chamber_record(seconds: f64) -> ImuSeries {
    let run = ChamberRun {
        temperature: thermonav::sim::chamber::ChamberTemperature::SetPoint {
            temperature_c: 10.0,
        },
        unit: thermonav::sim::unit::SimulatedUnit::default(),
        power_on: 1,
        duration_s: seconds,
        clock: SampleClock::new(50.0, 0.0, 0.0).unwrap(),
        site: calgary(),
        wander: ChamberWander {
            sigma_c: 0.05,
            correlation_time_s: 600.0,
        },
        seed: 31,
    };
    simulate_chamber_run(&adis16364_like(), &run)
        .unwrap()
        .series
}

/// The samples of `range`, for feeding a series piece by piece.
pub(crate) fn piece(series: &ImuSeries, range: std::ops::Range<usize>) -> ImuSeries {
    let mut out = ImuSeries::new(series.kind.unwrap());
    out.time = series.time[range.clone()].to_vec();
    for c in Channel::ALL {
        out.channels[c.index()] = series.channel(c)[range.clone()].to_vec();
    }
    out.temperature_c = series.temperature_c.as_ref().map(|t| t[range].to_vec());
    out
}

fn relative(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { (a / b - 1.0).abs() }
}

fn same_estimate(a: &GaussMarkovEstimate, b: &GaussMarkovEstimate, tolerance: f64) -> bool {
    match (a, b) {
        (
            GaussMarkovEstimate::Model {
                correlation_time_s: t1,
                sigma: s1,
                ci95_correlation_time_s: c1,
            },
            GaussMarkovEstimate::Model {
                correlation_time_s: t2,
                sigma: s2,
                ci95_correlation_time_s: c2,
            },
        ) => {
            let bounds = c1.iter().zip(c2).all(|(x, y)| match (x, y) {
                (Some(x), Some(y)) => relative(*x, *y) < tolerance,
                (None, None) => true,
                _ => false,
            });
            relative(*t1, *t2) < tolerance && relative(*s1, *s2) < tolerance && bounds
        }
        _ => a == b,
    }
}

// Oracle: the in-memory characterisation of the same 3-hour 50 Hz simulated chamber record
// (540 000 samples, regular clock), streamed in pieces of 10 007 samples after a 16 384-sample
// prefix, so every stage really streams. Bit for bit: temperature, preprocessing and the
// exact likelihood (same block sums in the same order). To 1e-9 relative: the AR-based and
// ACF Gauss-Markov models and AR coefficients (FFT versus direct filter sums: rounding
// only), and the Allan points up to the exact bound; above it the decimated-overlap points
// differ by less than 2 % of their confidence half-width.
#[test]
fn streaming_characterisation_equals_the_in_memory_one() {
    let series = chamber_record(3.0 * 3600.0);
    let settings = CharacterizeSettings::default();
    let (memory, memory_reports) = characterize(&series, 10.0, "sim", &settings).unwrap();
    let streaming = StreamingSettings {
        prefix_samples: 1 << 14,
        ..StreamingSettings::default()
    };
    let mut stream = StreamingCharacterizer::new(settings.clone(), streaming);
    let mut start = 0;
    while start < series.len() {
        let end = (start + 10_007).min(series.len());
        stream.push(&piece(&series, start..end)).unwrap();
        start = end;
    }
    assert_eq!(stream.samples(), series.len());
    assert_eq!(stream.mean_temperature_c(), series.mean_temperature_c());
    let (entry, reports) = stream.finish(10.0, "sim").unwrap();
    assert_eq!(entry.preprocessing, memory.preprocessing);
    for channel in Channel::ALL {
        let (a, b) = (&entry.channels[&channel], &memory.channels[&channel]);
        assert_eq!(
            a.gauss_markov.get(GaussMarkovSource::IRREGULAR_ML),
            b.gauss_markov.get(GaussMarkovSource::IRREGULAR_ML)
        );
        assert!(same_estimate(
            a.gauss_markov.get(GaussMarkovSource::AR_BASED),
            b.gauss_markov.get(GaussMarkovSource::AR_BASED),
            1e-9
        ));
        assert!(same_estimate(
            a.gauss_markov.get(GaussMarkovSource::ACF_FIT),
            b.gauss_markov.get(GaussMarkovSource::ACF_FIT),
            1e-9
        ));
        assert_eq!(a.ar.coefficients.len(), b.ar.coefficients.len());
        for (x, y) in a.ar.coefficients.iter().zip(&b.ar.coefficients) {
            assert!(relative(*x, *y) < 1e-9, "{channel:?}: {x} vs {y}");
        }
        let (r, m) = (&reports[&channel], &memory_reports[&channel]);
        assert_eq!(r.allan.averaging_factor, m.allan.averaging_factor);
        for (i, &f) in r.allan.averaging_factor.iter().enumerate() {
            let (x, y) = (r.allan.adev[i], m.allan.adev[i]);
            if f <= streaming.allan.exact_max_factor {
                assert!(relative(x, y) < 1e-9, "{channel:?} m {f}: {x} vs {y}");
            } else {
                let half_width = (m.allan_limits.1[i] - m.allan_limits.0[i]) / 2.0;
                assert!((x - y).abs() < 0.02 * half_width, "{channel:?} m {f}");
            }
        }
    }
}

// A record that ends within the prefix is characterised by the in-memory path itself.
#[test]
fn a_record_within_the_prefix_gives_the_in_memory_result_exactly() {
    let series = chamber_record(1800.0);
    let settings = CharacterizeSettings::default();
    let (memory, _) = characterize(&series, 10.0, "sim", &settings).unwrap();
    let mut stream = StreamingCharacterizer::new(settings, StreamingSettings::default());
    stream.push(&piece(&series, 0..50_000)).unwrap();
    stream.push(&piece(&series, 50_000..series.len())).unwrap();
    assert_eq!(stream.finish(10.0, "sim").unwrap().0, memory);
}
