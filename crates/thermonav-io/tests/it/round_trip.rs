//! Write then read gives back the same bits: values in shortest round-trip form, times as exact
//! nanoseconds, angles in the degree value that converts back to the same radians.

use crate::support::within_ulps;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use thermonav::gnss::{GnssFix, HeadingObservation};
use thermonav::imu::{Channel, ImuSample, ImuSeries, SampleKind};
use thermonav::time::Timestamp;
use thermonav::trajectory::TrajectoryPoint;
use thermonav::units::deg_to_rad;
use thermonav_io::{
    ImuWriter, Strictness, TemperatureColumn, WriteError, read_gnss, read_imu, read_imu_file,
    read_trajectory, write_gnss, write_imu, write_imu_file, write_trajectory,
};

/// A value of any magnitude and sign, with awkward special cases mixed in.
fn awkward_value(rng: &mut ChaCha8Rng) -> f64 {
    match rng.random_range(0..10) {
        0 => [
            0.0,
            -0.0,
            1e-300,
            -5e-324,
            1.7976931348623157e308,
            0.1,
            1e16,
        ][rng.random_range(0..7)],
        // Positive and below 2, of any exponent down to subnormals.
        1 => f64::from_bits(rng.random::<u64>() >> 2),
        _ => (rng.random::<f64>() - 0.5) * 10f64.powi(rng.random_range(-9..6)),
    }
}

/// Strictly increasing times with irregular steps, starting before zero.
fn irregular_times(rng: &mut ChaCha8Rng, n: usize) -> Vec<Timestamp> {
    let mut nanos = -1_234_567_891_i64;
    (0..n)
        .map(|_| {
            nanos += rng.random_range(1..20_000_000);
            Timestamp::from_nanos(nanos)
        })
        .collect()
}

fn random_series(rng: &mut ChaCha8Rng, kind: SampleKind, n: usize, temperature: bool) -> ImuSeries {
    let mut series = ImuSeries::new(kind);
    for time in irregular_times(rng, n) {
        series.push(&ImuSample {
            time,
            gyro: [awkward_value(rng), awkward_value(rng), awkward_value(rng)],
            accel: [awkward_value(rng), awkward_value(rng), awkward_value(rng)],
            temperature_c: temperature.then(|| awkward_value(rng)),
        });
    }
    series
}

fn assert_same_bits(read: &ImuSeries, written: &ImuSeries) {
    assert_eq!(read.kind, written.kind);
    assert_eq!(read.time, written.time);
    for channel in Channel::ALL {
        let bits = |s: &ImuSeries| {
            s.channel(channel)
                .iter()
                .map(|v| v.to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(read), bits(written), "{channel:?}");
    }
    let temperature_bits = |s: &ImuSeries| {
        s.temperature_c
            .as_ref()
            .map(|t| t.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
    };
    assert_eq!(temperature_bits(read), temperature_bits(written));
}

#[test]
fn imu_rates_with_temperature_round_trip_bit_exact() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let series = random_series(&mut rng, SampleKind::Rates, 5_000, true);
    let mut text = Vec::new();
    write_imu(&mut text, &series).unwrap();
    // Lenient: the random values reach 1e308, beyond what a strict reader accepts (1e15);
    // the writer's exactness is what is tested.
    let back = read_imu(&text[..], "mem", Strictness::Lenient).unwrap();
    assert_same_bits(&back, &series);
}

#[test]
fn imu_increments_round_trip_bit_exact_through_a_file() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let series = random_series(&mut rng, SampleKind::Increments, 2_000, false);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("inc.csv");
    write_imu_file(&path, &series).unwrap();
    // Lenient: the random values reach 1e308, beyond what a strict reader accepts (1e15);
    // the writer's exactness is what is tested.
    let back = read_imu_file(&path, Strictness::Lenient).unwrap();
    assert_same_bits(&back, &series);
}

#[test]
fn imu_writer_prints_canonical_si_text() {
    let series = read_imu(
        &b"t_s,gx_deg_s,gy_rad_s,gz_rad_s,ax_g,ay_m_s2,az_m_s2\n12.005,0,0.5,-2.5e-7,1,0,-9.8\n"[..],
        "mem",
        Strictness::Strict,
    )
    .unwrap();
    let mut text = Vec::new();
    write_imu(&mut text, &series).unwrap();
    assert_eq!(
        String::from_utf8(text).unwrap(),
        "t_s,gx_rad_s,gy_rad_s,gz_rad_s,ax_m_s2,ay_m_s2,az_m_s2\n\
         12.005000000,0,0.5,-2.5e-7,9.80665,0,-9.8\n"
    );
}

#[test]
fn imu_writer_rejects_malformed_series() {
    let mut sink = Vec::new();
    assert!(matches!(
        write_imu(&mut sink, &ImuSeries::new(SampleKind::Rates)),
        Err(WriteError::Empty { what: "samples" })
    ));
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut ragged = random_series(&mut rng, SampleKind::Rates, 3, false);
    ragged.channels[4].pop();
    assert_eq!(
        write_imu(&mut sink, &ragged).unwrap_err().to_string(),
        "column ay has 2 values but the time axis has 3"
    );
    let mut unknown = random_series(&mut rng, SampleKind::Rates, 3, false);
    unknown.kind = None;
    assert!(matches!(
        write_imu(&mut sink, &unknown),
        Err(WriteError::UnknownKind)
    ));

    let mut writer =
        ImuWriter::new(Vec::new(), SampleKind::Rates, TemperatureColumn::Written).unwrap();
    let sample = ImuSample {
        time: Timestamp::from_nanos(0),
        gyro: [0.0; 3],
        accel: [0.0; 3],
        temperature_c: None,
    };
    assert_eq!(
        writer.write_sample(&sample).unwrap_err().to_string(),
        "sample 0 has no temperature but the file has a temp_c column"
    );
}

