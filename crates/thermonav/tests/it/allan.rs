//! Overlapping Allan deviation against allantools (real ADIS16405 data), Stable32 and the
//! published NBS14 values; confidence limits against Stable32; noise terms against closed forms.

use crate::{shared_column as read_column, shared_data};
use rand_distr::{Distribution, StandardNormal};
use thermonav::rng::named_rng;
use thermonav::stoch::allan::{
    AllanCurve, AllanIntervals, TauGrid, confidence_intervals, overlapping_adev,
};
use thermonav::stoch::noise_terms::{
    BIAS_INSTABILITY_FACTOR, Bound, avar_gauss_markov, avar_random_walk, avar_white,
    fit_noise_terms,
};

/// Stable32 rows: (AF, #, alpha, min, sigma, max).
pub(crate) fn stable32(path: &str) -> Vec<(usize, usize, i32, f64, f64, f64)> {
    std::fs::read_to_string(shared_data(path))
        .expect("shared data present")
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            (
                f[0].parse().unwrap(),
                f[2].parse().unwrap(),
                f[3].parse().unwrap(),
                f[4].parse().unwrap(),
                f[5].parse().unwrap(),
                f[6].parse().unwrap(),
            )
        })
        .collect()
}

/// The slow, obviously correct definition: each second difference of phase,
/// x_{i+2m} − 2x_{i+m} + x_i = Σ_j (y_{i+m+j} − y_{i+j}), summed sample by sample, O(N m) per τ.
fn slow_oadev(y: &[f64], m: usize) -> f64 {
    let n = y.len() + 1 - 2 * m;
    let mut total = 0.0;
    for i in 0..n {
        let mut d = 0.0;
        for j in 0..m {
            d += y[i + m + j] - y[i + j];
        }
        total += d * d;
    }
    (total / (2.0 * (m * m) as f64 * n as f64)).sqrt()
}

#[test]
fn fast_oadev_equals_the_slow_definition() {
    // Same quantity: the slow version sums the second differences sample by sample. 1e-12
    // relative is rounding.
    let mut rng = named_rng(4, "allan-slow");
    let y: Vec<f64> = (0..3000)
        .map(|_| 1.0 + <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng))
        .collect();
    let curve = overlapping_adev(
        &y,
        10.0,
        &TauGrid::Explicit(vec![1, 2, 3, 7, 50, 300, 1500]),
    )
    .unwrap();
    for (i, &m) in curve.averaging_factor.iter().enumerate() {
        let slow = slow_oadev(&y, m);
        assert!(
            (curve.adev[i] / slow - 1.0).abs() < 1e-12,
            "m {m}: {} vs {slow}",
            curve.adev[i]
        );
        assert_eq!(curve.n_terms[i], 3000 - 2 * m + 1);
    }
}

/// The six channels of the real ADIS16405 run 1 (10^6 samples at 100 Hz).
pub(crate) fn adis_16405_columns() -> Vec<Vec<f64>> {
    adis_16405_run(1)
}

/// The six channels (deg/s, g) of ADIS16405 static run `run` in `../shared/data`.
pub(crate) fn adis_16405_run(run: usize) -> Vec<Vec<f64>> {
    use std::io::{BufRead, BufReader};
    let path = format!("smac-imudata/adis_16405_imu{run}.csv.gz");
    let file = std::fs::File::open(shared_data(&path)).expect("ADIS data");
    let mut columns = vec![Vec::new(); 6];
    for line in BufReader::new(flate2::read::GzDecoder::new(file))
        .lines()
        .skip(1)
    {
        for (c, v) in line.expect("text").split(',').enumerate() {
            columns[c].push(v.parse::<f64>().expect("number"));
        }
    }
    columns
}

/// allantools' octave rows of one channel: (m, n_terms, adev).
pub(crate) type PeerRows = Vec<(usize, usize, f64)>;

