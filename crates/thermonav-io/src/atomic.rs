//! Files that appear whole or not at all.
//!
//! Output goes to a temporary file in the target's directory (same file system, so the final
//! rename is atomic); [`AtomicFile::commit`] flushes it, syncs it to disk and renames it onto
//! the target. Dropping an uncommitted [`AtomicFile`] (an error, a panic) deletes the temporary
//! file and leaves any existing target untouched. Every temporary file not yet committed or
//! dropped is listed, so that a signal handler can remove them ([`remove_pending_temporaries`]):
//! an interrupted command leaves no hidden partial file behind.

use crate::error::WriteError;
use serde::Serialize;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use tempfile::NamedTempFile;

/// An output file written through a temporary file and renamed into place on commit.
pub struct AtomicFile {
    target: PathBuf,
    temporary: BufWriter<NamedTempFile>,
    _pending: Pending,
}

/// The temporary files of the [`AtomicFile`]s alive now.
static PENDING: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// A temporary file's place in [`PENDING`], given up when dropped (after a commit has renamed
/// the file, or after the temporary file itself was deleted).
struct Pending(PathBuf);

impl Pending {
    fn register(path: &Path) -> Self {
        let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        pending.push(path.to_path_buf());
        Self(path.to_path_buf())
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(k) = pending.iter().position(|p| *p == self.0) {
            pending.swap_remove(k);
        }
    }
}

/// Deletes every temporary file of an [`AtomicFile`] not yet committed, for a signal handler
/// about to end the process (targets are untouched); returns how many were deleted.
pub fn remove_pending_temporaries() -> usize {
    let mut pending = PENDING.lock().unwrap_or_else(|e| e.into_inner());
    pending
        .drain(..)
        .filter(|p| std::fs::remove_file(p).is_ok())
        .count()
}

impl AtomicFile {
    /// Starts writing `path`: creates a hidden temporary file beside it (`.name.XXXXXX.tmp`).
    ///
    /// # Errors
    /// [`WriteError::CreateTemporary`] when the directory does not exist or is not writable.
    pub fn create(path: impl AsRef<Path>) -> Result<Self, WriteError> {
        let target = path.as_ref().to_path_buf();
        let temporary =
            temporary_beside(&target).map_err(|source| WriteError::CreateTemporary {
                path: target.display().to_string(),
                source,
            })?;
        let pending = Pending::register(temporary.path());
        Ok(Self {
            target,
            temporary: BufWriter::with_capacity(1 << 16, temporary),
            _pending: pending,
        })
    }

    /// The path the file will have once committed.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Flushes, syncs and renames the temporary file onto the target, replacing it.
    ///
    /// # Errors
    /// [`WriteError::Commit`]; the temporary file is then removed and the target untouched.
    pub fn commit(self) -> Result<(), WriteError> {
        let path = self.target.display().to_string();
        let commit_error = |source| WriteError::Commit {
            path: path.clone(),
            source,
        };
        let temporary = self
            .temporary
            .into_inner()
            .map_err(|e| commit_error(e.into_error()))?;
        temporary.as_file().sync_all().map_err(commit_error)?;
        temporary
            .persist(&self.target)
            .map_err(|e| commit_error(e.error))?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.temporary.write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.temporary.write_all(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.temporary.flush()
    }
}

/// Bytes of the target's name kept in its temporary's name: with the dots, six random
/// characters and `.tmp`, the temporary's name stays within the 255 bytes most file systems
/// allow for a name (a 250-byte target name failed on its temporary before).
const TEMPORARY_NAME_KEPT_BYTES: usize = 200;

/// `text` cut to at most `bytes` bytes at a character boundary.
fn shortened(text: &str, bytes: usize) -> &str {
    let mut end = text.len().min(bytes);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    &text[..end]
}

/// A new temporary file in the directory of `target`, readable as an ordinary new file would be.
fn temporary_beside(target: &Path) -> io::Result<NamedTempFile> {
    let directory = match target.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let name = target.file_name().unwrap_or(target.as_os_str());
    let prefix = format!(
        ".{}.",
        shortened(&name.to_string_lossy(), TEMPORARY_NAME_KEPT_BYTES)
    );
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(directory)
}

/// Writes `path` through `write` atomically: the target appears only when `write` succeeds and
/// the file is safely on disk; otherwise nothing is left behind and an existing target is kept.
///
/// # Errors
/// The error of `write`, or of creating or committing the file, wrapped in
/// [`WriteError::InFile`] with the path when it does not name it already.
///
/// # Example
/// ```
/// # let dir = tempfile::tempdir()?;
/// # let path = dir.path().join("notes.txt");
/// use std::io::Write;
/// thermonav_io::write_atomically(&path, |file| Ok(file.write_all(b"hello\n")?))?;
/// assert_eq!(std::fs::read_to_string(&path)?, "hello\n");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_atomically(
    path: impl AsRef<Path>,
    write: impl FnOnce(&mut AtomicFile) -> Result<(), WriteError>,
) -> Result<(), WriteError> {
    let mut file = AtomicFile::create(path)?;
    match write(&mut file) {
        Ok(()) => file.commit(),
        Err(error) => Err(WriteError::InFile {
            path: file.target.display().to_string(),
            source: Box::new(error),
        }),
    }
}

/// Writes `value` as pretty-printed JSON (with a final newline) to `path`, atomically.
///
/// # Errors
/// As [`write_atomically`]; [`WriteError::Io`] of kind `InvalidData` when `value` holds a
/// number that is not finite ([`crate::finite`]: nothing is written).
pub fn write_json_atomically(
    path: impl AsRef<Path>,
    value: &impl Serialize,
) -> Result<(), WriteError> {
    write_atomically(path, |file| {
        file.write_all(crate::finite::finite_json_pretty(value)?.as_bytes())?;
        file.write_all(b"\n")?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_target_name_still_gets_a_temporary() {
        // 250 bytes: the longest names most file systems allow are 255, which a temporary
        // named ".{name}.XXXXXX.tmp" would pass.
        let dir = tempfile::tempdir().unwrap();
        let name = format!("{}.json", "é".repeat(100) + &"a".repeat(45));
        assert_eq!(name.len(), 250);
        let path = dir.path().join(&name);
        write_atomically(&path, |file| Ok(file.write_all(b"{}\n")?)).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "{}\n");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        assert_eq!(shortened("éa", 1), "");
    }
}
