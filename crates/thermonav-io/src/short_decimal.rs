//! Exact parsing of the short decimals that fill sensor CSVs (`-0.00686996749`, `20.0000007`,
//! `1.23456789e-05`), several times faster than a general parser.
//!
//! A decimal of at most 19 digits is an integer m (its digits) times a power of ten e, which
//! [`crate::decimal_value`] turns into the correctly rounded `f64` when e is small enough
//! (Clinger's fast path, or Eisel-Lemire for m past 2^53): the value `str::parse::<f64>` gives.
//! Digits are taken eight at a time from one 64-bit load. Everything else (more digits, larger
//! exponents, `.5`, `5.`, `inf`, `nan`) is left to [`fast_float2`], which is exact too and
//! accepts the same grammar.

use crate::decimal_value::decimal_value;

/// Most decimal digits a `u64` accumulates without overflow.
pub(crate) const MAX_DIGITS: usize = 19;

/// Most exponent digits taken on the fast path (an exponent beyond 22 falls back anyway).
pub(crate) const MAX_EXPONENT_DIGITS: usize = 3;

/// One in each byte of a word.
const EACH_BYTE: u64 = 0x0101_0101_0101_0101;

/// Parses the number at the start of `text` (`-1.5`, `2e-3`, `nan`, `inf`): its value and how
/// many bytes it takes, exactly as [`fast_float2::parse_partial`] (and, for the bytes taken,
/// `str::parse::<f64>`) would.
#[inline]
pub(crate) fn parse_float_prefix(text: &[u8]) -> Option<(f64, usize)> {
    match short_decimal_prefix(text) {
        Some(parsed) => Some(parsed),
        None => fast_float2::parse_partial(text).ok(),
    }
}

/// The fast path: `[+-]digits[.digits][(e|E)[+-]digits]` within the exact range (see the
/// module's documentation), or `None` for anything else, which the caller parses in full.
#[inline]
fn short_decimal_prefix(text: &[u8]) -> Option<(f64, usize)> {
    let negative = text.first() == Some(&b'-');
    let mut position = usize::from(matches!(text.first(), Some(b'-' | b'+')));
    let mut mantissa = 0_u64;
    let whole_digits = take_digits(text, &mut position, &mut mantissa);
    if whole_digits == 0 {
        return None;
    }
    let mut fraction_digits = 0;
    if text.get(position) == Some(&b'.') {
        position += 1;
        fraction_digits = take_digits(text, &mut position, &mut mantissa);
        if fraction_digits == 0 {
            return None;
        }
    }
    if whole_digits + fraction_digits > MAX_DIGITS {
        return None;
    }
    let exponent = exponent_suffix(text, &mut position)? - fraction_digits as i64;
    let value = decimal_value(mantissa, i32::try_from(exponent).ok()?)?;
    Some((if negative { -value } else { value }, position))
}

/// Appends the decimal digits at `text[*position..]` to `mantissa` (wrapping: the caller
/// refuses more than [`MAX_DIGITS`]) and moves past them; how many there were.
#[inline]
fn take_digits(text: &[u8], position: &mut usize, mantissa: &mut u64) -> usize {
    let start = *position;
    while let Some(chunk) = text.get(*position..*position + 8) {
        let word = u64::from_le_bytes(chunk.try_into().expect("eight bytes"));
        if leading_digits(word) < 8 {
            break;
        }
        *mantissa = mantissa
            .wrapping_mul(100_000_000)
            .wrapping_add(digits_value(word, 8));
        *position += 8;
    }
    while let Some(digit) = text.get(*position).map(|b| b.wrapping_sub(b'0')) {
        if digit > 9 {
            break;
        }
        *mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(digit));
        *position += 1;
    }
    *position - start
}

/// How many of the eight bytes of `word`, from the first (lowest), are ASCII digits before the
/// first byte that is not (0 ..= 8).
///
/// A byte's top bit is set in `below` when it is under `'0'` (the subtraction borrows) or at
/// least 0xB0, and in `above` when it is over `'9'` and under 0xBA (adding 0x46 reaches 0x80);
/// a digit sets neither. A borrow or carry moves only towards later bytes, so every byte up to
/// and including the first non-digit is flagged exactly; later flags do not matter.
#[inline(always)]
pub(crate) fn leading_digits(word: u64) -> usize {
    let below = word.wrapping_sub(0x30 * EACH_BYTE);
    let above = word.wrapping_add(0x46 * EACH_BYTE);
    let flags = (below | above) & (0x80 * EACH_BYTE);
    (flags.trailing_zeros() / 8) as usize
}

