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
//! connection record (the index section at the end repeats them). The file is read record by
//! record, each chunk through its decompressor as it comes ([`read_ros1`]).

use super::bytes::{Expansion, check_expansion, chunk_bounds};
use super::messages::Encoding;
use super::source::{Origin, Source};
use super::{Bag, BagFormat, Sink};
use crate::error::ReadError;
use std::collections::HashMap;
use std::io::Read;

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

/// Longest record header accepted: 16 MiB. A header holds a few short fields (op, conn,
/// topic, time, compression, size); the message definitions are in the data.
pub const MAX_HEADER_BYTES: u32 = 16 << 20;

/// Reading state.
struct Reader<'a, S> {
    input: &'a str,
    /// Topic index of the sink by connection id.
    connections: HashMap<u32, usize>,
    /// Messages of connections not yet defined, by connection id, in record order.
    pending: HashMap<u32, Vec<Pending>>,
    /// What the compressed chunks expanded to, against the file's bound.
    expansion: Expansion,
    /// The bytes of the message being read (reused).
    buffer: Vec<u8>,
    sink: &'a mut S,
}

/// Decodes the bytes of a ROS 1 bag (v2.0), named `input` in errors.
///
/// # Errors
/// Those of [`read_ros1`].
pub fn decode_ros1(bytes: &[u8], input: &str) -> Result<Bag, ReadError> {
    let mut bag = Bag::new(BagFormat::Ros1Bag);
    read_ros1(bytes, bytes.len() as u64, input, &mut bag)?;
    Ok(bag)
}

/// Reads a ROS 1 bag (v2.0) of `file_bytes` bytes from `reader`, record by record, into
/// `sink`: memory is a record's header and the data the sink wants (and the messages that come
/// before their connection record), whatever the file's length; a chunk is read through its
/// decompressor as it comes.
///
/// # Errors
/// [`crate::error::ReadErrorKind::Unusable`] with the byte offset: a wrong magic (or another
/// version), a record cut short, a header longer than [`MAX_HEADER_BYTES`] or without its
/// required fields, a chunk of another compression than none/bz2/lz4, beyond the bounds of
/// [`super::bytes::chunk_bounds`] or that does not decompress to its `size`, a message of a
/// connection that no connection record defines; the sink's errors.
pub fn read_ros1<S: Sink>(
    reader: impl Read,
    file_bytes: u64,
    input: &str,
    sink: &mut S,
) -> Result<(), ReadError> {
    let mut source = Source::new(reader, 0, input, Origin::File);
    let mut head = Vec::new();
    let got = source.read_into(MAGIC.len() as u64, "the ROS 1 bag line", &mut head);
    if got.is_err() || head != MAGIC {
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
        expansion: Expansion::for_file(file_bytes),
        buffer: Vec::new(),
        sink,
    };
    reader.records(&mut source, false)?;
    reader.finish()
}

