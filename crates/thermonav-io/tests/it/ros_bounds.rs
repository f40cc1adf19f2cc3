//! ROS bags that ask for unbounded work (issue 37): chunks that expand to 1 GiB, a file whose
//! chunks together expand far beyond it, millions of messages too short for their type. The
//! bags are built here byte by byte from the formats' descriptions (mcap.dev specification, ROS
//! wiki "Bags/Format/2.0"); the zstd frames are made of RLE blocks (RFC 8878 section 3.1.1.2),
//! the bz2 stream of 1 GiB of zeros is tests/data/ros/zeros_1gib.bz2 (785 bytes, written by
//! tools/oracles/bz2_bomb.py with Python's bz2 module).

use std::time::{Duration, Instant};
use thermonav_io::ros::bytes::{MAX_CHUNK_BYTES, MIN_EXPANSION_BYTES};
use thermonav_io::ros::extract::{TopicChoice, imu_series};
use thermonav_io::ros::{BagFormat, decode_bag};

/// 1 GiB.
const GIB: u64 = 1 << 30;

/// Every refusal here comes well within this (each would take seconds and a GiB if the bytes
/// were decompressed).
const QUICK: Duration = Duration::from_secs(2);

/// The error `bytes` give as a bag of `format` named `input`, and how long it took.
fn refusal(bytes: &[u8], input: &str, format: BagFormat) -> (String, Duration) {
    let start = Instant::now();
    match decode_bag(bytes, input, format) {
        Ok(bag) => panic!("expected an error, read {} messages", bag.message_count()),
        Err(e) => (e.to_string(), start.elapsed()),
    }
}

/// A u32-prefixed string, as MCAP writes them.
fn string(out: &mut Vec<u8>, s: &str) {
    out.extend((s.len() as u32).to_le_bytes());
    out.extend(s.as_bytes());
}

/// An MCAP record: opcode, u64 length, body.
fn record(out: &mut Vec<u8>, opcode: u8, body: &[u8]) {
    out.push(opcode);
    out.extend((body.len() as u64).to_le_bytes());
    out.extend(body);
}

/// The MCAP magic, a Header, a `sensor_msgs/msg/Imu` schema and its channel 1 on `/imu` (CDR).
fn mcap_head() -> Vec<u8> {
    let mut out = b"\x89MCAP0\r\n".to_vec();
    let mut header = Vec::new();
    string(&mut header, "ros2");
    string(&mut header, "thermonav test");
    record(&mut out, 0x01, &header);
    let mut schema = 1u16.to_le_bytes().to_vec();
    string(&mut schema, "sensor_msgs/msg/Imu");
    string(&mut schema, "ros2msg");
    string(&mut schema, "");
    record(&mut out, 0x03, &schema);
    let mut channel = [1u16.to_le_bytes(), 1u16.to_le_bytes()].concat();
    string(&mut channel, "/imu");
    string(&mut channel, "cdr");
    channel.extend(0u32.to_le_bytes());
    record(&mut out, 0x04, &channel);
    out
}

/// A Message record on channel 1.
fn mcap_message(sequence: u32, data: &[u8]) -> Vec<u8> {
    let mut body = 1u16.to_le_bytes().to_vec();
    body.extend(sequence.to_le_bytes());
    body.extend((1_000 + u64::from(sequence)).to_le_bytes());
    body.extend((1_000 + u64::from(sequence)).to_le_bytes());
    body.extend(data);
    let mut out = Vec::new();
    record(&mut out, 0x05, &body);
    out
}

/// A Chunk record of `compression` declaring `declared` bytes, holding `records` as given.
fn mcap_chunk(compression: &str, declared: u64, records: &[u8]) -> Vec<u8> {
    let mut body = [
        0u64.to_le_bytes(),
        0u64.to_le_bytes(),
        declared.to_le_bytes(),
    ]
    .concat();
    body.extend(0u32.to_le_bytes());
    string(&mut body, compression);
    body.extend((records.len() as u64).to_le_bytes());
    body.extend(records);
    let mut out = Vec::new();
    record(&mut out, 0x06, &body);
    out
}

/// Data End, Footer and the closing magic.
fn mcap_tail() -> Vec<u8> {
    let mut out = Vec::new();
    record(&mut out, 0x0F, &0u32.to_le_bytes());
    record(&mut out, 0x02, &[0u8; 20]);
    out.extend(b"\x89MCAP0\r\n");
    out
}

/// Offset of a chunk's records from the start of its record (opcode, length, start and end
/// times, uncompressed size and CRC, the compression string, the records length).
fn records_offset(compression: &str) -> u64 {
    1 + 8 + 8 + 8 + 8 + 4 + 4 + compression.len() as u64 + 8
}

