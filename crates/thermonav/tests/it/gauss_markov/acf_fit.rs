//! The classical autocovariance fit and the 1/e shortcut, against closed forms and SciPy's
//! `curve_fit`.

use thermonav::stoch::gauss_markov::{
    AcfFit, AcfGaussMarkov, EFoldingTime, GaussMarkovError, LagWindow, ZeroLag, e_folding_time,
    fit_gauss_markov_to_autocovariance,
};

use super::{numbers, oracle_json, relative_error};

fn fitted(outcome: AcfGaussMarkov) -> AcfFit {
    match outcome {
        AcfGaussMarkov::Fitted(fit) => fit,
        AcfGaussMarkov::NotDecaying => panic!("expected a fit"),
    }
}

/// `sigma^2 exp(-k dt / Tc)` for lags `0..=max_lag`, plus white-noise variance at lag 0.
fn theoretical(sigma2: f64, tc_s: f64, dt_s: f64, white_variance: f64, max_lag: usize) -> Vec<f64> {
    (0..=max_lag)
        .map(|k| {
            sigma2 * (-(k as f64) * dt_s / tc_s).exp() + if k == 0 { white_variance } else { 0.0 }
        })
        .collect()
}

#[test]
fn an_exact_exponential_is_recovered_with_every_window() {
    // Closed form: the data are exactly sigma^2 exp(-tau/Tc) on the fitted lags, so the
    // least-squares solution is the truth; rounding of the data (~1e-16) and of the solver
    // leave ~1e-13, tested at 1e-9.
    let dt_s = 0.01;
    for (white, zero_lag) in [(0.0, ZeroLag::Include), (0.8, ZeroLag::Exclude)] {
        let gamma = theoretical(2.25, 0.137, dt_s, white, 200);
        for window in [
            LagWindow::FirstZeroCrossing,
            LagWindow::UntilRhoBelow((-3.0_f64).exp()),
            LagWindow::MaxLag(25),
        ] {
            let fit =
                fitted(fit_gauss_markov_to_autocovariance(&gamma, dt_s, window, zero_lag).unwrap());
            let label = format!("{window:?} {zero_lag:?}");
            assert!(
                relative_error(fit.model.variance(), 2.25) < 1e-9,
                "{label}: {fit:?}"
            );
            assert!(
                relative_error(fit.model.correlation_time_s(), 0.137) < 1e-9,
                "{label}"
            );
            assert!(fit.residual_sum_of_squares < 1e-20, "{label}");
        }
    }
}

#[test]
fn windows_keep_the_documented_lags() {
    // rho(k) = exp(-k/10): at or above the threshold just under exp(-2) up to k = 20 (the
    // margin 1e-12 absorbs the rounding of rho(20)), below it from k = 21 on.
    let gamma = theoretical(1.0, 0.1, 0.01, 0.0, 60);
    let window = LagWindow::UntilRhoBelow((-2.0_f64).exp() * (1.0 - 1e-12));
    let fit =
        fitted(fit_gauss_markov_to_autocovariance(&gamma, 0.01, window, ZeroLag::Exclude).unwrap());
    assert_eq!((fit.first_lag, fit.last_lag), (1, 20));
    let fit = fitted(
        fit_gauss_markov_to_autocovariance(&gamma, 0.01, LagWindow::MaxLag(500), ZeroLag::Include)
            .unwrap(),
    );
    assert_eq!((fit.first_lag, fit.last_lag), (0, 60));
}

fn window_of(case: &serde_json::Value) -> LagWindow {
    let window = &case["window"];
    match window["kind"].as_str().unwrap() {
        "first_zero_crossing" => LagWindow::FirstZeroCrossing,
        "until_rho_below" => LagWindow::UntilRhoBelow(window["threshold"].as_f64().unwrap()),
        "max_lag" => LagWindow::MaxLag(window["max_lag"].as_u64().unwrap() as usize),
        other => panic!("unknown window {other}"),
    }
}

#[test]
fn a_noisy_autocovariance_fit_matches_scipy_curve_fit() {
    // tools/oracles/gm_acf_fit.py: sample autocovariance of a simulated GM + white noise,
    // fitted by SciPy curve_fit (MINPACK LM, tolerances 1e-15) per window. Both solvers stop
    // at the same least-squares minimum; SciPy's own two solvers agree to 6e-10 there, so
    // 1e-7 on the parameters and 1e-9 on the (second-order insensitive) residual sum.
    let oracle = oracle_json("gm_acf_fit.json");
    let gamma = numbers(&oracle["autocovariance"]);
    let dt_s = oracle["lag_dt_s"].as_f64().unwrap();
    for case in oracle["cases"].as_array().unwrap() {
        let zero_lag = match case["zero_lag"].as_str().unwrap() {
            "include" => ZeroLag::Include,
            _ => ZeroLag::Exclude,
        };
        let window = window_of(case);
        let fit =
            fitted(fit_gauss_markov_to_autocovariance(&gamma, dt_s, window, zero_lag).unwrap());
        let get = |key: &str| case[key].as_f64().unwrap();
        assert_eq!(fit.first_lag as u64, case["first_lag"].as_u64().unwrap());
        assert_eq!(
            fit.last_lag as u64,
            case["last_lag"].as_u64().unwrap(),
            "{window:?}"
        );
        assert!(
            relative_error(fit.model.variance(), get("sigma2")) < 1e-7,
            "{window:?}"
        );
        assert!(
            relative_error(fit.model.correlation_time_s(), get("tc_s")) < 1e-7,
            "{window:?}"
        );
        assert!(
            relative_error(fit.residual_sum_of_squares, get("rss")) < 1e-9,
            "{window:?}"
        );
    }
}

