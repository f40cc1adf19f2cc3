//! Physical lines of a text input, read into one reused buffer.

use crate::error::{ReadError, ReadErrorKind};
use std::io::{BufRead, Read};

/// Longest line accepted, bytes: far beyond any CSV row, small enough to bound memory when the
/// input is not a text file.
pub(crate) const MAX_LINE_BYTES: u64 = 1 << 20;

/// Non-blank lines of an input, numbered as physical lines (1-based).
///
/// Blank lines (empty or whitespace only) are skipped wherever they are but still counted, so
/// line numbers in errors match an editor's. Line ends `\n` and `\r\n` are both accepted.
pub(crate) struct Lines<R> {
    reader: R,
    input: String,
    buffer: Vec<u8>,
    content_len: usize,
    number: u64,
}

impl<R: BufRead> Lines<R> {
    /// Lines of `reader`, which errors call `input`.
    pub(crate) fn new(reader: R, input: String) -> Self {
        Self {
            reader,
            input,
            buffer: Vec::with_capacity(256),
            content_len: 0,
            number: 0,
        }
    }

    /// Moves to the next non-blank line; `Ok(false)` at the end of the input.
    pub(crate) fn advance(&mut self) -> Result<bool, ReadError> {
        loop {
            if !self.read_physical_line()? {
                return Ok(false);
            }
            if !self.current().iter().all(u8::is_ascii_whitespace) {
                return Ok(true);
            }
        }
    }

    /// The current line without its line end.
    pub(crate) fn current(&self) -> &[u8] {
        &self.buffer[..self.content_len]
    }

    /// 1-based number of the current line (0 before the first).
    pub(crate) fn number(&self) -> u64 {
        self.number
    }

    /// An error about the current line.
    pub(crate) fn error_here(&self, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.input.as_str(), Some(self.number), kind)
    }

    /// An error about an earlier line, `number`.
    pub(crate) fn error_at(&self, number: u64, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.input.as_str(), Some(number), kind)
    }

    /// An error about the whole input.
    pub(crate) fn error_in_input(&self, kind: ReadErrorKind) -> ReadError {
        ReadError::new(self.input.as_str(), None, kind)
    }

    fn read_physical_line(&mut self) -> Result<bool, ReadError> {
        self.buffer.clear();
        let read = (&mut self.reader)
            .take(MAX_LINE_BYTES)
            .read_until(b'\n', &mut self.buffer);
        let read = read.map_err(|e| self.error_in_input(ReadErrorKind::Read(e)))?;
        if read == 0 {
            return Ok(false);
        }
        self.number += 1;
        let ended = self.buffer.last() == Some(&b'\n');
        if !ended && read as u64 == MAX_LINE_BYTES {
            return Err(self.error_here(ReadErrorKind::LineTooLong {
                limit_bytes: MAX_LINE_BYTES,
            }));
        }
        self.content_len = content_length(&self.buffer);
        Ok(true)
    }
}

/// Length of a line without its trailing `\n` or `\r\n`.
fn content_length(line: &[u8]) -> usize {
    let without_lf = line.strip_suffix(b"\n").unwrap_or(line);
    without_lf.strip_suffix(b"\r").unwrap_or(without_lf).len()
}