/// A zstd frame (RFC 8878) of `raw` as a raw block, then `zeros` zero bytes as RLE blocks of
/// 128 KiB (4 bytes each): a window of 128 KiB, no content size, no checksum.
fn zstd_frame(raw: &[u8], zeros: u64) -> Vec<u8> {
    const BLOCK: u64 = 128 << 10;
    let mut out = vec![0x28, 0xB5, 0x2F, 0xFD, 0x00, 7 << 3];
    let header = |size: u64, kind: u64, last: bool| {
        let v = (size << 3) | (kind << 1) | u64::from(last);
        [v as u8, (v >> 8) as u8, (v >> 16) as u8]
    };
    out.extend(header(raw.len() as u64, 0, zeros == 0));
    out.extend(raw);
    let mut left = zeros;
    while left > 0 {
        let size = left.min(BLOCK);
        left -= size;
        out.extend(header(size, 1, left == 0));
        out.push(0);
    }
    out
}

/// One MCAP record of an opcode no reader knows (0x00, skipped), of `length` zero bytes, as
/// the bytes before its body: what a chunk of `9 + length` bytes holds.
fn skipped_record_head(length: u64) -> Vec<u8> {
    let mut head = vec![0x00];
    head.extend(length.to_le_bytes());
    head
}

#[test]
fn a_zstd_chunk_declaring_1_gib_is_refused_before_anything_is_decompressed() {
    let head = mcap_head();
    let records = zstd_frame(&skipped_record_head(GIB - 9), GIB - 9);
    assert!(records.len() < 40_000, "{} bytes", records.len());
    let bag = [head.clone(), mcap_chunk("zstd", GIB, &records), mcap_tail()].concat();
    let (err, took) = refusal(&bag, "bomb.mcap", BagFormat::Ros2Mcap);
    let expected = format!(
        "bomb.mcap: at byte {}: the zstd chunk declares 1073741824 bytes uncompressed ({} \
         compressed), above the 67108864-byte (64 MiB) limit of a chunk",
        head.len(),
        records.len()
    );
    assert!(err.starts_with(&expected), "{err}");
    assert!(took < QUICK, "{took:?}");
}

#[test]
fn a_zstd_chunk_expanding_to_1_gib_but_declaring_less_stops_one_byte_past_its_declaration() {
    let head = mcap_head();
    let records = zstd_frame(&skipped_record_head(GIB - 9), GIB - 9);
    let bag = [
        head.clone(),
        mcap_chunk("zstd", 4096, &records),
        mcap_tail(),
    ]
    .concat();
    let (err, took) = refusal(&bag, "liar.mcap", BagFormat::Ros2Mcap);
    let at = head.len();
    assert!(
        err.starts_with(&format!(
            "liar.mcap: at byte {at}: the zstd chunk ({} bytes compressed) expands to more than \
             the 4096 bytes its record declares",
            records.len()
        )),
        "{err}"
    );
    assert!(took < QUICK, "{took:?}");
}

#[test]
fn an_lz4_chunk_expanding_to_1_gib_is_refused_at_its_declaration() {
    use std::io::{Read, Write};
    let mut encoder = lz4_flex::frame::FrameEncoder::new(Vec::new());
    let mut zeros = std::io::repeat(0).take(GIB);
    std::io::copy(&mut zeros, &mut encoder).unwrap();
    encoder.flush().unwrap();
    let frame = encoder.finish().unwrap();
    assert!(frame.len() < 8 << 20, "{} bytes", frame.len());
    let head = mcap_head();
    for (declared, expected) in [
        (
            GIB,
            "the lz4 chunk declares 1073741824 bytes uncompressed".to_string(),
        ),
        (
            1000,
            format!(
                "the lz4 chunk ({} bytes compressed) expands to more than the 1000 bytes its \
                 record declares",
                frame.len()
            ),
        ),
    ] {
        let bag = [
            head.clone(),
            mcap_chunk("lz4", declared, &frame),
            mcap_tail(),
        ]
        .concat();
        let (err, took) = refusal(&bag, "lz4.mcap", BagFormat::Ros2Mcap);
        assert!(err.contains(&expected), "{err}");
        assert!(took < QUICK, "{took:?}");
    }
}

/// A ROS 1 record: header fields `name=value`, then the data.
fn ros1_record(fields: &[(&str, &[u8])], data: &[u8]) -> Vec<u8> {
    let mut header = Vec::new();
    for (name, value) in fields {
        header.extend(((name.len() + 1 + value.len()) as u32).to_le_bytes());
        header.extend(name.as_bytes());
        header.push(b'=');
        header.extend(*value);
    }
    let mut out = (header.len() as u32).to_le_bytes().to_vec();
    out.extend(header);
    out.extend((data.len() as u32).to_le_bytes());
    out.extend(data);
    out
}