/// allantools 2024.6 oadev(y, rate=100, data_type='freq') of each ADIS16405 channel, octave
/// grid, printed with 10 significant digits.
pub(crate) fn adis_16405_allantools() -> Vec<PeerRows> {
    let peer = std::fs::read_to_string(shared_data(
        "peer-results-on-real-data/adis_16405_imu1_oadev_allantools.csv",
    ))
    .expect("peer");
    let names = [
        "Gyro_X", "Gyro_Y", "Gyro_Z", "Accel_X", "Accel_Y", "Accel_Z",
    ];
    names
        .iter()
        .map(|name| {
            peer.lines()
                .skip(1)
                .map(|l| l.split(',').collect::<Vec<&str>>())
                .filter(|f| f[0] == *name)
                .map(|f| {
                    (
                        f[1].parse().unwrap(),
                        f[3].parse().unwrap(),
                        f[4].parse().unwrap(),
                    )
                })
                .collect()
        })
        .collect()
}

/// The curve has allantools' factors and term counts, and its deviations to 1e-9 relative
/// (the printed precision) at every factor up to `exact_up_to`.
pub(crate) fn assert_matches_allantools(curve: &AllanCurve, rows: &PeerRows, exact_up_to: usize) {
    assert_eq!(rows.len(), curve.adev.len(), "number of taus");
    for (i, &(m, n_terms, expected)) in rows.iter().enumerate() {
        assert_eq!((curve.averaging_factor[i], curve.n_terms[i]), (m, n_terms));
        if m <= exact_up_to {
            let got = curve.adev[i];
            assert!(
                (got / expected - 1.0).abs() < 1e-9,
                "m {m}: {got} vs {expected}"
            );
        }
    }
}

#[test]
fn matches_allantools_on_the_real_adis16405_run() {
    let columns = adis_16405_columns();
    for (y, rows) in columns.iter().zip(&adis_16405_allantools()) {
        let curve = overlapping_adev(y, 100.0, &TauGrid::Octave).unwrap();
        assert_matches_allantools(&curve, rows, usize::MAX);
    }
}

#[test]
fn matches_published_nbs14_values() {
    // NIST SP 1065 pp. 107-108 (Stable32), 7 significant digits: 1e-6 relative.
    let y = read_column("allantools/nbs14/nbs14_1000_frequency.txt");
    let curve = overlapping_adev(&y, 1.0, &TauGrid::Explicit(vec![1, 10, 100])).unwrap();
    for (got, expected) in curve.adev.iter().zip([0.2922319, 0.09159953, 0.03241343]) {
        assert!((got / expected - 1.0).abs() < 1e-6, "{got} vs {expected}");
    }
    let ten = [
        892.0, 809.0, 823.0, 798.0, 671.0, 644.0, 883.0, 903.0, 677.0,
    ];
    let curve = overlapping_adev(&ten, 1.0, &TauGrid::Explicit(vec![1, 2])).unwrap();
    assert!(
        (curve.adev[0] / 91.22945 - 1.0).abs() < 1e-6
            && (curve.adev[1] / 85.95287 - 1.0).abs() < 1e-6
    );
}

#[test]
fn matches_stable32_on_pink_frequency_noise_with_tau0_42_s() {
    // Stable32 prints 5 significant digits: 1e-4 relative (allantools' tolerance); τ = AF·42 s
    // (its printed τ column has only 5 digits). Octave grid and '#' column identical.
    let y = read_column("allantools/pink_frequency/pink_frequency.txt");
    let rows = stable32("allantools/pink_frequency/s32_oadev_octave.txt");
    let curve = overlapping_adev(&y, 1.0 / 42.0, &TauGrid::Octave).unwrap();
    for (af, n, _, _, sigma, _) in rows.iter().take_while(|r| r.0 <= 2048) {
        let i = curve
            .averaging_factor
            .iter()
            .position(|m| m == af)
            .expect("octave factor present");
        assert_eq!(curve.n_terms[i], *n);
        assert!((curve.tau_s[i] - *af as f64 * 42.0).abs() < 1e-9);
        assert!(
            (curve.adev[i] / sigma - 1.0).abs() < 1e-4,
            "AF {af}: {} vs {sigma}",
            curve.adev[i]
        );
    }
}

