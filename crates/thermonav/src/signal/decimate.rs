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

/// Relative slack of [`check_anti_alias`], for rates and widths typed in decimal
/// (0.4 + 0.2/2 is 0.5 only to rounding in general).
pub const ANTI_ALIAS_SLACK: f64 = 1e-9;

/// Whether a Kaiser low-pass of `cutoff_hz` and `transition_hz` may precede decimation to
/// `target_rate_hz`: its stop band, from cutoff + transition/2 (the design centres the
/// transition on the cut-off, as SciPy's `kaiserord` + `firwin`), must start at or below the new
/// Nyquist frequency target/2. Only frequencies above the new Nyquist frequency fold back, and
/// those are then all attenuated by the design's full attenuation; the transition band itself
/// lies below it and is kept, not aliased. (`characterize`'s defaults, 0.4 Hz + 0.2 Hz to
/// 1 Hz, put the stop-band edge exactly on the 0.5 Hz Nyquist frequency.)
///
/// # Errors
/// [`SignalError::Aliasing`] when the stop band starts above the new Nyquist frequency
/// (more than [`ANTI_ALIAS_SLACK`] relative); [`SignalError::Spec`] for a value that is not
/// finite and positive.
pub fn check_anti_alias(
    cutoff_hz: f64,
    transition_hz: f64,
    target_rate_hz: f64,
) -> Result<(), SignalError> {
    let values = [cutoff_hz, transition_hz, target_rate_hz];
    if !values.iter().all(|v| v.is_finite() && *v > 0.0) {
        return Err(SignalError::Spec {
            message: format!(
                "cut-off {cutoff_hz} Hz, transition {transition_hz} Hz and decimated rate {target_rate_hz} Hz must be finite and positive"
            ),
        });
    }
    let stop_band_hz = cutoff_hz + transition_hz / 2.0;
    let nyquist_hz = target_rate_hz / 2.0;
    if stop_band_hz <= nyquist_hz * (1.0 + ANTI_ALIAS_SLACK) {
        return Ok(());
    }
    Err(SignalError::Aliasing {
        cutoff_hz,
        transition_hz,
        stop_band_hz,
        nyquist_hz,
        target_rate_hz,
    })
}

/// The indices j = 0, F, 2F, … (F = `factor`) kept by a decimation after a filter whose output
/// at j reads the input from j − `edge` to j + `edge`: those with `edge` ≤ j ≤ n − 1 − `edge`,
/// whose whole window lies inside the n samples (no edge extension reaches them), as the
/// range `first..end` to step through by F (empty when none fits).
pub fn valid_decimated_indices(n: usize, edge: usize, factor: usize) -> std::ops::Range<usize> {
    let factor = factor.max(1);
    let first = edge.div_ceil(factor) * factor;
    let end = n.saturating_sub(edge);
    if first >= end {
        return n..n;
    }
    first..end
}

/// The elements of `x` at [`valid_decimated_indices`]`(x.len(), edge, factor)`.
pub fn decimate_valid<T: Copy>(x: &[T], edge: usize, factor: usize) -> Vec<T> {
    let kept = valid_decimated_indices(x.len(), edge, factor);
    x[kept].iter().step_by(factor.max(1)).copied().collect()
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

    // The rule written out: stop band cut-off + transition/2 against target/2.
    #[test]
    fn anti_alias_rule_puts_the_stop_band_at_or_below_the_new_nyquist() {
        assert_eq!(
            check_anti_alias(0.4, 0.2, 1.0),
            Ok(()),
            "characterize's defaults"
        );
        assert_eq!(check_anti_alias(0.3, 0.4, 1.0), Ok(()));
        assert!(check_anti_alias(0.41, 0.2, 1.0).is_err());
        assert!(check_anti_alias(5.0, 1.0, 10.0).is_err());
        assert_eq!(check_anti_alias(4.5, 1.0, 10.0), Ok(()));
        let message = check_anti_alias(0.45, 0.2, 1.0).unwrap_err().to_string();
        assert!(
            message.contains("0.55") && message.contains("Nyquist"),
            "{message}"
        );
        assert!(matches!(
            check_anti_alias(f64::NAN, 0.2, 1.0),
            Err(SignalError::Spec { .. })
        ));
        assert!(matches!(
            check_anti_alias(0.4, 0.2, -1.0),
            Err(SignalError::Spec { .. })
        ));
    }

    // Written out by hand: 20 samples, window ±3, every 4th of the grid 0, 4, 8, …: 4, 8, 12,
    // 16 (16 + 3 = 19 is the last sample); 0 reads samples -3..3, and 20 is past the end.
    #[test]
    fn valid_indices_are_the_grid_points_whose_window_is_inside() {
        let x: Vec<usize> = (0..20).collect();
        assert_eq!(decimate_valid(&x, 3, 4), vec![4, 8, 12, 16]);
        assert_eq!(decimate_valid(&x, 4, 4), vec![4, 8, 12]);
        assert_eq!(decimate_valid(&x, 0, 5), vec![0, 5, 10, 15]);
        assert!(decimate_valid(&x, 10, 3).is_empty());
        assert!(decimate_valid(&x, 30, 3).is_empty());
        assert_eq!(valid_decimated_indices(20, 3, 0), 3..17);
        assert_eq!(valid_decimated_indices(20, 30, 3), 20..20);
    }

    #[test]
    fn keeps_every_nth_from_the_first() {
        assert_eq!(decimate(&[0, 1, 2, 3, 4, 5, 6], 3), vec![0, 3, 6]);
        assert_eq!(decimate(&[1.5], 20), vec![1.5]);
    }
}
