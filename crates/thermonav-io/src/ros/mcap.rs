//! MCAP files (the ROS 2 default storage since Iron), read from the MCAP specification
//! (mcap.dev/spec, format version 0).
//!
//! A file is the 8-byte magic `\x89MCAP0\r\n`, records of `u8 opcode`, `u64 length`, `length`
//! bytes (all little-endian; strings are a u32 length and UTF-8 bytes), and the magic again.
//! Read here: Header (0x01), Schema (0x03: `u16 id`, name, encoding, `u32`-prefixed data),
//! Channel (0x04: `u16 id`, `u16 schema_id`, topic, message encoding, metadata), Message (0x05:
//! `u16 channel_id`, `u32 sequence`, `u64 log_time`, `u64 publish_time`, data) and Chunk (0x06:
//! start and end times, `u64 uncompressed_size`, `u32 uncompressed_crc`, compression
//! `""`/`zstd`/`lz4`, `u64`-prefixed records, which are Schema, Channel and Message records).
//! Everything else (message indexes, chunk indexes, attachments, metadata, statistics, summary
//! offsets) is skipped by its length. Reading stops at the Data End (0x0F) or Footer (0x02)
//! record; the summary section after it only repeats schemas and channels. CRCs are not
//! checked. A topic's type is its schema's name (`sensor_msgs/msg/Imu`); a channel's message
//! encoding `cdr` is ROS 2 CDR, `ros1` the ROS 1 serialisation. Offsets in errors are file
//! offsets; inside a chunk they are the chunk's records offset plus the position in its
//! uncompressed records.

use super::bytes::{Cursor, Expansion, decompress};
use super::messages::Encoding;
use super::{Bag, BagFormat, log_time};
use crate::error::ReadError;
use std::collections::HashMap;

/// The first (and last) 8 bytes of an MCAP file.
pub const MAGIC: [u8; 8] = *b"\x89MCAP0\r\n";

/// Reading state: schemas and channels by id, the bag so far.
struct Reader<'a> {
    input: &'a str,
    /// Schema name by id.
    schemas: HashMap<u16, String>,
    /// Topic index of the bag by channel id.
    channels: HashMap<u16, usize>,
    /// What the compressed chunks expanded to, against the file's bound.
    expansion: Expansion,
    bag: Bag,
}

/// Decodes the bytes of an MCAP file, named `input` in errors.
///
/// # Errors
/// [`crate::error::ReadErrorKind::Unusable`] with the byte offset: a wrong magic, a record cut
/// short, a string that is not UTF-8, a channel naming an undefined schema, a message naming
/// an undefined channel, a chunk of another compression than none/zstd/lz4 or whose data does
/// not decompress to its declared size.
pub fn decode_mcap(bytes: &[u8], input: &str) -> Result<Bag, ReadError> {
    let mut cursor = Cursor::new(bytes, 0, input);
    if cursor.take(8, "the MCAP magic")? != MAGIC {
        return Err(super::bytes::at(
            input,
            0,
            "expected the MCAP magic bytes \\x89MCAP0\\r\\n (not an MCAP file)",
        ));
    }
    let mut reader = Reader {
        input,
        schemas: HashMap::new(),
        channels: HashMap::new(),
        expansion: Expansion::for_file(bytes.len() as u64),
        bag: Bag::new(BagFormat::Ros2Mcap),
    };
    reader.records(&mut cursor, false)?;
    Ok(reader.bag)
}

impl Reader<'_> {
    /// Reads records until the cursor is empty or the data section ends.
    fn records(&mut self, cursor: &mut Cursor<'_>, in_chunk: bool) -> Result<(), ReadError> {
        while !cursor.is_empty() {
            if !in_chunk && cursor.remaining() == 8 && cursor.clone().rest() == MAGIC {
                return Ok(());
            }
            let record_start = cursor.offset();
            let opcode = cursor.u8("a record opcode")?;
            let length = cursor.u64_le("a record length")?;
            let record_at = cursor.clone();
            let content = cursor.take(length, "a record's content")?;
            let mut body = Cursor::new(content, record_at.offset(), self.input);
            match (opcode, in_chunk) {
                (0x02 | 0x0F, false) => return Ok(()),
                (0x03, _) => self.schema(&mut body)?,
                (0x04, _) => self.channel(&mut body)?,
                (0x05, _) => self.message(&mut body, record_start)?,
                (0x06, false) => self.chunk(&mut body, record_start)?,
                _ => {}
            }
        }
        Ok(())
    }

    /// A Schema record: its name by id.
    fn schema(&mut self, body: &mut Cursor<'_>) -> Result<(), ReadError> {
        let id = body.u16_le("a schema id")?;
        let name = string(body, "a schema name")?;
        self.schemas.insert(id, name);
        Ok(())
    }

    /// A Channel record: a topic of the bag.
    fn channel(&mut self, body: &mut Cursor<'_>) -> Result<(), ReadError> {
        let id = body.u16_le("a channel id")?;
        let schema_id = body.u16_le("a channel's schema id")?;
        let topic = string(body, "a channel topic")?;
        let encoding = match string(body, "a channel message encoding")?.as_str() {
            "cdr" => Encoding::Cdr,
            "ros1" => Encoding::Ros1,
            other => Encoding::Other(other.to_string()),
        };
        let type_name = match schema_id {
            0 => String::new(),
            _ => self.schemas.get(&schema_id).cloned().ok_or_else(|| {
                body.error(format_args!(
                    "channel {id} ({topic}) names schema {schema_id}, which no earlier Schema \
                     record defines"
                ))
            })?,
        };
        let k = self.bag.topic_index(&topic, &type_name, encoding);
        self.channels.insert(id, k);
        Ok(())
    }

    /// A Message record, found at file offset `offset`.
    fn message(&mut self, body: &mut Cursor<'_>, offset: u64) -> Result<(), ReadError> {
        let channel = body.u16_le("a message's channel id")?;
        body.u32_le("a message sequence")?;
        let log_time_ns = log_time(body.u64_le("a message log time")?, body)?;
        body.u64_le("a message publish time")?;
        let k = *self.channels.get(&channel).ok_or_else(|| {
            body.error(format_args!(
                "a message on channel {channel}, which no earlier Channel record defines"
            ))
        })?;
        let data = body.rest();
        self.bag.push(k, log_time_ns, offset, data, self.input)
    }

    /// A Chunk record starting at file offset `offset`: its records, decompressed.
    fn chunk(&mut self, body: &mut Cursor<'_>, offset: u64) -> Result<(), ReadError> {
        body.u64_le("a chunk start time")?;
        body.u64_le("a chunk end time")?;
        let declared = body.u64_le("a chunk's uncompressed size")?;
        body.u32_le("a chunk's uncompressed CRC")?;
        let compression = string(body, "a chunk compression")?;
        let length = body.u64_le("a chunk's records length")?;
        let at = body.clone();
        let data = body.take(length, "a chunk's records")?;
        let records = decompress(
            &compression,
            data,
            declared,
            offset,
            &at,
            &mut self.expansion,
        )?;
        let mut inner = Cursor::new(&records, at.offset(), self.input);
        self.records(&mut inner, true)
    }
}

/// A u32-prefixed UTF-8 string.
fn string(body: &mut Cursor<'_>, what: &str) -> Result<String, ReadError> {
    let len = body.u32_le(what)?;
    let at = body.clone();
    let bytes = body.take(u64::from(len), what)?;
    String::from_utf8(bytes.to_vec())
        .map_err(|_| at.error(format_args!("expected {what} in UTF-8")))
}
