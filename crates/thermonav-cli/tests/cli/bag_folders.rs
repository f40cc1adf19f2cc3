//! ROS 2 bag folders (`metadata.yaml` and the storage files it lists, as `ros2 bag record`
//! writes them) read by every command that reads a bag, and a bag's topics chosen with
//! `--topic` on each of them (issue 38, rows 1 and 2). The MCAP files are written here record by
//! record after the MCAP specification (unchunked, CDR little-endian, as rosbag2's mcap storage
//! writes them without compression); the db3 file is the io crate's oracle bag.

use crate::{Normal, arg, files_in, outcome, thermonav};
use std::ops::Range;
use std::path::{Path, PathBuf};
use thermonav_io::{Strictness, read_imu_file};

/// `thermonav ARGS`: status, stdout, stderr.
fn run(args: &[&str]) -> (i32, String, String) {
    outcome(&thermonav(args))
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

/// An MCAP file being written: its magic, Header, and a schema and a CDR channel per topic.
struct Mcap(Vec<u8>);

impl Mcap {
    /// Topic `k` of `topics` (name, type) is schema and channel `k + 1`.
    fn new(topics: &[(&str, &str)]) -> Self {
        let mut out = b"\x89MCAP0\r\n".to_vec();
        let mut header = Vec::new();
        string(&mut header, "ros2");
        string(&mut header, "thermonav test");
        record(&mut out, 0x01, &header);
        for (k, (topic, type_name)) in topics.iter().enumerate() {
            let id = (k as u16 + 1).to_le_bytes();
            let mut schema = id.to_vec();
            string(&mut schema, type_name);
            string(&mut schema, "ros2msg");
            string(&mut schema, "");
            record(&mut out, 0x03, &schema);
            let mut channel = [id, id].concat();
            string(&mut channel, topic);
            string(&mut channel, "cdr");
            channel.extend(0u32.to_le_bytes());
            record(&mut out, 0x04, &channel);
        }
        Self(out)
    }

    /// A message on `channel`, logged 2 ms after `stamp_ns`.
    fn message(&mut self, channel: u16, sequence: u32, stamp_ns: u64, data: &[u8]) {
        let mut body = channel.to_le_bytes().to_vec();
        body.extend(sequence.to_le_bytes());
        body.extend((stamp_ns + 2_000_000).to_le_bytes());
        body.extend((stamp_ns + 2_000_000).to_le_bytes());
        body.extend(data);
        record(&mut self.0, 0x05, &body);
    }

    /// Data End, Footer and the closing magic.
    fn finish(mut self) -> Vec<u8> {
        record(&mut self.0, 0x0F, &0u32.to_le_bytes());
        record(&mut self.0, 0x02, &[0u8; 20]);
        self.0.extend(b"\x89MCAP0\r\n");
        self.0
    }
}

/// A CDR (little-endian) `std_msgs/Header` stamped `stamp_ns` with an empty frame id, padded
/// to the 8-byte alignment of the float64 that follow.
fn cdr_header(stamp_ns: u64) -> Vec<u8> {
    let mut out = vec![0, 1, 0, 0];
    out.extend(((stamp_ns / 1_000_000_000) as i32).to_le_bytes());
    out.extend(((stamp_ns % 1_000_000_000) as u32).to_le_bytes());
    out.extend(1u32.to_le_bytes());
    out.extend([0, 0, 0, 0]);
    out
}

/// A CDR `sensor_msgs/Imu` (ROS body axes, z up), no orientation.
fn cdr_imu(stamp_ns: u64, gyro: [f64; 3], accel: [f64; 3]) -> Vec<u8> {
    let mut out = cdr_header(stamp_ns);
    let fields = [
        [0.0; 4].as_slice(),
        &[0.0; 9],
        &gyro,
        &[0.0; 9],
        &accel,
        &[0.0; 9],
    ];
    out.extend(fields.concat().iter().flat_map(|v| v.to_le_bytes()));
    out
}

/// A CDR `sensor_msgs/Temperature`.
fn cdr_temperature(stamp_ns: u64, temperature_c: f64) -> Vec<u8> {
    let mut out = cdr_header(stamp_ns);
    out.extend(temperature_c.to_le_bytes());
    out.extend(0f64.to_le_bytes());
    out
}

/// First header stamp, ns.
const T0_NS: u64 = 1_700_000_000_000_000_000;
/// Sample period of the IMU, ns (100 Hz).
const PERIOD_NS: u64 = 10_000_000;

/// Sample `k` of a static IMU (white noise, level, z up) of seed `seed`: (gyro, accel).
fn static_sample(noise: &mut Normal) -> ([f64; 3], [f64; 3]) {
    let gyro = [0; 3].map(|_| 1e-3 * noise.sample());
    let accel = [0.0, 0.0, 9.80665].map(|g| g + 2e-2 * noise.sample());
    (gyro, accel)
}

/// An MCAP bag of the static IMU's samples `samples` (100 Hz) on `/imu/data` with a 25 °C
/// temperature every 100th sample on `/imu/temperature`, and a second Imu topic `/imu/raw`
/// holding the first `raw` samples with twice the gyro noise (its channel declared even when
/// it holds no message).
fn static_mcap(samples: Range<u64>, raw: u64) -> Vec<u8> {
    let imu = "sensor_msgs/msg/Imu";
    let topics = [
        ("/imu/data", imu),
        ("/imu/temperature", "sensor_msgs/msg/Temperature"),
        ("/imu/raw", imu),
    ];
    let mut bag = Mcap::new(&topics);
    let mut noise = Normal(0x9E37_79B9_7F4A_7C15 ^ samples.start);
    for k in samples.clone() {
        let stamp = T0_NS + k * PERIOD_NS;
        let (gyro, accel) = static_sample(&mut noise);
        bag.message(1, k as u32, stamp, &cdr_imu(stamp, gyro, accel));
        if k % 100 == 0 {
            bag.message(2, k as u32, stamp, &cdr_temperature(stamp, 25.0));
        }
        if k - samples.start < raw {
            bag.message(
                3,
                k as u32,
                stamp,
                &cdr_imu(stamp, gyro.map(|g| 2.0 * g), accel),
            );
        }
    }
    bag.finish()
}

/// The metadata.yaml rosbag2 writes for a bag of `storage` whose files are `files` (in the
/// order recorded), with the keys a reader must skip: topics, QoS strings, file entries.
fn metadata_yaml(storage: &str, files: &[&str]) -> String {
    let paths: String = files.iter().map(|f| format!("    - {f}\n")).collect();
    let entries: String = files
        .iter()
        .map(|f| format!("    - path: {f}\n      message_count: 1\n"))
        .collect();
    format!(
        "rosbag2_bagfile_information:
  version: 5
  storage_identifier: {storage}
  duration:
    nanoseconds: 300000000000
  topics_with_message_count:
    - topic_metadata:
        name: /imu/data
        type: sensor_msgs/msg/Imu
        serialization_format: cdr
        offered_qos_profiles: \"- history: 3\\n  depth: 0\\n  reliability: 1\\n\"
      message_count: 30000
  compression_format: \"\"
  compression_mode: \"\"
  relative_file_paths:
{paths}  files:
{entries}"
    )
}

/// A ROS 2 bag folder `dir/name` of `files` (name, bytes), listed in that order.
fn bag_folder(dir: &Path, name: &str, storage: &str, files: &[(&str, Vec<u8>)]) -> PathBuf {
    let folder = dir.join(name);
    std::fs::create_dir(&folder).unwrap();
    for (file, bytes) in files {
        std::fs::write(folder.join(file), bytes).unwrap();
    }
    let names: Vec<&str> = files.iter().map(|(f, _)| *f).collect();
    std::fs::write(folder.join("metadata.yaml"), metadata_yaml(storage, &names)).unwrap();
    folder
}

/// The io crate's oracle bag `name`.
fn oracle_bag(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../thermonav-io/tests/data/ros")
        .join(name)
}

#[test]
fn characterize_reads_a_ros2_bag_folder_through_its_metadata_every_file_in_order() {
    let dir = tempfile::tempdir().unwrap();
    // Split in two as `ros2 bag record --max-bag-duration` does; listed first is the file
    // whose name sorts last, so that the order can only come from metadata.yaml.
    let files = [
        ("run_b_0.mcap", static_mcap(0..15_000, 0)),
        ("run_a_1.mcap", static_mcap(15_000..30_000, 0)),
    ];
    let folder = bag_folder(dir.path(), "run", "mcap", &files);
    let bank = dir.path().join("bank.json");
    let (status, _, stderr) = run(&["characterize", arg(&folder), "--out", arg(&bank)]);
    assert_eq!(status, 0, "{stderr}");
    let bank: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&bank).unwrap()).unwrap();
    assert_eq!(bank["entries"][0]["temperature_c"], 25.0);
    assert_eq!(bank["entries"][0]["source"], "run");
    // Every message of both files, in order: what convert writes of the folder.
    let csv = dir.path().join("imu.csv");
    let (status, _, stderr) = run(&["convert", arg(&folder), "--out", arg(&csv)]);
    assert_eq!(status, 0, "{stderr}");
    let series = read_imu_file(&csv, Strictness::Strict).unwrap();
    assert_eq!(series.len(), 30_000);
    let stamps: Vec<i64> = series.time.iter().map(|t| t.as_nanos()).collect();
    assert_eq!(stamps[0], T0_NS as i64);
    assert_eq!(stamps[29_999], (T0_NS + 29_999 * PERIOD_NS) as i64);
    assert!(stamps.windows(2).all(|w| w[1] - w[0] == PERIOD_NS as i64));
    // Streamed record by record, the folder gives the bank it gives in memory.
    let streamed = dir.path().join("streamed.json");
    let args = [
        "characterize",
        arg(&folder),
        "--reading",
        "streaming",
        "--out",
        arg(&streamed),
    ];
    let (status, _, stderr) = run(&args);
    assert_eq!(status, 0, "{stderr}");
    let streamed: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&streamed).unwrap()).unwrap();
    for channel in ["gx", "az"] {
        let ar = |b: &serde_json::Value| b["entries"][0]["channels"][channel]["ar"].clone();
        assert_eq!(ar(&bank), ar(&streamed), "{channel}");
    }
}