#[test]
fn confidence_limits_follow_stable32_on_the_ocxo() {
    // Stable32's OCXO octave table (0.683 confidence). Its deviations differ from ours by up to
    // 1.3e-3 (Stable32 normalises the raw frequency differently), so the limits are compared
    // relative to each program's own deviation. The noise types must equal Stable32's on every
    // row (lag-1 autocorrelation with at least 30 averages, B1 ratio below). With exact
    // chi-square quantiles at 0.683 (not Stable32's own, see allan_confidence.rs for those) the
    // limits stay within 5e-3 of Stable32's.
    let f = read_column("allantools/ocxo/ocxo_frequency.txt");
    let y: Vec<f64> = f.iter().map(|v| v / 1e7 - 1.0).collect();
    let rows = stable32("allantools/ocxo/oadev_octave.txt");
    let factors: Vec<usize> = rows.iter().map(|r| r.0).collect();
    let curve = overlapping_adev(&y, 1.0, &TauGrid::Explicit(factors)).unwrap();
    let ci = confidence_intervals(&y, &curve, 0.683);
    for (i, (af, _, alpha, low, sigma, high)) in rows.iter().enumerate() {
        assert_eq!(ci.alpha[i], *alpha, "AF {af}: noise type");
        let ours = (ci.low[i] / curve.adev[i], ci.high[i] / curve.adev[i]);
        let theirs = (low / sigma, high / sigma);
        assert!(
            (ours.0 / theirs.0 - 1.0).abs() < 5e-3,
            "AF {af}: low {ours:?} vs {theirs:?}"
        );
        assert!(
            (ours.1 / theirs.1 - 1.0).abs() < 5e-3,
            "AF {af}: high {ours:?} vs {theirs:?}"
        );
        assert!(ci.low[i] < curve.adev[i] && curve.adev[i] < ci.high[i]);
    }
}

fn white_plus_walk(n: usize, rate: f64, white: f64, walk: f64, seed: u64) -> Vec<f64> {
    let mut rng = named_rng(seed, "allan-terms");
    let dt = 1.0 / rate;
    let mut b = 0.0;
    (0..n)
        .map(|_| {
            let z1: f64 = StandardNormal.sample(&mut rng);
            let z2: f64 = StandardNormal.sample(&mut rng);
            b += walk * dt.sqrt() * z2;
            b + white / dt.sqrt() * z1
        })
        .collect()
}

#[test]
fn noise_terms_recover_white_noise_and_rate_random_walk_densities() {
    // N = 1e-3, K = 1e-5 at 100 Hz for 2e6 samples: the white region (slope −½) spans
    // τ ≲ 10 s and the walk (slope +½) τ ≳ 1000 s. Each reading averages many τ whose
    // individual relative errors are ~1/√(2 n_terms/m) ≤ 10 %; 10 % on N and 25 % on K (few
    // long-τ points carry it) are three to four standard errors.
    let y = white_plus_walk(2_000_000, 100.0, 1e-3, 1e-5, 5);
    let curve = overlapping_adev(&y, 100.0, &TauGrid::Octave).unwrap();
    let terms = fit_noise_terms(&curve, &confidence_intervals(&y, &curve, 0.683));
    let n = terms.random_walk.expect("white region");
    assert!((n.value / 1e-3 - 1.0).abs() < 0.10, "N {}", n.value);
    let k = terms.rate_random_walk.expect("walk region");
    assert!((k.value / 1e-5 - 1.0).abs() < 0.25, "K {}", k.value);
    assert!(
        terms.bias_instability.is_ok(),
        "the floor between them reads as bias instability"
    );
}

