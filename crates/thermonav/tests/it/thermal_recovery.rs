//! The whole chain simulator → record means → calibration, against the simulator's truth.
//!
//! # The oracle
//! A simulated unit (serial number) keeps the same repeatable bias curve
//! b(T) = b_unit + c₁ ΔT + c₂ ΔT² in every run ([`SimulatedUnit::repeatable_curves`]); each
//! power-on adds an offset of sd `power_on_offset_sigma` (0.1 deg/s, 0.27 mg in the built-in
//! profile), returned per run in `truth.channels[ch].power_on_offset`. What a static record
//! reads once the true signal u is removed is b(T) + u · s(T) + offset, with s(T) the
//! deterministic scale-factor error (ppm/°C × ΔT): negligible for the gyros (u is Earth rate,
//! u · s ≤ 2e-7 rad/s against a 1.7e-3 rad/s offset sd) and the horizontal accelerometers
//! (u ≈ 0), but 0.02 mg/°C on az, where u = −g: up to 1.3 mg at −40 °C, five offset sds. A
//! static level unit cannot tell that term from a bias (`ScaleFactorCalibration`), so az's
//! fitted curve holds both and the oracle adds u · s(T) to every channel's repeatable curve
//! ([`oracle`]). Without it az is covered in none of the campaigns (asserted below, so the
//! need for the term stays visible).
//!
//! # Why J = 4 power-ons
//! The curve's constant is the mean of the J power-on offsets, so its band half-width is
//! about max(Scheffé, t_{J−1}) · σ̂_b / √J. With J = 2 that is 12.7 σ̂_b / 1.41; J = 3 gives
//! 4.30 / 1.73 = 2.5 σ̂_b. Measured over the 120 channel-campaigns of this file (median of the
//! largest half-width at the set points, in offset sds): J = 2: 6.8, J = 3: 2.26, J = 4: 1.51.
//! J = 4 is the smallest that meets the 2 σ target; [`three_power_ons_miss_the_width_target`]
//! keeps the J = 3 measurement honest.
//!
//! # Why coverage in 90..99 % over 120 channel-campaigns
//! The 6 channels of a campaign draw their noise and offsets from separate named streams, so
//! the 120 channel-campaigns are independent trials. At a true rate of 95 % the binomial sd
//! of the observed rate is √(0.95 · 0.05 / 120) = 2.0 %: 90 % is 2.5 sd below, so a band that
//! really holds 95 % fails the lower limit with probability < 1 %, while one that holds only
//! 85 % passes with probability about 4 %. The upper limit 99 % (118 of 120) is 2 sd above
//! 95 %: it fails a band so wide that it nearly always covers. Measured: 112/120 = 93.3 %.
//!
//! A longer run (200 campaigns, 1200 channel-campaigns, [`coverage_measurement`], ignored by
//! default) gives 1118/1200 = 93.2 % (sd 0.63 %), about 2.9 sd below the nominal 95 %. The
//! cause is heteroscedastic record noise. A 600 s record is shorter than the bias's
//! correlation time at the hot end (Tc 700-2250 s, σ × 1.6-1.7 at 60 °C), so its mean keeps
//! nearly the whole Gauss-Markov σ: the accelerometers' record-mean noise is 0.19 σ_p at −20 °C
//! (Tc 25 s) and 0.79-0.94 σ_p at 60 °C, against a pooled residual sd of 0.46-0.53 σ_p. The
//! fit assumes one noise variance, so its band is too narrow at 60 °C, where a third of the
//! misses fall (27 of 82). For the gyros the record noise is only 0.06-0.2 σ_p, and they cover
//! 569/600 = 94.8 %, as t_{J−1} predicts; the accelerometers cover 549/600 = 91.5 %. Longer
//! records do not cure it: with 3600 s records (100 campaigns) the gyros cover 286/300 = 95.3 %,
//! the accelerometers still 275/300 = 91.7 %, 15 of 39 misses at 60 °C, because the record-mean
//! variance stays about 2σ²Tc/L and so keeps the Tc ratio between set points. A cure would
//! weight each record by its own noise variance (e.g. from its Allan variance), which the
//! calibration does not do. The test is left as it is: the 20-campaign rate lies within the
//! range, and the shortfall is reported, not hidden.
//!
//! # The ramp
//! One log of the same unit swept −40 → 60 °C at 1 °C/min (6000 s, its own power-on) is cut
//! into [`BLOCK_S`] = 600 s block means (10 blocks, 10 °C each). The bias's correlation time
//! spans 25 s to 2250 s across temperature and axis: a block should be several correlation
//! times long for its means to be nearly independent, as the fit assumes, but a long block
//! leaves few blocks for a cubic fit and a wide Scheffé multiple. At 600 s the blocks are
//! longer than Tc everywhere but at 40-60 °C. Raw samples are correlated over up to 45 000
//! samples, so a fit to them has a hopelessly narrow band: measured, it covers the ramp's true
//! curve at every set point in 2 of 120 channels (asserted < 50 %). Averaging the quadratic
//! over a 10 °C block moves its mean by c₂ · (10 °C)²/12, under 5e-4 deg/s, small against the
//! noise. Measured shape agreement (see the test): 120/120, largest ratio of the difference to
//! the sum of half-widths 0.92. The 600 s block band alone covers the ramp's truth in only 92 of
//! 120 channels: the hot-end blocks are still correlated, so the block band is too narrow too.

