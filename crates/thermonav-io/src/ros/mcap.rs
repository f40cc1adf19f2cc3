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

use super::bytes::{Cursor, Expansion, chunk_bounds};
use super::messages::Encoding;
use super::source::{Origin, Source};
use super::{Bag, BagFormat, Sink, log_time};
use crate::error::ReadError;
use std::collections::HashMap;
use std::io::Read;

/// The first (and last) 8 bytes of an MCAP file.
pub const MAGIC: [u8; 8] = *b"\x89MCAP0\r\n";

/// Bytes of a Message record before its data: channel id, sequence, log and publish times.
const MESSAGE_HEAD: u64 = 2 + 4 + 8 + 8;

/// Reading state: schemas and channels by id, and where the topics and messages go.
struct Reader<'a, S> {
    input: &'a str,
    /// Schema name by id.
    schemas: HashMap<u16, String>,
    /// Topic index of the sink by channel id.
    channels: HashMap<u16, usize>,
    /// What the compressed chunks expanded to, against the file's bound.
    expansion: Expansion,
    /// The bytes of the message being read (reused).
    buffer: Vec<u8>,
    sink: &'a mut S,
}

/// Decodes the bytes of an MCAP file, named `input` in errors.
///
/// # Errors
/// Those of [`read_mcap`].
pub fn decode_mcap(bytes: &[u8], input: &str) -> Result<Bag, ReadError> {
    let mut bag = Bag::new(BagFormat::Ros2Mcap);
    read_mcap(bytes, bytes.len() as u64, input, &mut bag)?;
    Ok(bag)
}

/// Reads an MCAP file of `file_bytes` bytes from `reader`, record by record, into `sink`:
/// memory is a record's bytes at a time (a message's data only when the sink wants them) and a
/// chunk's decompressor, whatever the file's length.
///
/// # Errors
/// [`crate::error::ReadErrorKind::Unusable`] with the byte offset: a wrong magic, a record cut
/// short, a string that is not UTF-8, a channel naming an undefined schema, a message naming
/// an undefined channel, a chunk of another compression than none/zstd/lz4, beyond the bounds
/// of [`super::bytes::chunk_bounds`], or whose data does not decompress to its declared size;
/// the sink's errors.
pub fn read_mcap<S: Sink>(
    reader: impl Read,
    file_bytes: u64,
    input: &str,
    sink: &mut S,
) -> Result<(), ReadError> {
    let mut source = Source::new(reader, 0, input, Origin::File);
    if source.array::<8>("the MCAP magic")? != MAGIC {
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
        expansion: Expansion::for_file(file_bytes),
        buffer: Vec::new(),
        sink,
    };
    reader.records(&mut source, false)
}

