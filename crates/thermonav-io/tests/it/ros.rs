//! ROS bags: the files of tests/data/ros, written by `tools/oracles/ros_bags.py` with the PyPI
//! packages rosbags 0.11.9 and mcap 1.6.0, read back against the values the script wrote
//! (`expected.json`), value for value. The floats are binary64 in the bags and in the JSON
//! (Python's repr round-trips), so every comparison is exact; the only arithmetic on them is a
//! sign change (ROS body axes to FRD), which is exact too.

use serde_json::Value;
use thermonav::time::Timestamp;
use thermonav::units::deg_to_rad;
use thermonav_io::ros::extract::{TopicChoice, gnss_fixes, imu_series};
use thermonav_io::ros::messages::MessageType;
use thermonav_io::ros::sqlite::{Database, Value as SqlValue};
use thermonav_io::ros::{Bag, BagFormat, decode_bag, read_bag_file};

fn dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros")
}

fn expected() -> Value {
    let text = std::fs::read_to_string(dir().join("expected.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn bag(name: &str) -> Bag {
    read_bag_file(dir().join(name), None).unwrap()
}

/// Every bag of the oracle, with its format.
const BAGS: [(&str, BagFormat); 8] = [
    ("static_none.mcap", BagFormat::Ros2Mcap),
    ("static_zstd.mcap", BagFormat::Ros2Mcap),
    ("static_lz4.mcap", BagFormat::Ros2Mcap),
    ("static_unchunked_be.mcap", BagFormat::Ros2Mcap),
    ("static.db3", BagFormat::Ros2Db3),
    ("static.bag", BagFormat::Ros1Bag),
    ("static_lz4.bag", BagFormat::Ros1Bag),
    ("static_bz2.bag", BagFormat::Ros1Bag),
];

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

fn ns(v: &Value) -> i64 {
    v.as_i64().unwrap()
}

fn choice() -> TopicChoice<'static> {
    TopicChoice {
        imu: Some("/imu/data"),
        ..TopicChoice::default()
    }
}

#[test]
fn each_bag_is_detected_by_its_magic_and_lists_its_topics_with_counts() {
    for (name, format) in BAGS {
        let bag = bag(name);
        assert_eq!(bag.format, format, "{name}");
        let count = |topic: &str| bag.topics.iter().find(|t| t.name == topic).map(|t| t.count);
        assert_eq!(count("/imu/data"), Some(150), "{name}");
        assert_eq!(count("/imu/temperature"), Some(30), "{name}");
        assert_eq!(count("/gnss/fix"), Some(8), "{name}");
        let imu = bag.topics.iter().find(|t| t.name == "/imu/data").unwrap();
        assert_eq!(imu.message_type, Some(MessageType::Imu), "{name}");
    }
}

#[test]
fn imu_values_are_the_written_ones_in_frd_at_the_header_stamps() {
    let expected = expected();
    let rows = expected["imu"].as_array().unwrap();
    let temperatures = expected["temperature"].as_array().unwrap();
    for (name, _) in BAGS {
        let extract = imu_series(&bag(name), choice(), name).unwrap();
        let s = &extract.series;
        assert_eq!(s.len(), rows.len(), "{name}");
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(
                s.time[k],
                Timestamp::from_nanos(ns(&row["stamp_ns"])),
                "{name} {k}"
            );
            let (g, a) = (&row["gyro"], &row["accel"]);
            let frd = [
                f(&g[0]),
                -f(&g[1]),
                -f(&g[2]),
                f(&a[0]),
                -f(&a[1]),
                -f(&a[2]),
            ];
            for (c, value) in frd.iter().enumerate() {
                assert_eq!(s.channels[c][k], *value, "{name} sample {k} channel {c}");
            }
            // The nearest temperature message by header stamp, by a full scan.
            let t = s.time[k].as_nanos();
            let nearest = temperatures
                .iter()
                .min_by_key(|r| ((ns(&r["stamp_ns"]) - t).abs(), ns(&r["stamp_ns"])))
                .unwrap();
            let temp = s.temperature_c.as_ref().unwrap()[k];
            assert_eq!(temp, f(&nearest["temperature_c"]), "{name} sample {k} temp");
        }
        assert_eq!(
            extract.temperature_topic.as_deref(),
            Some("/imu/temperature")
        );
        // Record time = stamp + 2 ms + 1 us per message (the script's rule).
        let lag = extract.stamp_lag_s.unwrap();
        assert_eq!(lag.max_s, -0.002, "{name}");
        assert_eq!(lag.min_s, -(2_000_000.0 + 1000.0 * 149.0) * 1e-9, "{name}");
    }
}

#[test]
fn a_level_static_unit_reads_minus_g_on_z_in_frd() {
    let extract = imu_series(&bag("static_zstd.mcap"), choice(), "b").unwrap();
    let az = &extract.series.channels[5];
    let mean = az.iter().sum::<f64>() / az.len() as f64;
    assert!((mean + 9.80665).abs() < 0.01, "mean az {mean}");
}