/// A ROS 1 chunk record of `compression` declaring `size` bytes, holding `data`.
fn ros1_chunk(compression: &str, size: u32, data: &[u8]) -> Vec<u8> {
    ros1_record(
        &[
            ("op", &[0x05]),
            ("compression", compression.as_bytes()),
            ("size", &size.to_le_bytes()),
        ],
        data,
    )
}

/// A connection record of connection `conn` on `topic` of `type_name`.
fn ros1_connection(conn: u32, topic: &str, type_name: &str) -> Vec<u8> {
    let data = ros1_record(&[("type", type_name.as_bytes())], &[]);
    // The data of a connection record are header fields only (no data length after them).
    let fields = data[4..data.len() - 4].to_vec();
    ros1_record(
        &[
            ("op", &[0x07]),
            ("conn", &conn.to_le_bytes()),
            ("topic", topic.as_bytes()),
        ],
        &fields,
    )
}

/// A message data record of connection `conn` at `secs`.
fn ros1_message(conn: u32, secs: u32, data: &[u8]) -> Vec<u8> {
    let time = [secs.to_le_bytes(), 0u32.to_le_bytes()].concat();
    ros1_record(
        &[
            ("op", &[0x02]),
            ("conn", &conn.to_le_bytes()),
            ("time", &time),
        ],
        data,
    )
}

/// A ROS 1 serialised `sensor_msgs/Imu` stamped `secs`, of angular velocity `gyro` and linear
/// acceleration `accel` (ROS body axes), orientation and covariances zero.
fn ros1_imu(secs: u32, gyro: [f64; 3], accel: [f64; 3]) -> Vec<u8> {
    let mut out = [0u32.to_le_bytes(), secs.to_le_bytes(), 0u32.to_le_bytes()].concat();
    out.extend(0u32.to_le_bytes());
    let mut floats = vec![0.0; 13];
    floats.extend(gyro);
    floats.extend([0.0; 9]);
    floats.extend(accel);
    floats.extend([0.0; 9]);
    for v in floats {
        out.extend(v.to_le_bytes());
    }
    out
}

#[test]
fn a_bz2_chunk_expanding_to_1_gib_is_refused_at_its_declaration() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros");
    let stream = std::fs::read(dir.join("zeros_1gib.bz2")).unwrap();
    assert_eq!(stream.len(), 785);
    for (size, expected) in [
        (
            1u32 << 30,
            "the bz2 chunk declares 1073741824 bytes uncompressed (785 compressed)",
        ),
        (
            1000,
            "the bz2 chunk (785 bytes compressed) expands to more than the 1000 bytes its \
             record declares",
        ),
    ] {
        let bag = [b"#ROSBAG V2.0\n".to_vec(), ros1_chunk("bz2", size, &stream)].concat();
        let (err, took) = refusal(&bag, "bomb.bag", BagFormat::Ros1Bag);
        assert!(err.starts_with("bomb.bag: at byte 13: "), "{err}");
        assert!(err.contains(expected), "{err}");
        assert!(took < QUICK, "{took:?}");
    }
}

#[test]
fn chunks_each_within_the_cap_are_refused_once_the_file_has_expanded_past_its_bound() {
    // Two zstd chunks of 40 MiB each (one skipped record of zeros), from a file of 3 KB: the
    // first is read, the second would take the file past its 64 MiB floor.
    let length = 40 << 20;
    let content = zstd_frame(&skipped_record_head(length - 9), length - 9);
    let chunk = mcap_chunk("zstd", length, &content);
    let head = mcap_head();
    let one = [head.clone(), chunk.clone(), mcap_tail()].concat();
    assert!(decode_bag(&one, "one.mcap", BagFormat::Ros2Mcap).is_ok());
    let two = [head.clone(), chunk.clone(), chunk.clone(), mcap_tail()].concat();
    let (err, took) = refusal(&two, "two.mcap", BagFormat::Ros2Mcap);
    let expected = format!(
        "two.mcap: at byte {}: the zstd chunk declares {length} bytes uncompressed ({} \
         compressed), which would bring the file's chunks to {} bytes, above the \
         {MIN_EXPANSION_BYTES}-byte limit for this {}-byte file",
        head.len() + chunk.len(),
        content.len(),
        2 * length,
        two.len()
    );
    assert!(err.starts_with(&expected), "{err}");
    assert!(took < QUICK, "{took:?}");
    assert_eq!(MAX_CHUNK_BYTES, 64 << 20);
}

