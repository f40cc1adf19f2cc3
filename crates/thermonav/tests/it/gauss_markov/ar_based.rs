//! The AR-based Gauss-Markov model (eqs. 8-10) against statsmodels values and closed forms.

use std::path::PathBuf;

use thermonav::stoch::gauss_markov::{
    Ar1Estimate, ArGaussMarkov, ArGaussMarkovFit, ConfidenceLevel, GaussMarkov, GaussMarkovError,
    NoGaussMarkovEquivalent, UpperBound, gauss_markov_from_ar1,
};

use super::relative_error;

const LEVEL: ConfidenceLevel = ConfidenceLevel::NINETY_FIVE_PERCENT;
/// Two-sided 95 % normal quantile (tabulated).
const Z95: f64 = 1.959_963_984_540_054;

fn model_of(estimate: &Ar1Estimate) -> ArGaussMarkovFit {
    match gauss_markov_from_ar1(estimate, LEVEL).unwrap() {
        ArGaussMarkov::Model(fit) => fit,
        other => panic!("expected a model, got {other:?}"),
    }
}

/// `peer-results-on-real-data`: statsmodels 0.15.0 Yule-Walker AR(1) of 1-s block means of a
/// real static ADIS16405 run, with `tau = -dt / ln phi1` computed by the data's author.
fn statsmodels_results() -> serde_json::Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(
        "../../../shared/data/peer-results-on-real-data/adis_16405_imu1_1s_ar_statsmodels.json",
    );
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap()
}

#[test]
fn correlation_times_match_statsmodels_on_real_imu_data() {
    let results = statsmodels_results();
    let channels = results["results"].as_object().unwrap();
    assert_eq!(channels.len(), 6);
    for (channel, fit) in channels {
        let phi = fit["yw_order1_phi"][0].as_f64().unwrap();
        let innovation_sd = fit["yw_order1_sigma"].as_f64().unwrap();
        let n = fit["n"].as_f64().unwrap();
        let expected_tau = fit["gauss_markov_tau_s_from_yw_ar1"].as_f64().unwrap();
        // Asymptotic se of an AR(1) coefficient, sqrt((1 - phi^2)/n); it does not enter Tc.
        let se = ((1.0 - phi * phi) / n).sqrt();
        let estimate = Ar1Estimate::new(phi, se, innovation_sd * innovation_sd, 1.0).unwrap();
        let fit = model_of(&estimate);
        // Same formula, same inputs: agreement to rounding (1e-13).
        let tc = fit.model.correlation_time_s();
        assert!(
            relative_error(tc, expected_tau) < 1e-13,
            "{channel}: {tc} vs {expected_tau}"
        );
        // Stationary variance of the AR(1) process, var(w) / (1 - phi^2).
        let variance = innovation_sd * innovation_sd / (1.0 - phi * phi);
        assert!(
            relative_error(fit.model.variance(), variance) < 1e-13,
            "{channel}"
        );
        assert!(fit.correlation_time_interval.contains(tc));
    }
}

#[test]
fn interval_maps_the_normal_interval_of_c1_through_tc() {
    // c1 = 0.9 +- 1.96 * 0.01 at dt = 5 ms; Tc(c) = -dt / ln c at both ends (closed form).
    let estimate = Ar1Estimate::new(0.9, 0.01, 2e-4, 0.005).unwrap();
    let fit = model_of(&estimate);
    let tc = |c: f64| -0.005 / c.ln();
    assert!(relative_error(fit.model.correlation_time_s(), tc(0.9)) < 1e-15);
    let interval = fit.correlation_time_interval;
    // The quantile comes from statrs (1e-15 relative): 1e-12 on the mapped bounds.
    assert!(relative_error(interval.lower_s, tc(0.9 - Z95 * 0.01)) < 1e-12);
    let UpperBound::Finite(upper_s) = interval.upper else {
        panic!("finite upper bound expected")
    };
    assert!(relative_error(upper_s, tc(0.9 + Z95 * 0.01)) < 1e-12);
    assert_eq!(interval.level, LEVEL);
}

