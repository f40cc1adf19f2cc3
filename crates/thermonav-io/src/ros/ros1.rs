//! ROS 1 bags, format version 2.0, read from the ROS wiki's "Bags/Format/2.0".
//!
//! A file is the line `#ROSBAG V2.0\n`, then records of `u32 header_len`, the header (fields of
//! `u32 field_len` and `name=value`), `u32 data_len` and the data, all little-endian. The
//! header's `op` field says what a record is: 0x03 bag header, 0x05 chunk (`compression`
//! `none`, `bz2` or `lz4` (the LZ4 frame format), `size` uncompressed; its data are message data
//! and connection records), 0x07 connection (`conn` id and `topic` in the header; `type`,
//! `md5sum`, `message_definition` as fields in the data), 0x02 message data (`conn`, `time` as
//! `u32 secs, u32 nsecs`; the data is the serialised message), 0x04 index data and 0x06 chunk
//! info (skipped). Connections may come after the messages that use them (the index section
//! repeats them at the end), so messages are resolved once the whole file is read.

use super::bytes::{Cursor, decompress};
use super::messages::Encoding;
use super::{Bag, BagFormat};
use crate::error::ReadError;
use std::collections::HashMap;

/// The first 13 bytes of a ROS 1 bag, version 2.0.
pub const MAGIC: &[u8; 13] = b"#ROSBAG V2.0\n";

/// A record's header fields.
struct Header<'a> {
    fields: Vec<(&'a [u8], &'a [u8])>,
    /// File offset of the record (inside a chunk: the chunk's data offset plus the position
    /// in its uncompressed records).
    offset: u64,
}

impl<'a> Header<'a> {
    /// Splits the header bytes into fields.
    fn parse(bytes: &'a [u8], offset: u64, input: &str) -> Result<Self, ReadError> {
        let mut fields = Vec::new();
        let mut rest = bytes;
        while !rest.is_empty() {
            let bad = |what: &str| {
                super::bytes::at(
                    input,
                    offset,
                    format_args!("in the record's header: {what}"),
                )
            };
            let (len, tail) = match rest.split_first_chunk::<4>() {
                Some((len, tail)) => (u32::from_le_bytes(*len) as usize, tail),
                None => return Err(bad("a field length is cut short")),
            };
            if len > tail.len() {
                return Err(bad(&format!(
                    "a field of {len} bytes, but {} are left",
                    tail.len()
                )));
            }
            let (field, tail) = tail.split_at(len);
            let eq = field
                .iter()
                .position(|&b| b == b'=')
                .ok_or_else(|| bad("expected a field name=value (no '=')"))?;
            fields.push((&field[..eq], &field[eq + 1..]));
            rest = tail;
        }
        Ok(Self { fields, offset })
    }

    /// The value of field `name`.
    fn get(&self, name: &str) -> Option<&'a [u8]> {
        self.fields
            .iter()
            .find(|(n, _)| *n == name.as_bytes())
            .map(|&(_, v)| v)
    }

    /// Field `name`, required, `N` bytes long.
    fn fixed<const N: usize>(&self, name: &str, input: &str) -> Result<[u8; N], ReadError> {
        match self.get(name) {
            Some(v) if v.len() == N => Ok(std::array::from_fn(|i| v[i])),
            _ => Err(super::bytes::at(
                input,
                self.offset,
                format_args!("expected a {N}-byte header field {name}"),
            )),
        }
    }

    /// Field `name` as text.
    fn text(&self, name: &str, input: &str) -> Result<String, ReadError> {
        self.get(name)
            .map(|v| String::from_utf8_lossy(v).into_owned())
            .ok_or_else(|| {
                super::bytes::at(
                    input,
                    self.offset,
                    format_args!("expected a header field {name}"),
                )
            })
    }
}

/// A message record not yet given its topic.
struct Pending {
    conn: u32,
    log_time_ns: i64,
    offset: u64,
    range: (usize, usize),
    /// Index of the buffer the data are in (0: the file; k: chunk k).
    buffer: usize,
}

/// Reading state.
struct Reader<'a> {
    input: &'a str,
    /// Topic name and type by connection id.
    connections: HashMap<u32, (String, String)>,
    pending: Vec<Pending>,
    /// Decompressed chunks (index 0 stands for the file itself).
    chunks: Vec<Vec<u8>>,
}

