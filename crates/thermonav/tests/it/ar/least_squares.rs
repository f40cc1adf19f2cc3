//! Covariance and modified covariance against numpy least squares and statsmodels `AutoReg`
//! (tools/oracles/ar_least_squares.py), Stata/gretl AR(9) OLS on sunspots and MATLAB `parcorr`.

use serde_json::Value;
use thermonav::stoch::ar::{ArMethod, ArModel, ArSpec, MeanModel, Order, fit_ar_with};

use super::data::{self, assert_close, assert_scalar};

fn fit(x: &[f64], p: usize, method: ArMethod, mean: MeanModel) -> ArModel {
    fit_ar_with(x, &ArSpec::new(Order::Fixed(p), method).with_mean(mean)).unwrap()
}

/// (model parameters with the intercept first when present, standard errors likewise).
fn params_and_bse(model: &ArModel) -> (Vec<f64>, Vec<f64>) {
    let mut params = Vec::new();
    let mut bse = Vec::new();
    if let Some(c) = model.intercept {
        params.push(c.value);
        bse.push(c.std_error);
    }
    params.extend(&model.coefficients);
    bse.extend(&model.coefficient_std_errors);
    (params, bse)
}

/// An oracle series: name, samples, and the oracle entry of each order.
type OracleCase = (String, Vec<f64>, Vec<(usize, Value)>);

/// Each oracle series with its per-order entries.
fn oracle_cases() -> Vec<OracleCase> {
    let oracle = data::least_squares_oracle();
    oracle["series"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let orders = s["orders"]
                .as_object()
                .unwrap()
                .iter()
                .map(|(p, v)| (p.parse().unwrap(), v.clone()))
                .collect();
            (
                s["name"].as_str().unwrap().to_owned(),
                data::floats(&s["x"]),
                orders,
            )
        })
        .collect()
}

#[test]
fn covariance_method_matches_numpy_lstsq_and_autoreg() {
    // numpy lstsq (SVD) vs our Cholesky on normal equations: the normal equations square the
    // condition number (< 1e3 here), so 1e-10 on parameters of order 1-5 and 1e-10 relative on
    // sigma^2 and standard errors is rounding plus a wide margin.
    for (name, x, orders) in oracle_cases() {
        for (p, entry) in orders {
            for (key, mean) in [
                ("zero", MeanModel::Zero),
                ("sample_mean", MeanModel::SampleMean),
                ("intercept", MeanModel::Intercept),
            ] {
                let label = format!("{name} p={p} {key}");
                let expected = &entry["covariance"][key];
                let model = fit(&x, p, ArMethod::Covariance, mean);
                let (params, bse) = params_and_bse(&model);
                assert_close(
                    &params,
                    &data::floats(&expected["params"]),
                    1e-10,
                    0.0,
                    &label,
                );
                assert_close(&bse, &data::floats(&expected["bse"]), 0.0, 1e-10, &label);
                assert_scalar(
                    model.noise_variance,
                    data::float(&expected["sigma2"]),
                    0.0,
                    1e-10,
                    &label,
                );
            }
            let autoreg = &entry["autoreg"];
            let demeaned = fit(&x, p, ArMethod::Covariance, MeanModel::SampleMean);
            let (params, bse) = params_and_bse(&demeaned);
            let expected = &autoreg["trend_n_on_demeaned"];
            assert_close(
                &params,
                &data::floats(&expected["params"]),
                1e-10,
                0.0,
                "AutoReg n",
            );
            assert_close(
                &bse,
                &data::floats(&expected["bse"]),
                0.0,
                1e-10,
                "AutoReg n bse",
            );
            assert_scalar(
                demeaned.noise_variance,
                data::float(&expected["sigma2"]),
                0.0,
                1e-10,
                "AutoReg n",
            );
            let residuals = demeaned.residuals(&x).unwrap();
            assert_close(
                &residuals,
                &data::floats(&expected["resid"]),
                1e-10,
                0.0,
                "AutoReg resid",
            );
            let with_constant = fit(&x, p, ArMethod::Covariance, MeanModel::Intercept);
            let (params, bse) = params_and_bse(&with_constant);
            let expected = &autoreg["trend_c_on_raw"];
            assert_close(
                &params,
                &data::floats(&expected["params"]),
                1e-10,
                0.0,
                "AutoReg c",
            );
            assert_close(
                &bse,
                &data::floats(&expected["bse"]),
                0.0,
                1e-10,
                "AutoReg c bse",
            );
        }
    }
}