#[test]
fn millions_of_one_byte_imu_messages_are_refused_at_the_first_before_any_is_kept() {
    // 2 million one-byte messages: 64 MB of records in one zstd chunk (a few hundred KB).
    let message = mcap_message(0, &[0x2a]);
    let count = (MAX_CHUNK_BYTES as usize) / message.len();
    let records = message.repeat(count);
    let compressed = ruzstd::encoding::compress_to_vec(
        records.as_slice(),
        ruzstd::encoding::CompressionLevel::Fastest,
    );
    let head = mcap_head();
    let bag = [
        head.clone(),
        mcap_chunk("zstd", records.len() as u64, &compressed),
        mcap_tail(),
    ]
    .concat();
    assert!(bag.len() < 4 << 20, "{} bytes", bag.len());
    let (err, took) = refusal(&bag, "short.mcap", BagFormat::Ros2Mcap);
    let at = head.len() as u64 + records_offset("zstd");
    assert!(
        err.starts_with(&format!(
            "short.mcap: at byte {at}: /imu message 0 (sensor_msgs/msg/Imu) is 1 bytes, \
             shorter than the 308 bytes a message of that type takes at the least"
        )),
        "{err}"
    );
    assert!(took < QUICK, "{took:?}");
}

#[test]
fn a_ros1_imu_message_one_byte_short_is_refused_naming_its_index_and_offset() {
    let connection = ros1_connection(0, "/imu", "sensor_msgs/Imu");
    let good = ros1_message(0, 1, &ros1_imu(1, [0.0; 3], [0.0, 0.0, 9.8]));
    let full = ros1_imu(2, [0.0; 3], [0.0, 0.0, 9.8]);
    // A ROS 1 Imu with an empty frame_id is 16 + 296 bytes; the reader's bound, 308, leaves
    // out the seq: cut to 307 it cannot be one.
    assert_eq!(full.len(), 312);
    let short = ros1_message(0, 2, &full[..307]);
    let prefix = [b"#ROSBAG V2.0\n".to_vec(), connection, good].concat();
    let bag = [prefix.clone(), short].concat();
    let (err, _) = refusal(&bag, "cut.bag", BagFormat::Ros1Bag);
    assert!(
        err.starts_with(&format!(
            "cut.bag: at byte {}: /imu message 1 (sensor_msgs/Imu) is 307 bytes, shorter than \
             the 308 bytes",
            prefix.len()
        )),
        "{err}"
    );
}

#[test]
fn a_ros1_message_before_its_connection_record_is_read_in_record_order() {
    // Connection 3's first message comes before its connection record (the index section of
    // a bag repeats connections at the end); the topic keeps record order.
    let bag = [
        b"#ROSBAG V2.0\n".to_vec(),
        ros1_message(3, 10, &ros1_imu(10, [0.1, 0.0, 0.0], [0.0, 0.0, 9.8])),
        ros1_connection(3, "/imu", "sensor_msgs/Imu"),
        ros1_message(3, 11, &ros1_imu(11, [0.2, 0.0, 0.0], [0.0, 0.0, 9.8])),
    ]
    .concat();
    let bag = decode_bag(&bag, "late.bag", BagFormat::Ros1Bag).unwrap();
    let series = imu_series(&bag, TopicChoice::default(), "late.bag")
        .unwrap()
        .series;
    assert_eq!(series.channels[0], vec![0.1, 0.2]);
    assert_eq!(series.time[1].as_nanos(), 11_000_000_000);
    // Without the connection record at all, the message is refused naming its offset.
    let orphan = [
        b"#ROSBAG V2.0\n".to_vec(),
        ros1_message(3, 10, &ros1_imu(10, [0.1, 0.0, 0.0], [0.0, 0.0, 9.8])),
    ]
    .concat();
    let (err, _) = refusal(&orphan, "orphan.bag", BagFormat::Ros1Bag);
    assert!(
        err.starts_with(
            "orphan.bag: at byte 13: a message of connection 3, which no connection record \
             defines"
        ),
        "{err}"
    );
}

/// The pages of tests/data/ros/static.db3 (4096 bytes each, 1-based) that are overflow pages of
/// the /blob row: after their 4-byte next-page number, the letters 'A'..'Z' in sequence.
fn blob_overflow_pages(db: &[u8]) -> Vec<usize> {
    (2..=db.len() / 4096)
        .filter(|&n| {
            let page = &db[(n - 1) * 4096..n * 4096];
            page[4..64]
                .windows(2)
                .all(|w| w[0].is_ascii_uppercase() && (w[1] - b'A') == (w[0] - b'A' + 1) % 26)
        })
        .collect()
}