#[test]
fn gnss_fixes_are_the_written_ones() {
    let expected = expected();
    let rows = expected["fixes"].as_array().unwrap();
    for (name, _) in BAGS {
        let extract = gnss_fixes(&bag(name), None, name).unwrap();
        assert_eq!(extract.fixes.len(), rows.len(), "{name}");
        assert_eq!(extract.messages_without_fix, 0);
        for (fix, row) in extract.fixes.iter().zip(rows) {
            assert_eq!(
                fix.time,
                Timestamp::from_nanos(ns(&row["stamp_ns"])),
                "{name}"
            );
            assert_eq!(
                fix.latitude_rad,
                deg_to_rad(f(&row["latitude_deg"])),
                "{name}"
            );
            assert_eq!(
                fix.longitude_rad,
                deg_to_rad(f(&row["longitude_deg"])),
                "{name}"
            );
            assert_eq!(fix.height_m, f(&row["altitude_m"]), "{name}");
            let c = &row["position_covariance"];
            let sd = [f(&c[4]).sqrt(), f(&c[0]).sqrt(), f(&c[8]).sqrt()];
            assert_eq!(fix.position_sd_ned_m, Some(sd), "{name}");
        }
    }
}

#[test]
fn without_a_topic_the_only_one_of_the_type_is_taken_and_several_are_listed() {
    let bag = bag("static_zstd.mcap");
    let err = imu_series(&bag, TopicChoice::default(), "z.mcap")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("2 topics of type sensor_msgs/msg/Imu")
            && err.contains("/imu/data (sensor_msgs/msg/Imu, 150 messages)")
            && err.contains("/imu/raw (sensor_msgs/msg/Imu, 5 messages)")
            && err.contains("--topic"),
        "{err}"
    );
    let raw = TopicChoice {
        imu: Some("/imu/raw"),
        ..TopicChoice::default()
    };
    let extract = imu_series(&bag, raw, "z.mcap").unwrap();
    assert_eq!(extract.series.len(), 5);
    assert_eq!(extract.series.channels[1][0], -0.2);
    let single = imu_series(&self::bag("static.db3"), TopicChoice::default(), "s.db3").unwrap();
    assert_eq!(single.topic, "/imu/data");
    let wrong = TopicChoice {
        imu: Some("/gnss/fix"),
        ..TopicChoice::default()
    };
    let err = imu_series(&bag, wrong, "z.mcap").unwrap_err().to_string();
    assert!(
        err.contains("topic /gnss/fix is sensor_msgs/msg/NavSatFix, not sensor_msgs/msg/Imu"),
        "{err}"
    );
    let missing = TopicChoice {
        imu: Some("/nope"),
        ..TopicChoice::default()
    };
    let err = imu_series(&bag, missing, "z.mcap").unwrap_err().to_string();
    assert!(
        err.contains("no topic /nope in the bag (topics: /imu/data"),
        "{err}"
    );
}

#[test]
fn the_db3_blob_spilling_onto_overflow_pages_reads_back_whole() {
    let bytes = std::fs::read(dir().join("static.db3")).unwrap();
    let db = Database::open(&bytes, "static.db3").unwrap();
    let root = db
        .schema()
        .unwrap()
        .into_iter()
        .find(|e| e.name == "messages")
        .unwrap()
        .root_page;
    let text_len = expected()["blob_text_len"].as_u64().unwrap() as usize;
    let mut blobs = Vec::new();
    db.rows(root, &mut |row| {
        if let Some(SqlValue::Blob(data)) = row.values.get(3) {
            if data.len() > 1000 {
                blobs.push(data.clone());
            }
        }
        Ok(())
    })
    .unwrap();
    assert_eq!(blobs.len(), 1);
    // CDR of std_msgs/String: encapsulation 00 01 00 00, u32 length with the NUL, the text, NUL.
    let mut cdr = vec![0, 1, 0, 0];
    cdr.extend_from_slice(&(text_len as u32 + 1).to_le_bytes());
    cdr.extend((0..text_len).map(|i| b'A' + (i % 26) as u8));
    cdr.push(0);
    assert_eq!(blobs[0][..cdr.len()], cdr[..]);
    assert!(
        blobs[0].len() - cdr.len() < 4,
        "only CDR end padding after the string"
    );
    let topics = bag("static.db3");
    let blob = topics.topics.iter().find(|t| t.name == "/blob").unwrap();
    assert_eq!(
        (blob.count, blob.messages.len()),
        (1, 0),
        "counted, not kept"
    );
}

