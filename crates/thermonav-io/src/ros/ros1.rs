//! ROS 1 bags, format version 2.0, read from the ROS wiki's "Bags/Format/2.0".
//!
//! A file is the line `#ROSBAG V2.0\n`, then records of `u32 header_len`, the header (fields of
//! `u32 field_len` and `name=value`), `u32 data_len` and the data, all little-endian. The
//! header's `op` field says what a record is: 0x03 bag header, 0x05 chunk (`compression`
//! `none`, `bz2` or `lz4` (the LZ4 frame format), `size` uncompressed; its data are message data
//! and connection records), 0x07 connection (`conn` id and `topic` in the header; `type`,
//! `md5sum`, `message_definition` as fields in the data), 0x02 message data (`conn`, `time` as
//! `u32 secs, u32 nsecs`; the data is the serialised message), 0x04 index data and 0x06 chunk
//! info (skipped). A message is given its topic as it is read when its connection record came
//! before it (as recorders write them); one that comes before its connection is kept until the
//! connection record (the index section at the end repeats them). A chunk is dropped once read.

use super::bytes::{Cursor, Expansion, decompress};
use super::messages::Encoding;
use super::{Bag, BagFormat, Sink};
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

/// A message record read before the connection record that gives its topic.
struct Pending {
    log_time_ns: i64,
    offset: u64,
    data: Vec<u8>,
}

/// Reading state.
struct Reader<'a> {
    input: &'a str,
    /// Topic index of the bag by connection id.
    connections: HashMap<u32, usize>,
    /// Messages of connections not yet defined, by connection id, in record order.
    pending: HashMap<u32, Vec<Pending>>,
    /// What the compressed chunks expanded to, against the file's bound.
    expansion: Expansion,
    bag: Bag,
}

/// Decodes the bytes of a ROS 1 bag (v2.0), named `input` in errors.
///
/// # Errors
/// [`crate::error::ReadErrorKind::Unusable`] with the byte offset: a wrong magic (or another
/// version), a record cut short, a header without its required fields, a chunk of another
/// compression than none/bz2/lz4 or that does not decompress to its `size` (or beyond the
/// bounds of [`super::bytes::decompress`]), a message of a connection that no connection
/// record defines, a message shorter than its type.
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
        pending: HashMap::new(),
        expansion: Expansion::for_file(bytes.len() as u64),
        bag: Bag::new(BagFormat::Ros1Bag),
    };
    let mut cursor = Cursor::new(&bytes[MAGIC.len()..], MAGIC.len() as u64, input);
    reader.records(&mut cursor, false)?;
    reader.finish()
}

impl Reader<'_> {
    /// The records of `cursor` (`in_chunk`: the records of a chunk).
    fn records(&mut self, cursor: &mut Cursor<'_>, in_chunk: bool) -> Result<(), ReadError> {
        while !cursor.is_empty() {
            let offset = cursor.offset();
            let header_len = cursor.u32_le("a record header length")?;
            let header_bytes = cursor.take(u64::from(header_len), "a record header")?;
            let header = Header::parse(header_bytes, offset, self.input)?;
            let data_len = cursor.u32_le("a record data length")?;
            let data_at = cursor.clone();
            let data = cursor.take(u64::from(data_len), "a record's data")?;
            match header.fixed::<1>("op", self.input)?[0] {
                0x05 if !in_chunk => self.chunk(&header, data, &data_at)?,
                0x07 => self.connection(&header, data, &data_at)?,
                0x02 => self.message(&header, data)?,
                _ => {}
            }
        }
        Ok(())
    }

    /// A chunk record: its records, decompressed (and dropped once read).
    fn chunk(
        &mut self,
        header: &Header<'_>,
        data: &[u8],
        at: &Cursor<'_>,
    ) -> Result<(), ReadError> {
        let compression = header.text("compression", self.input)?;
        let size = u32::from_le_bytes(header.fixed("size", self.input)?);
        let records = decompress(
            &compression,
            data,
            u64::from(size),
            header.offset,
            at,
            &mut self.expansion,
        )?;
        let mut cursor = Cursor::new(&records, at.offset(), self.input);
        self.records(&mut cursor, true)
    }

    /// A connection record: its topic, and the messages that waited for it.
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
        let k = self.bag.topic_index(&topic, &type_name, Encoding::Ros1);
        self.connections.insert(conn, k);
        for m in self.pending.remove(&conn).unwrap_or_default() {
            self.bag
                .push(k, m.log_time_ns, m.offset, &m.data, self.input)?;
        }
        Ok(())
    }

    /// A message data record whose serialised message is `data`.
    fn message(&mut self, header: &Header<'_>, data: &[u8]) -> Result<(), ReadError> {
        let conn = u32::from_le_bytes(header.fixed("conn", self.input)?);
        let time: [u8; 8] = header.fixed("time", self.input)?;
        let secs = u32::from_le_bytes([time[0], time[1], time[2], time[3]]);
        let nsecs = u32::from_le_bytes([time[4], time[5], time[6], time[7]]);
        let log_time_ns = i64::from(secs) * 1_000_000_000 + i64::from(nsecs);
        match self.connections.get(&conn) {
            Some(&k) => self
                .bag
                .push(k, log_time_ns, header.offset, data, self.input),
            None => {
                self.pending.entry(conn).or_default().push(Pending {
                    log_time_ns,
                    offset: header.offset,
                    data: data.to_vec(),
                });
                Ok(())
            }
        }
    }

    /// The bag, once no message waits for its connection.
    fn finish(self) -> Result<Bag, ReadError> {
        let orphan = self
            .pending
            .iter()
            .filter_map(|(conn, messages)| Some((messages.first()?.offset, *conn)))
            .min();
        match orphan {
            Some((offset, conn)) => Err(super::bytes::at(
                self.input,
                offset,
                format_args!("a message of connection {conn}, which no connection record defines"),
            )),
            None => Ok(self.bag),
        }
    }
}
