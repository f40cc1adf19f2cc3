//! Reading a record into the columns of an earlier one gives what a fresh read gives: the
//! series a campaign's records are read into in turn.

use thermonav_io::{FileSplit, ImuOptions, Strictness, read_imu_file_into, read_imu_file_with};

const HEADER_WITH_TEMPERATURE: &str =
    "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c";
const HEADER_RATES_ONLY: &str = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,az_m_s2";

/// A record of `rows` rows under `header`, each value a function of the row and the column.
fn record(header: &str, rows: usize, seed: f64) -> String {
    let columns = header.split(',').count();
    let mut text = format!("{header}\n");
    for k in 0..rows {
        let mut fields = vec![format!("{:.9}", k as f64 * 0.005)];
        for c in 1..columns {
            let value = match c {
                4..=6 if header.contains("ax") => -9.80665 + 0.01 * (seed + (k * c) as f64).sin(),
                _ if header.ends_with("az_m_s2") && c == columns - 1 => -9.8 + 0.001 * seed,
                7 => 20.0 + 0.01 * (k as f64 / 97.0).cos(),
                _ => 1e-3 * (seed * c as f64 + k as f64).sin(),
            };
            fields.push(format!("{value}"));
        }
        text.push_str(&fields.join(","));
        text.push('\n');
    }
    text
}

// Records read in turn, each into the previous one's series: with temperatures twice (a
// campaign's case: the temperature column reused), without, with again, one whose row 700
// is not a number (an error: the same error as a fresh read, the spare dropped), and a
// header-only file. Each equals its fresh read (columns, present channels, temperature column
// and kind).
#[test]
fn a_record_read_into_a_spare_series_is_its_fresh_read() {
    let dir = tempfile::tempdir().unwrap();
    let broken: String = (record(HEADER_WITH_TEMPERATURE, 1000, 4.0).lines())
        .enumerate()
        .map(|(k, line)| match k {
            700 => format!("{line}x\n"),
            _ => format!("{line}\n"),
        })
        .collect();
    let files = [
        record(HEADER_WITH_TEMPERATURE, 5000, 1.0),
        record(HEADER_WITH_TEMPERATURE, 4000, 5.0),
        record(HEADER_RATES_ONLY, 1200, 2.0),
        record(HEADER_WITH_TEMPERATURE, 3000, 3.0),
        broken,
        format!("{HEADER_WITH_TEMPERATURE}\n"),
    ];
    let mut errors = 0;
    let options = ImuOptions {
        split: FileSplit::OnePass,
        ..ImuOptions::default()
    };
    let mut spare = None;
    for (k, text) in files.iter().enumerate() {
        let path = dir.path().join(format!("imu_{k}.csv"));
        std::fs::write(&path, text).unwrap();
        let fresh = read_imu_file_with(&path, Strictness::Lenient, &options);
        let reused = read_imu_file_into(&path, Strictness::Lenient, &options, spare.take());
        match (fresh, reused) {
            (Ok(fresh), Ok(reused)) => {
                assert_eq!(reused, fresh, "file {k}");
                spare = Some(reused);
            }
            (Err(fresh), Err(reused)) => {
                assert_eq!(reused.to_string(), fresh.to_string());
                errors += 1;
            }
            (fresh, reused) => panic!("file {k}: {fresh:?} / {reused:?}"),
        }
    }
    assert!(errors >= 1, "the broken record is refused");
}