/// The error `bytes` give as a bag of `format`.
fn error_of(bytes: &[u8], format: BagFormat) -> String {
    match decode_bag(bytes, "bad", format) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn every_cut_of_every_bag_gives_an_error_or_a_bag_never_a_panic() {
    for (name, format) in BAGS {
        let bytes = std::fs::read(dir().join(name)).unwrap();
        for cut in (0..bytes.len()).step_by(97) {
            let _ = decode_bag(&bytes[..cut], "cut", format);
        }
        assert!(
            error_of(&bytes[..bytes.len() / 2], format).starts_with("bad: at byte")
                || format == BagFormat::Ros2Db3
        );
    }
}

#[test]
fn damaged_bags_are_refused_naming_the_offset_and_what_was_expected() {
    let mcap = std::fs::read(dir().join("static_zstd.mcap")).unwrap();
    assert!(
        error_of(b"\x89MCAX0\r\n", BagFormat::Ros2Mcap)
            .contains("at byte 0: expected the MCAP magic")
    );
    // The first record after the magic (Header) with a huge length.
    let mut huge = mcap.clone();
    huge[9..17].copy_from_slice(&u64::MAX.to_le_bytes());
    let err = error_of(&huge, BagFormat::Ros2Mcap);
    assert!(
        err.contains("at byte 17: expected a record's content of 18446744073709551615 bytes"),
        "{err}"
    );
    // The first chunk's compression renamed.
    let at = mcap.windows(4).position(|w| w == b"zstd").unwrap();
    let mut unknown = mcap.clone();
    unknown[at..at + 4].copy_from_slice(b"brot");
    let err = error_of(&unknown, BagFormat::Ros2Mcap);
    assert!(
        err.contains(
            "chunk compression \"brot\" is not supported (expected none, zstd, lz4 or bz2)"
        ),
        "{err}"
    );
    let bag1 = std::fs::read(dir().join("static_lz4.bag")).unwrap();
    let at = bag1
        .windows(15)
        .position(|w| w == b"compression=lz4")
        .unwrap();
    let mut unknown = bag1.clone();
    unknown[at + 12..at + 15].copy_from_slice(b"lzo");
    let err = error_of(&unknown, BagFormat::Ros1Bag);
    assert!(
        err.contains("chunk compression \"lzo\" is not supported"),
        "{err}"
    );
    assert!(
        error_of(b"#ROSBAG V1.2\n", BagFormat::Ros1Bag)
            .contains("expected the line \"#ROSBAG V2.0\"")
    );
    let db = std::fs::read(dir().join("static.db3")).unwrap();
    let err = error_of(&db[..4096 * 3], BagFormat::Ros2Db3);
    assert!(err.contains("at byte 28: the header gives 24 pages of 4096 bytes, but the file holds 3 (a truncated file)"), "{err}");
    let mut utf16 = db.clone();
    utf16[59] = 2;
    assert!(
        error_of(&utf16, BagFormat::Ros2Db3).contains("text encoding 2 (UTF-16) is not supported")
    );
}

#[test]
fn a_db3_with_pending_write_ahead_log_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let db = tmp.path().join("bag.db3");
    std::fs::copy(dir().join("static.db3"), &db).unwrap();
    std::fs::write(tmp.path().join("bag.db3-wal"), [0u8; 64]).unwrap();
    let err = read_bag_file(&db, None).unwrap_err().to_string();
    assert!(
        err.contains("bag.db3-wal holds 64 bytes of write-ahead log not yet in the database file"),
        "{err}"
    );
}

#[test]
fn random_corruptions_of_every_bag_give_an_error_or_a_bag_never_a_panic() {
    use rand::{RngExt, SeedableRng};
    use thermonav_io::parsers::Parser;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(16);
    let parsers = [Parser::Ros2Mcap, Parser::Ros2Db3, Parser::Ros1Bag];
    for (name, format) in BAGS {
        let parser = parsers[format as usize];
        let bytes = std::fs::read(dir().join(name)).unwrap();
        for _ in 0..150 {
            let mut damaged = bytes.clone();
            for _ in 0..rng.random_range(1..8) {
                let at = rng.random_range(0..damaged.len());
                damaged[at] = rng.random();
            }
            let _ = parser.record_count(&damaged, name);
        }
    }
}

#[test]
fn twist_stamped_messages_decode_to_the_written_values() {
    use thermonav_io::ros::messages::decode_twist_stamped;
    let expected = expected();
    let rows = expected["twists"].as_array().unwrap();
    for name in ["static_none.mcap", "static_unchunked_be.mcap", "static.bag"] {
        let bag = bag(name);
        let topic = bag.topics.iter().find(|t| t.name == "/gnss/vel").unwrap();
        assert_eq!(topic.message_type, Some(MessageType::TwistStamped));
        assert_eq!(topic.messages.len(), rows.len(), "{name}");
        for (m, row) in topic.messages.iter().zip(rows) {
            let twist = decode_twist_stamped(&m.data, &topic.encoding, name, m.offset).unwrap();
            assert_eq!(twist.stamp_ns, ns(&row["stamp_ns"]), "{name}");
            assert_eq!(m.log_time_ns, ns(&row["log_time_ns"]), "{name}");
            for k in 0..3 {
                assert_eq!(twist.linear[k], f(&row["linear"][k]), "{name}");
                assert_eq!(twist.angular[k], f(&row["angular"][k]), "{name}");
            }
        }
    }
}