use std::collections::BTreeMap;
use thermonav::imu::Channel;
use thermonav::sensor::{SensorProfile, adis16364_like};
use thermonav::sim::chamber::{
    ChamberRecord, ChamberRun, ChamberTemperature, ChamberWander, Ramp, calgary,
    simulate_chamber_run, static_signal,
};
use thermonav::sim::clock::SampleClock;
use thermonav::sim::unit::SimulatedUnit;
use thermonav::stoch::thermal::{
    FitSettings, PowerOnRecord, TemperaturePoint, ThermalCalibration, ThermalCurve, block_means,
    calibrate, fit_bias_curve,
};

/// Chamber set points, °C.
const SET_POINTS_C: [f64; 6] = [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0];
/// Campaigns, each a different unit serial and seed.
const CAMPAIGNS: u64 = 20;
/// Power-ons per campaign, each visiting every set point (module docs, "Why J = 4").
const POWER_ONS: u32 = 4;
/// Sampling rate, Hz.
const RATE_HZ: f64 = 20.0;
/// Length of a set-point record, s.
const RECORD_S: f64 = 600.0;
/// Block length of the ramp's block means, s (module docs, "The ramp").
const BLOCK_S: f64 = 600.0;
/// The sweep of the ramp log.
const RAMP: Ramp = Ramp {
    start_c: -40.0,
    end_c: 60.0,
    rate_c_per_min: 1.0,
};

fn unit(campaign: u64) -> SimulatedUnit {
    SimulatedUnit {
        serial: 1000 + campaign,
    }
}

fn seed(campaign: u64) -> u64 {
    5000 + campaign
}

fn settings() -> FitSettings {
    FitSettings {
        reference_temperature_c: Some(25.0),
        ..FitSettings::default()
    }
}

fn mean(x: &[f64]) -> f64 {
    x.iter().sum::<f64>() / x.len() as f64
}

/// One chamber run with the campaign defaults' clock (50 µs jitter, one sample in a thousand
/// dropped) and wander (0.05 °C, 600 s).
fn record(campaign: u64, temperature: ChamberTemperature, power_on: u32) -> ChamberRecord {
    let run = ChamberRun {
        temperature,
        duration_s: RECORD_S,
        unit: unit(campaign),
        power_on,
        clock: SampleClock::new(RATE_HZ, 50e-6, 0.001).expect("valid clock"),
        site: calgary(),
        wander: ChamberWander {
            sigma_c: 0.05,
            correlation_time_s: 600.0,
        },
        seed: seed(campaign),
    };
    simulate_chamber_run(&adis16364_like(), &run).expect("valid run")
}

/// `power_ons` power-ons (labelled 1..), each visiting every set point.
fn campaign(campaign: u64, power_ons: u32) -> Vec<ChamberRecord> {
    (1..=power_ons)
        .flat_map(|p| SET_POINTS_C.iter().map(move |&t| (t, p)))
        .map(|(temperature_c, p)| {
            record(campaign, ChamberTemperature::SetPoint { temperature_c }, p)
        })
        .collect()
}

