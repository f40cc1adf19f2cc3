//! Order selection: criterion values against the formulas applied to statsmodels' per-order
//! innovation variances, and recovery of a known order.

use thermonav::stoch::ar::{ArMethod, Order, OrderCriterion, fit_ar};

use super::data::{self, assert_close};

/// AIC, BIC, FPE as documented in `stoch::ar::order`, from an oracle variance.
fn criterion(c: OrderCriterion, n: f64, p: f64, sigma2: f64) -> f64 {
    match c {
        OrderCriterion::Aic => n * sigma2.ln() + 2.0 * p,
        OrderCriterion::Bic => n * sigma2.ln() + p * n.ln(),
        OrderCriterion::Fpe => sigma2 * (n + p) / (n - p),
    }
}

#[test]
fn criteria_match_the_formulas_on_statsmodels_variances() {
    // statsmodels pacf_burg sigma2 (orders 0..8) and yule_walker sigma (orders 1..8; order 0
    // is gamma(0), the sample variance) are computed independently of us; the criterion values
    // of order p depend on them through N ln sigma^2: 1e-10 relative on sigma^2 becomes
    // 1e-10 N absolute.
    let oracle = data::least_squares_oracle();
    for series in oracle["series"].as_array().unwrap() {
        let x = data::floats(&series["x"]);
        let n = x.len() as f64;
        let sel = &series["order_selection"];
        let max_order = sel["max_order"].as_u64().unwrap() as usize;
        let burg_sigma2 = data::floats(&sel["burg_sigma2_orders_0_to_max"]);
        let mean = x.iter().sum::<f64>() / n;
        let gamma0 = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
        let yw_sigma2: Vec<f64> = std::iter::once(gamma0)
            .chain(
                data::floats(&sel["yule_walker_sigma_orders_1_to_max"])
                    .iter()
                    .map(|s| s * s),
            )
            .collect();
        for (method, sigma2) in [
            (ArMethod::Burg, &burg_sigma2),
            (ArMethod::YuleWalker, &yw_sigma2),
        ] {
            for c in OrderCriterion::ALL {
                let model = fit_ar(
                    &x,
                    Order::Auto {
                        criterion: c,
                        max_order,
                    },
                    method,
                )
                .unwrap();
                let selection = model.selection.clone().unwrap();
                let expected: Vec<f64> = (0..=max_order)
                    .map(|p| criterion(c, n, p as f64, sigma2[p]))
                    .collect();
                let label = format!("{} {method} {c}", series["name"]);
                assert_close(&selection.values, &expected, 1e-10 * n, 1e-10, &label);
                let best =
                    (0..=max_order).fold(0, |b, p| if expected[p] < expected[b] { p } else { b });
                assert_eq!(model.order, best, "{label}");
            }
        }
    }
}

#[test]
fn bic_recovers_the_order_of_a_long_ar2_series() {
    // 20 000 samples of AR(2) (0.6, -0.3): the order-3.. improvements are O(1) in N ln sigma^2,
    // below BIC's ln N = 9.9 penalty, while dropping to order 1 costs ~ N * 0.09. Every method
    // must pick 2, and the selected model must equal the fixed-order fit.
    let x = data::simulate_ar(&[0.6, -0.3], 20_000, 42);
    let auto = Order::Auto {
        criterion: OrderCriterion::Bic,
        max_order: 10,
    };
    for method in ArMethod::ALL {
        let model = fit_ar(&x, auto, method).unwrap();
        assert_eq!(model.order, 2, "{method}");
        assert_eq!(model.selection.as_ref().unwrap().values.len(), 11);
        let fixed = fit_ar(&x, Order::Fixed(2), method).unwrap();
        // Equal up to the order in which the lagged sums were blocked.
        assert_close(
            &model.coefficients,
            &fixed.coefficients,
            1e-13,
            0.0,
            method.name(),
        );
        assert_close(
            &[model.noise_variance],
            &[fixed.noise_variance],
            0.0,
            1e-13,
            method.name(),
        );
    }
}

#[test]
fn names_round_trip() {
    for method in ArMethod::ALL {
        assert_eq!(method.name().parse::<ArMethod>(), Ok(method));
    }
    for c in OrderCriterion::ALL {
        assert_eq!(c.to_string().parse::<OrderCriterion>(), Ok(c));
    }
    assert_eq!(
        ["yule-walker", "burg", "covariance", "modified-covariance"],
        ArMethod::ALL.map(ArMethod::name)
    );
    assert!("levinson".parse::<ArMethod>().is_err());
    assert!("hq".parse::<OrderCriterion>().is_err());
}
