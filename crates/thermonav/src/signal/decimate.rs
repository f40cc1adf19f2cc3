//! Decimation after an anti-alias filter: keep every n-th sample.

use super::SignalError;

/// Relative tolerance on the rate ratio: a logger's nominal rate comes from its median sample
/// interval and can be off its design value by parts per thousand.
pub const RATE_RATIO_TOLERANCE: f64 = 1e-3;

/// The integer factor taking `input_rate_hz` to `target_rate_hz`.
///
/// # Errors
/// [`SignalError::Decimation`] when either rate is not finite and positive, the target is above
/// the input rate, or the ratio is not an integer within [`RATE_RATIO_TOLERANCE`].
pub fn decimation_factor(input_rate_hz: f64, target_rate_hz: f64) -> Result<usize, SignalError> {
    let refuse = |reason: &str| SignalError::Decimation {
        input_rate_hz,
        target_rate_hz,
        reason: reason.to_string(),
    };
    if !(input_rate_hz.is_finite()
        && input_rate_hz > 0.0
        && target_rate_hz.is_finite()
        && target_rate_hz > 0.0)
    {
        return Err(refuse("rates must be finite and positive"));
    }
    let ratio = input_rate_hz / target_rate_hz;
    let factor = ratio.round();
    if factor < 1.0 {
        return Err(refuse("the target is above the input rate"));
    }
    if (ratio - factor).abs() > RATE_RATIO_TOLERANCE * ratio {
        return Err(refuse(
            "the input rate is not an integer multiple of the target",
        ));
    }
    Ok(factor as usize)
}

/// Every `factor`-th element, starting with the first.
pub fn decimate<T: Copy>(x: &[T], factor: usize) -> Vec<T> {
    x.iter().step_by(factor.max(1)).copied().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_are_integer_ratios() {
        assert_eq!(decimation_factor(200.0, 10.0), Ok(20));
        assert_eq!(decimation_factor(199.98, 10.0), Ok(20));
        assert!(decimation_factor(200.0, 3.0).is_err());
        assert!(decimation_factor(200.0, 400.0).is_err());
        assert!(decimation_factor(f64::NAN, 1.0).is_err());
        let message = decimation_factor(200.0, 3.0).unwrap_err().to_string();
        assert!(
            message.contains("200") && message.contains('3'),
            "{message}"
        );
    }

    #[test]
    fn keeps_every_nth_from_the_first() {
        assert_eq!(decimate(&[0, 1, 2, 3, 4, 5, 6], 3), vec![0, 3, 6]);
        assert_eq!(decimate(&[1.5], 20), vec![1.5]);
    }
}