#[test]
fn a_folder_without_metadata_is_refused_naming_it_and_the_bag_files_it_holds() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("copied");
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(folder.join("copied_0.mcap"), static_mcap(0..10, 0)).unwrap();
    let bank = dir.path().join("bank.json");
    for command in [
        vec!["characterize", arg(&folder), "--out", arg(&bank)],
        vec!["allan", arg(&folder)],
        vec!["gmwm", arg(&folder)],
    ] {
        let (status, _, stderr) = run(&command);
        assert_eq!(status, 1, "{command:?}: {stderr}");
        assert!(
            stderr.contains(&format!(
                "{}: a folder without metadata.yaml: expected a ROS 2 bag folder",
                folder.display()
            )),
            "{stderr}"
        );
        assert!(stderr.contains("it holds copied_0.mcap"), "{stderr}");
        assert!(!stderr.contains("os error"), "{stderr}");
    }
    assert!(!bank.exists());
    // A metadata.yaml that lists a file that is not there names it.
    std::fs::write(
        folder.join("metadata.yaml"),
        metadata_yaml("mcap", &["copied_0.mcap", "copied_1.mcap"]),
    )
    .unwrap();
    let (status, _, stderr) = run(&["allan", arg(&folder)]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains(
            "metadata.yaml: relative_file_paths lists copied_1.mcap, which is not a file"
        ),
        "{stderr}"
    );
}