#[test]
fn a_db3_overflow_page_naming_itself_is_refused_naming_the_row() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros");
    let db = std::fs::read(dir.join("static.db3")).unwrap();
    assert!(decode_bag(&db, "static.db3", BagFormat::Ros2Db3).is_ok());
    let pages = blob_overflow_pages(&db);
    // 10,000 characters of text past the local part: at least two overflow pages, chained.
    assert!(pages.len() >= 2, "{pages:?}");
    let next = |n: usize| u32::from_be_bytes(db[(n - 1) * 4096..][..4].try_into().unwrap());
    let linked = *pages.iter().find(|&&n| next(n) != 0).unwrap();
    let mut looped = db.clone();
    looped[(linked - 1) * 4096..][..4].copy_from_slice(&(linked as u32).to_be_bytes());
    let (err, took) = refusal(&looped, "loop.db3", BagFormat::Ros2Db3);
    assert!(
        err.contains(&format!(
            "byte payload reaches page {linked} a second time, after"
        )) && err.contains("(a chain that loops or is shared: a corrupt file)"),
        "{err}"
    );
    assert!(err.starts_with("loop.db3: at byte "), "{err}");
    assert!(took < QUICK, "{took:?}");
}

/// A ROS 1 serialised `sensor_msgs/Temperature` stamped `secs` of `temperature_c`.
fn ros1_temperature(secs: u32, temperature_c: f64) -> Vec<u8> {
    let mut out = [0u32.to_le_bytes(), secs.to_le_bytes(), 0u32.to_le_bytes()].concat();
    out.extend(0u32.to_le_bytes());
    out.extend(temperature_c.to_le_bytes());
    out.extend(0.0f64.to_le_bytes());
    out
}

/// A ROS 1 bag of `/imu` (connection 0) messages of angular velocity `gyro[k]` and linear
/// acceleration `accel[k]` (ROS body axes) at k + 1 s, and `/temp` (connection 1) messages of
/// `temps[k]` at k + 1 s; returns the bag and each record's offset (Imu then Temperature).
fn ros1_bag(gyro: &[[f64; 3]], accel: &[[f64; 3]], temps: &[f64]) -> (Vec<u8>, Vec<usize>) {
    let mut out = [
        b"#ROSBAG V2.0\n".to_vec(),
        ros1_connection(0, "/imu", "sensor_msgs/Imu"),
        ros1_connection(1, "/temp", "sensor_msgs/Temperature"),
    ]
    .concat();
    let mut offsets = Vec::new();
    for (k, (g, a)) in gyro.iter().zip(accel).enumerate() {
        offsets.push(out.len());
        let secs = k as u32 + 1;
        out.extend(ros1_message(0, secs, &ros1_imu(secs, *g, *a)));
    }
    for (k, t) in temps.iter().enumerate() {
        offsets.push(out.len());
        let secs = k as u32 + 1;
        out.extend(ros1_message(1, secs, &ros1_temperature(secs, *t)));
    }
    (out, offsets)
}

/// The error of [`imu_series`] on `bag` (a ROS 1 bag) named `input`.
fn extract_error(bag: &[u8], input: &str) -> String {
    let bag = decode_bag(bag, input, BagFormat::Ros1Bag).unwrap();
    match imu_series(&bag, TopicChoice::default(), input) {
        Ok(extract) => panic!("expected an error, read {} samples", extract.series.len()),
        Err(e) => e.to_string(),
    }
}

const LEVEL: [f64; 3] = [0.0, 0.0, 9.8];

#[test]
fn an_accelerometer_at_minus_1e300_is_refused_naming_the_message() {
    let (bag, offsets) = ros1_bag(&[[0.0; 3]; 3], &[LEVEL, LEVEL, [-1e300, 0.0, 9.8]], &[25.0]);
    let err = extract_error(&bag, "huge.bag");
    assert_eq!(
        err,
        format!(
            "huge.bag: at byte {}: /imu message 2: ax is -1e300 in SI, beyond the 1e15 any \
             sensor reading stays within (in FRD)",
            offsets[2]
        )
    );
}

#[test]
fn a_gyro_at_1e30_or_nan_is_refused_naming_the_message() {
    // ROS y left is FRD y right: the value changes sign.
    let (bag, offsets) = ros1_bag(&[[0.0; 3], [0.0, 1e30, 0.0]], &[LEVEL; 2], &[]);
    let err = extract_error(&bag, "fast.bag");
    assert!(
        err.starts_with(&format!(
            "fast.bag: at byte {}: /imu message 1: gy is -1e30 in SI",
            offsets[1]
        )),
        "{err}"
    );
    let (bag, _) = ros1_bag(&[[f64::NAN, 0.0, 0.0]], &[LEVEL], &[]);
    let err = extract_error(&bag, "nan.bag");
    assert!(
        err.contains("/imu message 0: gx is NaN, not a finite number"),
        "{err}"
    );
}

