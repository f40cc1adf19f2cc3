//! Reading a bag record by record from any [`Read`] (a file through a buffer, or the
//! decompressor of a chunk) with bounded buffers: a length field is never allocated for, the
//! bytes grow with the data, so a lying length costs at most the bytes that are there; bytes
//! not needed are skipped without being kept. Each failure is a [`ReadError`] naming the input,
//! the byte offset and what was expected there, as [`super::bytes::Cursor`] does for a slice.

use super::bytes::at;
use crate::error::{ReadError, ReadErrorKind};
use std::io::Read;

/// Where the bytes of a [`Source`] come from, for its read errors.
#[derive(Debug, Clone, Copy)]
pub enum Origin<'a> {
    /// The file itself: an I/O error is a read error of the file.
    File,
    /// A chunk's decompressor: an I/O error is data that do not decompress.
    Chunk {
        /// File offset of the chunk record.
        offset: u64,
        /// Its compression.
        compression: &'a str,
    },
}

/// Bytes read in order from `reader`, which start at file offset `base`.
pub struct Source<'a, R> {
    reader: R,
    /// Bytes read (or skipped) so far.
    pos: u64,
    /// File offset of the first byte (for a decompressed chunk: the chunk's records offset).
    base: u64,
    /// The input's name.
    pub input: &'a str,
    origin: Origin<'a>,
}

impl<'a, R: Read> Source<'a, R> {
    /// A source reading `reader`, whose first byte is at file offset `base` of `input`.
    pub fn new(reader: R, base: u64, input: &'a str, origin: Origin<'a>) -> Self {
        Self {
            reader,
            pos: 0,
            base,
            input,
            origin,
        }
    }

    /// The file offset of the next byte.
    pub fn offset(&self) -> u64 {
        self.base + self.pos
    }

    /// Bytes read or skipped so far.
    pub fn consumed(&self) -> u64 {
        self.pos
    }

    /// An error at the current offset.
    pub fn error(&self, what: impl std::fmt::Display) -> ReadError {
        at(self.input, self.offset(), what)
    }

    /// The error for an I/O failure of the reader.
    fn io_error(&self, e: std::io::Error) -> ReadError {
        match self.origin {
            Origin::File => ReadError::new(self.input, None, ReadErrorKind::Read(e)),
            Origin::Chunk {
                offset,
                compression,
            } => at(
                self.input,
                offset,
                format_args!("the {compression} chunk does not decompress: {e}"),
            ),
        }
    }

    /// The error for `n` bytes of `what` of which only `got` are there.
    fn short(&self, what: &str, n: u64, got: u64) -> ReadError {
        self.error(format_args!(
            "expected {what} of {n} bytes, but only {got} bytes are left (a truncated file, or a \
             corrupt length field)"
        ))
    }

    /// Up to `n` bytes into `out` (cleared first), growing with the data; how many came.
    fn fill(&mut self, n: u64, out: &mut Vec<u8>) -> Result<u64, ReadError> {
        out.clear();
        let got = (&mut self.reader)
            .take(n)
            .read_to_end(out)
            .map_err(|e| self.io_error(e))? as u64;
        Ok(got)
    }

    /// The next `n` bytes into `out`, `what` naming them when fewer are left.
    pub fn read_into(&mut self, n: u64, what: &str, out: &mut Vec<u8>) -> Result<(), ReadError> {
        let got = self.fill(n, out)?;
        if got < n {
            return Err(self.short(what, n, got));
        }
        self.pos += n;
        Ok(())
    }

    /// The next `n` bytes, `what` naming them when fewer are left.
    pub fn bytes(&mut self, n: u64, what: &str) -> Result<Vec<u8>, ReadError> {
        let mut out = Vec::new();
        self.read_into(n, what, &mut out)?;
        Ok(out)
    }

    /// Skips `n` bytes without keeping them.
    pub fn skip(&mut self, n: u64, what: &str) -> Result<(), ReadError> {
        let got = std::io::copy(&mut (&mut self.reader).take(n), &mut std::io::sink())
            .map_err(|e| self.io_error(e))?;
        if got < n {
            return Err(self.short(what, n, got));
        }
        self.pos += n;
        Ok(())
    }

    /// The next `N` bytes, or `None` at the end of the data (no byte left).
    pub fn array_or_end<const N: usize>(
        &mut self,
        what: &str,
    ) -> Result<Option<[u8; N]>, ReadError> {
        let mut out = Vec::with_capacity(N);
        let got = self.fill(N as u64, &mut out)?;
        match got {
            0 => Ok(None),
            _ if got < N as u64 => Err(self.short(what, N as u64, got)),
            _ => {
                self.pos += N as u64;
                Ok(Some(std::array::from_fn(|i| out[i])))
            }
        }
    }

    /// The next `N` bytes.
    pub fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], ReadError> {
        match self.array_or_end(what)? {
            Some(a) => Ok(a),
            None => Err(self.short(what, N as u64, 0)),
        }
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

    /// True when no byte is left (reads one byte ahead: for the end of a chunk only).
    pub fn at_end(&mut self) -> Result<bool, ReadError> {
        let mut out = Vec::with_capacity(1);
        Ok(self.fill(1, &mut out)? == 0)
    }

    /// The reader, for a chunk's records to be read from a part of it.
    pub fn reader(&mut self) -> &mut R {
        &mut self.reader
    }

    /// Counts `n` bytes read through [`Source::reader`].
    pub fn advance(&mut self, n: u64) {
        self.pos += n;
    }
}