impl<S: Sink> Reader<'_, S> {
    /// The records of `source` (`in_chunk`: the records of a chunk).
    fn records<R: Read>(
        &mut self,
        source: &mut Source<'_, R>,
        in_chunk: bool,
    ) -> Result<(), ReadError> {
        loop {
            let offset = source.offset();
            let Some(len) = source.array_or_end::<4>("a record header length")? else {
                return Ok(());
            };
            let header_len = u32::from_le_bytes(len);
            if header_len > MAX_HEADER_BYTES {
                return Err(source.error(format_args!(
                    "expected a record header of {header_len} bytes: above the \
                     {MAX_HEADER_BYTES} bytes any recorder writes (a corrupt length field)"
                )));
            }
            let header_bytes = source.bytes(u64::from(header_len), "a record header")?;
            let header = Header::parse(&header_bytes, offset, self.input)?;
            let data_len = u64::from(source.u32_le("a record data length")?);
            let data_at = source.offset();
            match header.fixed::<1>("op", self.input)?[0] {
                0x05 if !in_chunk => self.chunk(&header, source, data_len, data_at)?,
                0x07 => {
                    let data = source.bytes(data_len, "a record's data")?;
                    self.connection(&header, &data, data_at)?;
                }
                0x02 => self.message(&header, source, data_len)?,
                _ => source.skip(data_len, "a record's data")?,
            }
        }
    }

    /// A chunk record whose `length` bytes of data start at file offset `data_at`: its
    /// records, read through the decompressor as they come.
    fn chunk<R: Read>(
        &mut self,
        header: &Header<'_>,
        source: &mut Source<'_, R>,
        length: u64,
        data_at: u64,
    ) -> Result<(), ReadError> {
        let input = self.input;
        let compression = header.text("compression", input)?;
        let size = u64::from(u32::from_le_bytes(header.fixed("size", input)?));
        let offsets = (header.offset, data_at);
        chunk_bounds(
            &compression,
            length,
            size,
            offsets,
            input,
            &mut self.expansion,
        )?;
        let mut stored = source.reader().take(length);
        let outcome = self.chunk_records(&mut stored, &compression, size, offsets);
        let left = stored.limit();
        let skipped = std::io::copy(&mut stored, &mut std::io::sink())
            .map_err(|e| ReadError::new(input, None, crate::error::ReadErrorKind::Read(e)))?;
        if skipped < left {
            return Err(super::bytes::at(
                input,
                data_at,
                format_args!(
                    "expected a chunk's records of {length} bytes, but only {} bytes are left (a \
                     truncated file, or a corrupt length field)",
                    length - left + skipped
                ),
            ));
        }
        let (produced, more) = outcome?;
        check_expansion(
            &compression,
            (produced, more),
            size,
            length,
            header.offset,
            input,
        )?;
        source.advance(length);
        Ok(())
    }

    /// The records of a chunk of `compression` from its stored bytes, at most `declared`
    /// bytes once decompressed: how many bytes they took and whether the decompressor had
    /// more. `at` is the file offsets of the chunk record and of its data.
    fn chunk_records(
        &mut self,
        stored: &mut dyn Read,
        compression: &str,
        declared: u64,
        (offset, data_at): (u64, u64),
    ) -> Result<(u64, bool), ReadError> {
        let input = self.input;
        let decoder = super::bytes::chunk_decoder(compression, stored, input, offset)?;
        let origin = Origin::Chunk {
            offset,
            compression,
        };
        let mut inner = Source::new(decoder.take(declared), data_at, input, origin);
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

    /// A connection record: its topic, and the messages that waited for it.
    fn connection(
        &mut self,
        header: &Header<'_>,
        data: &[u8],
        data_at: u64,
    ) -> Result<(), ReadError> {
        let conn = u32::from_le_bytes(header.fixed("conn", self.input)?);
        let topic = header.text("topic", self.input)?;
        let fields = Header::parse(data, data_at, self.input)?;
        let type_name = fields.text("type", self.input)?;
        let k = self.sink.topic_index(&topic, &type_name, Encoding::Ros1);
        self.connections.insert(conn, k);
        for m in self.pending.remove(&conn).unwrap_or_default() {
            match self.sink.wants(k) {
                true => self
                    .sink
                    .push(k, m.log_time_ns, m.offset, &m.data, self.input)?,
                false => self.sink.count(k),
            }
        }
        Ok(())
    }

    /// A message data record of `length` bytes of data: read when the sink wants them (or
    /// when its connection is not known yet), else skipped and counted.
    fn message<R: Read>(
        &mut self,
        header: &Header<'_>,
        source: &mut Source<'_, R>,
        length: u64,
    ) -> Result<(), ReadError> {
        let conn = u32::from_le_bytes(header.fixed("conn", self.input)?);
        let time: [u8; 8] = header.fixed("time", self.input)?;
        let secs = u32::from_le_bytes([time[0], time[1], time[2], time[3]]);
        let nsecs = u32::from_le_bytes([time[4], time[5], time[6], time[7]]);
        let log_time_ns = i64::from(secs) * 1_000_000_000 + i64::from(nsecs);
        let Some(&k) = self.connections.get(&conn) else {
            let data = source.bytes(length, "a record's data")?;
            self.pending.entry(conn).or_default().push(Pending {
                log_time_ns,
                offset: header.offset,
                data,
            });
            return Ok(());
        };
        if !self.sink.wants(k) {
            self.sink.count(k);
            return source.skip(length, "a record's data");
        }
        let mut data = std::mem::take(&mut self.buffer);
        source.read_into(length, "a record's data", &mut data)?;
        let pushed = self
            .sink
            .push(k, log_time_ns, header.offset, &data, self.input);
        self.buffer = data;
        pushed
    }

    /// Once the file is read, no message may wait for its connection.
    fn finish(self) -> Result<(), ReadError> {
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
            None => Ok(()),
        }
    }
}