/// Each record's mean, less the true signal, at its mean temperature.
fn observations(records: &[ChamberRecord]) -> BTreeMap<Channel, Vec<PowerOnRecord>> {
    let mut out: BTreeMap<Channel, Vec<PowerOnRecord>> = BTreeMap::new();
    for r in records {
        let temperature_c = mean(r.series.temperature_c.as_ref().expect("temperatures"));
        for channel in Channel::ALL {
            out.entry(channel).or_default().push(PowerOnRecord {
                power_on: r.truth.power_on,
                temperature_c,
                value: mean(r.series.channel(channel)) - r.truth.channels[&channel].true_signal,
            });
        }
    }
    out
}

fn calibrated(campaign_index: u64, power_ons: u32) -> ThermalCalibration {
    calibrate(
        &observations(&campaign(campaign_index, power_ons)),
        settings(),
    )
    .expect("calibration")
}

/// The oracle: the unit's repeatable curve plus, when `with_scale_factor`, the static signal
/// times the deterministic scale-factor error (module docs, "The oracle").
fn oracle(
    profile: &SensorProfile,
    unit: SimulatedUnit,
    channel: Channel,
    with_scale_factor: bool,
) -> impl Fn(f64) -> f64 {
    let curve = unit.repeatable_curves(profile)[&channel].clone();
    let ppm_per_c = profile.channels[&channel].scale_factor_temperature_coefficient_ppm_per_c;
    let u = static_signal(calgary())[channel.index()];
    let reference_c = profile.reference_temperature_c;
    let scale = f64::from(u8::from(with_scale_factor));
    move |t| curve.value_at(t) + scale * u * ppm_per_c * (t - reference_c) * 1e-6
}

/// True when the band holds `truth` at every set point.
fn covers(curve: &ThermalCurve, truth: impl Fn(f64) -> f64) -> bool {
    SET_POINTS_C.iter().all(|&t| {
        let (value, half) = curve.band_at(t);
        (value - truth(t)).abs() <= half
    })
}

/// The largest band half-width at the set points.
fn widest(curve: &ThermalCurve) -> f64 {
    SET_POINTS_C
        .iter()
        .map(|&t| curve.band_at(t).1)
        .fold(0.0, f64::max)
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    let n = x.len();
    if n % 2 == 1 {
        x[n / 2]
    } else {
        0.5 * (x[n / 2 - 1] + x[n / 2])
    }
}

/// What the campaigns of `power_ons` power-ons give over every channel-campaign.
struct CampaignStats {
    covered: usize,
    trials: usize,
    /// Az channels whose band holds the bare repeatable curve (no scale-factor term).
    az_covered_without_scale_factor: usize,
    /// Largest half-width at the set points over the channel's offset sd, per trial.
    width_ratios: Vec<f64>,
}

fn campaign_stats(power_ons: u32) -> CampaignStats {
    let profile = adis16364_like();
    let mut stats = CampaignStats {
        covered: 0,
        trials: 0,
        az_covered_without_scale_factor: 0,
        width_ratios: Vec::new(),
    };
    for c in 0..CAMPAIGNS {
        let calibration = calibrated(c, power_ons);
        for channel in Channel::ALL {
            let curve = &calibration.channels[&channel].bias;
            stats.covered += usize::from(covers(curve, oracle(&profile, unit(c), channel, true)));
            if channel == Channel::Az {
                stats.az_covered_without_scale_factor +=
                    usize::from(covers(curve, oracle(&profile, unit(c), channel, false)));
            }
            stats.trials += 1;
            let sigma = profile.channels[&channel].power_on_offset_sigma;
            stats.width_ratios.push(widest(curve) / sigma);
        }
    }
    stats
}