/// The oracle of the real runs: the line σ = N/√τ fitted by least squares to ln σ over the
/// octave points with 0.1 ≤ τ ≤ 10 s, its slope fixed at −½, so ln N = mean(ln σ_i + ½ ln τ_i).
fn minus_half_line_over_0p1_to_10_s(curve: &AllanCurve) -> f64 {
    let readings: Vec<f64> = (0..curve.tau_s.len())
        .filter(|&i| (0.1..=10.0).contains(&curve.tau_s[i]))
        .map(|i| curve.adev[i].ln() + 0.5 * curve.tau_s[i].ln())
        .collect();
    assert!(readings.len() >= 5, "octave grid from 0.01 s");
    (readings.iter().sum::<f64>() / readings.len() as f64).exp()
}

#[test]
fn white_noise_agrees_with_the_minus_half_line_on_every_adis16405_run() {
    // ARW (gyros) and VRW (accelerometers) of both static ADIS16405 runs against the −½ line
    // fitted over τ = 0.1-10 s. 10 % is the tolerance: the accelerometer curves are not
    // straight there (a bump at τ = 0.64 s, σ√τ between 0.75 and 1.2 times the line), so a
    // reading over a sub-region may differ by that much; the estimate's own statistical error
    // is below 1 % (10^6 samples). Before, the density averaged every point of slope near −½
    // anywhere (1300-2600 s too) and came out at 0.90-1.58 times the line.
    for run in [1, 2] {
        for (channel, y) in adis_16405_run(run).iter().enumerate() {
            let curve = overlapping_adev(y, 100.0, &TauGrid::Octave).unwrap();
            let limits = confidence_intervals(y, &curve, 0.683);
            let n = fit_noise_terms(&curve, &limits)
                .random_walk
                .expect("white region");
            let line = minus_half_line_over_0p1_to_10_s(&curve);
            assert!(
                (n.value / line - 1.0).abs() < 0.10,
                "run {run} channel {channel}: N {} vs line {line} over {}-{} s",
                n.value,
                n.tau_min_s,
                n.tau_max_s
            );
            let ci = n.ci.expect("interval");
            assert!(ci.low < n.value && n.value < ci.high, "{ci:?}");
            assert!(n.tau_max_s < 100.0, "one short-τ region: {n:?}");
        }
    }
}

#[test]
fn white_noise_equals_the_simulated_density_on_every_chamber_channel() {
    // The demo's 0 °C chamber record (built-in ADIS16364-like profile, seed 2009, 3 h; here at
    // 100 Hz), whose Gauss-Markov biases (Tc 144-375 s) give a second slope −½ region at
    // τ ≫ Tc that the old reading averaged in (1.29-1.66 × the truth on 4 of 6 channels). The
    // reading over τ = 0.16-20 s has a relative standard error under 1 %, and the Gauss-Markov
    // rise adds under 2 % to σ at 20 s: 5 % is the tolerance, with margin.
    use thermonav::sensor::adis16364_like;
    use thermonav::sim::chamber::{
        ChamberRun, ChamberTemperature, ChamberWander, calgary, simulate_chamber_run,
    };
    use thermonav::sim::clock::SampleClock;
    let run = ChamberRun {
        temperature: ChamberTemperature::SetPoint { temperature_c: 0.0 },
        unit: thermonav::sim::unit::SimulatedUnit::default(),
        power_on: 1,
        duration_s: 10_800.0,
        clock: SampleClock::new(100.0, 50e-6, 0.0).unwrap(),
        site: calgary(),
        wander: ChamberWander {
            sigma_c: 0.05,
            correlation_time_s: 600.0,
        },
        seed: 2009,
    };
    let record = simulate_chamber_run(&adis16364_like(), &run).unwrap();
    for (channel, truth) in &record.truth.channels {
        let y = record.series.channel(*channel);
        let curve = overlapping_adev(y, 100.0, &TauGrid::Octave).unwrap();
        let terms = fit_noise_terms(&curve, &confidence_intervals(y, &curve, 0.683));
        let n = terms.random_walk.expect("white region");
        let ratio = n.value / truth.white_noise_density;
        assert!((ratio - 1.0).abs() < 0.05, "{channel:?}: {ratio} ({n:?})");
        assert!(n.tau_max_s < truth.gauss_markov.correlation_time_s);
    }
}

