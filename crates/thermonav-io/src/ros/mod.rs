//! ROS bags: ROS 2 MCAP ([`mcap`]), ROS 2 SQLite `.db3` storage ([`db3`], over the minimal
//! SQLite reader [`sqlite`]) and ROS 1 bag v2.0 ([`ros1`]), read from the formats' public
//! descriptions (mcap.dev specification, sqlite.org "Database File Format", ROS wiki "Bags/Format/2.0").
//!
//! Each reader gives one [`Bag`]: its topics with their type, serialisation and message count,
//! and the bytes of the messages of the types [`messages`] decodes (`sensor_msgs/Imu`,
//! `NavSatFix`, `Temperature`, `geometry_msgs/TwistStamped`); the messages of other types are
//! counted and dropped, so memory follows the data that is used. The MCAP and ROS 1 readers
//! read a file record by record ([`source::Source`], chunks through their decompressor as they
//! come) into any [`Sink`], so that [`extract::stream_imu_series`] can decode a long bag's IMU
//! into pieces without keeping its messages; a db3 (SQLite pages) is read whole. Decompression
//! is bounded ([`bytes::chunk_bounds`]): a chunk at most 64 MiB, a file's chunks together at
//! most 100 times its size (64 MiB at least). [`extract`] turns a topic into
//! thermonav's series: the sample time is the message's **header stamp**, not the record (log)
//! time, and the ROS body axes (REP 103: x forward, y left, z up) become FRD.
//!
//! A ROS 2 bag folder (`metadata.yaml` and its storage files, as `ros2 bag record` writes it,
//! [`folder`]) reads as one bag: the files one after the other, in the order the metadata lists
//! them, into the same [`Sink`], so topics of the same name and type are one topic and header
//! stamps must go on increasing from one file to the next.
//!
//! Every error is a [`ReadError`] naming the file and the byte offset (of the record, or of the
//! chunk record for what lies inside a compressed chunk) and what was expected there. No length
//! field is trusted: each is checked against the bytes that are left before anything is taken.

pub mod bytes;
pub mod db3;
pub mod extract;
pub mod folder;
pub mod mcap;
pub mod messages;
pub mod ros1;
pub mod source;
pub mod sqlite;

use crate::error::{ReadError, ReadErrorKind};
use messages::{Encoding, MessageType};
use serde::Serialize;
use std::path::Path;

/// The container format of a bag.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BagFormat {
    /// ROS 2 bag in MCAP storage (`.mcap`).
    Ros2Mcap,
    /// ROS 2 bag in SQLite storage (`.db3`).
    Ros2Db3,
    /// ROS 1 bag, format version 2.0 (`.bag`).
    Ros1Bag,
}

impl BagFormat {
    /// The format whose magic bytes `head` (the file's first bytes) starts with.
    pub fn detect(head: &[u8]) -> Option<Self> {
        if head.starts_with(&mcap::MAGIC) {
            Some(Self::Ros2Mcap)
        } else if head.starts_with(sqlite::MAGIC) {
            Some(Self::Ros2Db3)
        } else if head.starts_with(ros1::MAGIC) {
            Some(Self::Ros1Bag)
        } else {
            None
        }
    }

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Ros2Mcap => "ros2-mcap",
            Self::Ros2Db3 => "ros2-db3",
            Self::Ros1Bag => "ros1-bag",
        }
    }
}

/// One message kept from a bag.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Message {
    /// Record (log) time, ns: when the recorder received it.
    pub log_time_ns: i64,
    /// File offset of the message's record (of its chunk record when compressed).
    pub offset: u64,
    /// The serialised message.
    pub data: Vec<u8>,
}

/// One topic of a bag.
#[derive(Debug, Clone, PartialEq)]
pub struct Topic {
    /// Topic name (`/imu/data`).
    pub name: String,
    /// Message type as the bag names it (`sensor_msgs/msg/Imu` or `sensor_msgs/Imu`).
    pub type_name: String,
    /// The type, when this module decodes it.
    pub message_type: Option<MessageType>,
    /// Serialisation of its messages.
    pub encoding: Encoding,
    /// Number of messages in the bag.
    pub count: usize,
    /// The messages, in record order, when the type is decoded (else empty).
    pub messages: Vec<Message>,
}

/// A bag's topics.
#[derive(Debug, Clone, PartialEq)]
pub struct Bag {
    /// The container format.
    pub format: BagFormat,
    /// The topics, in the order the file defines them.
    pub topics: Vec<Topic>,
}

impl Bag {
    /// A new empty bag of `format`.
    fn new(format: BagFormat) -> Self {
        Self {
            format,
            topics: Vec::new(),
        }
    }