#[test]
fn e_folding_time_is_exact_for_an_exponential_and_matches_the_oracle() {
    // ln rho is linear between lags for an exponential, so the interpolated crossing is Tc
    // to rounding (1e-12).
    let gamma = theoretical(3.0, 0.123, 0.01, 0.0, 50);
    let EFoldingTime::Crossed { correlation_time_s } = e_folding_time(&gamma, 0.01).unwrap() else {
        panic!("crossing expected")
    };
    assert!(relative_error(correlation_time_s, 0.123) < 1e-12);
    // The noisy autocovariance of the SciPy oracle, same definition computed in Python.
    let oracle = oracle_json("gm_acf_fit.json");
    let gamma = numbers(&oracle["autocovariance"]);
    let expected = oracle["e_folding_tc_s"].as_f64().unwrap();
    let EFoldingTime::Crossed { correlation_time_s } = e_folding_time(&gamma, 0.01).unwrap() else {
        panic!("crossing expected")
    };
    assert!(relative_error(correlation_time_s, expected) < 1e-12);
    // White noise on top lowers rho at every lag > 0, so the shortcut underestimates Tc.
    let with_white = theoretical(3.0, 0.123, 0.01, 1.0, 50);
    let EFoldingTime::Crossed { correlation_time_s } = e_folding_time(&with_white, 0.01).unwrap()
    else {
        panic!("crossing expected")
    };
    assert!(correlation_time_s < 0.9 * 0.123);
    // A slow decay never reaches 1/e within the lags given.
    let slow = theoretical(1.0, 10.0, 0.01, 0.0, 20);
    assert_eq!(
        e_folding_time(&slow, 0.01).unwrap(),
        EFoldingTime::NotReached { max_lag_s: 0.2 }
    );
}

#[test]
fn a_growing_autocovariance_has_no_model() {
    let growing: Vec<f64> = (0..20).map(|k| 1.0 + 0.01 * k as f64).collect();
    assert_eq!(
        fit_gauss_markov_to_autocovariance(&growing, 0.1, LagWindow::MaxLag(10), ZeroLag::Include),
        Ok(AcfGaussMarkov::NotDecaying)
    );
}

#[test]
fn bad_autocovariances_and_windows_are_typed_errors() {
    let fit = |gamma: &[f64], window| {
        fit_gauss_markov_to_autocovariance(gamma, 0.01, window, ZeroLag::Exclude)
    };
    let good = theoretical(1.0, 0.1, 0.01, 0.0, 30);
    assert!(matches!(
        fit(&[-1.0, 0.5, 0.2], LagWindow::FirstZeroCrossing),
        Err(GaussMarkovError::NotPositive { .. })
    ));
    assert!(matches!(
        fit(&[1.0, f64::NAN, 0.2], LagWindow::FirstZeroCrossing),
        Err(GaussMarkovError::NonFinite { index: 1, .. })
    ));
    assert_eq!(
        fit(&[1.0], LagWindow::FirstZeroCrossing),
        Err(GaussMarkovError::TooShort { needed: 2, got: 1 })
    );
    for threshold in [0.0, 1.0, f64::NAN] {
        assert!(matches!(
            fit(&good, LagWindow::UntilRhoBelow(threshold)),
            Err(GaussMarkovError::InvalidRhoThreshold { .. })
        ));
    }
    // Lag 0 excluded and only lag 1 kept: one lag for two parameters.
    assert_eq!(
        fit(&good, LagWindow::MaxLag(1)),
        Err(GaussMarkovError::TooFewLags { needed: 2, got: 1 })
    );
    // Two lags kept but only one positive value to start the log-linear fit from.
    assert_eq!(
        fit(&[1.0, 0.5, -0.1], LagWindow::MaxLag(2)),
        Err(GaussMarkovError::TooFewLags { needed: 2, got: 1 })
    );
    assert!(matches!(
        fit_gauss_markov_to_autocovariance(&good, 0.0, LagWindow::MaxLag(5), ZeroLag::Include),
        Err(GaussMarkovError::NotPositive { .. })
    ));
}