/// The value of the first `count` (1 ..= 8) bytes of `word`, which are ASCII digits, the first
/// the most significant.
///
/// The digits become byte lanes of 0 ..= 9 (no borrow reaches them: every byte before them is a
/// digit), are shifted to the top of the word (the bytes after them fall out; zero lanes come in
/// as leading zeros), and are combined as pairs, then quadruples, then all eight, each by one
/// multiply of packed lanes (no lane overflows: 99, 9999 and 99999999 fit their lanes).
#[inline(always)]
pub(crate) fn digits_value(word: u64, count: usize) -> u64 {
    debug_assert!((1..=8).contains(&count));
    let lanes = word.wrapping_sub(0x30 * EACH_BYTE) << (8 * (8 - count));
    let pairs = (lanes * 10 + (lanes >> 8)) & 0x00FF_00FF_00FF_00FF;
    let quads = (pairs * 100 + (pairs >> 16)) & 0x0000_FFFF_0000_FFFF;
    (quads * 10_000 + (quads >> 32)) & 0xFFFF_FFFF
}

/// The exponent of an `e`/`E` suffix at `text[*position..]`, moving past it; 0 without one
/// (an `e` without digits is not part of the number); `None` for more exponent digits than the
/// fast path takes.
#[inline]
fn exponent_suffix(text: &[u8], position: &mut usize) -> Option<i64> {
    if !matches!(text.get(*position), Some(b'e' | b'E')) {
        return Some(0);
    }
    let sign_len = usize::from(matches!(text.get(*position + 1), Some(b'-' | b'+')));
    let negative = text.get(*position + 1) == Some(&b'-');
    let start = *position + 1 + sign_len;
    let digits = text
        .get(start..)
        .unwrap_or_default()
        .iter()
        .take_while(|b| b.is_ascii_digit())
        .count();
    if digits == 0 {
        return Some(0);
    }
    if digits > MAX_EXPONENT_DIGITS {
        return None;
    }
    let magnitude = text[start..start + digits]
        .iter()
        .fold(0_i64, |acc, &b| acc * 10 + i64::from(b - b'0'));
    *position = start + digits;
    Some(if negative { -magnitude } else { magnitude })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random decimal: sign, whole digits, fraction, exponent, each present or not, with
    /// lengths from 0 to 25 digits so that both sides of every limit of the fast path (19
    /// digits, 2^53, |e| ≤ 22) are reached; leading zeros, `-0`, and exponents down to
    /// subnormal and up to overflow.
    fn random_decimal(rng: &mut ChaCha8Rng) -> String {
        let digits = |rng: &mut ChaCha8Rng, n: usize| -> String {
            let zeros = if rng.random_range(0..4) == 0 {
                rng.random_range(0..n + 1)
            } else {
                0
            };
            (0..n)
                .map(|i| match i < zeros {
                    true => '0',
                    false => char::from(b'0' + rng.random_range(0..10_u8)),
                })
                .collect()
        };
        let mut text = String::new();
        match rng.random_range(0..4) {
            0 => text.push('-'),
            1 => text.push('+'),
            _ => {}
        }
        let whole = rng.random_range(0..12);
        text.push_str(&digits(rng, whole));
        if rng.random_range(0..5) > 0 {
            text.push('.');
            let fraction = rng.random_range(0..26);
            text.push_str(&digits(rng, fraction));
        }
        if rng.random_range(0..3) == 0 {
            text.push(if rng.random_range(0..2) == 0 {
                'e'
            } else {
                'E'
            });
            match rng.random_range(0..3) {
                0 => text.push('-'),
                1 => text.push('+'),
                _ => {}
            }
            let exponent: i32 = match rng.random_range(0..4) {
                0 => rng.random_range(0..30),
                1 => rng.random_range(290..330),
                2 => 0,
                _ => rng.random_range(0..10_000),
            };
            text.push_str(&exponent.to_string());
        }
        text
    }

    /// Text that may follow a number in a line.
    fn random_suffix(rng: &mut ChaCha8Rng) -> &'static str {
        [
            "", ",", " ,", "\t", "e", "e+", "E-", ".", "x", ".5", "e5x", "1",
        ][rng.random_range(0..12)]
    }

    /// The oracle: the longest prefix that `str::parse::<f64>` accepts as a plain decimal
    /// (std's parser is correctly rounded), found by trying every prefix from the longest.
    fn std_prefix(text: &str) -> Option<(f64, usize)> {
        (1..=text.len()).rev().find_map(|len| {
            let prefix = &text[..len];
            let plain = !prefix.contains(|c: char| c.is_ascii_alphabetic() && c != 'e' && c != 'E');
            plain
                .then(|| prefix.parse::<f64>().ok().map(|v| (v, len)))
                .flatten()
        })
    }

    fn bits(parsed: Option<(f64, usize)>) -> Option<(u64, usize)> {
        parsed.map(|(value, len)| (value.to_bits(), len))
    }

    #[test]
    fn random_decimals_parse_to_std_bits_and_to_the_general_parsers_length() {
        let mut rng = ChaCha8Rng::seed_from_u64(2009);
        let mut fast = 0;
        for _ in 0..300_000 {
            let text = format!("{}{}", random_decimal(&mut rng), random_suffix(&mut rng));
            let ours = parse_float_prefix(text.as_bytes());
            fast += usize::from(short_decimal_prefix(text.as_bytes()).is_some());
            // Same value and length as the parser used before (nothing newly accepted or
            // refused), and the value std gives for the bytes taken.
            assert_eq!(
                bits(ours),
                bits(fast_float2::parse_partial(text.as_bytes()).ok()),
                "{text:?}"
            );
            if let Some((value, len)) = ours {
                let std: f64 = text[..len].parse().unwrap();
                assert_eq!(value.to_bits(), std.to_bits(), "{text:?}");
            }
        }
        // The cases reach both paths in earnest.
        assert!(
            fast > 50_000 && fast < 250_000,
            "{fast} of 300000 on the fast path"
        );
    }

    #[test]
    fn sensor_values_written_at_nine_and_seventeen_digits_read_back_exactly() {
        let mut rng = ChaCha8Rng::seed_from_u64(52);
        for _ in 0..200_000 {
            let value = (rng.random::<f64>() - 0.5) * 10f64.powi(rng.random_range(-8..5));
            for text in [
                format!("{value:.8e}"),
                format!("{value}"),
                format!("{:.9}", value),
            ] {
                let ours = short_decimal_prefix(text.as_bytes())
                    .or_else(|| fast_float2::parse_partial(text.as_bytes()).ok());
                let std: f64 = text.parse().unwrap();
                assert_eq!(
                    ours.map(|(v, l)| (v.to_bits(), l)),
                    Some((std.to_bits(), text.len())),
                    "{text}"
                );
            }
        }
    }

    #[test]
    fn edge_cases_match_std() {
        for text in [
            "0",
            "-0",
            "-0.0",
            "+0.0",
            "9007199254740992",
            "9007199254740993",
            "1e22",
            "1e23",
            "1e-22",
            "4.9e-324",
            "2.2250738585072014e-308",
            "1.7976931348623157e308",
            "9999999999999999999",
            "0.1",
            "0.30000000000000004",
            "123456789012345678e-22",
            "-9.80665",
            "20.0000007",
            "0.00686996749",
            "1.23456789e-05",
        ] {
            let (value, len) = parse_float_prefix(text.as_bytes()).unwrap();
            assert_eq!(len, text.len(), "{text}");
            assert_eq!(
                value.to_bits(),
                text.parse::<f64>().unwrap().to_bits(),
                "{text}"
            );
        }
        assert_eq!(std_prefix("-0.5e3,"), Some((-500.0, 6)));
        for text in ["", "-", "+", ".", "e5", "-e5", "abc", ",1"] {
            assert_eq!(
                bits(parse_float_prefix(text.as_bytes())),
                bits(std_prefix(text)),
                "{text:?}"
            );
        }
    }

    #[test]
    fn eight_digit_words_are_recognised_and_valued() {
        for text in [*b"00000000", *b"12345678", *b"99999999", *b"90817263"] {
            let word = u64::from_le_bytes(text);
            assert_eq!(leading_digits(word), 8);
            let expected: u64 = std::str::from_utf8(&text).unwrap().parse().unwrap();
            assert_eq!(digits_value(word, 8), expected);
        }
        for byte in (0..=255_u8).filter(|b| !b.is_ascii_digit()) {
            for place in 0..8 {
                let mut text = *b"12345678";
                text[place] = byte;
                assert!(
                    leading_digits(u64::from_le_bytes(text)) < 8,
                    "{byte} at {place}"
                );
            }
        }
    }
}
