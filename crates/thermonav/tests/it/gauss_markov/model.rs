//! The model's closed forms (eqs. 1-4) and its validation.

use thermonav::stoch::gauss_markov::{
    ConfidenceLevel, CorrelationTimeInterval, GaussMarkov, GaussMarkovError, UpperBound,
};

use super::relative_error;

#[test]
fn exact_driving_noise_keeps_the_variance_stationary_at_every_step_length() {
    // Closed form: phi^2 sigma^2 + var(w) = sigma^2 (eqs. 3-4) for any dt. Both terms are
    // computed to a few ulp, hence 1e-15.
    let model = GaussMarkov::new(2.5, 0.3).unwrap();
    for dt_s in [1e-9, 1e-4, 0.005, 0.5, 2.5, 40.0, 1e3] {
        let phi = model.phi(dt_s);
        let stationary = phi * phi * model.variance() + model.driving_noise_variance(dt_s);
        assert!(
            relative_error(stationary, model.variance()) < 1e-15,
            "dt = {dt_s}"
        );
    }
}

#[test]
fn driving_noise_variance_is_eq_4_and_accurate_for_tiny_steps() {
    let model = GaussMarkov::new(2.5, 0.3).unwrap();
    // Moderate steps: the plain formula of eq. 4 has no cancellation problem there (1e-14).
    for dt_s in [0.01, 0.5, 3.0] {
        let plain = 0.09 * (1.0 - (-2.0 * dt_s / 2.5_f64).exp());
        assert!(relative_error(model.driving_noise_variance(dt_s), plain) < 1e-14);
    }
    // Tiny step: Taylor series 2x - 2x^2 + 4x^3/3 of 1 - exp(-2x), x = dt/Tc = 4e-10; the
    // truncation is ~x^3 relative, so the series is exact to rounding (1e-15).
    let x = 1e-9 / 2.5;
    let series = 0.09 * (2.0 * x - 2.0 * x * x + 4.0 * x * x * x / 3.0);
    assert!(relative_error(model.driving_noise_variance(1e-9), series) < 1e-15);
    // The first-order q dt of eq. 1 differs by ~dt/Tc relative: small only for small steps.
    let q_dt = model.spectral_density_q() * 0.5;
    assert!(relative_error(q_dt, model.driving_noise_variance(0.5)) > 0.1);
}

#[test]
fn autocorrelation_and_spectral_density_are_eqs_1_and_2() {
    let model = GaussMarkov::new(0.8, 1.5).unwrap();
    // R(0) = sigma^2, R(Tc) = sigma^2 / e, R(-tau) = R(tau); q = 2 sigma^2 / Tc (exact forms).
    assert_eq!(model.autocorrelation(0.0), 2.25);
    assert!(relative_error(model.autocorrelation(0.8), 2.25 / std::f64::consts::E) < 1e-15);
    assert_eq!(model.autocorrelation(-0.3), model.autocorrelation(0.3));
    assert!(relative_error(model.spectral_density_q(), 2.0 * 2.25 / 0.8) < 1e-15);
    assert_eq!(model.correlation_time_s(), 0.8);
    assert_eq!(model.sigma(), 1.5);
}

#[test]
fn one_step_is_the_exact_transition() {
    // x_k = phi x_{k-1} + sqrt(var w) n, by hand.
    let model = GaussMarkov::new(0.8, 1.5).unwrap();
    let expected =
        (-0.1_f64 / 0.8).exp() * 0.7 + (2.25 * (1.0 - (-0.2_f64 / 0.8).exp())).sqrt() * -1.3;
    assert!(relative_error(model.next_value(0.7, 0.1, -1.3), expected) < 1e-14);
}

#[test]
fn invalid_parameters_are_rejected() {
    for (tc, sigma) in [
        (0.0, 1.0),
        (-1.0, 1.0),
        (f64::NAN, 1.0),
        (1.0, f64::INFINITY),
    ] {
        assert!(matches!(
            GaussMarkov::new(tc, sigma),
            Err(GaussMarkovError::NotPositive { .. })
        ));
    }
    // sigma^2 overflows; q = 2 sigma^2 / Tc overflows for a tiny Tc.
    assert!(matches!(
        GaussMarkov::new(1.0, 1e200),
        Err(GaussMarkovError::OutOfRange { .. })
    ));
    assert!(matches!(
        GaussMarkov::new(1e-310, 1e5),
        Err(GaussMarkovError::OutOfRange { .. })
    ));
}

#[test]
fn serde_round_trips_and_validates() {
    let model = GaussMarkov::new(12.5, 0.01).unwrap();
    let text = serde_json::to_string(&model).unwrap();
    assert_eq!(serde_json::from_str::<GaussMarkov>(&text).unwrap(), model);
    let bad = r#"{"correlation_time_s": -1.0, "sigma": 1.0}"#;
    assert!(serde_json::from_str::<GaussMarkov>(bad).is_err());
}

#[test]
fn confidence_level_quantiles_are_the_standard_values() {
    // Tabulated: z_0.975 = 1.959963984540054, chi2_1(0.95) = 3.841458820694124. statrs inverts
    // the normal CDF to ~1e-15; 1e-12 leaves room.
    let level = ConfidenceLevel::NINETY_FIVE_PERCENT;
    assert!((level.normal_quantile() - 1.959_963_984_540_054).abs() < 1e-12);
    assert!((level.chi_square_1dof_quantile() - 3.841_458_820_694_124).abs() < 1e-11);
    assert!(
        (ConfidenceLevel::new(0.99).unwrap().normal_quantile() - 2.575_829_303_548_9).abs() < 1e-11
    );
    for bad in [0.0, 1.0, -0.5, f64::NAN] {
        assert!(matches!(
            ConfidenceLevel::new(bad),
            Err(GaussMarkovError::InvalidConfidenceLevel { .. })
        ));
    }
}

#[test]
fn interval_membership_respects_an_unbounded_upper_end() {
    let level = ConfidenceLevel::NINETY_FIVE_PERCENT;
    let bounded = CorrelationTimeInterval {
        lower_s: 1.0,
        upper: UpperBound::Finite(3.0),
        level,
    };
    assert!(bounded.contains(1.0) && bounded.contains(3.0) && !bounded.contains(3.1));
    let unbounded = CorrelationTimeInterval {
        upper: UpperBound::Unbounded,
        ..bounded
    };
    assert!(unbounded.contains(1e300) && !unbounded.contains(0.5));
}
