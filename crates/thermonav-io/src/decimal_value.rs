//! The correctly rounded `f64` of w·10^q, for a decimal already split into its digits as an
//! integer w (a `u64`) and its power of ten q: what `str::parse::<f64>` gives for the text.
//!
//! Two exact routes, tried in order:
//! - Clinger's fast path (W. D. Clinger, *How to Read Floating Point Numbers Accurately*, PLDI
//!   1990): w ≤ 2^53 and |q| ≤ 22 make w and 10^|q| exact in `f64`, and one IEEE division or
//!   multiplication rounds the exact result once.
//! - The Eisel-Lemire algorithm (D. Lemire, *Number Parsing at a Gigabyte per Second*, Software:
//!   Practice and Experience 51(8), 2021) for the rest, which in sensor files are the values
//!   printed at 17 significant digits (`0.019198621771937624`): w normalised to 64 bits times a
//!   128-bit truncation of 5^q gives the leading bits of the exact product, enough to round it
//!   correctly for every q in [`MIN_POWER`, `MAX_POWER`] (inside the range where Lemire shows the
//!   truncated product always decides the rounding); exact halfway cases, possible only for
//!   small q, are rounded to even.
//!
//! The 128-bit powers of five are computed when the program is compiled, from their definition
//! (integer long division), and the whole route is checked against `str::parse::<f64>` on
//! random and halfway-case decimals in the tests. A q outside the range, or a subnormal result,
//! gives `None`, and the caller uses its general parser.

/// Smallest power of ten taken (Lemire's bound below which the truncated product may not decide
/// the rounding is −27).
pub(crate) const MIN_POWER: i32 = -27;
/// Largest power of ten taken: enough for sensor values; the table stays small.
pub(crate) const MAX_POWER: i32 = 22;

/// 10^0 ..= 10^22: the powers of ten an `f64` holds exactly.
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// Largest integer below which every integer is exact in an `f64`.
const MAX_EXACT_MANTISSA: u64 = 1 << 53;

/// Explicit mantissa bits of an `f64`.
const MANTISSA_BITS: u32 = 52;
/// Bits kept below the 53 of the result when the product is shifted: one to round, two to
/// tell a halfway case.
const SHIFT: u32 = 64 - MANTISSA_BITS - 3;
/// Exponent bias of an `f64`.
const EXPONENT_BIAS: i32 = 1023;

/// The correctly rounded value of `mantissa`·10^`power` (non-negative), or `None` when neither
/// exact route covers it.
#[inline(always)]
pub(crate) fn decimal_value(mantissa: u64, power: i32) -> Option<f64> {
    if mantissa <= MAX_EXACT_MANTISSA && (-22..=22).contains(&power) {
        let magnitude = mantissa as f64;
        return Some(match power {
            0.. => magnitude * EXACT_POWERS_OF_TEN[power as usize],
            _ => magnitude / EXACT_POWERS_OF_TEN[power.unsigned_abs() as usize],
        });
    }
    eisel_lemire(mantissa, power)
}

/// The Eisel-Lemire route; `None` outside [`MIN_POWER`, `MAX_POWER`] or for a subnormal result.
#[inline]
fn eisel_lemire(mantissa: u64, power: i32) -> Option<f64> {
    if mantissa == 0 {
        return Some(0.0);
    }
    if !(MIN_POWER..=MAX_POWER).contains(&power) {
        return None;
    }
    let zeros = mantissa.leading_zeros();
    let normalised = mantissa << zeros;
    let (high, low) = leading_product(normalised, power);
    let top_bit = (high >> 63) as u32;
    let mut bits = high >> (top_bit + SHIFT);
    let mut exponent = binary_exponent(power) + top_bit as i32 - zeros as i32 + EXPONENT_BIAS;
    if exponent <= 0 {
        return None;
    }
    // An exact halfway case (the bits shifted out all zero, and nothing below them) rounds to
    // even; it can only happen when 5^|q| is small enough for the product to be exact.
    let halfway = low <= 1
        && (-4..=23).contains(&power)
        && bits & 3 == 1
        && bits << (top_bit + SHIFT) == high;
    if halfway {
        bits &= !1;
    }
    bits += bits & 1;
    bits >>= 1;
    if bits >= 2 << MANTISSA_BITS {
        bits = 1 << MANTISSA_BITS;
        exponent += 1;
    }
    bits &= !(1 << MANTISSA_BITS);
    Some(f64::from_bits(bits | (exponent as u64) << MANTISSA_BITS))
}