#[test]
fn a_temperature_in_kelvin_or_at_1e30_is_refused_naming_the_message_with_a_hint() {
    let (bag, offsets) = ros1_bag(&[[0.0; 3]; 2], &[LEVEL; 2], &[25.0, 298.15]);
    let err = extract_error(&bag, "kelvin.bag");
    assert_eq!(
        err,
        format!(
            "kelvin.bag: at byte {}: /temp message 1: temperature 298.15 °C is outside \
             -80..150 °C, the range of a sensor's temperature (in kelvin? 298.15 K is 25.00 °C)",
            offsets[3]
        )
    );
    let (bag, _) = ros1_bag(&[[0.0; 3]; 2], &[LEVEL; 2], &[1e30, 25.0]);
    let err = extract_error(&bag, "hot.bag");
    assert!(
        err.contains("/temp message 0: temperature 1000000000000000000000000000000 °C is outside")
            && !err.contains("kelvin"),
        "{err}"
    );
    let (bag, _) = ros1_bag(&[[0.0; 3]; 2], &[LEVEL; 2], &[f64::INFINITY, 25.0]);
    assert!(extract_error(&bag, "inf.bag").contains("/temp message 0: temperature inf °C"));
    // The range's ends and a NaN ("not measured", left out) are read.
    let (bag, _) = ros1_bag(&[[0.0; 3]; 3], &[LEVEL; 3], &[-80.0, f64::NAN, 150.0]);
    let bag = decode_bag(&bag, "ends.bag", BagFormat::Ros1Bag).unwrap();
    let series = imu_series(&bag, TopicChoice::default(), "ends.bag")
        .unwrap()
        .series;
    assert_eq!(series.temperature_c, Some(vec![-80.0, -80.0, 150.0]));
}

#[test]
fn the_oracle_bags_with_their_first_temperature_in_kelvin_are_refused_in_every_format() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros");
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let first = expected["temperature"][0]["temperature_c"]
        .as_f64()
        .unwrap();
    let kelvin = first + 273.15;
    // The bags whose messages are stored as they are (no compressed chunk).
    for (name, format, big_endian) in [
        ("static_none.mcap", BagFormat::Ros2Mcap, false),
        ("static_unchunked_be.mcap", BagFormat::Ros2Mcap, true),
        ("static.db3", BagFormat::Ros2Db3, false),
        ("static.bag", BagFormat::Ros1Bag, false),
    ] {
        let mut bytes = std::fs::read(dir.join(name)).unwrap();
        let (from, to) = match big_endian {
            true => (first.to_be_bytes(), kelvin.to_be_bytes()),
            false => (first.to_le_bytes(), kelvin.to_le_bytes()),
        };
        let at = bytes.windows(8).position(|w| w == from).unwrap();
        bytes[at..at + 8].copy_from_slice(&to);
        let bag = decode_bag(&bytes, name, format).unwrap();
        let choice = TopicChoice {
            imu: Some("/imu/data"),
            ..TopicChoice::default()
        };
        let err = imu_series(&bag, choice, name).unwrap_err().to_string();
        assert!(
            err.starts_with(&format!("{name}: at byte "))
                && err.contains(&format!(
                    "/imu/temperature message 0: temperature {kelvin} °C is outside -80..150 °C"
                ))
                && err.contains(&format!(
                    "(in kelvin? {kelvin} K is {:.2} °C)",
                    kelvin - 273.15
                )),
            "{name}: {err}"
        );
    }
}

#[test]
fn a_topic_without_messages_is_listed_but_never_a_candidate() {
    // A second Imu connection and a Temperature connection, neither used.
    let (mut bag, _) = ros1_bag(&[[0.0; 3]; 2], &[LEVEL; 2], &[]);
    bag.extend(ros1_connection(5, "/imu/unused", "sensor_msgs/Imu"));
    bag.extend(ros1_connection(
        6,
        "/temp/unused",
        "sensor_msgs/Temperature",
    ));
    let bag = decode_bag(&bag, "quiet.bag", BagFormat::Ros1Bag).unwrap();
    let extract = imu_series(&bag, TopicChoice::default(), "quiet.bag").unwrap();
    assert_eq!(extract.topic, "/imu");
    assert_eq!(extract.series.len(), 2);
    assert_eq!(extract.temperature_topic, None);
    // Asked for by name, the empty topic is named as empty.
    let choice = TopicChoice {
        imu: Some("/imu/unused"),
        ..TopicChoice::default()
    };
    let err = imu_series(&bag, choice, "quiet.bag")
        .unwrap_err()
        .to_string();
    assert_eq!(err, "quiet.bag: topic /imu/unused has no message");
    // With no topic holding messages, the error lists the empty ones with their counts.
    let (empty, _) = ros1_bag(&[], &[], &[]);
    let empty = decode_bag(&empty, "empty.bag", BagFormat::Ros1Bag).unwrap();
    let err = imu_series(&empty, TopicChoice::default(), "empty.bag")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains(
            "no sensor_msgs/msg/Imu topic in the bag (topics: /imu (sensor_msgs/Imu, 0 messages)"
        ),
        "{err}"
    );
}