#[test]
fn a_db3_bag_folder_reads_as_its_file_and_its_next_file_must_go_on_in_time() {
    let dir = tempfile::tempdir().unwrap();
    let db3 = std::fs::read(oracle_bag("static.db3")).unwrap();
    let folder = bag_folder(dir.path(), "one", "sqlite3", &[("one_0.db3", db3.clone())]);
    let (from_folder, from_file) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
    let (status, _, stderr) = run(&["convert", arg(&folder), "--out", arg(&from_folder)]);
    assert_eq!(status, 0, "{stderr}");
    let file = oracle_bag("static.db3");
    assert_eq!(run(&["convert", arg(&file), "--out", arg(&from_file)]).0, 0);
    assert_eq!(
        std::fs::read_to_string(&from_folder).unwrap(),
        std::fs::read_to_string(&from_file).unwrap()
    );
    let (status, from_bag, stderr) = run(&["allan", arg(&folder), "--json"]);
    assert_eq!(status, 0, "{stderr}");
    assert!(from_bag.contains("\"channels\""), "{from_bag}");
    // The same recording twice: the second file's first stamp is not after the first's last.
    let files = [("twice_0.db3", db3.clone()), ("twice_1.db3", db3)];
    let twice = bag_folder(dir.path(), "twice", "sqlite3", &files);
    let (status, _, stderr) = run(&["allan", arg(&twice)]);
    assert_eq!(status, 1, "{stderr}");
    let second = twice.join("twice_1.db3");
    assert!(
        stderr.contains(&format!("{}: at byte", second.display()))
            && stderr.contains("/imu/data message 150 is stamped"),
        "{stderr}"
    );
}