#[test]
fn modified_covariance_matches_numpy_forward_backward_lstsq() {
    // Same reasoning and tolerances as the covariance method.
    for (name, x, orders) in oracle_cases() {
        for (p, entry) in orders {
            for (key, mean) in [
                ("zero", MeanModel::Zero),
                ("sample_mean", MeanModel::SampleMean),
            ] {
                let label = format!("{name} p={p} {key}");
                let expected = &entry["modified_covariance"][key];
                let model = fit(&x, p, ArMethod::ModifiedCovariance, mean);
                assert_close(
                    &model.coefficients,
                    &data::floats(&expected["params"]),
                    1e-10,
                    0.0,
                    &label,
                );
                assert_scalar(
                    model.noise_variance,
                    data::float(&expected["sigma2"]),
                    0.0,
                    1e-10,
                    &label,
                );
            }
        }
    }
}

#[test]
fn sunspots_ar9_with_constant_matches_stata_and_gretl() {
    // Stata: conditional OLS AR(9) with constant, 300 effective observations. Parameters are
    // printed with 14 significant digits and bse_stata with 10: 1e-9 and 1e-8 relative. Stata's
    // bse use RSS / n_eff (our noise_variance); gretl's use RSS / (n_eff - k), k = 10, and are
    // printed with 6 digits (5e-6 relative); Stata's RMSE is sqrt(RSS / (n_eff - k)), printed
    // with 15 digits.
    let reference = data::statsmodels_reference();
    let stata = &reference["ar9_ols_sunspots_stata"];
    let model = fit(
        &data::sunspots(),
        9,
        ArMethod::Covariance,
        MeanModel::Intercept,
    );
    let (params, bse) = params_and_bse(&model);
    assert_close(
        &params,
        &data::floats(&stata["params_const_then_phi1to9"]),
        0.0,
        1e-9,
        "params",
    );
    assert_close(
        &bse,
        &data::floats(&stata["bse_stata"]),
        0.0,
        1e-8,
        "bse Stata",
    );
    let (n_eff, k) = (300.0, 10.0);
    let dof_factor = f64::sqrt(n_eff / (n_eff - k));
    let bse_gretl: Vec<f64> = bse.iter().map(|s| s * dof_factor).collect();
    assert_close(
        &bse_gretl,
        &data::floats(&stata["bse_gretl"]),
        0.0,
        5e-6,
        "bse gretl",
    );
    let rmse = (model.noise_variance * n_eff / (n_eff - k)).sqrt();
    assert_scalar(rmse, data::float(&stata["rmse"]), 0.0, 1e-10, "RMSE");
}

#[test]
fn ols_partial_autocorrelation_matches_matlab_parcorr() {
    // MATLAB parcorr (= statsmodels pacf_ols) is the last coefficient of the order-k
    // regression with a constant: our covariance method with an intercept. Printed with 8-9
    // decimals: 1e-8 absolute.
    let reference = data::statsmodels_reference();
    let expected = &reference["matlab_acf_pacf_xar2"];
    for (x, key) in [
        (data::x100(), "pacf100_lags0to20"),
        (data::x1000(), "pacf1000_lags0to20"),
    ] {
        let pacf: Vec<f64> = (1..=20)
            .map(|k| {
                *fit(&x, k, ArMethod::Covariance, MeanModel::Intercept)
                    .coefficients
                    .last()
                    .unwrap()
            })
            .collect();
        assert_close(&pacf, &data::floats(&expected[key])[1..], 1e-8, 0.0, key);
    }
}

#[test]
fn strongly_correlated_series_takes_the_exact_residual_path() {
    // AR(1) with c = 0.99999 summed over 8 samples: sigma^2 / gamma(0) ~ 1e-6, so
    // Phi_00 - b'theta would cancel; the estimator recomputes the residuals. Oracle: the
    // residual sum of squares from ArModel::residuals (the explicit prediction errors) for
    // the forward method, 1e-12 relative.
    let x: Vec<f64> = data::simulate_ar(&[0.99999], 3000, 9)
        .windows(8)
        .map(|w| w.iter().sum::<f64>())
        .collect();
    let model = fit(&x, 3, ArMethod::Covariance, MeanModel::SampleMean);
    let residuals = model.residuals(&x).unwrap();
    let rss: f64 = residuals.iter().map(|e| e * e).sum();
    assert_scalar(
        model.noise_variance,
        rss / (x.len() - 3) as f64,
        0.0,
        1e-12,
        "sigma^2",
    );
}
