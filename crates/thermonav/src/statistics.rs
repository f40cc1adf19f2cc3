//! Order statistics of plain numbers, for any module: the median of sorted values and the
//! median absolute deviation. (The generic filter's gate scales by a median NIS; a production
//! lot's outlier rule by the MAD.)

/// Median of values sorted in increasing order (mean of the middle two for an even count).
///
/// # Panics
/// Never on a non-empty slice; an empty slice gives NaN.
pub fn median_of_sorted(sorted: &[f64]) -> f64 {
    let n = sorted.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => sorted[n / 2],
        _ => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// Median absolute deviation of `values` from `median` (unscaled).
pub fn median_absolute_deviation(values: &[f64], median: f64) -> f64 {
    let mut deviations: Vec<f64> = values.iter().map(|v| (v - median).abs()).collect();
    deviations.sort_by(f64::total_cmp);
    median_of_sorted(&deviations)
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed forms worked by hand.
    #[test]
    fn median_and_mad_of_small_samples() {
        assert_eq!(median_of_sorted(&[1.0, 2.0, 10.0]), 2.0);
        assert_eq!(median_of_sorted(&[1.0, 2.0, 3.0, 4.0]), 2.5);
        assert!(median_of_sorted(&[]).is_nan());
        // [1, 2, 3, 4, 100]: median 3, deviations 2 1 0 1 97, their median 1.
        let values = [1.0, 2.0, 3.0, 4.0, 100.0];
        assert_eq!(median_absolute_deviation(&values, 3.0), 1.0);
    }
}
