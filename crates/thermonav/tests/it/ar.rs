//! Autocorrelation and AR estimators against R, MATLAB, Stata, statsmodels, spectrum and numpy
//! (../shared/data/statsmodels, ../shared/data/spectrum, ../shared/data/peer-results-on-real-data,
//! tools/oracles/ar_least_squares.py).

use crate::{oracle_json, shared_column as column, shared_data};
use serde_json::Value;
use thermonav::stoch::acf::{Demean, autocorrelation, autocovariance, autocovariance_direct};
use thermonav::stoch::ar::order::{Criterion, Order, fit_ar_order};
use thermonav::stoch::ar::whiteness::ljung_box;
use thermonav::stoch::ar::{ArError, ArMethod, Intercept, conditional_ols, fit_ar, fit_ar_with};

fn num(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(num).collect()
}

fn json(path: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(shared_data(path)).expect("shared data present"))
        .expect("JSON")
}

fn sunspots() -> Vec<f64> {
    std::fs::read_to_string(shared_data("statsmodels/sunspots.csv"))
        .expect("sunspots present")
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .nth(1)
                .expect("two columns")
                .parse()
                .expect("number")
        })
        .collect()
}

fn x1000() -> Vec<f64> {
    column("statsmodels/xar2.txt")
        .iter()
        .map(|v| v / 1000.0)
        .collect()
}

fn assert_all_close(ours: &[f64], theirs: &[f64], tolerance: f64, what: &str) {
    assert_eq!(ours.len(), theirs.len(), "{what}: lengths");
    for (k, (a, b)) in ours.iter().zip(theirs).enumerate() {
        assert!((a - b).abs() <= tolerance, "{what}[{k}]: {a} vs {b}");
    }
}

// FFT against the direct sum: same estimator, two algorithms, rounding ~1e-13 relative.
#[test]
fn fft_autocovariance_equals_the_direct_sum() {
    let x = x1000();
    let fast = autocovariance(&x, 50, Demean::Subtract).unwrap();
    let slow = autocovariance_direct(&x, 50, Demean::Subtract).unwrap();
    assert_all_close(&fast, &slow, 1e-12 * slow[0], "autocovariance");
}

// MATLAB autocorr (biased, demeaned), printed to 8 decimals: 5e-9 is half the last digit.
#[test]
fn autocorrelation_matches_matlab() {
    let r = json("statsmodels/ar_reference.json");
    let x = x1000();
    let acf1000 = autocorrelation(&x, 20, Demean::Subtract).unwrap();
    assert_all_close(
        &acf1000,
        &nums(&r["matlab_acf_pacf_xar2"]["acf1000_lags0to20"]),
        5e-9,
        "acf x1000",
    );
    let acf100 = autocorrelation(&x[900..], 20, Demean::Subtract).unwrap();
    assert_all_close(
        &acf100,
        &nums(&r["matlab_acf_pacf_xar2"]["acf100_lags0to20"]),
        5e-9,
        "acf x100",
    );
}

// R ar.yw on sunspots (same estimator; R printed 17 digits): 1e-10.
#[test]
fn yule_walker_matches_r_on_sunspots() {
    let r = json("statsmodels/ar_reference.json");
    let model = fit_ar(&sunspots(), 4, ArMethod::YuleWalker).unwrap();
    assert_all_close(
        &model.coefficients,
        &nums(&r["yule_walker_sunspots_order4"]["expected_phi_from_R"]),
        1e-10,
        "phi",
    );
}

// MATLAB ar(x, p, 'yw') returns the A-polynomial (a = −phi), printed to 8 decimals: 5e-9.
#[test]
fn yule_walker_matches_matlab_at_orders_10_and_20() {
    let r = json("statsmodels/ar_reference.json");
    let x = x1000();
    for (data, order, key) in [
        (&x[900..], 10, "x100_order10"),
        (&x[..], 20, "x1000_order20"),
    ] {
        let model = fit_ar(data, order, ArMethod::YuleWalker).unwrap();
        let a = nums(&r["matlab_yule_walker_xar2"][key]["arcoef_A_polynomial"]);
        let phi: Vec<f64> = a[1..].iter().map(|v| -v).collect();
        assert_all_close(&model.coefficients, &phi, 5e-9, key);
    }
}