/// White noise of density `white` plus a first-order Gauss-Markov process (σ, Tc), exactly
/// discretised: b_k = φ b_{k−1} + σ √(1 − φ²) w_k, φ = exp(−dt/Tc).
fn white_plus_gauss_markov(n: usize, rate: f64, white: f64, gm: (f64, f64), seed: u64) -> Vec<f64> {
    let mut rng = named_rng(seed, "allan-white-gm");
    let (sigma, tc) = gm;
    let dt = 1.0 / rate;
    let phi = (-dt / tc).exp();
    let mut b = sigma * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng);
    (0..n)
        .map(|_| {
            let z1: f64 = StandardNormal.sample(&mut rng);
            let z2: f64 = StandardNormal.sample(&mut rng);
            b = phi * b + sigma * (1.0 - phi * phi).sqrt() * z2;
            b + white / dt.sqrt() * z1
        })
        .collect()
}

#[test]
fn white_noise_and_gauss_markov_give_no_rate_random_walk_and_a_bound_on_b() {
    // Closed form (IEEE 952 Annex C): white + Gauss-Markov has no slope +½ at τ ≫ Tc, where
    // the curve falls as √(2σ²Tc/τ); its minimum is the longest τ, so B is only bounded.
    // (1) white-dominated (N 1e-3, σ 1e-4, Tc 20 s): the rise never reaches +½;
    // (2) Gauss-Markov-dominated (N 1e-4, σ 1e-2, Tc 100 s): slope +½ at τ ≈ 1-30 s, then the
    //     peak near 190 s and the fall; the +½ stretch is not a random walk (its minimum is
    //     the white-to-Gauss-Markov crossover, inside the curve).
    for (white, gm, seed) in [(1e-3, (1e-4, 20.0), 11), (1e-4, (1e-2, 100.0), 12)] {
        let y = white_plus_gauss_markov(400_000, 10.0, white, gm, seed);
        let curve = overlapping_adev(&y, 10.0, &TauGrid::Octave).unwrap();
        let terms = fit_noise_terms(&curve, &confidence_intervals(&y, &curve, 0.683));
        let reason = terms.rate_random_walk.expect_err("no K").reason;
        assert!(reason.contains("slope +0.5"), "{reason}");
        if seed == 12 {
            // The white-to-Gauss-Markov crossover (τ ≈ 0.2 s) is this curve's minimum.
            continue;
        }
        let b = terms.bias_instability.expect("bounded");
        let last = curve.adev.len() - 1;
        assert_eq!(b.bound, Bound::AtMost, "{b:?}");
        assert_eq!(b.tau_min_s, curve.tau_s[last]);
        let expected = curve.adev[last] / BIAS_INSTABILITY_FACTOR;
        assert!((b.value / expected - 1.0).abs() < 1e-12);
    }
}

#[test]
fn bias_instability_at_a_falling_curve_end_is_an_upper_bound() {
    // A closed-form white-noise curve σ = N/√τ (no floor in range): the minimum is the last
    // point, so B is at most σ_last / 0.664, flagged as a bound, with the point's limits.
    let tau_s: Vec<f64> = (0..12).map(|k| 0.01 * 2f64.powi(k)).collect();
    let adev: Vec<f64> = tau_s.iter().map(|t| 1e-3 / t.sqrt()).collect();
    let curve = AllanCurve {
        averaging_factor: (0..12).map(|k| 1 << k).collect(),
        n_terms: vec![1000; 12],
        n_samples: 100_000,
        tau0_s: 0.01,
        tau_s,
        adev: adev.clone(),
    };
    let limits = AllanIntervals {
        level: 0.683,
        alpha: vec![0; 12],
        edf: vec![100.0; 12],
        low: adev.iter().map(|a| a * 0.9).collect(),
        high: adev.iter().map(|a| a * 1.1).collect(),
    };
    let terms = fit_noise_terms(&curve, &limits);
    let b = terms.bias_instability.unwrap();
    assert_eq!(b.bound, Bound::AtMost);
    assert!((b.value / (adev[11] / BIAS_INSTABILITY_FACTOR) - 1.0).abs() < 1e-12);
    let ci = b.ci.unwrap();
    assert!((ci.low / b.value - 0.9).abs() < 1e-12 && (ci.high / b.value - 1.1).abs() < 1e-12);
    // The line itself is read exactly over τ ≥ 10 samples (m = 16 … 2048).
    let n = terms.random_walk.unwrap();
    assert!((n.value / 1e-3 - 1.0).abs() < 1e-12 && n.tau_min_s == 0.16 && n.points == 8);
    assert!(terms.rate_random_walk.is_err() && terms.quantization.is_err());
}

