//! Numbers and times as text: exact decimal seconds, shortest round-trip floats.
//!
//! Times are read digit by digit into integer nanoseconds, so `1700000000.005` keeps its last
//! nanosecond (an `f64` would round it to ~0.2 µs), and written back from the integer with nine
//! decimals. Values are written in the shortest decimal form that parses back to the same `f64`,
//! so a write-read round trip is bit-exact.

use std::fmt;
use std::io::{self, Write};
use thermonav::time::{NANOS_PER_SECOND, Timestamp};
use thermonav::units::{deg_to_rad, rad_to_deg};

/// Digits of a second kept exactly (nanoseconds).
const FRACTION_DIGITS: usize = 9;

/// Parses the number at the start of `text` (`-1.5`, `2e-3`, `nan`, `inf`): its value and how
/// many bytes it takes.
#[inline]
pub(crate) fn parse_value_prefix(text: &[u8]) -> Option<(f64, usize)> {
    crate::short_decimal::parse_float_prefix(text)
}

/// Parses the seconds at the start of `text` into a timestamp, and how many bytes they take.
/// Plain decimals (`-12.005`) are read exactly, rounded to the nearest nanosecond (ties away
/// from zero); other forms (`1.5e3`) go through `f64`. `None` for text that is no time, or a
/// time beyond ±9.2e9 s.
#[inline]
pub(crate) fn parse_time_prefix(text: &[u8]) -> Option<(Timestamp, usize)> {
    match decimal_nanos_prefix(text) {
        Some((nanos, len)) if !matches!(text.get(len), Some(b'e' | b'E')) => {
            Some((Timestamp::from_nanos(nanos), len))
        }
        _ => {
            let (seconds, len) = parse_value_prefix(text)?;
            Some((Timestamp::from_seconds(seconds).ok()?, len))
        }
    }
}

/// `[+-]digits[.digits]` at the start of `text` as integer nanoseconds, and its length; `None`
/// when there is no digit or on overflow.
fn decimal_nanos_prefix(text: &[u8]) -> Option<(i64, usize)> {
    let (negative, start) = match text.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let (seconds, whole_len) = digits_prefix(&text[start..])?;
    let mut end = start + whole_len;
    let mut fraction = (0, false);
    let mut fraction_len = 0;
    if text.get(end) == Some(&b'.') {
        (fraction, fraction_len) = fraction_prefix(&text[end + 1..]);
        end += 1 + fraction_len;
    }
    if whole_len + fraction_len == 0 {
        return None;
    }
    let (fraction_nanos, round_up) = fraction;
    let nanos = seconds
        .checked_mul(NANOS_PER_SECOND)?
        .checked_add(fraction_nanos + i64::from(round_up))?;
    Some((if negative { -nanos } else { nanos }, end))
}

/// The leading decimal digits of `text` as an integer, and how many there are; `None` on
/// overflow.
fn digits_prefix(text: &[u8]) -> Option<(i64, usize)> {
    let len = text.iter().take_while(|b| b.is_ascii_digit()).count();
    let value = text[..len].iter().try_fold(0_i64, |acc, &b| {
        acc.checked_mul(10)?.checked_add(i64::from(b - b'0'))
    })?;
    Some((value, len))
}

/// Leading digits after a decimal point as (nanoseconds, whether the tenth digit rounds up),
/// and how many digits there are.
fn fraction_prefix(text: &[u8]) -> ((i64, bool), usize) {
    let len = text.iter().take_while(|b| b.is_ascii_digit()).count();
    let kept = &text[..len.min(FRACTION_DIGITS)];
    let nanos = kept
        .iter()
        .fold(0_i64, |acc, &b| acc * 10 + i64::from(b - b'0'));
    let scale = 10_i64.pow((FRACTION_DIGITS - kept.len()) as u32);
    let round_up = len > FRACTION_DIGITS && text[FRACTION_DIGITS] >= b'5';
    ((nanos * scale, round_up), len)
}

/// A timestamp printed as seconds with nine decimals, exactly (`12.005000000`, `-0.500000000`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SecondsText(pub(crate) Timestamp);

