//! A data line of a canonical CSV decoded in one pass, for the shape nearly every line has:
//! fields of plain decimals (`-0.00123456789`, `8.73043875e-05`, `12.005000000`) separated by
//! single commas, with no blanks.
//!
//! The fields are walked in the header's order straight from the line buffer, each number read
//! with word-at-a-time (SWAR) digit scans: eight bytes are loaded at once, the run of leading
//! digits is found from a bit mask (no branch per digit, so no mispredicted branch on the
//! varying digit counts), and its value is formed by three multiplies of packed lanes. The
//! digits, read as an integer, and the power of ten then go to [`crate::decimal_value`]'s exact
//! routes (Clinger's fast path for up to 2^53 and 10^±22, Eisel-Lemire for the 17-digit values
//! of shortest round-trip printing), so each value is the correctly rounded `f64` of its
//! decimal, as `str::parse::<f64>` gives.
//!
//! Anything else (blanks, `+`, digits past `u64`, a large exponent, `nan`, a wrong field count, a
//! value a strict reader refuses, too few bytes left in the buffer for a word load) makes the
//! line's decoding give up, and the caller decodes the line with the general parser, which gives
//! the same values or the error naming the line and what was expected. A line is accepted here
//! only when the general parser would read the same numbers from it.

use crate::decimal_value::decimal_value;
use crate::layout::{Layout, MAX_SLOTS, Target};
use crate::short_decimal::{MAX_EXPONENT_DIGITS, digits_value, leading_digits};
use thermonav::time::{NANOS_PER_SECOND, Timestamp};

/// 10^0 ..= 10^9 as integers (digit-run scales).
const INTEGER_POWERS_OF_TEN: [u64; 10] = [
    1,
    10,
    100,
    1_000,
    10_000,
    100_000,
    1_000_000,
    10_000_000,
    100_000_000,
    1_000_000_000,
];

/// The eight bytes at `text[at..]` as a little-endian word (the first byte lowest); `None` when
/// fewer than eight bytes are left.
#[inline(always)]
fn word_at(text: &[u8], at: usize) -> Option<u64> {
    let bytes: [u8; 8] = text.get(at..at + 8)?.try_into().ok()?;
    Some(u64::from_le_bytes(bytes))
}

/// A run of one to seven digits at `text[at..]`: its value and length. `None` for no digit, for
/// eight or more (the caller's field is then too long for its fast path), or near the buffer's
/// end.
#[inline(always)]
fn short_run(text: &[u8], at: usize) -> Option<(u64, usize)> {
    let word = word_at(text, at)?;
    let count = leading_digits(word);
    match count {
        1..=7 => Some((digits_value(word, count), count)),
        _ => None,
    }
}

/// A run of one to fifteen digits at `text[at..]`: its value and length; `None` for none, more,
/// or too few bytes left.
#[inline(always)]
fn long_run(text: &[u8], at: usize) -> Option<(u64, usize)> {
    let word = word_at(text, at)?;
    let count = leading_digits(word);
    match count {
        0 => None,
        8 => {
            let high = digits_value(word, 8);
            let next = word_at(text, at + 8)?;
            match leading_digits(next) {
                0 => Some((high, 8)),
                8 => None,
                more => Some((
                    high * INTEGER_POWERS_OF_TEN[more] + digits_value(next, more),
                    8 + more,
                )),
            }
        }
        _ => Some((digits_value(word, count), count)),
    }
}

/// The digits at `text[at..]` appended to `mantissa` (decimal shift and add, eight digits a
/// word), and how many there were; `None` for no digit, more than [`MAX_FRACTION_DIGITS`], a
/// value past `u64`, or too few bytes left for a word load.
#[inline(always)]
fn appended_digits(text: &[u8], at: usize, mantissa: u64) -> Option<(u64, usize)> {
    let (mut mantissa, mut count) = (mantissa, 0);
    loop {
        let word = word_at(text, at + count)?;
        let run = leading_digits(word);
        if run == 0 {
            break;
        }
        mantissa = mantissa
            .checked_mul(INTEGER_POWERS_OF_TEN[run])?
            .checked_add(digits_value(word, run))?;
        count += run;
        if run < 8 {
            break;
        }
        if count >= MAX_FRACTION_DIGITS {
            return None;
        }
    }
    (count > 0).then_some((mantissa, count))
}

