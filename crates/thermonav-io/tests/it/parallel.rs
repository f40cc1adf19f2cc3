//! Large files are read as two halves on two threads; the result and every error must be those
//! of the one-pass reader.

use std::fmt::Write as _;
use thermonav_io::{Strictness, read_imu, read_imu_file};

/// 140 000 rows of about 75 bytes (> 8 MiB, so the parallel path is taken), times in 5 ms steps.
fn lines() -> Vec<String> {
    (0..140_000)
        .map(|k| {
            let t = k as f64 * 0.005;
            let mut line = format!("{t:.9}");
            for c in 0..6 {
                let _ = write!(line, ",{}", ((k * 7 + c * 13) % 1000) as f64 * 1e-3 - 0.5);
            }
            let _ = write!(line, ",{}", 20.0 + (k % 10) as f64 * 0.01);
            line
        })
        .collect()
}

fn text(lines: &[String]) -> String {
    let mut text = String::from("t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n");
    for l in lines {
        text.push_str(l);
        text.push('\n');
    }
    text
}

/// Index of the first data line that starts after the middle byte of the file.
fn line_after_middle(lines: &[String]) -> usize {
    let total = text(lines).len();
    let mut offset = "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2,temp_c\n".len();
    for (k, l) in lines.iter().enumerate() {
        if offset > total / 2 {
            return k;
        }
        offset += l.len() + 1;
    }
    lines.len()
}

#[test]
fn two_halves_give_the_one_pass_result() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.csv");
    let body = text(&lines());
    assert!(body.len() > 8 << 20);
    std::fs::write(&path, &body).unwrap();
    let parallel = read_imu_file(&path, Strictness::Strict).unwrap();
    let sequential = read_imu(body.as_bytes(), "big.csv", Strictness::Strict).unwrap();
    assert_eq!(parallel, sequential);
    assert_eq!(parallel.len(), 140_000);
}

#[test]
fn errors_in_the_second_half_name_the_file_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.csv");
    let mut rows = lines();
    rows[120_000] = rows[120_000].replacen(',', ",abc", 1);
    std::fs::write(&path, text(&rows)).unwrap();
    let message = read_imu_file(&path, Strictness::Strict)
        .unwrap_err()
        .to_string();
    // Data line k is on file line k + 2 (line 1 is the header).
    assert!(message.contains("bad.csv:120002:"), "{message}");
}

#[test]
fn time_going_back_across_the_split_is_caught_under_strict_reading() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("split.csv");
    let mut rows = lines();
    let k = line_after_middle(&rows);
    let previous_time = rows[k - 1].split(',').next().unwrap().to_string();
    let rest = rows[k].split_once(',').unwrap().1.to_string();
    rows[k] = format!("{previous_time},{rest}");
    let body = text(&rows);
    std::fs::write(&path, &body).unwrap();
    let message = read_imu_file(&path, Strictness::Strict)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains(&format!("split.csv:{}:", k + 2)),
        "{message}"
    );
    let lenient = read_imu_file(&path, Strictness::Lenient).unwrap();
    assert_eq!(
        lenient,
        read_imu(body.as_bytes(), "split.csv", Strictness::Lenient).unwrap()
    );
}