/// Pieces of `piece_len` samples, the stamp lags kept when `lags`, the GNSS messages not.
fn options(piece_len: usize, lags: bool) -> thermonav_io::ros::extract::StreamOptions {
    thermonav_io::ros::extract::StreamOptions {
        piece_len,
        stamp_lags: lags,
        gnss: false,
    }
}

/// The GNSS fixes of `bag` read whole.
fn gnss_fixes_of(
    bag: &thermonav_io::ros::Bag,
    name: &str,
) -> thermonav_io::ros::extract::GnssExtract {
    thermonav_io::ros::extract::gnss_fixes(bag, None, name).unwrap()
}

#[test]
fn a_bag_streamed_in_pieces_gives_the_series_read_whole() {
    use thermonav_io::ros::extract::stream_imu_series;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros");
    for name in [
        "static_none.mcap",
        "static_zstd.mcap",
        "static_lz4.mcap",
        "static_unchunked_be.mcap",
        "static_10hz.mcap",
        "static.bag",
        "static_lz4.bag",
        "static_bz2.bag",
    ] {
        let path = dir.join(name);
        let choice = TopicChoice {
            imu: (name != "static_10hz.mcap").then_some("/imu/data"),
            ..TopicChoice::default()
        };
        // The bag read whole from its bytes, by the same decoder over a slice.
        let bytes = std::fs::read(&path).unwrap();
        let format = BagFormat::detect(&bytes).unwrap();
        let whole_bag = decode_bag(&bytes, name, format).unwrap();
        let whole = imu_series(&whole_bag, choice, name).unwrap();
        let mut pieces = Vec::new();
        let streamed = stream_imu_series(&path, choice, options(7, true), &mut |piece| {
            pieces.push(piece);
            Ok(())
        })
        .unwrap();
        assert_eq!(streamed.samples, whole.series.len(), "{name}");
        assert_eq!(streamed.topic, whole.topic);
        assert_eq!(streamed.temperature_topic, whole.temperature_topic);
        assert_eq!(streamed.stamp_lag_s, whole.stamp_lag_s, "{name}");
        let counts = |bag: &thermonav_io::ros::Bag| {
            let topics = bag.topics.iter();
            topics
                .map(|t| (t.name.clone(), t.count))
                .collect::<Vec<_>>()
        };
        assert_eq!(counts(&streamed.bag), counts(&whole_bag), "{name}");
        // Without GNSS asked for, no NavSatFix message is kept (only counted).
        let kept = |bag: &thermonav_io::ros::Bag, topic: &str| {
            let found = bag.topics.iter().find(|t| t.name == topic);
            found.map(|t| t.messages.len())
        };
        if name != "static_10hz.mcap" {
            assert_eq!(kept(&streamed.bag, "/gnss/fix"), Some(0), "{name}");
            assert_eq!(kept(&whole_bag, "/gnss/fix"), Some(8), "{name}");
        }
        let (extract, bag) = thermonav_io::ros::extract::stream_imu_extract(&path, choice).unwrap();
        assert_eq!(extract, whole, "{name}");
        if name != "static_10hz.mcap" {
            let fixes = thermonav_io::ros::extract::gnss_fixes(&bag, None, name).unwrap();
            assert_eq!(fixes, gnss_fixes_of(&whole_bag, name), "{name}");
        }
        assert!(pieces.iter().all(|p| p.len() <= 7 && !p.is_empty()));
        let (mut times, mut channels) = (Vec::new(), vec![Vec::new(); 6]);
        let mut temperatures = Vec::new();
        for piece in &pieces {
            times.extend_from_slice(&piece.time);
            for (c, values) in channels.iter_mut().enumerate() {
                values.extend_from_slice(&piece.channels[c]);
            }
            temperatures.extend(piece.temperature_c.clone().unwrap());
        }
        assert_eq!(times, whole.series.time, "{name}");
        for (c, values) in channels.iter().enumerate() {
            assert_eq!(
                values[..],
                whole.series.channels[c][..],
                "{name} channel {c}"
            );
        }
        assert_eq!(Some(temperatures), whole.series.temperature_c, "{name}");
    }
}