#[test]
fn interval_is_unbounded_above_when_the_c1_interval_reaches_one() {
    // 0.995 + 1.96 * 0.01 > 1: an AR(1) that may be a random walk has no upper Tc bound.
    let fit = model_of(&Ar1Estimate::new(0.995, 0.01, 1e-6, 0.01).unwrap());
    assert_eq!(fit.correlation_time_interval.upper, UpperBound::Unbounded);
    assert!(fit.correlation_time_interval.lower_s > 0.0);
    // 0.01 - 1.96 * 0.01 < 0: white noise is inside the interval, lower bound 0 s.
    let fit = model_of(&Ar1Estimate::new(0.01, 0.01, 1.0, 0.01).unwrap());
    assert_eq!(fit.correlation_time_interval.lower_s, 0.0);
    assert!(matches!(fit.correlation_time_interval.upper, UpperBound::Finite(u) if u.is_finite()));
}

#[test]
fn coefficients_outside_the_unit_interval_have_no_equivalent() {
    let outcome = |c1: f64| {
        gauss_markov_from_ar1(&Ar1Estimate::new(c1, 0.01, 1.0, 0.01).unwrap(), LEVEL).unwrap()
    };
    for c1 in [1.0, 1.02] {
        assert_eq!(
            outcome(c1),
            ArGaussMarkov::NoEquivalent(NoGaussMarkovEquivalent::RandomWalkOrDrift { c1 })
        );
    }
    for c1 in [0.0, -0.3, -1.5] {
        assert_eq!(
            outcome(c1),
            ArGaussMarkov::NoEquivalent(NoGaussMarkovEquivalent::NoPositiveCorrelation { c1 })
        );
    }
}

#[test]
fn gauss_markov_to_ar1_and_back_is_the_identity() {
    // Discretising a GM at dt gives c1 = phi(dt), var(w) = eq. 4; eqs. 10 and sigma^2 =
    // var(w)/(1 - c1^2) invert that exactly. Rounding of ln near 1 costs ~eps/(dt/Tc):
    // 1e-11 at dt/Tc = 1e-4.
    let model = GaussMarkov::new(3.7, 0.02).unwrap();
    for dt_s in [3.7e-4, 0.01, 0.37, 3.7, 11.0] {
        let estimate = Ar1Estimate::new(
            model.phi(dt_s),
            0.0,
            model.driving_noise_variance(dt_s),
            dt_s,
        )
        .unwrap();
        let back = model_of(&estimate).model;
        assert!(
            relative_error(back.correlation_time_s(), 3.7) < 1e-11,
            "dt = {dt_s}"
        );
        assert!(relative_error(back.sigma(), 0.02) < 1e-11, "dt = {dt_s}");
    }
}

#[test]
fn extreme_but_valid_inputs_give_finite_numbers_or_errors() {
    // c1 one ulp below 1 and an enormous innovation variance: sigma^2 would overflow.
    let c1 = 1.0 - f64::EPSILON / 2.0;
    let estimate = Ar1Estimate::new(c1, 0.0, 1e300, 1.0).unwrap();
    assert!(matches!(
        gauss_markov_from_ar1(&estimate, LEVEL),
        Err(GaussMarkovError::OutOfRange { .. })
    ));
    // The same c1 with a modest variance: a huge but finite Tc, and an unbounded interval
    // when its standard error is positive.
    let fit = model_of(&Ar1Estimate::new(c1, 1e-3, 1e-6, 1.0).unwrap());
    assert!(fit.model.correlation_time_s().is_finite());
    assert_eq!(fit.correlation_time_interval.upper, UpperBound::Unbounded);
    // An enormous dt and tiny c1 also stay finite.
    let fit = model_of(&Ar1Estimate::new(1e-300, 0.0, 1.0, 1e100).unwrap());
    assert!(fit.model.correlation_time_s().is_finite());
}

#[test]
fn invalid_ar1_estimates_are_rejected() {
    assert!(matches!(
        Ar1Estimate::new(f64::NAN, 0.1, 1.0, 0.01),
        Err(GaussMarkovError::NonFinite { .. })
    ));
    for se in [-0.1, f64::INFINITY, f64::NAN] {
        assert!(matches!(
            Ar1Estimate::new(0.5, se, 1.0, 0.01),
            Err(GaussMarkovError::InvalidStdError { .. })
        ));
    }
    assert!(matches!(
        Ar1Estimate::new(0.5, 0.1, 0.0, 0.01),
        Err(GaussMarkovError::NotPositive { .. })
    ));
    assert!(matches!(
        Ar1Estimate::new(0.5, 0.1, 1.0, -0.01),
        Err(GaussMarkovError::NotPositive { .. })
    ));
}