// Part 1. Targets and tolerances: module docs. Measured with J = 4: 112/120 covered (93.3 %),
// median width 1.51 offset sds, max 3.47; az without the scale-factor term 0/20.
#[test]
fn campaigns_recover_the_repeatable_curve_within_the_band() {
    let stats = campaign_stats(POWER_ONS);
    let coverage = stats.covered as f64 / stats.trials as f64;
    let max = stats.width_ratios.iter().copied().fold(0.0, f64::max);
    let med = median(stats.width_ratios);
    println!(
        "J = {POWER_ONS}: coverage {}/{} = {coverage:.3}; half-width / σ_p median {med:.3}, max \
         {max:.3}; az without u·s(T) covered {}/{CAMPAIGNS}",
        stats.covered, stats.trials, stats.az_covered_without_scale_factor
    );
    assert_eq!(stats.trials, 120);
    assert!(
        (0.90..=0.99).contains(&coverage),
        "coverage at the set points {coverage}"
    );
    assert!(med <= 2.0, "median half-width {med} offset sds");
    // The oracle needs az's u · s(T) (module docs): the bare curve lies outside the band.
    assert!(
        2 * stats.az_covered_without_scale_factor < CAMPAIGNS as usize,
        "az covered without u·s(T) in {} campaigns",
        stats.az_covered_without_scale_factor
    );
}

// Why not J = 3: t_2 = 4.30, so the half-width is about 4.30 σ̂_b / √3 = 2.5 σ̂_b, and its
// median over channels (σ̂_b with 2 dof has median ≈ 0.83 σ_b) about 2.1 σ_p. Measured: 2.26.
#[test]
fn three_power_ons_miss_the_width_target() {
    let med = median(campaign_stats(3).width_ratios);
    println!("J = 3: median half-width / σ_p {med:.3}");
    assert!(med > 2.0, "median half-width {med} offset sds with J = 3");
}

// Part 2. The ramp's curve (block means, fit_bias_curve) equals the campaign's up to a
// constant, its own power-on offset. After the mean difference over the set points is removed,
// ramp − campaign must lie within h_ramp + h_campaign at every set point. Were both bands
// honest, both would hold at once with probability ≥ 90 % (Bonferroni), and the constant
// removed is the part of the campaign band that dominates it (the offsets' mean): so ≥ 90 %
// is a fair floor (binomial sd at 90 % over 120 channels: 2.7 %). Measured: 120/120, worst
// ratio 0.92, median 0.15. The raw-sample fit is the counter-example of the module docs: its
// band covers the ramp's truth (repeatable curve + u·s + the ramp's offset) in 2/120 channels
// (an honest one would in ≥ 95 %); the 600 s block band in 92/120.
#[test]
fn a_ramp_gives_the_same_curve_up_to_a_constant() {
    let profile = adis16364_like();
    let block = (BLOCK_S * RATE_HZ).round() as usize;
    let (mut same_shape, mut raw_covered, mut block_covered, mut trials) = (0, 0, 0, 0);
    let mut ratios = Vec::new();
    for c in 0..CAMPAIGNS {
        let calibration = calibrated(c, POWER_ONS);
        let ramp = record(c, ChamberTemperature::Ramp(RAMP), POWER_ONS + 1);
        let temperatures = ramp.series.temperature_c.as_ref().expect("temperatures");
        for channel in Channel::ALL {
            let truth = &ramp.truth.channels[&channel];
            let values: Vec<f64> = ramp
                .series
                .channel(channel)
                .iter()
                .map(|v| v - truth.true_signal)
                .collect();
            let points = block_means(temperatures, &values, block).expect("blocks");
            let ramp_curve = fit_bias_curve(channel, &points, settings()).expect("ramp fit");
            let campaign_curve = &calibration.channels[&channel].bias;
            let differences: Vec<f64> = SET_POINTS_C
                .iter()
                .map(|&t| ramp_curve.value_at(t) - campaign_curve.value_at(t))
                .collect();
            let offset = mean(&differences);
            let ratio = SET_POINTS_C
                .iter()
                .zip(&differences)
                .map(|(&t, d)| {
                    (d - offset).abs() / (ramp_curve.band_at(t).1 + campaign_curve.band_at(t).1)
                })
                .fold(0.0, f64::max);
            ratios.push(ratio);
            same_shape += usize::from(ratio <= 1.0);
            let bare = oracle(&profile, unit(c), channel, true);
            let ramp_truth = |t: f64| bare(t) + truth.power_on_offset;
            block_covered += usize::from(covers(&ramp_curve, ramp_truth));
            let raw: Vec<TemperaturePoint> = temperatures
                .iter()
                .zip(&values)
                .map(|(&temperature_c, &value)| TemperaturePoint {
                    temperature_c,
                    value,
                })
                .collect();
            let raw_curve = fit_bias_curve(channel, &raw, settings()).expect("raw fit");
            raw_covered += usize::from(covers(&raw_curve, ramp_truth));
            trials += 1;
        }
    }
    let rate = same_shape as f64 / trials as f64;
    let worst = ratios.iter().copied().fold(0.0, f64::max);
    println!(
        "ramp: same shape {same_shape}/{trials}, ratio median {:.3} max {worst:.3}; the ramp's \
         truth inside the block band {block_covered}/{trials}, the raw-sample band \
         {raw_covered}/{trials}",
        median(ratios)
    );
    assert!(rate >= 0.90, "same shape in {rate} of the channels");
    assert!(
        2 * raw_covered < trials,
        "the raw-sample band covered in {raw_covered} of {trials}"
    );
}