#[test]
fn a_streamed_bag_refuses_a_bad_sample_naming_it_and_stops_at_the_callers_error() {
    use thermonav_io::ros::extract::stream_imu_series;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros");
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let ax = expected["imu"][20]["accel"][0].as_f64().unwrap();
    let mut bytes = std::fs::read(dir.join("static_none.mcap")).unwrap();
    let at = bytes
        .windows(8)
        .position(|w| w == ax.to_le_bytes())
        .unwrap();
    bytes[at..at + 8].copy_from_slice(&(-1e300f64).to_le_bytes());
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("huge.mcap");
    std::fs::write(&path, bytes).unwrap();
    let choice = TopicChoice {
        imu: Some("/imu/data"),
        ..TopicChoice::default()
    };
    let mut delivered = 0;
    let err = stream_imu_series(&path, choice, options(8, false), &mut |piece| {
        delivered += piece.len();
        Ok(())
    })
    .unwrap_err()
    .to_string();
    assert!(
        err.starts_with(&format!("{}: at byte ", path.display()))
            && err.contains("/imu/data message 20: ax is -1e300 in SI"),
        "{err}"
    );
    assert_eq!(delivered, 16, "the pieces before message 20");
    // An error of the caller stops the reading at once.
    let mut calls = 0;
    let path = dir.join("static_none.mcap");
    let err = stream_imu_series(&path, choice, options(8, false), &mut |_| {
        calls += 1;
        Err(thermonav_io::ReadError::new(
            "caller",
            None,
            thermonav_io::ReadErrorKind::Unusable("enough".to_string()),
        ))
    })
    .unwrap_err();
    assert_eq!((calls, err.to_string()), (1, "caller: enough".to_string()));
}

#[test]
fn a_ros1_record_header_longer_than_16_mib_is_refused_before_it_is_read() {
    let mut bag = b"#ROSBAG V2.0\n".to_vec();
    bag.extend(((16u32 << 20) + 1).to_le_bytes());
    bag.extend([0u8; 64]);
    let (err, _) = refusal(&bag, "long.bag", BagFormat::Ros1Bag);
    assert_eq!(
        err,
        "long.bag: at byte 17: expected a record header of 16777217 bytes: above the 16777216 \
         bytes any recorder writes (a corrupt length field)"
    );
}

#[test]
fn a_streamed_bag_refuses_a_temperature_in_kelvin_naming_the_message_as_read_whole() {
    use thermonav_io::ros::extract::stream_imu_series;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ros");
    let expected: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("expected.json")).unwrap()).unwrap();
    let first = expected["temperature"][3]["temperature_c"]
        .as_f64()
        .unwrap();
    let tmp = tempfile::tempdir().unwrap();
    for name in ["static_none.mcap", "static.bag"] {
        let mut bytes = std::fs::read(dir.join(name)).unwrap();
        let at = bytes
            .windows(8)
            .position(|w| w == first.to_le_bytes())
            .unwrap();
        bytes[at..at + 8].copy_from_slice(&298.15f64.to_le_bytes());
        let path = tmp.path().join(name);
        std::fs::write(&path, &bytes).unwrap();
        let choice = TopicChoice {
            imu: Some("/imu/data"),
            ..TopicChoice::default()
        };
        let streamed = stream_imu_series(&path, choice, options(8, false), &mut |_| Ok(()))
            .unwrap_err()
            .to_string();
        let format = BagFormat::detect(&bytes).unwrap();
        let bag = decode_bag(&bytes, &path.display().to_string(), format).unwrap();
        let whole = imu_series(&bag, choice, &path.display().to_string())
            .unwrap_err()
            .to_string();
        assert_eq!(streamed, whole, "{name}");
        assert!(
            streamed.contains("/imu/temperature message 3: temperature 298.15 °C")
                && streamed.contains("in kelvin?"),
            "{streamed}"
        );
    }
}

// Issue 37, a minor point: a zstd chunk that is not a zstd frame is refused in words, not with
// the decoder's debug text (`MagicNumberReadError(Error { .. })`).
#[test]
fn a_zstd_chunk_that_is_not_a_zstd_frame_is_refused_in_words() {
    let bag = [
        mcap_head(),
        mcap_chunk("zstd", 16, b"not a zstd frame"),
        mcap_tail(),
    ]
    .concat();
    let (err, _) = refusal(&bag, "notzstd.mcap", BagFormat::Ros2Mcap);
    assert!(
        err.contains("notzstd.mcap") && err.contains("the zstd chunk does not decompress"),
        "{err}"
    );
    assert!(
        !err.contains("Error {") && !err.contains("ReadError("),
        "{err}"
    );
}
