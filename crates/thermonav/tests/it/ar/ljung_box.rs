//! Ljung-Box against statsmodels `acorr_ljungbox` (tools/oracles/ar_least_squares.py).

use thermonav::stoch::ar::{ArError, ArMethod, Order, fit_ar, ljung_box};

use super::data::{self, assert_scalar};

#[test]
fn matches_statsmodels_acorr_ljungbox() {
    // Q is a short sum of squared autocorrelations: 1e-10 relative. The p-value goes through
    // statrs' regularised incomplete gamma vs scipy's chi2.sf: 1e-9 absolute.
    let oracle = data::least_squares_oracle();
    for case in oracle["ljung_box"].as_array().unwrap() {
        let x = data::floats(&case["x"]);
        let model_df = case["model_df"].as_u64().unwrap() as usize;
        let lags = case["lags"].as_array().unwrap();
        let stats = data::floats(&case["lb_stat"]);
        let p_values = data::floats(&case["lb_pvalue"]);
        for (i, lag) in lags.iter().enumerate() {
            let lag = lag.as_u64().unwrap() as usize;
            let label = format!("{} lag {lag}", case["series"]);
            let test = ljung_box(&x, lag, model_df).unwrap();
            assert_scalar(test.statistic, stats[i], 0.0, 1e-10, &label);
            assert_scalar(test.p_value, p_values[i], 1e-9, 0.0, &label);
            assert_eq!(test.degrees_of_freedom, lag - model_df);
        }
    }
}

#[test]
fn model_residual_test_matches_statsmodels_end_to_end() {
    // The first oracle series is statsmodels AutoReg(x - mean, 3, trend='n').resid of the ar3
    // series; fitting our covariance method on that series and testing its own residuals must
    // give the same Q (1e-9 relative: the residuals themselves differ in the last bits) and
    // p-value (1e-9 absolute, as above).
    let oracle = data::least_squares_oracle();
    let x = data::floats(&oracle["series"][0]["x"]);
    let case = &oracle["ljung_box"][0];
    assert_eq!(case["series"], "autoreg_resid_ar3_order3");
    let model = fit_ar(&x, Order::Fixed(3), ArMethod::Covariance).unwrap();
    for (i, lag) in [5, 10, 20].into_iter().enumerate() {
        let test = model.ljung_box(&x, lag).unwrap();
        assert_scalar(
            test.statistic,
            data::floats(&case["lb_stat"])[i],
            0.0,
            1e-9,
            "Q",
        );
        assert_scalar(
            test.p_value,
            data::floats(&case["lb_pvalue"])[i],
            1e-9,
            0.0,
            "p",
        );
    }
}

#[test]
fn invalid_lags_are_errors() {
    let x = data::simulate_ar(&[], 50, 1);
    assert_eq!(
        ljung_box(&x, 0, 0),
        Err(ArError::InvalidLags {
            lags: 0,
            n_residuals: 50
        })
    );
    assert_eq!(
        ljung_box(&x, 50, 0),
        Err(ArError::InvalidLags {
            lags: 50,
            n_residuals: 50
        })
    );
    assert_eq!(
        ljung_box(&x, 3, 3),
        Err(ArError::NoDegreesOfFreedom {
            lags: 3,
            fitted_params: 3
        })
    );
    assert_eq!(
        ljung_box(&[2.0; 20], 5, 1),
        Err(ArError::ZeroVariance { n_samples: 20 })
    );
    assert!(matches!(
        ljung_box(&[0.0, 1.0, f64::INFINITY, 2.0, 3.0], 2, 0),
        Err(ArError::NonFinite { index: 2, .. })
    ));
}