// R ar.burg on the MA(1) series, orders 1-5; statsmodels uses atol 1e-6 (R prints 7-8 digits).
#[test]
fn burg_matches_r_on_the_ma1_series() {
    let r = json("statsmodels/ar_reference.json");
    let y = column("statsmodels/burg_ma1_series.txt");
    for (p, expected) in r["burg_ma1_orders1to5"]["expected_phi_from_R_ar.burg"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
    {
        let model = fit_ar(&y, p + 1, ArMethod::Burg).unwrap();
        assert_all_close(
            &model.coefficients,
            &nums(expected),
            1e-6,
            &format!("burg order {}", p + 1),
        );
    }
}

// spectrum's small examples, no mean removal; printed to 5-6 digits (tolerance 1e-5), the
// variance P to 16 digits (1e-12).
#[test]
fn burg_and_yule_walker_match_spectrum() {
    let r = json("spectrum/ar_reference.json");
    let burg = &r["burg_real"];
    let model = fit_ar_with(&nums(&burg["data"]), 4, ArMethod::Burg, Demean::Keep).unwrap();
    let phi: Vec<f64> = nums(&burg["expected_a"]).iter().map(|a| -a).collect();
    assert_all_close(&model.coefficients, &phi, 1e-5, "burg phi");
    let k: Vec<f64> = nums(&burg["expected_reflection_k"])
        .iter()
        .map(|a| -a)
        .collect();
    assert_all_close(
        model.reflection.as_ref().unwrap(),
        &k,
        1e-5,
        "burg reflection",
    );
    assert!(
        (model.levinson_variance.unwrap() - num(&burg["expected_noise_variance_P"])).abs() < 1e-12
    );
    // statsmodels' definition of the Burg variance, quoted in the same file: 21.914524584881168.
    assert!(
        (model.noise_variance - 21.914_524_584_881_168).abs() < 1e-10,
        "{}",
        model.noise_variance
    );
    let yw = &r["yule_walker_real"];
    let model = fit_ar_with(&nums(&yw["data"]), 2, ArMethod::YuleWalker, Demean::Keep).unwrap();
    let phi: Vec<f64> = nums(&yw["expected_a"]).iter().map(|a| -a).collect();
    assert_all_close(&model.coefficients, &phi, 1e-12, "yw phi");
    assert!((model.noise_variance - num(&yw["expected_noise_variance"])).abs() < 1e-12);
}

// Stata's conditional OLS AR(9) with a constant on sunspots: parameters to 1e-8 relative.
// Standard errors: ours use s² = RSS/(n − k), as gretl (printed to 6 digits: 1e-5 relative);
// the Stata column in statsmodels' results uses the conditional-MLE s² = RSS/n, so it equals
// ours × √((n − k)/n) (10 printed digits: 1e-7 relative).
#[test]
fn conditional_ols_matches_stata() {
    let r = json("statsmodels/ar_reference.json");
    let stata = &r["ar9_ols_sunspots_stata"];
    let fit = conditional_ols(&sunspots(), 9, Intercept::Included).unwrap();
    assert_eq!(fit.n_obs, 300);
    for (k, (a, b)) in fit
        .params
        .iter()
        .zip(nums(&stata["params_const_then_phi1to9"]))
        .enumerate()
    {
        assert!(((a - b) / b).abs() < 1e-8, "param {k}: {a} vs {b}");
    }
    for (k, (a, b)) in fit
        .std_errors
        .iter()
        .zip(nums(&stata["bse_gretl"]))
        .enumerate()
    {
        assert!(((a - b) / b).abs() < 1e-5, "se {k} vs gretl: {a} vs {b}");
    }
    let mle_scale = (290.0_f64 / 300.0).sqrt();
    for (k, (a, b)) in fit
        .std_errors
        .iter()
        .zip(nums(&stata["bse_stata"]))
        .enumerate()
    {
        assert!(
            ((a * mle_scale - b) / b).abs() < 1e-7,
            "se {k} vs Stata: {a} vs {b}"
        );
    }
    assert!((fit.rmse - num(&stata["rmse"])).abs() < 1e-6 * fit.rmse);
}

// numpy lstsq on explicit regression matrices (tools/oracles/ar_least_squares.py): the same
// least-squares problem solved by SVD; agreement 1e-10.
#[test]
fn least_squares_methods_match_numpy() {
    let oracle = oracle_json("ar_least_squares.json");
    let x = x1000();
    for case in oracle["least_squares"].as_array().unwrap() {
        let p = case["order"].as_u64().unwrap() as usize;
        let cov = fit_ar(&x, p, ArMethod::Covariance).unwrap();
        assert_all_close(
            &cov.coefficients,
            &nums(&case["covariance_phi"]),
            1e-10,
            "covariance",
        );
        assert!((cov.noise_variance - num(&case["covariance_noise_variance"])).abs() < 1e-10);
        let mcov = fit_ar(&x, p, ArMethod::ModifiedCovariance).unwrap();
        assert_all_close(
            &mcov.coefficients,
            &nums(&case["modified_covariance_phi"]),
            1e-10,
            "modified covariance",
        );
        assert!(
            (mcov.noise_variance - num(&case["modified_covariance_noise_variance"])).abs() < 1e-10
        );
    }
}

// statsmodels acorr_ljungbox: same formula; statistic to 1e-9 relative, p-value to 1e-9
// (absolute) or 1e-6 relative for the tiny one.
#[test]
fn ljung_box_matches_statsmodels() {
    let oracle = oracle_json("ar_least_squares.json");
    let x = x1000();
    let mean = x.iter().sum::<f64>() / x.len() as f64;
    let c: Vec<f64> = x.iter().map(|v| v - mean).collect();
    let lb = ljung_box(&c, 10, 2).unwrap();
    let expected = &oracle["ljung_box_x1000_lag10_df2"];
    assert!(((lb.statistic - num(&expected["statistic"])) / lb.statistic).abs() < 1e-9);
    assert!(
        ((lb.p_value.unwrap() - num(&expected["p_value"])) / num(&expected["p_value"])).abs()
            < 1e-6
    );
    let white = &oracle["ljung_box_white"];
    let lb = ljung_box(&nums(&white["series"]), 15, 0).unwrap();
    assert!(((lb.statistic - num(&white["statistic"])) / lb.statistic).abs() < 1e-9);
    assert!((lb.p_value.unwrap() - num(&white["p_value"])).abs() < 1e-9);
}

/// One-second block means of the real ADIS16405 run (shared/data/smac-imudata, tests only).
fn adis_block_means() -> Vec<Vec<f64>> {
    use std::io::{BufRead, BufReader};
    let file = std::fs::File::open(shared_data("smac-imudata/adis_16405_imu1.csv.gz"))
        .expect("ADIS data present");
    let reader = BufReader::new(flate2::read::GzDecoder::new(file));
    let mut sums = vec![Vec::new(); 6];
    let mut block = [0.0; 6];
    for (k, line) in reader.lines().skip(1).enumerate() {
        let line = line.expect("text");
        for (c, v) in line.split(',').enumerate() {
            block[c] += v.parse::<f64>().expect("number");
        }
        if k % 100 == 99 {
            for c in 0..6 {
                sums[c].push(block[c] / 100.0);
                block[c] = 0.0;
            }
        }
    }
    sums
}

// statsmodels yule_walker(method='mle') and burg on the same block means of real MEMS data.
// The block sums are accumulated in a different order than numpy's, so agreement is to
// rounding of the means (~1e-16 relative) propagated through the fit: 1e-9 on phi and
// 1e-9 relative on the variances.
#[test]
fn yule_walker_and_burg_match_statsmodels_on_real_adis16405_data() {
    let peer = json("peer-results-on-real-data/adis_16405_imu1_1s_ar_statsmodels.json");
    let names = [
        "Gyro_X", "Gyro_Y", "Gyro_Z", "Accel_X", "Accel_Y", "Accel_Z",
    ];
    for (series, name) in adis_block_means().iter().zip(names) {
        let expected = &peer["results"][name];
        assert_eq!(series.len(), 10_000);
        for p in 1..=3 {
            let yw = fit_ar(series, p, ArMethod::YuleWalker).unwrap();
            assert_all_close(
                &yw.coefficients,
                &nums(&expected[format!("yw_order{p}_phi")]),
                1e-9,
                name,
            );
            let sigma = num(&expected[format!("yw_order{p}_sigma")]);
            assert!(
                (yw.noise_variance.sqrt() / sigma - 1.0).abs() < 1e-9,
                "{name} yw sigma"
            );
            let burg = fit_ar(series, p, ArMethod::Burg).unwrap();
            assert_all_close(
                &burg.coefficients,
                &nums(&expected[format!("burg_order{p}_phi")]),
                1e-9,
                name,
            );
            let s2 = num(&expected[format!("burg_order{p}_sigma2")]);
            assert!(
                (burg.noise_variance / s2 - 1.0).abs() < 1e-9,
                "{name} burg sigma2"
            );
        }
    }
}

// Order selection: an AR(2) series (xar2 is simulated AR(2)) must select p = 2 by BIC among
// 1..10 (BIC is consistent; with 1000 samples and |phi2| ≈ 0.5 the margin is large).
#[test]
fn bic_selects_the_true_order_of_an_ar2_series() {
    let model = fit_ar_order(
        &x1000(),
        Order::Auto {
            criterion: Criterion::Bic,
            max_order: 10,
        },
        ArMethod::Burg,
    )
    .unwrap();
    assert_eq!(model.order(), 2);
}

// Asymptotic standard errors: for AR(1), se(c1) = √((1 − c1²)/N) in closed form (Brockwell &
// Davis eq. 8.10.3); the estimator's plug-in value must match it to 1 %.
#[test]
fn ar1_standard_error_has_the_closed_form() {
    let x = x1000();
    let model = fit_ar(&x, 1, ArMethod::YuleWalker).unwrap();
    let c1 = model.coefficients[0];
    let closed = ((1.0 - c1 * c1) / x.len() as f64).sqrt();
    assert!(
        (model.std_errors[0] / closed - 1.0).abs() < 0.01,
        "{} vs {closed}",
        model.std_errors[0]
    );
}

#[test]
fn bad_input_is_refused_with_numbers() {
    assert_eq!(
        fit_ar(&[1.0; 50], 2, ArMethod::Burg),
        Err(ArError::Constant)
    );
    assert!(matches!(
        fit_ar(&[1.0, 2.0, 3.0], 4, ArMethod::YuleWalker),
        Err(ArError::TooShort {
            samples: 3,
            order: 4,
            ..
        })
    ));
    assert_eq!(
        fit_ar(&[1.0, 2.0, 3.0, 4.0], 0, ArMethod::Burg),
        Err(ArError::ZeroOrder)
    );
    let mut x = x1000();
    x[17] = f64::NAN;
    assert_eq!(
        fit_ar(&x, 2, ArMethod::Covariance),
        Err(ArError::NonFinite { index: 17 })
    );
    let message = fit_ar(&[1.0, 2.0, 3.0], 4, ArMethod::YuleWalker)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains('3') && message.contains("AR(4)"),
        "{message}"
    );
}
