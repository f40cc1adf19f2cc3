//! Kaiser-window FIR low-pass design, identical to SciPy's `kaiserord` + `firwin`.
//!
//! Kaiser's empirical formulas (Kaiser 1974; Oppenheim & Schafer, *Discrete-Time Signal
//! Processing*, 3rd ed., eqs. 7.62-7.63): for a stop-band attenuation and pass-band ripple of
//! A dB and a transition width Δω (rad/sample),
//! β = 0.1102 (A − 8.7) for A > 50, 0.5842 (A − 21)^0.4 + 0.07886 (A − 21) for 21 ≤ A ≤ 50,
//! 0 below; N = ⌈(A − 7.95) / (2.285 Δω)⌉ + 1 taps, with Δω = π · width / (fs/2) as SciPy
//! writes it. The taps are the ideal low-pass impulse response `h[m] = c·sinc(c·m)`,
//! m = n − (N−1)/2, c = cutoff / (fs/2), times the symmetric Kaiser window
//! `w[n] = I₀(β √(1 − (2n/(N−1) − 1)²)) / I₀(β)`, scaled so that the gain at DC is exactly 1.

use super::SignalError;

/// The transition width of a design that is not given one, Hz (`thermonav fir` and `filter`,
/// Python's `fir`, `zero_phase` and `decimate`).
pub const DEFAULT_TRANSITION_HZ: f64 = 1.0;

/// The stop-band attenuation and pass-band ripple of a design that is not given one, dB (the
/// commands and functions of [`DEFAULT_TRANSITION_HZ`], and characterisation's conditioning).
pub const DEFAULT_RIPPLE_DB: f64 = 60.0;

/// A validated Kaiser low-pass specification.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KaiserSpec {
    sample_rate_hz: f64,
    cutoff_hz: f64,
    transition_width_hz: f64,
    ripple_db: f64,
}

/// A designed linear-phase FIR filter.
#[derive(Debug, Clone, PartialEq)]
pub struct FirFilter {
    taps: Vec<f64>,
    beta: f64,
    sample_rate_hz: f64,
}

/// The smallest attenuation Kaiser's order formula accepts, dB (SciPy refuses below 8 dB).
pub const MIN_RIPPLE_DB: f64 = 8.0;
/// Largest number of taps designed (about 2 s of a 1 MHz signal; keeps memory bounded).
pub const MAX_TAPS: usize = 2_000_000;

impl KaiserSpec {
    /// The checks of [`KaiserSpec::new`] that need no sampling rate, for a specification whose
    /// rate is known later: cut-off and transition width finite and positive, ripple finite,
    /// positive and at least [`MIN_RIPPLE_DB`].
    ///
    /// # Errors
    /// [`SignalError::Spec`] naming the value, as [`KaiserSpec::new`] gives it.
    pub fn check_band(
        cutoff_hz: f64,
        transition_width_hz: f64,
        ripple_db: f64,
    ) -> Result<(), SignalError> {
        let spec = |message: String| Err(SignalError::Spec { message });
        for (name, value) in [
            ("cut-off", cutoff_hz),
            ("transition width", transition_width_hz),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return spec(format!("{name} {value} Hz must be finite and positive"));
            }
        }
        if !(ripple_db.is_finite() && ripple_db > 0.0) {
            return spec(format!("ripple {ripple_db} dB must be finite and positive"));
        }
        if ripple_db < MIN_RIPPLE_DB {
            return spec(format!(
                "ripple {ripple_db} dB is below {MIN_RIPPLE_DB} dB, where Kaiser's formula does not apply"
            ));
        }
        Ok(())
    }

    /// A specification: sampling rate, pass-band edge, transition width (all Hz) and ripple /
    /// attenuation (dB).
    ///
    /// # Errors
    /// [`SignalError::Spec`] when a value is not finite and positive, the cut-off is at or above
    /// the Nyquist frequency, the transition band extends past Nyquist, or the ripple is below
    /// 8 dB (outside Kaiser's formula).
    pub fn new(
        sample_rate_hz: f64,
        cutoff_hz: f64,
        transition_width_hz: f64,
        ripple_db: f64,
    ) -> Result<Self, SignalError> {
        let spec = |message: String| Err(SignalError::Spec { message });
        if !(sample_rate_hz.is_finite() && sample_rate_hz > 0.0) {
            return spec(format!(
                "sample rate {sample_rate_hz} Hz must be finite and positive"
            ));
        }
        Self::check_band(cutoff_hz, transition_width_hz, ripple_db)?;
        let nyquist_hz = sample_rate_hz / 2.0;
        if cutoff_hz >= nyquist_hz {
            return spec(format!(
                "cut-off {cutoff_hz} Hz must be below the Nyquist frequency {nyquist_hz} Hz of a {sample_rate_hz} Hz signal"
            ));
        }
        if cutoff_hz + transition_width_hz / 2.0 > nyquist_hz {
            return spec(format!(
                "cut-off {cutoff_hz} Hz plus half the transition width {transition_width_hz} Hz passes the Nyquist frequency {nyquist_hz} Hz"
            ));
        }
        Ok(Self {
            sample_rate_hz,
            cutoff_hz,
            transition_width_hz,
            ripple_db,
        })
    }

    /// Sampling rate, Hz.
    pub fn sample_rate_hz(&self) -> f64 {
        self.sample_rate_hz
    }

    /// Pass-band edge, Hz.
    pub fn cutoff_hz(&self) -> f64 {
        self.cutoff_hz
    }

    /// Transition width, Hz.
    pub fn transition_width_hz(&self) -> f64 {
        self.transition_width_hz
    }

    /// Ripple / attenuation, dB.
    pub fn ripple_db(&self) -> f64 {
        self.ripple_db
    }
}