/// ⌊q·log2 10⌋ + 63: the binary exponent of 10^q's normalised 128-bit form (the fixed-point
/// constant 217706/65536 is log2 10 to within 2e-6, exact for |q| far beyond the table's range).
#[inline(always)]
fn binary_exponent(power: i32) -> i32 {
    ((217_706 * power) >> 16) + 63
}

/// The high 64 bits of `normalised` × 5^`power` (128-bit truncated) and the next 64, the
/// second word computed only when the first leaves the rounding bits undecided.
#[inline(always)]
fn leading_product(normalised: u64, power: i32) -> (u64, u64) {
    let [high_factor, low_factor] = POWERS_OF_FIVE[(power - MIN_POWER) as usize];
    let first = u128::from(normalised) * u128::from(high_factor);
    let (mut high, mut low) = ((first >> 64) as u64, first as u64);
    const UNDECIDED: u64 = u64::MAX >> (MANTISSA_BITS + 3);
    if high & UNDECIDED == UNDECIDED {
        let second = ((u128::from(normalised) * u128::from(low_factor)) >> 64) as u64;
        let (sum, carry) = low.overflowing_add(second);
        low = sum;
        high += u64::from(carry);
    }
    (high, low)
}

/// 5^q for q in [`MIN_POWER`, `MAX_POWER`], normalised to 128 bits (top bit set) as
/// [high word, low word]: exact for q ≥ 0; for q < 0, ⌊2^(z+127) / 5^−q⌋ + 1 where 2^z is the
/// first power of two at least 5^−q, as Lemire's table has them for q ≥ −27.
const POWERS_OF_FIVE: [[u64; 2]; (MAX_POWER - MIN_POWER + 1) as usize] = powers_of_five();

const fn powers_of_five() -> [[u64; 2]; (MAX_POWER - MIN_POWER + 1) as usize] {
    let mut table = [[0_u64; 2]; (MAX_POWER - MIN_POWER + 1) as usize];
    let mut power = MIN_POWER;
    while power <= MAX_POWER {
        let value = match power >= 0 {
            true => normalised_power_of_five(power as u32),
            false => normalised_reciprocal_of_five(power.unsigned_abs()),
        };
        table[(power - MIN_POWER) as usize] = [(value >> 64) as u64, value as u64];
        power += 1;
    }
    table
}

/// 5^n shifted left until its top bit is bit 127 (n ≤ 55 keeps it exact).
const fn normalised_power_of_five(n: u32) -> u128 {
    let mut value = 5_u128.pow(n);
    while value < 1 << 127 {
        value <<= 1;
    }
    value
}