impl fmt::Display for SecondsText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let nanos = self.0.as_nanos();
        let sign = if nanos < 0 { "-" } else { "" };
        let magnitude = nanos.unsigned_abs();
        let per_second = NANOS_PER_SECOND.unsigned_abs();
        write!(
            f,
            "{sign}{}.{:09}",
            magnitude / per_second,
            magnitude % per_second
        )
    }
}

/// Writes a timestamp as exact seconds with nine decimals.
pub(crate) fn write_time(out: &mut impl Write, time: Timestamp) -> io::Result<()> {
    write!(out, "{}", SecondsText(time))
}

/// The degree value whose conversion to radians gives exactly `rad` bits, when one exists within
/// two units in the last place of `rad_to_deg(rad)`; otherwise `rad_to_deg(rad)`.
///
/// `deg_to_rad(rad_to_deg(x))` is not always `x` (two roundings), so writing plain
/// `rad_to_deg(x)` would lose the last bit of a value read from a file in degrees. Every value
/// that came from a degree text is recovered: the exact product `d·(π/180)` rounds to `rad`, so
/// `rad/(π/180)` lies within about one unit in the last place of `d`.
pub(crate) fn degrees_reading_back_exactly(rad: f64) -> f64 {
    let first = rad_to_deg(rad);
    if !first.is_finite() || first == 0.0 {
        return first;
    }
    let bits = first.to_bits();
    [0_u64, 1, u64::MAX, 2, u64::MAX - 1]
        .into_iter()
        .map(|step| f64::from_bits(bits.wrapping_add(step)))
        .find(|&deg| deg_to_rad(deg).to_bits() == rad.to_bits())
        .unwrap_or(first)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The time of a whole field, as the reader takes it.
    fn nanos(text: &str) -> Option<i64> {
        parse_time_prefix(text.as_bytes())
            .filter(|&(_, len)| len == text.len())
            .map(|(time, _)| time.as_nanos())
    }

    #[test]
    fn decimal_seconds_become_exact_nanoseconds() {
        assert_eq!(nanos("12.005"), Some(12_005_000_000));
        assert_eq!(
            nanos("1700000000.000000001"),
            Some(1_700_000_000_000_000_001)
        );
        assert_eq!(nanos("-0.5"), Some(-500_000_000));
        assert_eq!(nanos("+3"), Some(3_000_000_000));
        assert_eq!(nanos(".25"), Some(250_000_000));
        assert_eq!(nanos("7."), Some(7_000_000_000));
    }

    #[test]
    fn tenth_decimal_rounds_to_nearest_nanosecond() {
        assert_eq!(nanos("0.0000000014999"), Some(1));
        assert_eq!(nanos("0.0000000015"), Some(2));
        assert_eq!(nanos("-0.0000000015"), Some(-2));
    }

    #[test]
    fn scientific_time_goes_through_f64_and_garbage_is_rejected() {
        assert_eq!(nanos("1.5e3"), Some(1_500_000_000_000));
        for bad in [
            "",
            ".",
            "-",
            "1.2.3",
            "abc",
            "nan",
            "inf",
            "1e10",
            "99999999999999999999",
        ] {
            assert_eq!(nanos(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn time_text_is_exact_with_nine_decimals() {
        let text = |n| SecondsText(Timestamp::from_nanos(n)).to_string();
        assert_eq!(text(12_005_000_000), "12.005000000");
        assert_eq!(text(-500_000_000), "-0.500000000");
        assert_eq!(text(1), "0.000000001");
        assert_eq!(text(i64::MIN), "-9223372036.854775808");
    }
}

#[cfg(test)]
mod degree_tests {
    use super::*;

    /// Degree values spread over ±720° and many magnitudes, from a fixed linear congruential
    /// sequence (Knuth's MMIX constants).
    fn degree_values(count: usize) -> impl Iterator<Item = f64> {
        let mut state = 0x2009_u64;
        (0..count).map(move |_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let unit = (state >> 11) as f64 / (1_u64 << 53) as f64;
            (unit - 0.5) * 1440.0 * 10f64.powi(-((state % 7) as i32))
        })
    }

    #[test]
    fn every_radian_value_from_degrees_finds_a_degree_value_giving_its_bits() {
        for deg in degree_values(200_000) {
            let rad = deg_to_rad(deg);
            let found = degrees_reading_back_exactly(rad);
            assert_eq!(deg_to_rad(found).to_bits(), rad.to_bits(), "{deg}");
        }
    }
}
