//! The reader gives the same series whatever sizes the input arrives in: a line is decoded in
//! place only when it lies whole in the buffer, so lines cut by a read's end, blank lines, CRLF
//! ends and lines of other shapes must all come out as the values `str::parse` gives.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::io::{BufReader, Read};
use thermonav_io::{Strictness, read_imu};

/// Hands out at most `max_step` bytes per read, a random number each time.
struct RandomChunks<'a> {
    bytes: &'a [u8],
    rng: ChaCha8Rng,
    max_step: usize,
}

impl Read for RandomChunks<'_> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let step = self.rng.random_range(1..=self.max_step);
        let n = step.min(out.len()).min(self.bytes.len());
        out[..n].copy_from_slice(&self.bytes[..n]);
        self.bytes = &self.bytes[n..];
        Ok(n)
    }
}

/// A value in one of the shapes sensor files hold: 9 or 17 significant digits, an exponent,
/// an integer, with a blank before it now and then (the general decoder's shape).
fn value_text(rng: &mut ChaCha8Rng) -> String {
    let value = (rng.random::<f64>() - 0.5) * 10f64.powi(rng.random_range(-6..2));
    let text = match rng.random_range(0..5) {
        0 => format!("{value:.8e}"),
        1 => format!("{value}"),
        2 => format!("{:.9}", value),
        3 => format!("{}", (value * 1000.0).round()),
        _ => format!("{:.16e}", value),
    };
    match rng.random_range(0..40) {
        0 => format!(" {text}"),
        _ => text,
    }
}

#[test]
fn any_read_sizes_give_the_values_str_parse_gives() {
    let mut rng = ChaCha8Rng::seed_from_u64(33);
    let mut text = String::from("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n");
    let mut expected: Vec<[f64; 8]> = Vec::new();
    for k in 0..20_000 {
        let fields: Vec<String> = (0..6).map(|_| value_text(&mut rng)).collect();
        let temperature = format!("{}", 20.0 + rng.random::<f64>());
        let time = format!("{}.{:09}", k / 200, (k % 200) * 5_000_000);
        let mut row = [0.0; 8];
        row[0] = (k / 200) as f64 + ((k % 200) * 5_000_000) as f64 * 1e-9;
        for (slot, field) in row[1..7].iter_mut().zip(&fields) {
            *slot = field.trim().parse().unwrap();
        }
        row[7] = temperature.parse().unwrap();
        expected.push(row);
        let line_end = if rng.random_range(0..10) == 0 {
            "\r\n"
        } else {
            "\n"
        };
        text.push_str(&format!(
            "{time},{},{temperature}{line_end}",
            fields.join(",")
        ));
        if rng.random_range(0..200) == 0 {
            text.push('\n');
        }
    }
    let whole = read_imu(text.as_bytes(), "whole", Strictness::Strict).unwrap();
    for max_step in [1, 7, 64, 300, 5000, 70_000] {
        let chunks = RandomChunks {
            bytes: text.as_bytes(),
            rng: ChaCha8Rng::seed_from_u64(max_step as u64),
            max_step,
        };
        let series = read_imu(BufReader::new(chunks), "chunks", Strictness::Strict).unwrap();
        assert_eq!(series.len(), expected.len(), "max step {max_step}");
        for (k, row) in expected.iter().enumerate() {
            assert!(
                (series.time[k].as_seconds() - row[0]).abs() < 1e-9,
                "row {k}"
            );
            for c in 0..6 {
                assert_eq!(
                    series.channels[c][k].to_bits(),
                    row[c + 1].to_bits(),
                    "row {k} channel {c}"
                );
            }
            let temperature = series.temperature_c.as_ref().unwrap()[k];
            assert_eq!(temperature.to_bits(), row[7].to_bits(), "row {k}");
        }
        assert_eq!(series.time, whole.time, "max step {max_step}");
    }
}
