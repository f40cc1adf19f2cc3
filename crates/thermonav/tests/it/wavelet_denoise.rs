//! Wavelet de-noising against PyWavelets 1.9 (tools/oracles/wavelet_pywt.py): the Daubechies
//! filters, `dwt_max_level`, `wavedec`/`waverec` in modes symmetric and periodization,
//! `threshold`, and VisuShrink written out in numpy; the SURE and universal thresholds against
//! slow references written here from Donoho & Johnstone's definitions.
//!
//! Tolerances. Filters: 1e-14 absolute, the accuracy of the spectral factorisation in f64 up to
//! db10 (PyWavelets' tables are exact to the last digit). Transforms: 1e-12 × max(1, max |x|):
//! a coefficient at level L is L nested sums of F ≤ 20 products of O(1) terms, so rounding is
//! about L F ε ≈ 10 × 20 × 2.2e-16 ≈ 4e-14 of the signal's scale, and the two libraries add
//! in different orders (and carry the filters' own 1e-15 differences); 1e-12 is the issue's
//! tolerance and 25 × above that.

use crate::allan::adis_16405_run;
use crate::allan_family::numbers;
use crate::oracle_json;
use rand_distr::{Distribution, StandardNormal, Uniform};
use serde_json::Value;
use thermonav::imu::Channel;
use thermonav::rng::{SimRng, named_rng};
use thermonav::signal::wavelet::daubechies::Daubechies;
use thermonav::signal::wavelet::denoise::{DecompositionLevel, WaveletDenoise, denoise};
use thermonav::signal::wavelet::threshold::{
    ThresholdRule, Thresholding, hybrid_threshold_unit, noise_sigma_mad, sure_threshold_unit,
};
use thermonav::signal::wavelet::transform::{
    Decomposition, ExtensionMode, max_level, wavedec, waverec,
};
use thermonav::stoch::bank::GaussMarkovSource;
use thermonav::stoch::characterize::{
    CharacterizeError, CharacterizeSettings, Denoiser, characterize,
};
use thermonav::stoch::streaming::{StreamingCharacterizer, StreamingSettings};

fn mode_of(v: &Value) -> ExtensionMode {
    match v.as_str().expect("mode") {
        "symmetric" => ExtensionMode::Symmetric,
        "periodization" => ExtensionMode::Periodization,
        other => panic!("mode {other}"),
    }
}

fn wavelet_of(v: &Value) -> Daubechies {
    v.as_str().expect("name").parse().expect("dbN")
}

/// The series named in the oracle: a generated one stored in full, or the real slice read
/// from ../shared/data (its samples are not committed: CC BY-NC-SA).
fn series(oracle: &Value, name: &str) -> Vec<f64> {
    if let Some(stored) = oracle["series"].get(name) {
        return numbers(stored);
    }
    assert_eq!(name, "adis2_gyro_x");
    let slice = &oracle["real_slice"];
    assert_eq!(slice["column"], "Gyro_X");
    let start = slice["start"].as_u64().unwrap() as usize;
    let length = slice["length"].as_u64().unwrap() as usize;
    adis_16405_run(2)[0][start..start + length].to_vec()
}

/// |got − want| ≤ tol for every element, same length.
fn assert_close(got: &[f64], want: &[f64], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= tol, "{what}[{i}]: {g} vs {w}");
    }
}

fn scale_of(x: &[f64]) -> f64 {
    x.iter().fold(1.0, |m, v| m.max(v.abs()))
}

#[test]
fn daubechies_filters_equal_pywavelets_to_1e_14() {
    let oracle = oracle_json("wavelet_pywt.json");
    for order in 1..=Daubechies::MAX_ORDER {
        let bank = Daubechies::new(order).unwrap().filter_bank();
        let peer = &oracle["filter_banks"][format!("db{order}")];
        let ours = [&bank.dec_lo, &bank.dec_hi, &bank.rec_lo, &bank.rec_hi];
        for (k, filter) in ours.into_iter().enumerate() {
            assert_close(filter, &numbers(&peer[k]), 1e-14, &format!("db{order} {k}"));
        }
    }
}

#[test]
fn max_level_equals_dwt_max_level() {
    let oracle = oracle_json("wavelet_pywt.json");
    for row in oracle["max_level"].as_array().unwrap() {
        let [n, f, level] = [0, 1, 2].map(|i| row[i].as_u64().unwrap() as usize);
        assert_eq!(max_level(n, f), level, "n {n}, {f} taps");
    }
}