/// ⌊2^(z+127) / 5^n⌋ + 1, 2^z the first power of two at least 5^n (n ≤ 27, so 5^n < 2^64):
/// a quotient in [2^127, 2^128), found by long division one bit at a time.
const fn normalised_reciprocal_of_five(n: u32) -> u128 {
    let divisor = 5_u128.pow(n);
    let mut z = 0;
    while (1_u128 << z) < divisor {
        z += 1;
    }
    let top = z + 127;
    let (mut quotient, mut remainder) = (0_u128, 0_u128);
    let mut bit = top;
    while bit >= 0 {
        // The dividend 2^top: a one, then zeros.
        remainder = remainder * 2 + (bit == top) as u128;
        let quotient_bit = remainder >= divisor;
        if quotient_bit {
            remainder -= divisor;
        }
        quotient = (quotient << 1) | quotient_bit as u128;
        bit -= 1;
    }
    quotient + 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The oracle: std's correctly rounded parse of the decimal w·10^q written out.
    fn std_value(mantissa: u64, power: i32) -> f64 {
        format!("{mantissa}e{power}").parse().unwrap()
    }

    fn assert_std(mantissa: u64, power: i32) {
        if let Some(value) = decimal_value(mantissa, power) {
            assert_eq!(
                value.to_bits(),
                std_value(mantissa, power).to_bits(),
                "{mantissa}e{power}"
            );
        } else {
            assert!(
                !(MIN_POWER..=MAX_POWER).contains(&power),
                "{mantissa}e{power} refused inside the range"
            );
        }
    }

    #[test]
    fn table_entries_are_lemires_construction() {
        // [high, low] as tools/oracles/powers_of_five.py computes them with exact integers.
        let at = |q: i32| POWERS_OF_FIVE[(q - MIN_POWER) as usize];
        assert_eq!(at(-1), [0xcccc_cccc_cccc_cccc, 0xcccc_cccc_cccc_cccd]);
        assert_eq!(at(-2), [0xa3d7_0a3d_70a3_d70a, 0x3d70_a3d7_0a3d_70a4]);
        assert_eq!(at(-27), [0x9e74_d1b7_91e0_7e48, 0x775e_a264_cf55_347e]);
        assert_eq!(at(0), [0x8000_0000_0000_0000, 0]);
        assert_eq!(at(1), [0xa000_0000_0000_0000, 0]);
        assert_eq!(at(22), [0x8786_7832_6eac_9000, 0]);
    }

    #[test]
    fn random_mantissas_and_powers_give_std_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(2021);
        for _ in 0..1_000_000 {
            let digits = rng.random_range(1..=19_u32);
            let mantissa = rng.random_range(0..10_u64.pow(digits));
            let power = rng.random_range(MIN_POWER - 3..=MAX_POWER + 3);
            assert_std(mantissa, power);
        }
    }

    #[test]
    fn seventeen_digit_sensor_values_give_std_bits() {
        // Values printed at 17 significant digits (Rust's and Python's shortest round trip of
        // quantised rates and temperatures), whose mantissas pass 2^53.
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        for _ in 0..300_000 {
            let value = (rng.random::<f64>() - 0.5) * 10f64.powi(rng.random_range(-8..3));
            let text = format!("{:.16e}", value.abs());
            let (digits, exponent) = text.split_once('e').unwrap();
            let mantissa: u64 = digits.replace('.', "").parse().unwrap();
            let power = exponent.parse::<i32>().unwrap() - 16;
            assert_std(mantissa, power);
        }
    }

    #[test]
    fn halfway_cases_round_to_even() {
        // Odd integers in [2^53, 2^54) sit halfway between two doubles (spacing 2); x.5 in
        // [2^52, 2^53) too (spacing 1); and the same with trailing zeros (q > 0) or as
        // products with the powers of ten that keep them exact.
        let mut rng = ChaCha8Rng::seed_from_u64(53);
        for _ in 0..200_000 {
            let odd = (1_u64 << 53) + 2 * rng.random_range(0..1_u64 << 52) + 1;
            assert_std(odd, 0);
            let whole = (1_u64 << 52) + rng.random_range(0..1_u64 << 52);
            assert_std(whole * 10 + 5, -1);
            // Just off halfway, both sides.
            assert_std(whole * 100 + 49, -2);
            assert_std(whole * 100 + 51, -2);
            let small = (1_u64 << 53) / 1000 + 2 * rng.random_range(0..1_000_000) + 1;
            assert_std(small, 3);
        }
        for (mantissa, power) in [
            (9_007_199_254_740_993, 0),
            (9_007_199_254_740_995, 0),
            (18_014_398_509_481_985, 0),
            (45_035_996_273_704_965, -1),
            (u64::MAX, 0),
            (u64::MAX, MIN_POWER),
            (u64::MAX, MAX_POWER),
            (1, MIN_POWER),
            (1, MAX_POWER),
        ] {
            assert_std(mantissa, power);
        }
    }
}