/// Most fraction digits taken here: 17 significant digits after a few leading zeros.
const MAX_FRACTION_DIGITS: usize = 24;

/// The number `-?D{1,7}(.D+)?([eE][+-]?D{1,3})?` at `text[at..]` when its digits, read as an
/// integer, fit a `u64` and its value is within reach of [`decimal_value`]'s exact routes: its
/// value, correctly rounded, and where it ends.
#[inline(always)]
pub(crate) fn value_at(text: &[u8], at: usize) -> Option<(f64, usize)> {
    let negative = text.get(at) == Some(&b'-');
    let mut position = at + usize::from(negative);
    // One digit before the point (`-0.0123`, `9.80665`), the commonest shape, without a word.
    let (mut mantissa, whole) = match (text.get(position), text.get(position + 1)) {
        (Some(&digit @ b'0'..=b'9'), Some(b'.')) => (u64::from(digit - b'0'), 1),
        _ => short_run(text, position)?,
    };
    position += whole;
    let mut fraction = 0;
    if text.get(position) == Some(&b'.') {
        let count;
        (mantissa, count) = appended_digits(text, position + 1, mantissa)?;
        fraction = count;
        position += 1 + count;
    }
    let mut exponent = -(fraction as i32);
    if matches!(text.get(position), Some(b'e' | b'E')) {
        let (power, end) = exponent_at(text, position + 1)?;
        exponent += power as i32;
        position = end;
    }
    let value = decimal_value(mantissa, exponent)?;
    // The sign set without a branch (the value is +0 or more): a branch on it, taken at random
    // from field to field, is mispredicted half the time, which cost a fifth of the decoding.
    let signed = f64::from_bits(value.to_bits() | (u64::from(negative) << 63));
    Some((signed, position))
}

/// The exponent `[+-]?D{1,3}` at `text[at..]` (after the `e`) and where it ends; `None` without
/// a digit (the `e` is then no part of the number, which the general parser handles) or with
/// more than three.
#[inline(always)]
fn exponent_at(text: &[u8], at: usize) -> Option<(i64, usize)> {
    let sign = text.get(at).copied();
    let negative = sign == Some(b'-');
    let mut position = at + usize::from(matches!(sign, Some(b'-' | b'+')));
    let start = position;
    let mut magnitude = 0_i64;
    while let Some(digit) = text.get(position).map(|b| b.wrapping_sub(b'0')) {
        if digit > 9 {
            break;
        }
        magnitude = magnitude * 10 + i64::from(digit);
        position += 1;
        if position - start > MAX_EXPONENT_DIGITS {
            return None;
        }
    }
    if position == start {
        return None;
    }
    Some((if negative { -magnitude } else { magnitude }, position))
}

/// Seconds `-?D{1,15}(.D{1,9})?` at `text[at..]` as integer nanoseconds and where they end: the
/// value [`crate::text::parse_time_prefix`] gives (digits beyond the ninth decimal, which round,
/// and a bare trailing point are left to it).
#[inline(always)]
pub(crate) fn time_at(text: &[u8], at: usize) -> Option<(i64, usize)> {
    let negative = text.get(at) == Some(&b'-');
    let mut position = at + usize::from(negative);
    let (seconds, whole) = long_run(text, position)?;
    position += whole;
    let mut fraction_nanos = 0;
    if text.get(position) == Some(&b'.') {
        let (digits, count) = long_run(text, position + 1)?;
        if count > 9 {
            return None;
        }
        fraction_nanos = digits * INTEGER_POWERS_OF_TEN[9 - count];
        position += 1 + count;
    }
    // Seconds with an exponent are read through an `f64` by the general parser.
    if matches!(text.get(position), Some(b'e' | b'E')) {
        return None;
    }
    let nanos = i64::try_from(seconds)
        .ok()?
        .checked_mul(NANOS_PER_SECOND)?
        .checked_add(fraction_nanos as i64)?;
    Some((if negative { -nanos } else { nanos }, position))
}