#[test]
fn wavedec_and_waverec_equal_pywavelets_to_1e_12() {
    let oracle = oracle_json("wavelet_pywt.json");
    let cases = oracle["transforms"].as_array().unwrap();
    assert!(cases.len() >= 40, "{} cases", cases.len());
    for case in cases {
        let x = series(&oracle, case["series"].as_str().unwrap());
        let (wavelet, mode) = (wavelet_of(&case["wavelet"]), mode_of(&case["mode"]));
        let level = case["level"].as_u64().unwrap() as usize;
        let what = format!("{} {wavelet} {mode:?} level {level}", case["series"]);
        let bank = wavelet.filter_bank();
        let ours = wavedec(&x, &bank, mode, level).unwrap();
        let peer: Vec<Vec<f64>> = case["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(numbers)
            .collect();
        let tol = 1e-12 * scale_of(&x);
        assert_close(ours.approximation(), &peer[0], tol, &format!("{what} cA"));
        for (j, (d, p)) in ours.details().iter().zip(&peer[1..]).enumerate() {
            assert_close(d, p, tol, &format!("{what} cD[{j}]"));
        }
        // waverec on PyWavelets' own coefficients, so the inverse is tested on its input.
        let theirs =
            Decomposition::from_parts(peer[0].clone(), peer[1..].to_vec(), &bank, mode, x.len());
        let back = waverec(&theirs.unwrap(), &bank);
        assert_close(
            &back,
            &numbers(&case["waverec"]),
            tol,
            &format!("{what} waverec"),
        );
    }
}

#[test]
fn waverec_of_coefficients_no_signal_produced_equals_pywavelets() {
    let oracle = oracle_json("wavelet_pywt.json");
    for case in oracle["waverec_of_random"].as_array().unwrap() {
        let (wavelet, mode) = (wavelet_of(&case["wavelet"]), mode_of(&case["mode"]));
        let bank = wavelet.filter_bank();
        let c: Vec<Vec<f64>> = case["coefficients"]
            .as_array()
            .unwrap()
            .iter()
            .map(numbers)
            .collect();
        let n = case["signal_len"].as_u64().unwrap() as usize;
        let decomposition =
            Decomposition::from_parts(c[0].clone(), c[1..].to_vec(), &bank, mode, n);
        let back = waverec(&decomposition.unwrap(), &bank);
        assert_close(
            &back,
            &numbers(&case["waverec"]),
            1e-12 * 4.0,
            &format!("{wavelet} {mode:?}"),
        );
    }
}

#[test]
fn soft_and_hard_thresholding_equal_pywt_threshold() {
    let oracle = oracle_json("wavelet_pywt.json");
    let x = numbers(&oracle["threshold"]["x"]);
    for case in oracle["threshold"]["cases"].as_array().unwrap() {
        let value = case["value"].as_f64().unwrap();
        let kind = match case["mode"].as_str().unwrap() {
            "soft" => Thresholding::Soft,
            _ => Thresholding::Hard,
        };
        let mut ours = x.clone();
        kind.apply_to(&mut ours, value);
        // Exact up to the last bit of sign(x)(|x| − λ) against x (1 − λ/|x|): 1e-15 relative.
        assert_close(
            &ours,
            &numbers(&case["out"]),
            1e-15 * scale_of(&x),
            &format!("{kind:?} {value}"),
        );
    }
}

#[test]
fn visushrink_equals_its_numpy_transcription() {
    let oracle = oracle_json("wavelet_pywt.json");
    for case in oracle["visushrink"].as_array().unwrap() {
        let x = series(&oracle, case["series"].as_str().unwrap());
        let settings = WaveletDenoise {
            wavelet: wavelet_of(&case["wavelet"]),
            level: DecompositionLevel::Max,
            mode: mode_of(&case["mode"]),
            rule: ThresholdRule::Universal,
            thresholding: match case["thresholding"].as_str().unwrap() {
                "soft" => Thresholding::Soft,
                _ => Thresholding::Hard,
            },
        };
        let out = denoise(&x, &settings).unwrap();
        let what = format!("{} {:?}", case["series"], settings);
        assert_eq!(out.level as u64, case["level"].as_u64().unwrap(), "{what}");
        let sigma = case["sigma"].as_f64().unwrap();
        assert!((out.noise_sigma / sigma - 1.0).abs() < 1e-12, "{what}: σ̂");
        let lambda = case["lambda"].as_f64().unwrap();
        assert!(
            out.thresholds
                .iter()
                .all(|t| (t / lambda - 1.0).abs() < 1e-12),
            "{what}: λ"
        );
        assert_close(
            &out.values,
            &numbers(&case["out"]),
            1e-12 * scale_of(&x),
            &what,
        );
    }
}

/// One standard normal draw.
fn gaussian(rng: &mut SimRng) -> f64 {
    StandardNormal.sample(rng)
}

/// Seeded bands: Gaussian noise with a few large coefficients, some exact zeros and ties.
fn bands(seed: u64) -> Vec<Vec<f64>> {
    let mut rng = named_rng(seed, "wavelet-denoise/bands");
    let unit = Uniform::new(0.0, 1.0).expect("interval");
    [1usize, 2, 7, 64, 255, 1000]
        .iter()
        .flat_map(|&d| [0.0, 0.05, 0.4].map(|share| (d, share)))
        .map(|(d, share)| {
            (0..d)
                .map(|i| {
                    let noise: f64 = StandardNormal.sample(&mut rng);
                    match i % 17 {
                        3 => 0.0,
                        5 => 1.25,
                        _ if unit.sample(&mut rng) < share => 8.0 * noise,
                        _ => noise,
                    }
                })
                .collect()
        })
        .collect()
}

/// √(2 ln d), 0 for d ≤ 1.
fn slow_universal(d: usize) -> f64 {
    if d > 1 {
        (2.0 * (d as f64).ln()).sqrt()
    } else {
        0.0
    }
}

/// SURE(t) = d − 2 #{|x_i| ≤ t} + Σ min(|x_i|, t)², summed directly (Donoho & Johnstone 1995,
/// eq. 11), minimised by trying t = 0 and every |x_i| up to √(2 ln d): O(d²).
fn slow_sure(x: &[f64]) -> f64 {
    let d = x.len() as f64;
    let bound = slow_universal(x.len());
    let risk = |t: f64| {
        let kept = x.iter().filter(|v| v.abs() <= t).count() as f64;
        d - 2.0 * kept + x.iter().map(|v| v.abs().min(t).powi(2)).sum::<f64>()
    };
    let mut candidates: Vec<f64> = std::iter::once(0.0)
        .chain(x.iter().map(|v| v.abs()))
        .filter(|&t| t <= bound)
        .collect();
    candidates.sort_by(f64::total_cmp);
    let mut best = (f64::INFINITY, 0.0);
    for t in candidates {
        let r = risk(t);
        if r < best.0 - 1e-12 * d {
            best = (r, t);
        }
    }
    best.1
}

#[test]
fn sure_threshold_equals_the_slow_minimiser_of_stein_risk() {
    for band in bands(1995) {
        let ours = sure_threshold_unit(&band);
        let slow = slow_sure(&band);
        assert!(
            (ours - slow).abs() < 1e-12,
            "d {}: {ours} vs {slow}",
            band.len()
        );
    }
}

#[test]
fn hybrid_threshold_follows_the_sparsity_test() {
    for band in bands(1994) {
        let d = band.len() as f64;
        let s2 = (band.iter().map(|v| v * v).sum::<f64>() - d) / d;
        let gamma = d.log2().powf(1.5) / d.sqrt();
        let want = if s2 <= gamma {
            slow_universal(band.len())
        } else {
            slow_sure(&band)
        };
        let ours = hybrid_threshold_unit(&band);
        assert!(
            (ours - want).abs() < 1e-12,
            "d {}: {ours} vs {want}",
            band.len()
        );
    }
}

#[test]
fn universal_threshold_is_mad_sigma_times_sqrt_2_ln_n() {
    for band in bands(1993).into_iter().filter(|b| b.len() > 2) {
        let mut magnitudes: Vec<f64> = band.iter().map(|v| v.abs()).collect();
        magnitudes.sort_by(f64::total_cmp);
        let m = magnitudes.len();
        let median = (magnitudes[(m - 1) / 2] + magnitudes[m / 2]) / 2.0;
        let sigma = median / 0.6745;
        assert!((noise_sigma_mad(&band) - sigma).abs() <= 1e-15 * sigma);
        let n = 3 * m + 1;
        let lambda = ThresholdRule::Universal.threshold(&band, sigma, n);
        assert!((lambda - sigma * (2.0 * (n as f64).ln()).sqrt()).abs() <= 1e-15 * lambda);
    }
}

#[test]
fn sure_denoising_is_the_transform_with_the_slow_thresholds() {
    let mut rng = named_rng(42, "wavelet-denoise/sure");
    let x: Vec<f64> = (0..1537)
        .map(|i| (i as f64 / 40.0).sin() * 3.0 + gaussian(&mut rng))
        .collect();
    for (rule, hybrid) in [
        (ThresholdRule::Sure, false),
        (ThresholdRule::SureHybrid, true),
    ] {
        let settings = WaveletDenoise {
            rule,
            thresholding: Thresholding::Hard,
            ..WaveletDenoise::default()
        };
        let out = denoise(&x, &settings).unwrap();
        let bank = settings.wavelet.filter_bank();
        let mut reference = wavedec(&x, &bank, settings.mode, out.level).unwrap();
        let sigma = noise_sigma_mad(reference.finest_details());
        for band in reference.details_mut() {
            let unit: Vec<f64> = band.iter().map(|v| v / sigma).collect();
            let t = if hybrid {
                hybrid_threshold_unit(&unit)
            } else {
                slow_sure(&unit)
            };
            Thresholding::Hard.apply_to(band, sigma * t);
        }
        let mut back = waverec(&reference, &bank);
        back.truncate(x.len());
        assert_close(
            &out.values,
            &back,
            1e-12 * scale_of(&x),
            &format!("{rule:?}"),
        );
    }
}

#[test]
fn every_rule_reduces_the_error_on_a_noisy_smooth_signal() {
    let mut rng = named_rng(7, "wavelet-denoise/recovery");
    let clean: Vec<f64> = (0..4096)
        .map(|i| (i as f64 / 300.0).sin() + (i as f64 / 71.0).cos() * 0.5)
        .collect();
    let noisy: Vec<f64> = clean.iter().map(|c| c + 0.3 * gaussian(&mut rng)).collect();
    let mse = |y: &[f64]| {
        y.iter()
            .zip(&clean)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            / y.len() as f64
    };
    for rule in [
        ThresholdRule::Universal,
        ThresholdRule::Sure,
        ThresholdRule::SureHybrid,
    ] {
        for thresholding in [Thresholding::Soft, Thresholding::Hard] {
            let settings = WaveletDenoise {
                rule,
                thresholding,
                ..WaveletDenoise::default()
            };
            let out = denoise(&noisy, &settings).unwrap();
            assert!(
                mse(&out.values) < 0.2 * mse(&noisy),
                "{rule:?} {thresholding:?}: {}",
                mse(&out.values)
            );
            assert!(
                (out.noise_sigma / 0.3 - 1.0).abs() < 0.1,
                "σ̂ {}",
                out.noise_sigma
            );
        }
    }
}

/// `characterize` with the wavelet de-noiser: the bank says so (and not Kaiser), the series the
/// AR fit sees changes, the exact likelihood (on raw block means) does not.
#[test]
fn characterisation_records_the_wavelet_denoiser_and_only_the_ar_side_changes() {
    let series = crate::streaming::chamber_record(1200.0);
    let kaiser = CharacterizeSettings::default();
    let wavelet = CharacterizeSettings {
        denoise: Denoiser::Wavelet(WaveletDenoise::default()),
        ..kaiser.clone()
    };
    let (k, _) = characterize(&series, 10.0, "sim", &kaiser).unwrap();
    let (w, _) = characterize(&series, 10.0, "sim", &wavelet).unwrap();
    assert!(k.preprocessing.filter.is_some() && k.preprocessing.wavelet.is_none());
    let summary = w.preprocessing.wavelet.as_ref().expect("wavelet recorded");
    assert!(w.preprocessing.filter.is_none());
    assert_eq!(
        (summary.wavelet.as_str(), summary.threshold.as_str()),
        ("db4", "universal")
    );
    assert_eq!(summary.level, max_level(series.len(), 8));
    assert_eq!(w.preprocessing.decimation_factor, 50);
    for channel in Channel::ALL {
        let (km, wm) = (&k.channels[&channel], &w.channels[&channel]);
        assert_eq!(
            km.gauss_markov.get(GaussMarkovSource::IRREGULAR_ML),
            wm.gauss_markov.get(GaussMarkovSource::IRREGULAR_ML)
        );
        assert_ne!(km.ar.coefficients, wm.ar.coefficients, "{channel:?}");
    }
}

/// Streaming cannot de-noise by wavelets (the transform needs the whole record): refused.
#[test]
fn streamed_characterisation_refuses_the_wavelet_denoiser() {
    let series = crate::streaming::chamber_record(200.0);
    let settings = CharacterizeSettings {
        denoise: Denoiser::Wavelet(WaveletDenoise::default()),
        ..CharacterizeSettings::default()
    };
    let streaming = StreamingSettings {
        prefix_samples: 4096,
        ..StreamingSettings::default()
    };
    let mut stream = StreamingCharacterizer::new(settings, streaming);
    let error = stream.push(&crate::streaming::piece(&series, 0..series.len()));
    assert!(matches!(error, Err(CharacterizeError::Settings(m)) if m.contains("whole record")));
}
