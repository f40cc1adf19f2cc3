//! The IEEE Std 952 noise-term fit against closed forms (simulated white noise and rate
//! random walk of known density), the real ADIS16405 run and imu_utils' fits of six IMUs.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use thermonav::stoch::allan::{
    AllanCurve, FitSettings, TauGrid, TermEstimate, fit_noise_terms, overlapping_adev,
};
use thermonav::units;

use super::data;

fn relative_error(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn normals(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| StandardNormal.sample(&mut rng)).collect()
}

/// NIST SP 1065 Table 5 EDF of the overlapping Allan variance, white FM.
fn edf_white_fm(n: f64, m: f64) -> f64 {
    (3.0 * (n - 1.0) / (2.0 * m) - 2.0 * (n - 2.0) / n) * 4.0 * m * m / (4.0 * m * m + 5.0)
}

/// NIST SP 1065 Table 5 EDF of the overlapping Allan variance, random-walk FM.
fn edf_random_walk_fm(n: f64, m: f64) -> f64 {
    (n - 2.0) / m * ((n - 1.0).powi(2) - 3.0 * m * (n - 1.0) + 4.0 * m * m) / (n - 3.0).powi(2)
}

/// Bound on the standard deviation of the fitted ln C: the fit is the mean of ln sigma_i over
/// the region, each with sd ≈ 1/sqrt(2 edf_i); even fully correlated, the sd of the mean is
/// at most the mean of the sd_i.
fn log_level_sd_bound(curve: &AllanCurve, term: &TermEstimate, edf: impl Fn(f64) -> f64) -> f64 {
    let in_region =
        |i: &usize| curve.tau_s[*i] >= term.tau_min_s && curve.tau_s[*i] <= term.tau_max_s;
    let sds: Vec<f64> = (0..curve.tau_s.len())
        .filter(in_region)
        .map(|i| (2.0 * edf(curve.averaging_factor[i] as f64)).sqrt().recip())
        .collect();
    sds.iter().sum::<f64>() / sds.len() as f64
}

// Closed form: discrete white noise of density N (variance N^2 / tau0 per sample) has
// sigma^2(tau) = N^2 / tau exactly. Each point with edf >= 30 must lie within 5 standard
// deviations of ln sigma (1/sqrt(2 edf), SP 1065 white-FM EDF) of the theory, and the
// fitted N within 4 times the bound on the fit's standard deviation.
#[test]
fn white_noise_density_is_recovered() {
    let (rate_hz, density) = (100.0_f64, 0.01);
    let y: Vec<f64> = normals(1 << 18, 11)
        .iter()
        .map(|w| density * rate_hz.sqrt() * w)
        .collect();
    let n = y.len() as f64;
    let curve = overlapping_adev(&y, rate_hz, &TauGrid::Octave).unwrap();
    for (i, &m) in curve.averaging_factor.iter().enumerate() {
        let edf = edf_white_fm(n, m as f64);
        if edf >= 30.0 {
            let deviation = (curve.adev[i] / (density / curve.tau_s[i].sqrt())).ln();
            assert!(
                deviation.abs() < 5.0 / (2.0 * edf).sqrt(),
                "m={m}: {deviation}"
            );
        }
    }
    let terms = fit_noise_terms(&curve, &FitSettings::default()).unwrap();
    let walk = terms
        .random_walk
        .expect("white noise is one long slope -1/2 region");
    assert_eq!(walk.tau_min_s, 0.01);
    assert!(walk.n_points >= 12, "{walk:?}");
    let tolerance = 4.0 * log_level_sd_bound(&curve, &walk, |m| edf_white_fm(n, m));
    assert!(
        relative_error(walk.value, density) < tolerance,
        "{walk:?}, tol {tolerance}"
    );
    assert_eq!(terms.quantization, None);
    assert_eq!(terms.rate_ramp, None);
}

