//! Burg against R `ar.burg`, spectrum `arburg`, statsmodels `burg`, and a slow textbook Burg.

use thermonav::stoch::ar::{ArMethod, ArSpec, MeanModel, Order, fit_ar, fit_ar_with};

use super::data::{self, assert_close, assert_scalar};

/// Textbook Burg, as slow and plain as possible: at every stage the forward and backward
/// errors are recomputed from the data and the current A-polynomial. Returns
/// (c, partial autocorrelations, statsmodels sigma2, recursion power P).
fn naive_burg(y: &[f64], p: usize) -> (Vec<f64>, Vec<f64>, f64, f64) {
    let n = y.len();
    let mut a = vec![1.0]; // A-polynomial, a_0 = 1
    let mut pacf = Vec::new();
    let mut power = y.iter().map(|v| v * v).sum::<f64>() / n as f64;
    let mut sigma2 = power;
    for m in 1..=p {
        let f = |t: usize| (0..m).map(|i| a[i] * y[t - i]).sum::<f64>();
        let b = |t: usize| (0..m).map(|i| a[i] * y[t + 1 - m + i]).sum::<f64>();
        let num: f64 = (m..n).map(|t| f(t) * b(t - 1)).sum();
        let den: f64 = (m..n).map(|t| f(t) * f(t) + b(t - 1) * b(t - 1)).sum();
        let k = -2.0 * num / den;
        // a_i <- a_i + k a_{m-i}, i = 1..=m, with a_m = 0 before the update.
        let next: Vec<f64> = (0..=m)
            .map(|i| {
                let old = a.get(i).copied().unwrap_or(0.0);
                if i == 0 { old } else { old + k * a[m - i] }
            })
            .collect();
        a = next;
        pacf.push(-k);
        power *= 1.0 - k * k;
        let f = |t: usize| (0..=m).map(|i| a[i] * y[t - i]).sum::<f64>();
        let b = |t: usize| (0..=m).map(|i| a[i] * y[t - m + i]).sum::<f64>();
        sigma2 = (m..n).map(|t| f(t) * f(t) + b(t) * b(t)).sum::<f64>() / (2 * (n - m)) as f64;
    }
    (a[1..].iter().map(|v| -v).collect(), pacf, sigma2, power)
}

#[test]
fn ma1_series_matches_r_ar_burg_orders_1_to_5() {
    // R printed 7-8 significant digits; statsmodels' own test uses atol 1e-6 (data README).
    let reference = data::statsmodels_reference();
    let expected = reference["burg_ma1_orders1to5"]["expected_phi_from_R_ar.burg"]
        .as_array()
        .unwrap()
        .clone();
    let y = data::burg_ma1();
    for (i, phi) in expected.iter().enumerate() {
        let model = fit_ar(&y, Order::Fixed(i + 1), ArMethod::Burg).unwrap();
        assert_close(
            &model.coefficients,
            &data::floats(phi),
            1e-6,
            0.0,
            &format!("AR({})", i + 1),
        );
    }
}

#[test]
fn spectrum_example_gives_both_variance_definitions() {
    // spectrum arburg([1..7,-8], 4), no mean removal. a and k printed to 5-6 significant
    // digits (spectrum tests 5 decimals): 1e-5 and 1e-6 absolute. P = 22.44687609887804 and
    // statsmodels' sigma2 = 21.914524584881168 are full precision: 1e-12 relative. statsmodels'
    // phi printed with 7 decimals: 1e-7 absolute.
    let reference = data::spectrum_reference();
    let case = &reference["burg_real"];
    let x = data::floats(&case["data"]);
    let spec = ArSpec::new(Order::Fixed(4), ArMethod::Burg).with_mean(MeanModel::Zero);
    let model = fit_ar_with(&x, &spec).unwrap();
    let a: Vec<f64> = model.coefficients.iter().map(|c| -c).collect();
    assert_close(
        &a,
        &data::floats(&case["expected_a"]),
        1e-5,
        0.0,
        "A-polynomial",
    );
    let k: Vec<f64> = model
        .partial_autocorrelation
        .as_ref()
        .unwrap()
        .iter()
        .map(|c| -c)
        .collect();
    assert_close(
        &k,
        &data::floats(&case["expected_reflection_k"]),
        1e-6,
        0.0,
        "reflection",
    );
    let p = data::float(&case["expected_noise_variance_P"]);
    assert_scalar(model.recursion_power.unwrap(), p, 0.0, 1e-12, "spectrum P");
    assert_scalar(
        model.noise_variance,
        21.914524584881168,
        0.0,
        1e-12,
        "statsmodels sigma2",
    );
    let statsmodels_phi = [0.3258074, -0.00034571, -0.03378978, -0.09885273];
    assert_close(
        &model.coefficients,
        &statsmodels_phi,
        1e-7,
        0.0,
        "statsmodels phi",
    );
}

#[test]
fn fast_burg_matches_textbook_burg() {
    // The Gram-matrix Burg re-associates every sum; against the textbook recursion the
    // coefficients agree to rounding of well-conditioned sums: 1e-11 absolute on |c| ~ 1.
    // The variances carry the factors (1 - k_m^2), whose relative rounding is amplified by
    // 2 k^2 / (1 - k^2) (3650 for k = 0.99986 below): tolerance 1e-12 + 1e-14 times that sum.
    // Includes AR(1) with c = 0.999 (Gram path) and c = 0.99999 summed over 8 samples, whose
    // error energy falls below 1e-4 of the signal at stage 2 (explicit error sequences).
    let smooth: Vec<f64> = data::simulate_ar(&[0.99999], 4000, 3)
        .windows(8)
        .map(|w| w.iter().sum::<f64>())
        .collect();
    let cases = [
        (data::simulate_ar(&[0.6, -0.3, 0.2], 2000, 1), 6),
        (data::simulate_ar(&[0.999], 3000, 2), 3),
        (smooth, 5),
        (data::burg_ma1()[..777].to_vec(), 9),
    ];
    for (i, (x, p)) in cases.iter().enumerate() {
        let spec = ArSpec::new(Order::Fixed(*p), ArMethod::Burg).with_mean(MeanModel::Zero);
        let model = fit_ar_with(x, &spec).unwrap();
        let (c, pacf, sigma2, power) = naive_burg(x, *p);
        let label = format!("case {i}");
        let conditioning: f64 = pacf.iter().map(|k| 2.0 * k * k / (1.0 - k * k)).sum();
        let variance_tol = 1e-12 + 1e-14 * conditioning;
        assert_close(&model.coefficients, &c, 1e-11, 0.0, &label);
        assert_close(
            model.partial_autocorrelation.as_ref().unwrap(),
            &pacf,
            1e-11,
            0.0,
            &label,
        );
        assert_scalar(model.noise_variance, sigma2, 0.0, variance_tol, &label);
        assert_scalar(
            model.recursion_power.unwrap(),
            power,
            0.0,
            variance_tol,
            &label,
        );
    }
}
