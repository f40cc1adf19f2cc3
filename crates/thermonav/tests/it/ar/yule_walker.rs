//! Yule-Walker against R (sunspots), MATLAB (`ar(x, p, 'yw')` on xar2) and spectrum.

use thermonav::stoch::ar::{ArMethod, ArSpec, MeanModel, Order, fit_ar, fit_ar_with};

use super::data::{self, assert_close, assert_scalar};

#[test]
fn sunspots_ar4_matches_r() {
    // R's ar.yw(sunspots, order 4), mean removed, printed to 17 digits; statsmodels agrees to
    // 1.2e-14, so 1e-12 absolute allows only rounding.
    let reference = data::statsmodels_reference();
    let expected = data::floats(&reference["yule_walker_sunspots_order4"]["expected_phi_from_R"]);
    let model = fit_ar(&data::sunspots(), Order::Fixed(4), ArMethod::YuleWalker).unwrap();
    assert_close(
        &model.coefficients,
        &expected,
        1e-12,
        0.0,
        "sunspots YW AR(4)",
    );
}

#[test]
fn xar2_matches_matlab_ar_yw() {
    // MATLAB's A-polynomial a_i = -c_i, printed with 8 decimals: 1e-8 absolute.
    let reference = data::statsmodels_reference();
    let matlab = &reference["matlab_yule_walker_xar2"];
    for (x, order, key) in [
        (data::x100(), 10, "x100_order10"),
        (data::x1000(), 20, "x1000_order20"),
    ] {
        let a = data::floats(&matlab[key]["arcoef_A_polynomial"]);
        assert_eq!(a[0], 1.0);
        let expected: Vec<f64> = a[1..].iter().map(|v| -v).collect();
        let model = fit_ar(&x, Order::Fixed(order), ArMethod::YuleWalker).unwrap();
        assert_close(&model.coefficients, &expected, 1e-8, 0.0, key);
    }
}

#[test]
fn spectrum_order2_example_without_mean_removal() {
    // spectrum aryule([1,-1,1,1,1], 2), biased, no mean removal ("checked versus Octave"):
    // a = (0, -0.2), P = 0.96, k = (0, -0.2). Exact rationals: gamma = (1, -0.2, 0.2), so
    // 1e-14 leaves only rounding.
    let reference = data::spectrum_reference();
    let case = &reference["yule_walker_real"];
    let x = data::floats(&case["data"]);
    let spec = ArSpec::new(Order::Fixed(2), ArMethod::YuleWalker).with_mean(MeanModel::Zero);
    let model = fit_ar_with(&x, &spec).unwrap();
    let c_expected: Vec<f64> = data::floats(&case["expected_a"])
        .iter()
        .map(|a| -a)
        .collect();
    let pacf_expected: Vec<f64> = data::floats(&case["expected_reflection_k"])
        .iter()
        .map(|k| -k)
        .collect();
    assert_close(&model.coefficients, &c_expected, 1e-14, 0.0, "c");
    assert_close(
        model.partial_autocorrelation.as_ref().unwrap(),
        &pacf_expected,
        1e-14,
        0.0,
        "pacf",
    );
    assert_scalar(
        model.noise_variance,
        data::float(&case["expected_noise_variance"]),
        1e-14,
        0.0,
        "P",
    );
    assert_eq!(model.recursion_power, Some(model.noise_variance));
    assert_eq!(model.mean, 0.0);
}

#[test]
fn levinson_solves_the_toeplitz_system() {
    // Oracle: the Yule-Walker equations themselves, sum_j c_j gamma(|i-j|) = gamma(i), with
    // gamma from the naive double loop; and sigma^2 = gamma(0) - sum c_i gamma(i). Residual of
    // a 12x12 well-conditioned system: 1e-12 relative to gamma(0).
    let x = data::simulate_ar(&[0.7, -0.4, 0.2], 3000, 11);
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let gamma: Vec<f64> = (0..=12)
        .map(|k| {
            (0..n - k)
                .map(|t| (x[t] - mean) * (x[t + k] - mean))
                .sum::<f64>()
                / n as f64
        })
        .collect();
    let model = fit_ar(&x, Order::Fixed(12), ArMethod::YuleWalker).unwrap();
    let c = &model.coefficients;
    for i in 1..=12_usize {
        let lhs: f64 = (1..=12).map(|j| c[j - 1] * gamma[i.abs_diff(j)]).sum();
        assert!((lhs - gamma[i]).abs() < 1e-12 * gamma[0], "equation {i}");
    }
    let sigma2 = gamma[0] - (1..=12).map(|i| c[i - 1] * gamma[i]).sum::<f64>();
    assert_scalar(model.noise_variance, sigma2, 0.0, 1e-12, "sigma^2");
    // The last partial autocorrelation is the last coefficient.
    let pacf = model.partial_autocorrelation.unwrap();
    assert_eq!(pacf.len(), 12);
    assert_scalar(pacf[11], c[11], 1e-15, 0.0, "c_pp");
}
