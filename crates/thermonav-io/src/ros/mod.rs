//! ROS bags: ROS 2 MCAP ([`mcap`]), ROS 2 SQLite `.db3` storage ([`db3`], over the minimal
//! SQLite reader [`sqlite`]) and ROS 1 bag v2.0 ([`ros1`]), read from the formats' public
//! descriptions (mcap.dev specification, sqlite.org "Database File Format", ROS wiki "Bags/Format/2.0").
//!
//! Each reader gives one [`Bag`]: its topics with their type, serialisation and message count,
//! and the bytes of the messages of the types [`messages`] decodes (`sensor_msgs/Imu`,
//! `NavSatFix`, `Temperature`, `geometry_msgs/TwistStamped`); the messages of other types are
//! counted and dropped, so memory follows the data that is used. [`extract`] turns a topic into
//! thermonav's series: the sample time is the message's **header stamp**, not the record (log)
//! time, and the ROS body axes (REP 103: x forward, y left, z up) become FRD.
//!
//! Every error is a [`ReadError`] naming the file and the byte offset (of the record, or of the
//! chunk record for what lies inside a compressed chunk) and what was expected there. No length
//! field is trusted: each is checked against the bytes that are left before anything is taken.

pub mod bytes;
pub mod db3;
pub mod extract;
pub mod mcap;
pub mod messages;
pub mod ros1;
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
    fn topic_index(&mut self, name: &str, type_name: &str, encoding: Encoding) -> usize {
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
    fn push(
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

    /// Total messages of all topics.
    pub fn message_count(&self) -> usize {
        self.topics.iter().map(|t| t.count).sum()
    }
}

/// A record time in ns (u64 in the files) as i64.
fn log_time(ns: u64, at: &bytes::Cursor<'_>) -> Result<i64, ReadError> {
    i64::try_from(ns).map_err(|_| at.error(format_args!("record time {ns} ns is beyond 2262")))
}

/// Reads a bag in `format`, or the one its magic bytes tell when `None`.
///
/// # Errors
/// [`ReadErrorKind::Open`]/[`ReadErrorKind::Read`]; a file of no bag format; those of the
/// format's reader.
pub fn read_bag_file(path: impl AsRef<Path>, format: Option<BagFormat>) -> Result<Bag, ReadError> {
    let path = path.as_ref();
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
