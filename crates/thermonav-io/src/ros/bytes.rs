//! Bounds-checked little- and big-endian reads over a byte slice, each failure a [`ReadError`]
//! naming the input, the byte offset and what was expected there.

use crate::error::{ReadError, ReadErrorKind};

/// A problem at byte `offset` of `input`.
pub fn at(input: &str, offset: u64, what: impl std::fmt::Display) -> ReadError {
    ReadError::new(
        input,
        None,
        ReadErrorKind::Unusable(format!("at byte {offset}: {what}")),
    )
}

/// A cursor over `bytes`, which start at file offset `base` (for errors).
#[derive(Debug, Clone)]
pub struct Cursor<'a> {
    /// The bytes read.
    bytes: &'a [u8],
    /// Position in `bytes`.
    pos: usize,
    /// File offset of `bytes[0]` (for a decompressed chunk: the chunk record's offset).
    base: u64,
    /// The input's name.
    input: &'a str,
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `bytes`, found at file offset `base` of `input`.
    pub fn new(bytes: &'a [u8], base: u64, input: &'a str) -> Self {
        Self {
            bytes,
            pos: 0,
            base,
            input,
        }
    }

    /// The file offset of the next byte.
    pub fn offset(&self) -> u64 {
        self.base + self.pos as u64
    }

    /// Bytes left.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// Whether every byte was read.
    pub fn is_empty(&self) -> bool {
        self.remaining() == 0
    }

    /// An error at the current offset.
    pub fn error(&self, what: impl std::fmt::Display) -> ReadError {
        at(self.input, self.offset(), what)
    }

    /// The next `n` bytes, `what` naming them in the error when fewer are left.
    pub fn take(&mut self, n: u64, what: &str) -> Result<&'a [u8], ReadError> {
        match usize::try_from(n).ok().filter(|&n| n <= self.remaining()) {
            Some(n) => {
                let out = &self.bytes[self.pos..self.pos + n];
                self.pos += n;
                Ok(out)
            }
            None => Err(self.error(format_args!(
                "expected {what} of {n} bytes, but only {} bytes are left (a truncated file, or a \
                 corrupt length field)",
                self.remaining()
            ))),
        }
    }

    /// The next `N` bytes as an array.
    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ReadError> {
        let slice = self.take(N as u64, what)?;
        Ok(std::array::from_fn(|i| slice[i]))
    }

    /// A byte.
    pub fn u8(&mut self, what: &str) -> Result<u8, ReadError> {
        Ok(self.array::<1>(what)?[0])
    }

    /// A little-endian u16.
    pub fn u16_le(&mut self, what: &str) -> Result<u16, ReadError> {
        self.array(what).map(u16::from_le_bytes)
    }

    /// A little-endian u32.
    pub fn u32_le(&mut self, what: &str) -> Result<u32, ReadError> {
        self.array(what).map(u32::from_le_bytes)
    }

    /// A little-endian u64.
    pub fn u64_le(&mut self, what: &str) -> Result<u64, ReadError> {
        self.array(what).map(u64::from_le_bytes)
    }

    /// The rest of the bytes.
    pub fn rest(&mut self) -> &'a [u8] {
        let out = &self.bytes[self.pos..];
        self.pos = self.bytes.len();
        out
    }
}

/// Decompressed bytes of one chunk, at most `limit` bytes from `reader` (bytes grow with the
/// data, never allocated from a length field); `Err` with the decoder's text.
pub fn read_limited(reader: impl std::io::Read, limit: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let mut out = Vec::new();
    reader
        .take(limit.saturating_add(1))
        .read_to_end(&mut out)
        .map_err(|e| e.to_string())?;
    match out.len() as u64 > limit {
        true => Err(format!("more than the {limit} bytes the chunk declares")),
        false => Ok(out),
    }
}

/// Most bytes one chunk may declare when decompressed: 1 GiB.
pub const MAX_CHUNK_BYTES: u64 = 1 << 30;

/// A chunk of `compression` decompressed: `none`, `zstd` (MCAP), `lz4` (the LZ4 frame format,
/// in MCAP and ROS 1) or `bz2` (ROS 1). `declared` is the uncompressed size the record gives.
pub fn decompress(
    compression: &str,
    data: &[u8],
    declared: u64,
    cursor: &Cursor<'_>,
) -> Result<Vec<u8>, ReadError> {
    if declared > MAX_CHUNK_BYTES {
        return Err(cursor.error(format_args!(
            "a chunk declares {declared} bytes uncompressed, above the {MAX_CHUNK_BYTES}-byte limit"
        )));
    }
    let out = match compression {
        "" | "none" => Ok(data.to_vec()),
        "zstd" => ruzstd::decoding::StreamingDecoder::new(data)
            .map_err(|e| e.to_string())
            .and_then(|d| read_limited(d, declared)),
        "lz4" => read_limited(lz4_flex::frame::FrameDecoder::new(data), declared),
        "bz2" => read_limited(bzip2_rs::DecoderReader::new(data), declared),
        other => {
            return Err(cursor.error(format_args!(
                "chunk compression \"{other}\" is not supported (expected none, zstd, lz4 or bz2)"
            )));
        }
    };
    let out = out.map_err(|e| cursor.error(format_args!("{compression} chunk: {e}")))?;
    match out.len() as u64 == declared {
        true => Ok(out),
        false => Err(cursor.error(format_args!(
            "{compression} chunk holds {} bytes uncompressed, but its record declares {declared}",
            out.len()
        ))),
    }
}