/// Radians as they come from a file in degrees.
fn radians_from_degrees(rng: &mut ChaCha8Rng, range_deg: f64) -> f64 {
    deg_to_rad((rng.random::<f64>() * 2.0 - 1.0) * range_deg)
}

#[test]
fn gnss_round_trip_bit_exact_with_and_without_groups() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let times = irregular_times(&mut rng, 3_000);
    let full: Vec<GnssFix> = times
        .iter()
        .map(|&time| GnssFix {
            time,
            latitude_rad: radians_from_degrees(&mut rng, 90.0),
            longitude_rad: radians_from_degrees(&mut rng, 180.0),
            height_m: awkward_value(&mut rng),
            position_sd_ned_m: Some([rng.random(), rng.random(), rng.random()]),
            velocity_ned_m_s: Some([awkward_value(&mut rng), awkward_value(&mut rng), -0.0]),
            heading: Some(HeadingObservation {
                heading_rad: radians_from_degrees(&mut rng, 180.0),
                sd_rad: radians_from_degrees(&mut rng, 1.0).abs(),
            }),
        })
        .collect();
    let position_only: Vec<GnssFix> = full
        .iter()
        .map(|f| GnssFix {
            position_sd_ned_m: None,
            velocity_ned_m_s: None,
            heading: None,
            ..*f
        })
        .collect();
    for fixes in [full, position_only] {
        let mut text = Vec::new();
        write_gnss(&mut text, &fixes).unwrap();
        // Lenient: the random values reach 1e308, beyond what a strict reader accepts (1e15);
        // the writer's exactness is what is tested.
        let back = read_gnss(&text[..], "mem", Strictness::Lenient).unwrap();
        // Bit-exact: Debug of f64 shows every bit, and PartialEq would accept -0.0 == 0.0.
        assert_eq!(format!("{back:?}"), format!("{fixes:?}"));
    }
}

#[test]
fn gnss_angles_not_from_degrees_come_back_within_one_ulp() {
    // Not every radian value is deg·fl(π/180) for some degree value; those come back within one
    // unit in the last place (the writer prints rad/fl(π/180), within 1 ulp of the ideal).
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let fixes: Vec<GnssFix> = irregular_times(&mut rng, 3_000)
        .into_iter()
        .map(|time| GnssFix {
            time,
            latitude_rad: (rng.random::<f64>() - 0.5) * std::f64::consts::PI,
            longitude_rad: (rng.random::<f64>() - 0.5) * 6.0,
            height_m: 0.0,
            position_sd_ned_m: None,
            velocity_ned_m_s: None,
            heading: None,
        })
        .collect();
    let mut text = Vec::new();
    write_gnss(&mut text, &fixes).unwrap();
    let back = read_gnss(&text[..], "mem", Strictness::Strict).unwrap();
    for (b, f) in back.iter().zip(&fixes) {
        assert!(
            within_ulps(b.latitude_rad, f.latitude_rad, 1),
            "{b:?} {f:?}"
        );
        assert!(
            within_ulps(b.longitude_rad, f.longitude_rad, 1),
            "{b:?} {f:?}"
        );
    }
}

#[test]
fn gnss_writer_rejects_fixes_with_differing_groups() {
    let fix = GnssFix {
        time: Timestamp::from_nanos(0),
        latitude_rad: 0.0,
        longitude_rad: 0.0,
        height_m: 0.0,
        position_sd_ned_m: None,
        velocity_ned_m_s: None,
        heading: None,
    };
    let with_velocity = GnssFix {
        time: Timestamp::from_nanos(1),
        velocity_ned_m_s: Some([0.0; 3]),
        ..fix
    };
    let error = write_gnss(Vec::new(), &[fix, with_velocity]).unwrap_err();
    assert_eq!(
        error.to_string(),
        "fix 1 has the vn_m_s,ve_m_s,vd_m_s group, unlike fix 0"
    );
    assert!(matches!(
        write_gnss(Vec::new(), &[]),
        Err(WriteError::Empty { .. })
    ));
}

#[test]
fn trajectory_round_trip_bit_exact() {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    let points: Vec<TrajectoryPoint> = irregular_times(&mut rng, 3_000)
        .into_iter()
        .map(|time| TrajectoryPoint {
            time,
            latitude_rad: radians_from_degrees(&mut rng, 90.0),
            longitude_rad: radians_from_degrees(&mut rng, 180.0),
            height_m: awkward_value(&mut rng),
            velocity_ned_m_s: [
                awkward_value(&mut rng),
                awkward_value(&mut rng),
                awkward_value(&mut rng),
            ],
            roll_rad: radians_from_degrees(&mut rng, 180.0),
            pitch_rad: radians_from_degrees(&mut rng, 90.0),
            yaw_rad: radians_from_degrees(&mut rng, 360.0),
        })
        .collect();
    let mut text = Vec::new();
    write_trajectory(&mut text, &points).unwrap();
    // Lenient: the random values reach 1e308, beyond what a strict reader accepts (1e15);
    // the writer's exactness is what is tested.
    let back = read_trajectory(&text[..], "mem", Strictness::Lenient).unwrap();
    assert_eq!(format!("{back:?}"), format!("{points:?}"));
}