// Closed form: white noise N plus a discrete random walk of the rate with increments of
// variance K^2 tau0 has sigma^2 = N^2/tau + K^2 tau/3 (+ K^2 tau0 / (6m), negligible here).
// The fixed-slope line through a region ignores the other term, which raises ln sigma_i by
// exactly 0.5 ln(1 + other/this); so each coefficient is expected at truth * exp(mean of that
// over the region), within 4 times the bound on the fit's statistical standard deviation.
#[test]
fn rate_random_walk_and_white_noise_are_both_recovered() {
    let (rate_hz, n_density, k_density) = (100.0_f64, 1e-3, 1e-2);
    let tau0 = 1.0 / rate_hz;
    let white = normals(1 << 20, 21);
    let steps = normals(1 << 20, 22);
    let mut walk = 0.0;
    let y: Vec<f64> = white
        .iter()
        .zip(&steps)
        .map(|(w, s)| {
            walk += k_density * tau0.sqrt() * s;
            n_density / tau0.sqrt() * w + walk
        })
        .collect();
    let n = y.len() as f64;
    // Octave factors up to N/64, so the last point still has ~60 degrees of freedom.
    let ms: Vec<usize> = (0..=14).map(|k| 1 << k).collect();
    let curve = overlapping_adev(&y, rate_hz, &TauGrid::Explicit(ms)).unwrap();
    let terms = fit_noise_terms(&curve, &FitSettings::default()).unwrap();
    let expected = |truth: f64, term: &TermEstimate, other_over_this: &dyn Fn(f64) -> f64| {
        let region: Vec<f64> = curve
            .tau_s
            .iter()
            .copied()
            .filter(|t| *t >= term.tau_min_s && *t <= term.tau_max_s)
            .collect();
        let bias = region
            .iter()
            .map(|&t| 0.5 * (1.0 + other_over_this(t)).ln())
            .sum::<f64>()
            / region.len() as f64;
        truth * bias.exp()
    };
    let k_over_n = |t: f64| (k_density * k_density * t / 3.0) / (n_density * n_density / t);

    let walk_term = terms
        .random_walk
        .expect("white noise dominates the short taus");
    let tolerance = 4.0 * log_level_sd_bound(&curve, &walk_term, |m| edf_white_fm(n, m));
    let expected_n = expected(n_density, &walk_term, &k_over_n);
    assert!(
        relative_error(walk_term.value, expected_n) < tolerance,
        "{walk_term:?} vs {expected_n} tol {tolerance}"
    );

    let rrw = terms
        .rate_random_walk
        .expect("rate random walk dominates the long taus");
    let tolerance = 4.0 * log_level_sd_bound(&curve, &rrw, |m| edf_random_walk_fm(n, m));
    let expected_k = expected(k_density, &rrw, &|t| 1.0 / k_over_n(t));
    assert!(
        relative_error(rrw.value, expected_k) < tolerance,
        "{rrw:?} vs {expected_k} tol {tolerance}"
    );
    assert!(
        tolerance < 0.2,
        "the check must stay informative: {tolerance}"
    );
}

// Oracles for the real ADIS16405 run (gyros in deg/s): the data README's angle random walk
// "≈ 2.4-2.5 deg/√h" (a rounded reading; Gyro_Y reads 2.6), so [2.3, 2.7]; and allantools'
// own curve read at tau = 1.28 s (N ≈ sigma(tau) sqrt(tau)), within 3 % (our N is a line
// through the whole slope -1/2 region, 0.02-20 s, not one point).
#[test]
fn adis16405_gyro_angle_random_walk() {
    let (names, columns) = data::adis16405_run1();
    let oracle = data::lines("peer-results-on-real-data/adis_16405_imu1_oadev_allantools.csv");
    for (name, y) in names
        .iter()
        .zip(&columns)
        .filter(|(n, _)| n.starts_with("Gyro"))
    {
        let rad_per_s: Vec<f64> = y.iter().map(|&v| units::deg_to_rad(v)).collect();
        let curve = overlapping_adev(&rad_per_s, 100.0, &TauGrid::Octave).unwrap();
        let report = fit_noise_terms(&curve, &FitSettings::default())
            .unwrap()
            .gyro_report();
        let arw = report.arw_deg_per_sqrt_h.unwrap();
        assert!((2.3..=2.7).contains(&arw), "{name}: {arw} deg/√h");
        let row = oracle
            .iter()
            .map(|l| l.split(',').collect::<Vec<_>>())
            .find(|f| f[0] == name && f[1] == "128")
            .unwrap();
        let sigma_deg_per_s: f64 = row[4].parse().unwrap();
        let allantools_arw = sigma_deg_per_s * 1.28_f64.sqrt() * units::SECONDS_PER_HOUR.sqrt();
        assert!(
            relative_error(arw, allantools_arw) < 0.03,
            "{name}: {arw} vs {allantools_arw}"
        );
    }
}