// Part 3. One power-on, one record per set point: `calibrate` fits one curve to all six
// records, which then carries that power-on's offset. Its band must hold
// repeatable + u·s + offset (same 90..99 % range as part 1), and the offset convention is
// closed by the bare curve falling outside the band in most gyro channels (the gyros' record
// noise is 0.06-0.2 σ_p, so their band is far narrower than an offset). Measured: 110/120 =
// 91.7 % covered (low for the reason of the module docs: heteroscedastic record noise, which
// one pooled residual sd from six records cannot follow); the bare curve in 13/60 gyros.
#[test]
fn one_power_on_gives_the_curve_plus_its_offset() {
    let profile = adis16364_like();
    let (mut covered, mut bare_gyro, mut gyros, mut trials) = (0, 0, 0, 0);
    for c in 0..CAMPAIGNS {
        let records = campaign(c, 1);
        let calibration = calibrate(&observations(&records), settings()).expect("calibration");
        assert_eq!(calibration.power_ons, 1);
        for channel in Channel::ALL {
            let fitted = &calibration.channels[&channel];
            assert!(fitted.power_on_offsets.is_empty());
            let offset = records[0].truth.channels[&channel].power_on_offset;
            let bare = oracle(&profile, unit(c), channel, true);
            covered += usize::from(covers(&fitted.bias, |t| bare(t) + offset));
            if channel.index() < 3 {
                bare_gyro += usize::from(covers(&fitted.bias, &bare));
                gyros += 1;
            }
            trials += 1;
        }
    }
    let coverage = covered as f64 / trials as f64;
    println!(
        "one power-on: repeatable + offset covered {covered}/{trials} = {coverage:.3}; gyro \
         bare curve covered {bare_gyro}/{gyros}"
    );
    assert!(
        (0.90..=0.99).contains(&coverage),
        "coverage of repeatable + offset {coverage}"
    );
    assert!(
        2 * bare_gyro < gyros,
        "bare curve covered {bare_gyro}/{gyros}"
    );
}

/// The 200-campaign measurement behind the module docs' coverage figures: coverage per channel
/// and which set point is worst in each miss. About 12 s in release.
#[test]
#[ignore = "measurement, not a check: 1200 channel-campaigns"]
fn coverage_measurement() {
    let profile = adis16364_like();
    let mut covered: BTreeMap<Channel, usize> = BTreeMap::new();
    let mut worst_at = [0usize; 6];
    for c in 0..200 {
        let calibration = calibrated(c, POWER_ONS);
        for channel in Channel::ALL {
            let curve = &calibration.channels[&channel].bias;
            let truth = oracle(&profile, unit(c), channel, true);
            let ok = covers(curve, &truth);
            *covered.entry(channel).or_default() += usize::from(ok);
            if !ok {
                let ratio = |&t: &f64| {
                    let (value, half) = curve.band_at(t);
                    (value - truth(t)).abs() / half
                };
                let k = (0..6)
                    .max_by(|&a, &b| ratio(&SET_POINTS_C[a]).total_cmp(&ratio(&SET_POINTS_C[b])))
                    .expect("six set points");
                worst_at[k] += 1;
            }
        }
    }
    println!("covered per channel (of 200) {covered:?}; misses by worst set point {worst_at:?}");
}