/// Decodes the line `text[..line_len]` (`text` goes on past the line, into the buffer's later
/// bytes, so that every word load of the line's fields stays in bounds) into `values` by
/// `layout`, and returns its time; `None` when the line is not of the common shape or (`strict`)
/// holds a value the strict reader refuses, after which `values` hold any numbers.
///
/// A line decoded here has the same time and values, bit for bit, as the general decoder
/// gives it; `max_magnitude` is that decoder's strict bound.
#[inline(always)]
pub(crate) fn decode_line(
    text: &[u8],
    line_len: usize,
    layout: &Layout,
    (strict, max_magnitude): (bool, f64),
    values: &mut [f64; MAX_SLOTS],
) -> Option<Timestamp> {
    let (time, end) = decode_fields(text, line_len, layout, (strict, max_magnitude), values)?;
    (end == line_len).then_some(time)
}

/// Decodes the line that starts `text` (unread bytes of the buffer, the line's end not yet
/// looked for) as [`decode_line`] does, finding its end on the way: the time, the length of
/// the line's content and the bytes it takes with its `\n` or `\r\n`. `None` as for
/// [`decode_line`], and when no line end follows the last field inside `text`, so that a line
/// cut by the buffer's end is never taken.
#[inline(always)]
pub(crate) fn decode_next_line(
    text: &[u8],
    layout: &Layout,
    (strict, max_magnitude): (bool, f64),
    values: &mut [f64; MAX_SLOTS],
) -> Option<(Timestamp, usize, usize)> {
    let (time, end) = decode_fields(text, usize::MAX, layout, (strict, max_magnitude), values)?;
    match text.get(end..end + 2) {
        Some([b'\n', _]) => Some((time, end, end + 1)),
        Some([b'\r', b'\n']) => Some((time, end, end + 2)),
        // The last line, its newline the buffer's last byte.
        _ if text.get(end) == Some(&b'\n') => Some((time, end, end + 1)),
        _ => None,
    }
}

/// The fields of the line starting `text`, in the layout's order, separated by commas before
/// `limit`: the time and where the last field's number ends (what follows it is the caller's
/// to check).
#[inline(always)]
fn decode_fields(
    text: &[u8],
    limit: usize,
    layout: &Layout,
    (strict, max_magnitude): (bool, f64),
    values: &mut [f64; MAX_SLOTS],
) -> Option<(Timestamp, usize)> {
    if let Some(slots) = &layout.si_value_slots {
        return decode_si_fields(text, limit, slots, (strict, max_magnitude), values);
    }
    let mut time = 0;
    let mut position = 0;
    let last = layout.targets.len().checked_sub(1)?;
    for (column, target) in layout.targets.iter().enumerate() {
        let end = match *target {
            Target::Time => {
                let (nanos, end) = time_at(text, position)?;
                time = nanos;
                end
            }
            Target::Value { slot, unit } => {
                let (value, end) = value_at(text, position)?;
                let value = unit.to_si(value);
                if strict && refused(value, max_magnitude) {
                    return None;
                }
                *values.get_mut(slot)? = value;
                end
            }
        };
        if column == last {
            return Some((Timestamp::from_nanos(time), end));
        }
        // Every number but the last ends at a comma within the line.
        if end >= limit || text.get(end) != Some(&b',') {
            return None;
        }
        position = end + 1;
    }
    None
}

