//! Why a noise configuration cannot be written ([`NoiseExportError`]): what every format's
//! writer and the selection of the bank's noise at a temperature refuse, each naming what is
//! missing or unusable.

use thermonav::stoch::bank::{BankError, Selection};

/// Why a noise configuration cannot be written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NoiseExportError {
    /// The bank cannot be used.
    #[error(transparent)]
    Bank(#[from] BankError),
    /// No temperature given for a bank of several entries.
    #[error(
        "the bank has {entries} entries ({low_c} to {high_c} °C): give the operating temperature (--temperature-c)"
    )]
    NoTemperature {
        /// Entries in the bank.
        entries: usize,
        /// Its coldest entry, °C.
        low_c: f64,
        /// Its warmest entry, °C.
        high_c: f64,
    },
    /// A temperature beyond the bank's entries.
    #[error(
        "{temperature_c} °C is outside the bank's range {low_c} to {high_c} °C: {}; export at a temperature inside the range (the end entry is at {nearest_c} °C)",
        outside_words(*selection)
    )]
    OutsideRange {
        /// The temperature asked for, °C.
        temperature_c: f64,
        /// Coldest entry, °C.
        low_c: f64,
        /// Warmest entry, °C.
        high_c: f64,
        /// The selection asked for.
        selection: Selection,
        /// The entry nearest the temperature, °C.
        nearest_c: f64,
    },
    /// A quantity the format needs that the bank does not have.
    #[error(
        "{format} needs the {term} of {channel} at {temperature_c} °C, which the bank does not have: {reason}"
    )]
    MissingTerm {
        /// The format (filled in by [`super::noise_config_text`]).
        format: &'static str,
        /// The channel.
        channel: &'static str,
        /// The quantity, in words.
        term: &'static str,
        /// The operating temperature, °C.
        temperature_c: f64,
        /// The bank's reason.
        reason: String,
    },
    /// KF-GINS needs scale-factor noise that a static bank does not measure.
    #[error(
        "{0} needs the scale-factor standard deviation (gsstd, asstd, ppm), which a static record does not measure: give it with --scale-factor-std-ppm"
    )]
    ScaleFactorNeeded(&'static str),
    /// A scale-factor standard deviation that is not a number ≥ 0.
    #[error("--scale-factor-std-ppm {0}: expected a finite number >= 0 (ppm)")]
    ScaleFactorInvalid(f64),
    /// A value beyond a 32-bit float parameter (or not finite).
    #[error("{key} = {value:e} cannot be stored as a 32-bit float parameter: nothing written")]
    NotRepresentable {
        /// The parameter.
        key: String,
        /// The value.
        value: f64,
    },
    /// A value that would not be a finite number.
    #[error("{key} would be {value}, not a finite number: nothing written")]
    NotFinite {
        /// The key.
        key: String,
        /// The value.
        value: f64,
    },
}

fn outside_words(selection: Selection) -> &'static str {
    match selection {
        Selection::Nearest => {
            "the nearest entry would be used for a temperature it was not measured at"
        }
        Selection::Linear => "linear interpolation does not extrapolate",
    }
}