/// Decodes the bytes of a ROS 1 bag (v2.0), named `input` in errors.
///
/// # Errors
/// [`crate::error::ReadErrorKind::Unusable`] with the byte offset: a wrong magic (or another
/// version), a record cut short, a header without its required fields, a chunk of another
/// compression than none/bz2/lz4 or that does not decompress to its `size`, a message of a
/// connection that no connection record defines.
pub fn decode_ros1(bytes: &[u8], input: &str) -> Result<Bag, ReadError> {
    if !bytes.starts_with(MAGIC) {
        return Err(super::bytes::at(
            input,
            0,
            "expected the line \"#ROSBAG V2.0\" (not a ROS 1 bag of format version 2.0)",
        ));
    }
    let mut reader = Reader {
        input,
        connections: HashMap::new(),
        pending: Vec::new(),
        chunks: vec![Vec::new()],
    };
    let mut cursor = Cursor::new(&bytes[MAGIC.len()..], MAGIC.len() as u64, input);
    reader.records(&mut cursor, 0, 0)?;
    reader.finish(bytes)
}

impl Reader<'_> {
    /// The records of `cursor`, whose buffer `buffer` starts at cursor offset `base`.
    fn records(
        &mut self,
        cursor: &mut Cursor<'_>,
        buffer: usize,
        base: u64,
    ) -> Result<(), ReadError> {
        while !cursor.is_empty() {
            let offset = cursor.offset();
            let header_len = cursor.u32_le("a record header length")?;
            let header_bytes = cursor.take(u64::from(header_len), "a record header")?;
            let header = Header::parse(header_bytes, offset, self.input)?;
            let data_len = cursor.u32_le("a record data length")?;
            let data_at = cursor.clone();
            let data = cursor.take(u64::from(data_len), "a record's data")?;
            let start = (data_at.offset() - base) as usize;
            match header.fixed::<1>("op", self.input)?[0] {
                0x05 if buffer == 0 => self.chunk(&header, data, &data_at)?,
                0x07 => self.connection(&header, data, &data_at)?,
                0x02 => self.message(&header, (start, start + data.len()), buffer)?,
                _ => {}
            }
        }
        Ok(())
    }

    /// A chunk record: its records, decompressed.
    fn chunk(
        &mut self,
        header: &Header<'_>,
        data: &[u8],
        at: &Cursor<'_>,
    ) -> Result<(), ReadError> {
        let compression = header.text("compression", self.input)?;
        let size = u32::from_le_bytes(header.fixed("size", self.input)?);
        let records = decompress(&compression, data, u64::from(size), at)?;
        let k = self.chunks.len();
        self.chunks.push(records);
        let inner = std::mem::take(&mut self.chunks[k]);
        let mut cursor = Cursor::new(&inner, at.offset(), self.input);
        let outcome = self.records(&mut cursor, k, at.offset());
        self.chunks[k] = inner;
        outcome
    }

    /// A connection record.
    fn connection(
        &mut self,
        header: &Header<'_>,
        data: &[u8],
        at: &Cursor<'_>,
    ) -> Result<(), ReadError> {
        let conn = u32::from_le_bytes(header.fixed("conn", self.input)?);
        let topic = header.text("topic", self.input)?;
        let fields = Header::parse(data, at.offset(), self.input)?;
        let type_name = fields.text("type", self.input)?;
        self.connections.insert(conn, (topic, type_name));
        Ok(())
    }

    /// A message data record whose data is `range` of buffer `buffer`.
    fn message(
        &mut self,
        header: &Header<'_>,
        range: (usize, usize),
        buffer: usize,
    ) -> Result<(), ReadError> {
        let conn = u32::from_le_bytes(header.fixed("conn", self.input)?);
        let time: [u8; 8] = header.fixed("time", self.input)?;
        let secs = u32::from_le_bytes([time[0], time[1], time[2], time[3]]);
        let nsecs = u32::from_le_bytes([time[4], time[5], time[6], time[7]]);
        self.pending.push(Pending {
            conn,
            log_time_ns: i64::from(secs) * 1_000_000_000 + i64::from(nsecs),
            offset: header.offset,
            range,
            buffer,
        });
        Ok(())
    }

    /// The bag: every pending message given its connection's topic.
    fn finish(self, file: &[u8]) -> Result<Bag, ReadError> {
        let mut bag = Bag::new(BagFormat::Ros1Bag);
        let mut topic_of: HashMap<u32, usize> = HashMap::new();
        let mut ids: Vec<&u32> = self.connections.keys().collect();
        ids.sort();
        for id in ids {
            let (topic, type_name) = &self.connections[id];
            topic_of.insert(*id, bag.topic_index(topic, type_name, Encoding::Ros1));
        }
        for m in &self.pending {
            let k = *topic_of.get(&m.conn).ok_or_else(|| {
                super::bytes::at(
                    self.input,
                    m.offset,
                    format_args!(
                        "a message of connection {}, which no connection record defines",
                        m.conn
                    ),
                )
            })?;
            let buffer = if m.buffer == 0 {
                file
            } else {
                &self.chunks[m.buffer]
            };
            bag.push(k, m.log_time_ns, m.offset, &buffer[m.range.0..m.range.1]);
        }
        Ok(bag)
    }
}