fn imu_utils_yaml(imu: &str, axis: &str, key: &str) -> f64 {
    let lines = data::lines(&format!("imu-utils/{imu}_imu_param.yaml"));
    let start = lines
        .iter()
        .position(|l| l.trim() == format!("{axis}-axis:"))
        .unwrap();
    let line = lines[start..]
        .iter()
        .find(|l| l.trim().starts_with(key))
        .unwrap();
    line.split(':').nth(1).unwrap().trim().parse().unwrap()
}

fn imu_utils_gyro_curve(imu: &str, axis: &str) -> AllanCurve {
    let tau_s = data::column(&format!("imu-utils/data_{imu}_gyr_t.txt"));
    // imu_utils writes gyro deviations in "deg/h" as rad/s * 57.3 * 3600: undo exactly that.
    let adev: Vec<f64> = data::column(&format!("imu-utils/data_{imu}_gyr_{axis}.txt"))
        .iter()
        .map(|v| v / (57.3 * 3600.0))
        .collect();
    let n = tau_s.len();
    AllanCurve {
        tau_s,
        adev,
        n_terms: vec![0; n],
        averaging_factor: vec![0; n],
        sample_rate_hz: f64::NAN,
        n_samples: 0,
        warnings: Vec::new(),
    }
}

// Oracle: imu_utils (gaowenliang/imu_utils) fits sigma^2 = Q^2/tau^2 + N^2/tau + B^2 + K^2 tau
// + R^2 tau^2 to the same curves and reports gyr_n = sqrt(fitted sigma^2 at tau = 1 s) and
// gyr_w = the minimum of its fitted curve (both rad/s; BMI160's gyr_n also carries a
// sqrt(sample rate) factor, and its rate is not recorded, so its gyr_n is not comparable).
// Comparable: (1) our N (the slope -1/2 line alone) must lie between the white part of their
// sigma(1 s), roughly sqrt(gyr_n^2 - gyr_w^2), and gyr_n itself, with 5 % slack for their fit;
// (2) our floor (data minimum) vs their fitted minimum: each within 25 % (a five-term model
// through noisy long-tau points is not the data minimum), and the median ratio within 5 %.
#[test]
fn imu_utils_curves_give_comparable_terms() {
    let mut floor_ratios = Vec::new();
    for imu in ["16448", "A3", "N3", "BMI160", "gx4", "xsens"] {
        for axis in ["x", "y", "z"] {
            let curve = imu_utils_gyro_curve(imu, axis);
            let terms = fit_noise_terms(&curve, &FitSettings::default()).unwrap();
            let (gyr_n, gyr_w) = (
                imu_utils_yaml(imu, axis, "gyr_n"),
                imu_utils_yaml(imu, axis, "gyr_w"),
            );
            if imu != "BMI160" {
                let n = terms.random_walk.unwrap().value;
                let white_part = (gyr_n * gyr_n - gyr_w * gyr_w).sqrt();
                assert!(
                    n >= 0.95 * white_part && n <= 1.05 * gyr_n,
                    "{imu} {axis}: N {n:e}, gyr_n {gyr_n:e}"
                );
            }
            if let Some(b) = terms.bias_instability {
                let floor = b.value * (2.0 * std::f64::consts::LN_2 / std::f64::consts::PI).sqrt();
                let ratio = floor / gyr_w;
                assert!(
                    (0.75..=1.25).contains(&ratio),
                    "{imu} {axis}: floor ratio {ratio}"
                );
                floor_ratios.push(ratio);
            }
        }
    }
    assert!(floor_ratios.len() >= 15);
    floor_ratios.sort_by(f64::total_cmp);
    let median = floor_ratios[floor_ratios.len() / 2];
    assert!(
        (0.95..=1.05).contains(&median),
        "median floor ratio {median}"
    );
}