/// Whether the strict reader refuses `value`: beyond the finite bound `max_magnitude`, NaN and
/// the infinities (for which the comparison is false); the general decoder then gives the
/// error.
#[inline(always)]
fn refused(value: f64, max_magnitude: f64) -> bool {
    let within = value.abs() <= max_magnitude;
    !within
}

/// [`decode_fields`] for a layout of the time and then values in SI going to `slots` in order:
/// the same steps (the SI conversion is the identity) without a look at each column's target
/// and unit.
#[inline(always)]
fn decode_si_fields(
    text: &[u8],
    limit: usize,
    slots: &[usize],
    (strict, max_magnitude): (bool, f64),
    values: &mut [f64; MAX_SLOTS],
) -> Option<(Timestamp, usize)> {
    let (nanos, mut end) = time_at(text, 0)?;
    for &slot in slots {
        // Every number but the last ends at a comma within the line.
        if end >= limit || text.get(end) != Some(&b',') {
            return None;
        }
        let (value, value_end) = value_at(text, end + 1)?;
        if strict && refused(value, max_magnitude) {
            return None;
        }
        *values.get_mut(slot)? = value;
        end = value_end;
    }
    Some((Timestamp::from_nanos(nanos), end))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Padding after a number so that word loads stay in bounds, as the line buffer's later
    /// bytes do; starts with a byte that ends any number.
    const PAD: &str = "\n9999999999999999";

    #[test]
    fn leading_digit_counts_and_values_match_a_byte_by_byte_count() {
        let mut rng = ChaCha8Rng::seed_from_u64(77);
        let interesting = [
            b'0', b'5', b'9', b'/', b':', b'.', b',', b'e', b'\n', 0, 0x80, 0xB0, 0xB9, 0xBA, 0xFF,
        ];
        for round in 0..400_000 {
            let mut bytes = [0_u8; 8];
            for byte in &mut bytes {
                *byte = match round % 3 {
                    0 => rng.random(),
                    1 => interesting[rng.random_range(0..interesting.len())],
                    _ => match rng.random_range(0..4) {
                        0 => interesting[rng.random_range(0..interesting.len())],
                        _ => b'0' + rng.random_range(0..10_u8),
                    },
                };
            }
            let word = u64::from_le_bytes(bytes);
            let expected = bytes.iter().take_while(|b| b.is_ascii_digit()).count();
            assert_eq!(leading_digits(word), expected, "{bytes:?}");
            if expected > 0 {
                let value: u64 = std::str::from_utf8(&bytes[..expected])
                    .unwrap()
                    .parse()
                    .unwrap();
                assert_eq!(digits_value(word, expected), value, "{bytes:?}");
            }
        }
        // Every single byte value at every place after a digit run.
        for byte in 0..=255_u8 {
            for place in 0..8 {
                let mut bytes = *b"73056148";
                bytes[place] = byte;
                let expected = bytes.iter().take_while(|b| b.is_ascii_digit()).count();
                assert_eq!(leading_digits(u64::from_le_bytes(bytes)), expected);
            }
        }
    }

    /// A random decimal of the shapes the files hold: `%.9g` and shortest round-trip values
    /// (plain and with exponents), nine-decimal times, integers, and lengths past every limit
    /// of the fast path.
    fn random_decimal(rng: &mut ChaCha8Rng) -> String {
        let value = (rng.random::<f64>() - 0.5) * 10f64.powi(rng.random_range(-12..9));
        match rng.random_range(0..8) {
            0 => format!("{value:.8e}"),
            1 => format!("{value}"),
            2 => format!("{value:.9}"),
            3 => format!("{:.*}", rng.random_range(0..20), value),
            4 => format!("{}", rng.random_range(-100_000_i64..100_000)),
            5 => {
                // %.9g: nine significant digits, exponent form below 1e-4.
                let text = format!("{value:.8e}");
                let (mantissa, exponent) = text.split_once('e').unwrap();
                let exponent: i32 = exponent.parse().unwrap();
                match exponent {
                    -4..=8 => {
                        let decimals = (8 - exponent).max(0) as usize;
                        let plain = format!("{value:.decimals$}");
                        match plain.contains('.') {
                            true => plain.trim_end_matches('0').trim_end_matches('.').to_owned(),
                            false => plain,
                        }
                    }
                    _ => format!(
                        "{}e{}{:02}",
                        mantissa.trim_end_matches('0').trim_end_matches('.'),
                        if exponent < 0 { '-' } else { '+' },
                        exponent.abs()
                    ),
                }
            }
            6 => {
                let digits = rng.random_range(1..26);
                let point = rng.random_range(0..digits + 1);
                let mut text: String = (0..digits)
                    .map(|_| char::from(b'0' + rng.random_range(0..10_u8)))
                    .collect();
                text.insert(point, '.');
                if rng.random() {
                    text.insert(0, '-');
                }
                text
            }
            _ => {
                let mut text = format!("{:.*}", rng.random_range(1..12), value.abs());
                text.push(['e', 'E'][rng.random_range(0..2)]);
                text.push_str(["", "-", "+"][rng.random_range(0..3)]);
                text.push_str(&rng.random_range(0..40).to_string());
                text
            }
        }
    }

    #[test]
    fn values_are_std_bits_on_random_decimals_of_the_files_shapes() {
        let mut rng = ChaCha8Rng::seed_from_u64(2112);
        let mut fast = 0;
        for _ in 0..500_000 {
            let decimal = random_decimal(&mut rng);
            let text = format!("{decimal}{PAD}");
            if let Some((value, end)) = value_at(text.as_bytes(), 0) {
                fast += 1;
                assert_eq!(end, decimal.len(), "{decimal}");
                let std: f64 = decimal.parse().unwrap();
                assert_eq!(value.to_bits(), std.to_bits(), "{decimal}");
            }
        }
        assert!(fast > 300_000, "{fast} of 500000 on the fast path");
    }

    #[test]
    fn times_are_the_general_parsers_nanoseconds() {
        let mut rng = ChaCha8Rng::seed_from_u64(1001);
        let mut fast = 0;
        for _ in 0..300_000 {
            let seconds = match rng.random_range(0..3) {
                0 => format!("{:.9}", rng.random_range(-1e4..1e6)),
                1 => format!("{:.*}", rng.random_range(0..12), rng.random_range(0.0..2e9)),
                _ => random_decimal(&mut rng),
            };
            let text = format!("{seconds}{PAD}");
            if let Some((nanos, end)) = time_at(text.as_bytes(), 0) {
                fast += 1;
                let general = crate::text::parse_time_prefix(seconds.as_bytes());
                assert_eq!(
                    general.map(|(t, len)| (t.as_nanos(), len)),
                    Some((nanos, end)),
                    "{seconds}"
                );
            }
        }
        assert!(fast > 150_000, "{fast} of 300000 on the fast path");
    }

    #[test]
    fn numbers_cut_short_by_the_buffer_end_or_odd_forms_leave_the_fast_path() {
        for text in [
            "1.5",
            "-",
            "+1.5,000000000",
            ".5,00000000",
            "5.,00000000",
            "1e,000000000",
            "1e+,00000000",
            "1e1234,000000",
            "nan,00000000",
            " 1.5,00000000",
            "12345678.5,00000000000",
            "1.5e24,0000000",
        ] {
            assert_eq!(value_at(text.as_bytes(), 0), None, "{text}");
        }
        assert_eq!(
            value_at(b"-1.5e-3,0000000", 0).map(|(v, l)| (v.to_bits(), l)),
            Some(((-1.5e-3_f64).to_bits(), 7))
        );
    }

    /// A field as the files may hold it: mostly plain decimals, sometimes what only the
    /// general parser reads or what is an error.
    fn random_field(rng: &mut ChaCha8Rng, time: bool) -> String {
        match rng.random_range(0..400) {
            0 => " 1.5".into(),
            1 => "1.5 ".into(),
            2 => "+2".into(),
            3 => "nan".into(),
            4 => "inf".into(),
            5 => "".into(),
            6 => "abc".into(),
            7 => "1e400".into(),
            8 => "2e15".into(),
            9 => "1.5e".into(),
            10 => "0.12345678901234567890123".into(),
            11 => "12.0000000005".into(),
            12 => "1.".into(),
            _ if time => format!("{:.9}", rng.random_range(-10.0..5e5)),
            13..100 => random_decimal(rng),
            _ => format!("{:.9e}", rng.random::<f64>() - 0.5)
                .parse::<f64>()
                .unwrap()
                .to_string(),
        }
    }

    #[test]
    fn lines_decode_as_the_general_decoder_decodes_them() {
        use crate::layout::Schema;
        let schema = Schema {
            columns: &crate::imu::COLUMNS,
            expected: "",
            time_alternatives: "",
        };
        let headers = [
            "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c",
            "gx_deg_s,t_s,ax_g,gy_deg_h,az_mg,gz_rad_s,ay_m_s2",
            "dthx_deg,dthy_rad,dthz_rad,dvx_m_s,dvy_m_s,dvz_m_s,t_s",
        ];
        let mut rng = ChaCha8Rng::seed_from_u64(4711);
        let mut fast = 0;
        let cases = 200_000;
        for case in 0..cases {
            let header = headers[case % headers.len()];
            let layout = Layout::from_header(header, &schema, None).unwrap();
            // The first header takes the walk of SI values, the others the general one.
            assert_eq!(layout.si_value_slots.is_some(), case % headers.len() == 0);
            let fields = layout.targets.len() + usize::from(rng.random_range(0..60) == 0);
            let line: Vec<String> = (0..fields)
                .map(|k| {
                    let time = matches!(layout.targets.get(k), Some(Target::Time));
                    random_field(&mut rng, time)
                })
                .collect();
            let line = line.join(",");
            let text = format!("{line}{PAD}");
            for strictness in [crate::Strictness::Strict, crate::Strictness::Lenient] {
                let strict = strictness == crate::Strictness::Strict;
                let bound = (strict, crate::rows::MAX_MAGNITUDE);
                let mut ours = [0.0; MAX_SLOTS];
                let decoded = decode_line(text.as_bytes(), line.len(), &layout, bound, &mut ours);
                // Found in the unread bytes, the same line decodes to the same numbers and
                // takes its line end; cut anywhere before its line end, it is never taken.
                let line_end = ["\n", "\r\n"][case % 2];
                let unread = format!("{line}{line_end}{line}{PAD}");
                let mut found = [0.0; MAX_SLOTS];
                let next = decode_next_line(unread.as_bytes(), &layout, bound, &mut found);
                let expected = decoded.map(|t| (t, line.len(), line.len() + line_end.len()));
                assert_eq!(next, expected, "{line:?}");
                assert_eq!(ours.map(f64::to_bits), found.map(f64::to_bits), "{line:?}");
                let cut =
                    &unread.as_bytes()[..rng.random_range(0..=line.len() + line_end.len() - 1)];
                assert_eq!(
                    decode_next_line(cut, &layout, bound, &mut found),
                    None,
                    "{line:?}"
                );
                let Some(time) = decoded else {
                    continue;
                };
                fast += 1;
                let mut general = [0.0; MAX_SLOTS];
                let general_time =
                    crate::rows::decode_line(line.as_bytes(), &layout, strictness, &mut general)
                        .unwrap_or_else(|e| panic!("{line}: {e:?}"));
                assert_eq!(time, general_time, "{line}");
                for target in &layout.targets {
                    if let Target::Value { slot, .. } = *target {
                        assert_eq!(ours[slot].to_bits(), general[slot].to_bits(), "{line}");
                    }
                }
            }
        }
        // Most lines have no odd field and take the fast path.
        assert!(fast > cases / 2, "{fast} of {} decodings", 2 * cases);
    }
}
