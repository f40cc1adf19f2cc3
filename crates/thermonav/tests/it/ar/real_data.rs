//! Yule-Walker and Burg on the real ADIS16405 static run against statsmodels 0.15.0
//! (`peer-results-on-real-data/adis_16405_imu1_1s_ar_statsmodels.json`, data README §4).

use std::io::{BufRead, BufReader};

use flate2::read::GzDecoder;
use thermonav::stoch::ar::{ArMethod, Order, fit_ar};

use super::data::{self, assert_close, assert_scalar};

/// The six channels of `adis_16405_imu1.csv.gz`, each averaged over non-overlapping blocks of
/// 100 samples (1 s at 100 Hz), as the peer did: (header name, 10 000 block means).
fn one_second_block_means() -> Vec<(String, Vec<f64>)> {
    let file = std::fs::File::open(data::shared("smac-imudata/adis_16405_imu1.csv.gz"))
        .expect("data file");
    let mut lines = BufReader::new(GzDecoder::new(file))
        .lines()
        .map(|l| l.expect("gzip text"));
    let names: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    let mut sums = vec![Vec::new(); names.len()];
    for (row, line) in lines.enumerate() {
        if row % 100 == 0 {
            sums.iter_mut().for_each(|s| s.push(0.0));
        }
        for (channel, value) in line.split(',').enumerate() {
            *sums[channel].last_mut().unwrap() += value.parse::<f64>().expect("number");
        }
    }
    names
        .into_iter()
        .zip(sums)
        .map(|(name, s)| (name, s.iter().map(|v| v / 100.0).collect()))
        .collect()
}

#[test]
fn adis16405_one_second_means_match_statsmodels() {
    // statsmodels yule_walker(method='mle') returns sigma (not sigma^2) and burg returns sigma2;
    // both printed to full precision. Block means summed in a different order than numpy's
    // pairwise mean differ in the last bits: 1e-9 relative on sigma and 1e-9 absolute on
    // coefficients (|c| < 1) cover that with margin.
    let reference = data::read_json(data::shared(
        "peer-results-on-real-data/adis_16405_imu1_1s_ar_statsmodels.json",
    ));
    let channels = one_second_block_means();
    assert_eq!(channels.len(), 6);
    for (name, x) in &channels {
        let expected = &reference["results"][name.as_str()];
        assert_eq!(x.len(), expected["n"].as_u64().unwrap() as usize, "{name}");
        for p in 1..=3 {
            let label = format!("{name} AR({p})");
            let yw = fit_ar(x, Order::Fixed(p), ArMethod::YuleWalker).unwrap();
            assert_close(
                &yw.coefficients,
                &data::floats(&expected[format!("yw_order{p}_phi")]),
                1e-9,
                0.0,
                &label,
            );
            let sigma = data::float(&expected[format!("yw_order{p}_sigma")]);
            assert_scalar(yw.noise_variance.sqrt(), sigma, 0.0, 1e-9, &label);
            let burg = fit_ar(x, Order::Fixed(p), ArMethod::Burg).unwrap();
            assert_close(
                &burg.coefficients,
                &data::floats(&expected[format!("burg_order{p}_phi")]),
                1e-9,
                0.0,
                &label,
            );
            let sigma2 = data::float(&expected[format!("burg_order{p}_sigma2")]);
            assert_scalar(burg.noise_variance, sigma2, 0.0, 1e-9, &label);
        }
        // The peer's Gauss-Markov correlation time tau = -dt / ln c1 from YW AR(1), dt = 1 s.
        let c1 = fit_ar(x, Order::Fixed(1), ArMethod::YuleWalker)
            .unwrap()
            .coefficients[0];
        let tau_s = -1.0 / c1.ln();
        assert_scalar(
            tau_s,
            data::float(&expected["gauss_markov_tau_s_from_yw_ar1"]),
            0.0,
            1e-9,
            name,
        );
    }
}