    /// Index of the topic `name` of `type_name`, added (with `encoding`) when new.
    fn find_or_add_topic(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize {
        if let Some(k) = self
            .topics
            .iter()
            .position(|t| t.name == name && t.type_name == type_name && t.encoding == encoding)
        {
            return k;
        }
        let decoded = !matches!(encoding, Encoding::Other(_));
        self.topics.push(Topic {
            name: name.to_string(),
            type_name: type_name.to_string(),
            message_type: MessageType::of(type_name).filter(|_| decoded),
            encoding,
            count: 0,
            messages: Vec::new(),
        });
        self.topics.len() - 1
    }

    /// Adds a message to topic `k`, keeping its bytes when the type is decoded.
    ///
    /// # Errors
    /// A message of a decoded type shorter than the type's [`MessageType::min_bytes`] (a corrupt
    /// bag): refused here, before its bytes are kept, naming the topic, the message's index in
    /// it and the file offset `offset` of its record, so that memory follows real messages.
    fn keep(
        &mut self,
        k: usize,
        log_time_ns: i64,
        offset: u64,
        data: &[u8],
        input: &str,
    ) -> Result<(), ReadError> {
        let topic = &mut self.topics[k];
        let index = topic.count;
        topic.count += 1;
        let Some(kind) = topic.message_type else {
            return Ok(());
        };
        if data.len() < kind.min_bytes() {
            return Err(bytes::at(
                input,
                offset,
                format_args!(
                    "{} message {index} ({}) is {} bytes, shorter than the {} bytes a message \
                     of that type takes at the least (a corrupt bag, or a message of another \
                     type)",
                    topic.name,
                    topic.type_name,
                    data.len(),
                    kind.min_bytes()
                ),
            ));
        }
        topic.messages.push(Message {
            log_time_ns,
            offset,
            data: data.to_vec(),
        });
        Ok(())
    }

    /// Counts a message of topic `k` without keeping it.
    fn count(&mut self, k: usize) {
        self.topics[k].count += 1;
    }

    /// Total messages of all topics.
    pub fn message_count(&self) -> usize {
        self.topics.iter().map(|t| t.count).sum()
    }
}

/// Where a reader puts what it reads: the topics as they are defined, and each message, whose
/// bytes are read only when [`Sink::wants`] them (else it is only counted).
pub trait Sink {
    /// Index of the topic `name` of `type_name` in `encoding`, added when new.
    fn topic_index(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize;
    /// Whether the bytes of topic `k`'s messages are wanted.
    fn wants(&self, k: usize) -> bool;
    /// A message of topic `k` (wanted), recorded at `log_time_ns`, its record at file offset
    /// `offset` of `input`.
    ///
    /// # Errors
    /// The sink's refusal of the message.
    fn push(
        &mut self,
        k: usize,
        log_time_ns: i64,
        offset: u64,
        data: &[u8],
        input: &str,
    ) -> Result<(), ReadError>;
    /// A message of topic `k` not wanted: counted.
    fn count(&mut self, k: usize);
}

impl Sink for Bag {
    fn topic_index(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize {
        self.find_or_add_topic(name, type_name, encoding)
    }

    fn wants(&self, k: usize) -> bool {
        self.topics[k].message_type.is_some()
    }

    fn push(
        &mut self,
        k: usize,
        log_time_ns: i64,
        offset: u64,
        data: &[u8],
        input: &str,
    ) -> Result<(), ReadError> {
        self.keep(k, log_time_ns, offset, data, input)
    }

    fn count(&mut self, k: usize) {
        Bag::count(self, k);
    }
}

/// A record time in ns (u64 in the files) as i64.
fn log_time(ns: u64, at: &bytes::Cursor<'_>) -> Result<i64, ReadError> {
    i64::try_from(ns).map_err(|_| at.error(format_args!("record time {ns} ns is beyond 2262")))
}

/// Reads a bag in `format`, or the one its magic bytes tell when `None`. An MCAP file or a
/// ROS 1 bag is read record by record through a buffer (memory follows the messages kept, not
/// the file); a db3 and a gzip-compressed file are read whole. A ROS 2 bag folder is read in
/// its metadata's storage (`format` is not used), file after file ([`read_bag_into`]).
///
/// # Errors
/// [`ReadErrorKind::Open`]/[`ReadErrorKind::Read`]; a file of no bag format; a folder that is
/// no bag folder ([`folder::read_bag_folder`]); those of the format's reader.
pub fn read_bag_file(path: impl AsRef<Path>, format: Option<BagFormat>) -> Result<Bag, ReadError> {
    let path = path.as_ref();
    let input = path.display().to_string();
    if path.is_dir() {
        let format = folder::read_bag_folder(path)?.format;
        let mut bag = Bag::new(format);
        read_bag_into(path, format, &mut bag)?;
        return Ok(bag);
    }
    // A gzip-compressed bag is read whole, under the gzip reader's expansion bound.
    let streamed = !crate::is_compressed(path);
    let format = match (format, streamed) {
        (Some(f), _) => f,
        (None, true) => detect_file(path, &input)?,
        (None, false) => return read_whole_bag(path, None),
    };
    match (format, streamed) {
        (BagFormat::Ros2Mcap | BagFormat::Ros1Bag, true) => {
            let mut bag = Bag::new(format);
            read_bag_into(path, format, &mut bag)?;
            Ok(bag)
        }
        _ => read_whole_bag(path, Some(format)),
    }
}

/// Reads the bag at `path` whole, in `format` or the one its magic bytes tell.
fn read_whole_bag(path: &Path, format: Option<BagFormat>) -> Result<Bag, ReadError> {
    let (bytes, input) = crate::read_whole_file(path)?;
    let format = match format {
        Some(f) => f,
        None => BagFormat::detect(&bytes).ok_or_else(|| not_a_bag(&input))?,
    };
    if format == BagFormat::Ros2Db3 {
        db3::refuse_pending_wal(path, &input)?;
    }
    decode_bag(&bytes, &input, format)
}

/// Reads the bag at `path` into `sink`: an MCAP file or ROS 1 bag record by record; a db3
/// whole (its rows then go into `sink` as they are decoded); a ROS 2 bag folder file by file,
/// in the order its metadata lists them, each in the folder's storage (`format` is not used).
///
/// # Errors
/// [`ReadErrorKind::Open`]/[`ReadErrorKind::Read`]; those of [`folder::read_bag_folder`] and
/// of the format's reader, naming the storage file.
pub fn read_bag_into<S: Sink>(
    path: &Path,
    format: BagFormat,
    sink: &mut S,
) -> Result<(), ReadError> {
    if !path.is_dir() {
        return read_storage_into(path, format, sink);
    }
    let folder = folder::read_bag_folder(path)?;
    for file in &folder.files {
        read_storage_into(file, folder.format, sink)?;
    }
    Ok(())
}

/// Reads the bag file at `path`, in `format`, into `sink`.
fn read_storage_into<S: Sink>(
    path: &Path,
    format: BagFormat,
    sink: &mut S,
) -> Result<(), ReadError> {
    let input = path.display().to_string();
    if format == BagFormat::Ros2Db3 {
        let (bytes, input) = crate::read_whole_file(path)?;
        db3::refuse_pending_wal(path, &input)?;
        return db3::read_db3(&bytes, &input, sink);
    }
    let file = crate::open_input(path).map_err(|e| open_error(&input, e))?;
    let file_bytes = std::fs::metadata(path).map_or(0, |m| m.len());
    match format {
        BagFormat::Ros1Bag => ros1::read_ros1(file, file_bytes, &input, sink),
        _ => mcap::read_mcap(file, file_bytes, &input, sink),
    }
}

/// The format of the bag at `path`, told by its first bytes, or for a ROS 2 bag folder by its
/// `metadata.yaml`.
///
/// # Errors
/// The file cannot be opened or read; it starts like no bag; a folder that is no bag folder.
pub fn detect_file(path: &Path, input: &str) -> Result<BagFormat, ReadError> {
    use std::io::Read;
    if path.is_dir() {
        return Ok(folder::read_bag_folder(path)?.format);
    }
    let mut head = Vec::new();
    crate::open_input(path)
        .and_then(|file| file.take(16).read_to_end(&mut head))
        .map_err(|e| open_error(input, e))?;
    BagFormat::detect(&head).ok_or_else(|| not_a_bag(input))
}

/// The error for a file that cannot be opened or read.
fn open_error(input: &str, e: std::io::Error) -> ReadError {
    let kind = match e.kind() {
        std::io::ErrorKind::NotFound | std::io::ErrorKind::PermissionDenied => {
            ReadErrorKind::Open(e)
        }
        _ => ReadErrorKind::Read(e),
    };
    ReadError::new(input, None, kind)
}

/// The error for a file of no bag format.
fn not_a_bag(input: &str) -> ReadError {
    ReadError::new(
        input,
        None,
        ReadErrorKind::Unusable(
            "at byte 0: expected the magic bytes of a bag (MCAP \\x89MCAP0\\r\\n, SQLite \
             \"SQLite format 3\", ROS 1 \"#ROSBAG V2.0\")"
                .to_string(),
        ),
    )
}

/// Decodes the bytes of a bag in `format`, named `input` in errors.
///
/// # Errors
/// Those of [`mcap::decode_mcap`], [`db3::decode_db3`] or [`ros1::decode_ros1`].
pub fn decode_bag(bytes: &[u8], input: &str, format: BagFormat) -> Result<Bag, ReadError> {
    match format {
        BagFormat::Ros2Mcap => mcap::decode_mcap(bytes, input),
        BagFormat::Ros2Db3 => db3::decode_db3(bytes, input),
        BagFormat::Ros1Bag => ros1::decode_ros1(bytes, input),
    }
}
