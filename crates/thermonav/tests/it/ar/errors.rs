//! Bad input gives typed errors carrying the numbers, and no output is ever NaN or infinite.

use thermonav::stoch::ar::{
    ArError, ArMethod, ArModel, ArSpec, MeanModel, Order, OrderCriterion, fit_ar, fit_ar_with,
    min_samples,
};

use super::data;

fn all_finite(model: &ArModel) -> bool {
    let mut values = vec![model.noise_variance, model.mean];
    values.extend(&model.coefficients);
    values.extend(&model.coefficient_std_errors);
    values.extend(model.recursion_power);
    values.extend(model.partial_autocorrelation.iter().flatten());
    values.extend(model.intercept.iter().flat_map(|c| [c.value, c.std_error]));
    values.extend(model.selection.iter().flat_map(|s| s.values.clone()));
    values.iter().all(|v| v.is_finite())
}

#[test]
fn constant_series_is_zero_variance() {
    for method in ArMethod::ALL {
        assert_eq!(
            fit_ar(&[3.5; 40], Order::Fixed(2), method),
            Err(ArError::ZeroVariance { n_samples: 40 }),
            "{method}"
        );
        // Not exactly representable, long: the computed mean is off by rounding.
        assert_eq!(
            fit_ar(&[-1.01565; 100_000], Order::Fixed(2), method),
            Err(ArError::ZeroVariance { n_samples: 100_000 }),
            "{method}"
        );
        let zero = ArSpec::new(Order::Fixed(1), method).with_mean(MeanModel::Zero);
        assert_eq!(
            fit_ar_with(&[0.0; 40], &zero),
            Err(ArError::ZeroVariance { n_samples: 40 })
        );
    }
}

#[test]
fn too_short_series_names_the_minimum() {
    let x = [0.3, -0.1, 0.4, 0.2, -0.5];
    assert_eq!(
        fit_ar(&x, Order::Fixed(5), ArMethod::YuleWalker),
        Err(ArError::TooShort {
            method: ArMethod::YuleWalker,
            order: 5,
            n_samples: 5,
            min_samples: 6
        })
    );
    assert_eq!(
        fit_ar(&x, Order::Fixed(3), ArMethod::Covariance),
        Err(ArError::TooShort {
            method: ArMethod::Covariance,
            order: 3,
            n_samples: 5,
            min_samples: 7
        })
    );
    let auto = Order::Auto {
        criterion: OrderCriterion::Aic,
        max_order: 9,
    };
    assert!(matches!(
        fit_ar(&x, auto, ArMethod::Burg),
        Err(ArError::TooShort { order: 9, .. })
    ));
    assert!(matches!(
        fit_ar(&[1.0], Order::Fixed(0), ArMethod::Burg),
        Err(ArError::TooShort { .. })
    ));
    assert_eq!(
        min_samples(ArMethod::Covariance, MeanModel::Intercept, 3),
        8
    );
    assert_eq!(
        min_samples(ArMethod::ModifiedCovariance, MeanModel::SampleMean, 4),
        7
    );
    // Exactly the minimum works for every method.
    let x = data::simulate_ar(&[0.5], 200, 3);
    for method in ArMethod::ALL {
        let n = min_samples(method, MeanModel::SampleMean, 4);
        let model = fit_ar(&x[..n], Order::Fixed(4), method);
        assert!(
            model.as_ref().is_ok_and(all_finite),
            "{method} on {n} samples: {model:?}"
        );
    }
}

#[test]
fn non_finite_samples_are_rejected_with_their_index() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let mut x = data::simulate_ar(&[0.5], 100, 4);
        x[37] = bad;
        for method in ArMethod::ALL {
            match fit_ar(&x, Order::Fixed(2), method) {
                Err(ArError::NonFinite { index: 37, value }) => {
                    assert!(value.is_nan() == bad.is_nan() && (value.is_nan() || value == bad))
                }
                other => panic!("{method}: {other:?}"),
            }
        }
        let model = fit_ar(&x[..30], Order::Fixed(1), ArMethod::Burg).unwrap();
        assert!(matches!(
            model.residuals(&x),
            Err(ArError::NonFinite { index: 37, .. })
        ));
    }
}

#[test]
fn intercept_is_only_for_the_covariance_method() {
    let x = data::simulate_ar(&[0.5], 100, 5);
    for method in [
        ArMethod::YuleWalker,
        ArMethod::Burg,
        ArMethod::ModifiedCovariance,
    ] {
        let spec = ArSpec::new(Order::Fixed(1), method).with_mean(MeanModel::Intercept);
        assert_eq!(
            fit_ar_with(&x, &spec),
            Err(ArError::InterceptUnsupported { method })
        );
    }
}

#[test]
fn overflowing_magnitudes_are_rejected() {
    let x: Vec<f64> = data::simulate_ar(&[0.5], 100, 6)
        .iter()
        .map(|v| v * 1e200)
        .collect();
    assert!(matches!(
        fit_ar(&x, Order::Fixed(1), ArMethod::Burg),
        Err(ArError::Overflow { .. })
    ));
}

#[test]
fn degenerate_series_give_errors_or_finite_models() {
    // Perfectly predictable or rank-deficient inputs: a sinusoid (exact AR(2)), an alternating
    // sequence, a ramp, a step, tiny and large magnitudes, few samples. Whatever happens, no
    // NaN or infinity may come out.
    let n = 64;
    let series: Vec<Vec<f64>> = vec![
        (0..n).map(|t| (0.3 * t as f64).cos()).collect(),
        (0..n)
            .map(|t| if t % 2 == 0 { 1.0 } else { -1.0 })
            .collect(),
        (0..n).map(|t| t as f64).collect(),
        (0..n).map(|t| if t < n / 2 { 0.0 } else { 1.0 }).collect(),
        data::simulate_ar(&[0.5], n, 7)
            .iter()
            .map(|v| v * 1e-300)
            .collect(),
        data::simulate_ar(&[0.5], n, 7)
            .iter()
            .map(|v| v * 1e120)
            .collect(),
        vec![1.0, 2.0, 1.0],
    ];
    for (i, x) in series.iter().enumerate() {
        for method in ArMethod::ALL {
            for mean in [MeanModel::Zero, MeanModel::SampleMean] {
                for order in [Order::Fixed(1), Order::Fixed(2), Order::Fixed(6)] {
                    let result = fit_ar_with(x, &ArSpec::new(order, method).with_mean(mean));
                    if let Ok(model) = result {
                        assert!(
                            all_finite(&model),
                            "series {i} {method} {mean:?} {order:?}: {model:?}"
                        );
                        assert!(model.residuals(x).unwrap().iter().all(|e| e.is_finite()));
                    }
                }
            }
        }
    }
}

#[test]
fn order_zero_is_white_noise_around_the_mean() {
    // Order 0: no coefficients; the innovation variance is the biased sample variance for
    // every method (all four windows cover the whole series).
    let x = data::simulate_ar(&[], 500, 8);
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let variance = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    for method in ArMethod::ALL {
        let model = fit_ar(&x, Order::Fixed(0), method).unwrap();
        assert!(model.coefficients.is_empty() && model.coefficient_std_errors.is_empty());
        assert!(
            (model.noise_variance / variance - 1.0).abs() < 1e-12,
            "{method}"
        );
        assert!((model.mean - mean).abs() < 1e-15);
    }
}