/// Kaiser's β for an attenuation of `a` dB (SciPy `kaiser_beta`).
pub fn kaiser_beta(a: f64) -> f64 {
    if a > 50.0 {
        0.1102 * (a - 8.7)
    } else if a > 21.0 {
        0.5842 * (a - 21.0).powf(0.4) + 0.07886 * (a - 21.0)
    } else {
        0.0
    }
}

/// Number of taps and β for ripple `a` dB and a transition `width` normalised to Nyquist = 1
/// (SciPy `kaiserord`).
pub fn kaiser_order(a: f64, width: f64) -> (usize, f64) {
    (kaiser_taps(a, width).ceil() as usize, kaiser_beta(a))
}

/// The number of taps of [`kaiser_order`] before rounding (infinite for a zero width).
fn kaiser_taps(a: f64, width: f64) -> f64 {
    (a - 7.95) / 2.285 / (std::f64::consts::PI * width) + 1.0
}

/// Modified Bessel function of the first kind, order zero, by its power series
/// I₀(x) = Σ ((x/2)^k / k!)², summed until a term no longer changes the sum (relative error
/// ~1e-16 for the x ≤ 700 that Kaiser windows use).
pub fn bessel_i0(x: f64) -> f64 {
    let q = x * x / 4.0;
    let (mut sum, mut term, mut k) = (1.0_f64, 1.0_f64, 0.0_f64);
    loop {
        k += 1.0;
        term *= q / (k * k);
        let next = sum + term;
        if next == sum {
            return sum;
        }
        sum = next;
    }
}

/// Symmetric Kaiser window of `n` points (SciPy `get_window(('kaiser', β), n, fftbins=False)`).
pub fn kaiser_window(n: usize, beta: f64) -> Vec<f64> {
    if n == 1 {
        return vec![1.0];
    }
    let denominator = bessel_i0(beta);
    (0..n)
        .map(|k| {
            let r = 2.0 * k as f64 / (n - 1) as f64 - 1.0;
            bessel_i0(beta * (1.0 - r * r).max(0.0).sqrt()) / denominator
        })
        .collect()
}

/// sin(πx)/(πx), 1 at 0 (NumPy `sinc`).
fn sinc(x: f64) -> f64 {
    if x == 0.0 {
        1.0
    } else {
        let px = std::f64::consts::PI * x;
        px.sin() / px
    }
}

/// Windowed-sinc low-pass taps with DC gain 1 (SciPy `firwin(n, cutoff, window=w, fs=fs)`).
pub fn windowed_sinc_lowpass(n: usize, cutoff_normalised: f64, window: &[f64]) -> Vec<f64> {
    let alpha = 0.5 * (n as f64 - 1.0);
    let mut taps: Vec<f64> = (0..n)
        .map(|k| {
            let m = k as f64 - alpha;
            cutoff_normalised * sinc(cutoff_normalised * m) * window[k]
        })
        .collect();
    let dc_gain: f64 = taps.iter().sum();
    taps.iter_mut().for_each(|t| *t /= dc_gain);
    taps
}