#[test]
fn simulated_white_gauss_markov_and_walk_follow_the_theoretical_curve() {
    // A chamber record from the simulator with white noise, a Gauss-Markov bias and a bias
    // random walk (every other error off), against the closed-form sum of the three Allan
    // variances. The estimate's relative error at τ is about 1/√(2 edf); 4 of those or 3 %.
    use thermonav::sensor::{ChannelProfile, GaussMarkovPoint, adis16364_like};
    use thermonav::sim::chamber::{ChamberRun, ChamberWander, calgary, simulate_chamber_run};
    use thermonav::sim::clock::SampleClock;
    let (white, sigma, tc, walk) = (2e-3, 5e-4, 20.0, 2e-6);
    let bias = GaussMarkovPoint {
        temperature_c: 20.0,
        correlation_time_s: tc,
        sigma,
    };
    let profile =
        adis16364_like().with_every_channel(&ChannelProfile::stochastic_only(white, bias, walk));
    let run = ChamberRun {
        temperature: thermonav::sim::chamber::ChamberTemperature::SetPoint {
            temperature_c: 20.0,
        },
        unit: thermonav::sim::unit::SimulatedUnit::default(),
        power_on: 1,
        duration_s: 30_000.0,
        clock: SampleClock::new(50.0, 0.0, 0.0).unwrap(),
        site: calgary(),
        wander: ChamberWander {
            sigma_c: 0.05,
            correlation_time_s: 600.0,
        },
        seed: 8,
    };
    let record = simulate_chamber_run(&profile, &run).unwrap();
    let y = record.series.channel(thermonav::imu::Channel::Gx);
    let curve: AllanCurve = overlapping_adev(y, 50.0, &TauGrid::Octave).unwrap();
    let ci = confidence_intervals(y, &curve, 0.683);
    for i in 0..curve.tau_s.len() {
        let tau = curve.tau_s[i];
        if tau > 2000.0 {
            break;
        }
        let theory = (avar_white(white, tau)
            + avar_gauss_markov(sigma, tc, tau)
            + avar_random_walk(walk, tau))
        .sqrt();
        let relative_se = (2.0 / ci.edf[i]).sqrt() / 2.0;
        let tolerance = (4.0 * relative_se).max(0.03);
        assert!(
            (curve.adev[i] / theory - 1.0).abs() < tolerance,
            "τ {tau}: {} vs {theory} (tol {tolerance})",
            curve.adev[i]
        );
    }
}

#[test]
fn bad_input_is_refused() {
    assert!(overlapping_adev(&[1.0, 2.0], 1.0, &TauGrid::Octave).is_err());
    assert!(overlapping_adev(&[1.0, f64::NAN, 3.0, 4.0], 1.0, &TauGrid::Octave).is_err());
    assert!(overlapping_adev(&[1.0, 2.0, 3.0, 4.0], 0.0, &TauGrid::Octave).is_err());
    assert!(overlapping_adev(&[1.0, 2.0, 3.0, 4.0], 1.0, &TauGrid::Explicit(vec![10])).is_err());
    // A constant series has zero deviation, not NaN.
    let flat = overlapping_adev(&[2.5; 100], 1.0, &TauGrid::Octave).unwrap();
    assert!(flat.adev.iter().all(|&v| v == 0.0));
}