#[test]
fn an_imu_topic_without_messages_is_never_a_candidate() {
    // 60 000 messages on /imu/data, and /imu/raw declared without a message.
    let dir = tempfile::tempdir().unwrap();
    let bag = dir.path().join("bag.mcap");
    std::fs::write(&bag, static_mcap(0..60_000, 0)).unwrap();
    let bank = dir.path().join("bank.json");
    let (status, _, stderr) = run(&["characterize", arg(&bag), "--out", arg(&bank)]);
    assert_eq!(status, 0, "{stderr}");
    assert!(!stderr.contains("--topic"), "{stderr}");
    let text = std::fs::read_to_string(&bank).unwrap();
    assert!(text.contains("\"temperature_c\": 25.0"), "{text}");
}

#[test]
fn topic_chooses_the_imu_of_a_bag_on_every_command_that_reads_one() {
    let dir = tempfile::tempdir().unwrap();
    let bag = dir.path().join("bag.mcap");
    std::fs::write(&bag, static_mcap(0..30_000, 30_000)).unwrap();
    let bank = dir.path().join("bank.json");
    let (status, _, stderr) = run(&["characterize", arg(&bag), "--out", arg(&bank)]);
    assert_eq!(status, 1, "{stderr}");
    assert!(
        stderr.contains("/imu/data (sensor_msgs/msg/Imu, 30000 messages), /imu/raw (sensor_msgs/msg/Imu, 30000 messages); choose one with --topic"),
        "{stderr}"
    );
    let characterize = ["characterize", arg(&bag), "--out", arg(&bank)];
    for (command, topic) in [
        (characterize.to_vec(), "/imu/data"),
        (vec!["allan", arg(&bag), "--json"], "/imu/raw"),
        (vec!["gmwm", arg(&bag), "--json"], "/imu/data"),
    ] {
        let mut args = command.clone();
        args.extend(["--topic", topic, "--temperature-topic", "/imu/temperature"]);
        let (status, _, stderr) = run(&args);
        assert_eq!(status, 0, "{args:?}: {stderr}");
    }
    assert!(bank.exists());
    // /imu/raw carries twice the gyro noise: allan reads the topic it is given.
    let (_, raw, _) = run(&["allan", arg(&bag), "--topic", "/imu/raw", "--json"]);
    let (_, data, _) = run(&["allan", arg(&bag), "--topic", "/imu/data", "--json"]);
    assert_ne!(raw, data);
    // Asked of a file that is no bag, the option is refused as a usage error.
    let csv = dir.path().join("imu.csv");
    let args = [
        "convert",
        arg(&bag),
        "--topic",
        "/imu/data",
        "--out",
        arg(&csv),
    ];
    assert_eq!(run(&args).0, 0);
    let (status, _, stderr) = run(&["allan", arg(&csv), "--topic", "/imu/data"]);
    assert_eq!(status, 2, "{stderr}");
    assert!(
        stderr.contains("--topic and --temperature-topic choose the topics of a ROS bag"),
        "{stderr}"
    );
    assert_eq!(
        files_in(dir.path()),
        ["bag.mcap", "bank.json", "imu.csv", "imu.csv.json"]
    );
}