/// Designs the Kaiser low-pass of `spec`, tap for tap as SciPy does.
///
/// # Errors
/// [`SignalError::Spec`] when the design needs more than [`MAX_TAPS`] taps.
pub fn design_kaiser_lowpass(spec: &KaiserSpec) -> Result<FirFilter, SignalError> {
    let nyquist_hz = spec.sample_rate_hz / 2.0;
    let width = spec.transition_width_hz / nyquist_hz;
    let needed = kaiser_taps(spec.ripple_db, width);
    if needed.is_nan() || needed > MAX_TAPS as f64 {
        let count = if needed.is_finite() {
            format!("about {needed:.3e}")
        } else {
            "unboundedly many".to_string()
        };
        return Err(SignalError::Spec {
            message: format!(
                "the design needs {count} taps (more than {MAX_TAPS}): widen the transition band or lower the attenuation"
            ),
        });
    }
    let (n, beta) = kaiser_order(spec.ripple_db, width);
    let window = kaiser_window(n, beta);
    let taps = windowed_sinc_lowpass(n, spec.cutoff_hz / nyquist_hz, &window);
    Ok(FirFilter {
        taps,
        beta,
        sample_rate_hz: spec.sample_rate_hz,
    })
}

impl FirFilter {
    /// Number of taps.
    pub fn num_taps(&self) -> usize {
        self.taps.len()
    }

    /// The taps.
    pub fn taps(&self) -> &[f64] {
        &self.taps
    }

    /// Kaiser β.
    pub fn beta(&self) -> f64 {
        self.beta
    }

    /// Sampling rate the filter was designed for, Hz.
    pub fn sample_rate_hz(&self) -> f64 {
        self.sample_rate_hz
    }

    /// Group delay of the linear-phase filter, (N − 1)/2 samples, in seconds.
    pub fn group_delay_s(&self) -> f64 {
        0.5 * (self.taps.len() as f64 - 1.0) / self.sample_rate_hz
    }

    /// The same design with one tap more when the count is even, so that the delay is a whole
    /// number of samples (used by the one-pass zero-phase mode; the extra tap widens the
    /// Kaiser window by one sample and only sharpens the response).
    pub fn with_odd_taps(&self, spec: &KaiserSpec) -> FirFilter {
        if self.taps.len() % 2 == 1 {
            return self.clone();
        }
        let n = self.taps.len() + 1;
        let window = kaiser_window(n, self.beta);
        let taps = windowed_sinc_lowpass(n, spec.cutoff_hz / (spec.sample_rate_hz / 2.0), &window);
        FirFilter {
            taps,
            beta: self.beta,
            sample_rate_hz: self.sample_rate_hz,
        }
    }

    /// Magnitude of the frequency response at `frequency_hz` (direct DTFT sum).
    pub fn gain_at(&self, frequency_hz: f64) -> f64 {
        let w = std::f64::consts::TAU * frequency_hz / self.sample_rate_hz;
        let (re, im) = self
            .taps
            .iter()
            .enumerate()
            .fold((0.0, 0.0), |(re, im), (k, h)| {
                let (s, c) = (w * k as f64).sin_cos();
                (re + h * c, im - h * s)
            });
        re.hypot(im)
    }
}

#[cfg(test)]
mod too_long_tests {
    use super::*;

    #[test]
    fn a_design_too_long_to_count_says_how_long_without_wrapping() {
        // A transition of 1e-200 Hz at 200 Hz needs (60 − 7.95)/2.285/(π · 1e-202) + 1 ≈
        // 7.251e202 taps (Kaiser's formula): the message gives that figure, not a saturated
        // integer (it used to print 18446744073709551615).
        let spec = KaiserSpec::new(200.0, 5.0, 1e-200, 60.0).unwrap();
        let message = design_kaiser_lowpass(&spec).unwrap_err().to_string();
        assert!(message.contains("about 7.251e202 taps"), "{message}");
        assert!(!message.contains("18446744073709551615"), "{message}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // check_band is new's verdict where the rate does not bind (1 MHz, far above every band
    // here): the same values refused with the same message, the others accepted.
    #[test]
    fn check_band_refuses_what_new_refuses_without_a_rate() {
        let values = [-1.0, 0.0, 0.5, 7.9, 8.0, 60.0, f64::NAN, f64::INFINITY];
        for cutoff in values {
            for transition in values {
                for ripple in values {
                    let band = KaiserSpec::check_band(cutoff, transition, ripple);
                    let full = KaiserSpec::new(1e6, cutoff, transition, ripple).map(|_| ());
                    assert_eq!(band, full, "{cutoff} {transition} {ripple}");
                }
            }
        }
    }
}