impl<S: Sink> Reader<'_, S> {
    /// Reads records until the source ends or the data section does (`in_chunk`: the records
    /// of a chunk).
    fn records<R: Read>(
        &mut self,
        source: &mut Source<'_, R>,
        in_chunk: bool,
    ) -> Result<(), ReadError> {
        loop {
            let record_start = source.offset();
            let Some([opcode]) = source.array_or_end::<1>("a record opcode")? else {
                return Ok(());
            };
            if !in_chunk && opcode == MAGIC[0] {
                // The closing magic of a file without a Data End or Footer record.
                return match source.array::<7>("the closing MCAP magic")? == MAGIC[1..] {
                    true => Ok(()),
                    false => Err(super::bytes::at(
                        self.input,
                        record_start,
                        "expected a record or the closing MCAP magic",
                    )),
                };
            }
            let length = source.u64_le("a record length")?;
            let content_at = source.offset();
            match (opcode, in_chunk) {
                (0x02 | 0x0F, false) => return Ok(()),
                (0x03 | 0x04, _) => {
                    let content = source.bytes(length, "a record's content")?;
                    let mut body = Cursor::new(&content, content_at, self.input);
                    match opcode {
                        0x03 => self.schema(&mut body)?,
                        _ => self.channel(&mut body)?,
                    }
                }
                (0x05, _) => self.message(source, length, record_start)?,
                (0x06, false) => self.chunk(source, length, record_start)?,
                _ => source.skip(length, "a record's content")?,
            }
        }
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
        let k = self.sink.topic_index(&topic, &type_name, encoding);
        self.channels.insert(id, k);
        Ok(())
    }

    /// A Message record of `length` bytes, found at file offset `offset`: its data read when
    /// the sink wants them, else skipped and counted.
    fn message<R: Read>(
        &mut self,
        source: &mut Source<'_, R>,
        length: u64,
        offset: u64,
    ) -> Result<(), ReadError> {
        let head_at = source.offset();
        let head = source.bytes(length.min(MESSAGE_HEAD), "a record's content")?;
        let mut body = Cursor::new(&head, head_at, self.input);
        let channel = body.u16_le("a message's channel id")?;
        body.u32_le("a message sequence")?;
        let log_time_ns = log_time(body.u64_le("a message log time")?, &body)?;
        body.u64_le("a message publish time")?;
        let k = *self.channels.get(&channel).ok_or_else(|| {
            body.error(format_args!(
                "a message on channel {channel}, which no earlier Channel record defines"
            ))
        })?;
        let data_len = length - MESSAGE_HEAD;
        match self.sink.wants(k) {
            true => {
                let mut data = std::mem::take(&mut self.buffer);
                source.read_into(data_len, "a message's data", &mut data)?;
                let pushed = self.sink.push(k, log_time_ns, offset, &data, self.input);
                self.buffer = data;
                pushed
            }
            false => {
                source.skip(data_len, "a message's data")?;
                self.sink.count(k);
                Ok(())
            }
        }
    }

    /// A Chunk record of `length` bytes starting at file offset `offset`: its records, read
    /// through the decompressor as they come.
    fn chunk<R: Read>(
        &mut self,
        source: &mut Source<'_, R>,
        length: u64,
        offset: u64,
    ) -> Result<(), ReadError> {
        let input = self.input;
        let content_at = source.offset();
        let mut body = Source::new(
            source.reader().take(length),
            content_at,
            input,
            Origin::File,
        );
        body.u64_le("a chunk start time")?;
        body.u64_le("a chunk end time")?;
        let declared = body.u64_le("a chunk's uncompressed size")?;
        body.u32_le("a chunk's uncompressed CRC")?;
        let name_len = body.u32_le("a chunk compression")?;
        let name = body.bytes(u64::from(name_len), "a chunk compression")?;
        let compression = String::from_utf8(name)
            .map_err(|_| body.error("expected a chunk compression in UTF-8"))?;
        let records_len = body.u64_le("a chunk's records length")?;
        let records_at = body.offset();
        chunk_bounds(
            &compression,
            records_len,
            declared,
            (offset, records_at),
            input,
            &mut self.expansion,
        )?;
        let mut compressed = body.reader().take(records_len);
        let outcome = self.chunk_records(
            &mut compressed,
            &compression,
            declared,
            (offset, records_at),
        );
        // The rest of the chunk's stored bytes: a file that ends inside them is truncated,
        // whatever the decompressor made of what was there.
        let left = compressed.limit();
        let skipped = std::io::copy(&mut compressed, &mut std::io::sink())
            .map_err(|e| ReadError::new(input, None, crate::error::ReadErrorKind::Read(e)))?;
        if skipped < left {
            return Err(super::bytes::at(
                input,
                records_at,
                format_args!(
                    "expected a chunk's records of {records_len} bytes, but only {} bytes are \
                     left (a truncated file, or a corrupt length field)",
                    records_len - left + skipped
                ),
            ));
        }
        let (produced, more) = outcome?;
        super::bytes::check_expansion(
            &compression,
            (produced, more),
            declared,
            records_len,
            offset,
            input,
        )?;
        body.advance(records_len);
        body.skip(length - body.consumed(), "a record's content")?;
        source.advance(length);
        Ok(())
    }

    /// The records of a chunk of `compression` from its stored bytes `stored`, at most
    /// `declared` bytes of them once decompressed: how many bytes they took and whether the
    /// decompressor had more. `at` is the file offsets of the chunk record and of its records.
    fn chunk_records(
        &mut self,
        stored: &mut dyn Read,
        compression: &str,
        declared: u64,
        (offset, records_at): (u64, u64),
    ) -> Result<(u64, bool), ReadError> {
        let input = self.input;
        let decoder = super::bytes::chunk_decoder(compression, stored, input, offset)?;
        let origin = Origin::Chunk {
            offset,
            compression,
        };
        let mut inner = Source::new(decoder.take(declared), records_at, input, origin);
        let parsed = self.records(&mut inner, true);
        let produced = inner.consumed();
        if parsed.is_err() {
            // A record cut by the declared end of a chunk that expands further is that
            // chunk's fault: read to the declared end (at most 64 MiB) to tell.
            let left = inner.reader().limit();
            let _ = inner.skip(left, "a chunk's records");
        }
        let more = !Source::new(inner.reader().get_mut(), 0, input, origin).at_end()?;
        match parsed {
            Err(e) if !more => Err(e),
            _ => Ok((produced, more)),
        }
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
