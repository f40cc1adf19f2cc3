//! Coefficient standard errors: closed forms of the asymptotic covariance and a seeded Monte
//! Carlo check of what they claim.

use thermonav::stoch::ar::{ArMethod, Order, fit_ar};

use super::data::{self, assert_close};

#[test]
fn recursive_methods_match_closed_forms_for_ar1_and_ar2() {
    // sigma^2 Gamma_p^-1 / N for the fitted model (Brockwell & Davis 1991, Thm 8.1.1 and
    // Example 8.1.1): AR(1) var(c1) = (1 - c1^2) / N; AR(2) var(c1) = var(c2) = (1 - c2^2) / N.
    // Closed forms evaluated at the estimates themselves, so only rounding separates them.
    let x = data::simulate_ar(&[0.5, 0.2], 5000, 17);
    let n = x.len() as f64;
    for method in [ArMethod::YuleWalker, ArMethod::Burg] {
        let ar1 = fit_ar(&x, Order::Fixed(1), method).unwrap();
        let c1 = ar1.coefficients[0];
        assert_close(
            &ar1.coefficient_std_errors,
            &[((1.0 - c1 * c1) / n).sqrt()],
            0.0,
            1e-12,
            "AR(1)",
        );
        let ar2 = fit_ar(&x, Order::Fixed(2), method).unwrap();
        let se = ((1.0 - ar2.coefficients[1].powi(2)) / n).sqrt();
        assert_close(&ar2.coefficient_std_errors, &[se, se], 0.0, 1e-12, "AR(2)");
    }
}

#[test]
fn standard_errors_describe_the_monte_carlo_spread_of_c1() {
    // 400 AR(1) series (c = 0.9, N = 1000): the empirical standard deviation of c1_hat is
    // estimated with relative sampling error 1/sqrt(2 * 399) = 3.5 %; the asymptotic se
    // sqrt((1 - c^2)/N) = 0.0138 should match it within 15 % (4 sampling sigmas) for every
    // method. The Gauss-Markov correlation-time interval rests on this se(c1).
    let (c, n, runs) = (0.9, 1000, 400);
    for method in ArMethod::ALL {
        let mut estimates = Vec::with_capacity(runs);
        let mut reported = 0.0;
        for seed in 0..runs as u64 {
            let model = fit_ar(
                &data::simulate_ar(&[c], n, 1000 + seed),
                Order::Fixed(1),
                method,
            )
            .unwrap();
            estimates.push(model.coefficients[0]);
            reported += model.coefficient_std_errors[0] / runs as f64;
        }
        let mean = estimates.iter().sum::<f64>() / runs as f64;
        let spread =
            (estimates.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (runs - 1) as f64).sqrt();
        let asymptotic = ((1.0 - c * c) / n as f64).sqrt();
        assert!(
            (spread / asymptotic - 1.0).abs() < 0.15,
            "{method}: spread {spread} vs {asymptotic}"
        );
        assert!(
            (reported / asymptotic - 1.0).abs() < 0.05,
            "{method}: reported {reported}"
        );
    }
}

#[test]
fn least_squares_standard_errors_agree_with_the_asymptotic_form_on_long_series() {
    // Covariance (sigma^2 (X'X)^-1) and modified covariance (2 sigma^2 (X_fb'X_fb)^-1) both
    // estimate sigma^2 Gamma^-1 / N; on 50 000 samples of AR(2) they agree with the Yule-Walker
    // closed form to sampling error of the sample autocovariances, O(1/sqrt(N)) ~ 0.5 %: 2 %.
    let x = data::simulate_ar(&[0.5, 0.2], 50_000, 23);
    let yw = fit_ar(&x, Order::Fixed(2), ArMethod::YuleWalker).unwrap();
    for method in [ArMethod::Covariance, ArMethod::ModifiedCovariance] {
        let model = fit_ar(&x, Order::Fixed(2), method).unwrap();
        assert_close(
            &model.coefficient_std_errors,
            &yw.coefficient_std_errors,
            0.0,
            0.02,
            method.name(),
        );
    }
}
