//! One setting checked against its range, refused with a typed error naming the setting: the
//! checks every front end shares, written once. A setting is named as Python's keyword is
//! (`rate_hz`); the command line's option is the same name with dashes (`--rate-hz`,
//! [`SettingError::as_flag`]).
//!
//! ```
//! use thermonav::setting::{finite, positive};
//! assert_eq!(positive("rate_hz", 100.0), Ok(100.0));
//! let refused = positive("rate_hz", 0.0).unwrap_err();
//! assert_eq!(refused.to_string(), "rate_hz 0: expected a positive number");
//! assert_eq!(refused.as_flag(), "--rate-hz 0: expected a positive number");
//! assert!(finite("temperature_c", f64::NAN).is_err());
//! ```

/// A setting out of its range: its name (Python's keyword; the CLI's option is the same with
/// dashes), the value given and what was expected.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{name} {value}: {expected}")]
pub struct SettingError {
    /// The setting, snake_case (`process_noise_scale`).
    pub name: &'static str,
    /// The value given, as text.
    pub value: String,
    /// What was expected.
    pub expected: String,
}

impl SettingError {
    /// The refusal of `value` for `name`, saying what was `expected`.
    pub fn new(
        name: &'static str,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        Self {
            name,
            value: value.to_string(),
            expected: expected.into(),
        }
    }

    /// The refusal in the command line's words (`--process-noise-scale 0: ...`).
    pub fn as_flag(&self) -> String {
        format!("{} {}: {}", flag(self.name), self.value, self.expected)
    }
}

/// The command line's option of a setting: `rate_hz` is `--rate-hz`.
pub fn flag(name: &str) -> String {
    format!("--{}", name.replace('_', "-"))
}

/// `value` when it is finite and positive.
///
/// # Errors
/// [`SettingError`] naming `name`.
pub fn positive(name: &'static str, value: f64) -> Result<f64, SettingError> {
    match value.is_finite() && value > 0.0 {
        true => Ok(value),
        false => Err(SettingError::new(name, value, "expected a positive number")),
    }
}

/// `value` when it is finite (a temperature, °C; a time offset, s).
///
/// # Errors
/// [`SettingError`] naming `name`.
pub fn finite(name: &'static str, value: f64) -> Result<f64, SettingError> {
    match value.is_finite() {
        true => Ok(value),
        false => Err(SettingError::new(name, value, "expected a finite number")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refusal_names_the_setting_in_either_spelling() {
        assert_eq!(positive("block_s", 2.5), Ok(2.5));
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = positive("block_s", bad).unwrap_err();
            assert_eq!(e.name, "block_s");
            assert_eq!(
                e.as_flag(),
                format!("--block-s {bad}: expected a positive number")
            );
        }
        assert_eq!(finite("warm_up_from_c", -40.0), Ok(-40.0));
        assert_eq!(
            finite("warm_up_from_c", f64::NEG_INFINITY)
                .unwrap_err()
                .to_string(),
            "warm_up_from_c -inf: expected a finite number"
        );
    }
}
