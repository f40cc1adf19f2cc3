//! Ljung-Box against statsmodels `acorr_ljungbox` (tools/oracles/ar_least_squares.py).

use thermonav::stoch::ar::{ArError, ljung_box};

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
