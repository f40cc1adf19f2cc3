//! Outputs never alias inputs: every path a command will write (sidecars included) is
//! compared with every path it reads, by canonical path and, where both exist, by file
//! identity (device and inode, so a hard link or a second name of the same file is caught),
//! before anything is read or written.

use crate::failure::Failure;
use anyhow::anyhow;
use std::path::{Path, PathBuf};

/// What a command reads and writes.
#[derive(Debug, Default, Clone)]
pub struct Io {
    inputs: Vec<(&'static str, PathBuf)>,
    outputs: Vec<(&'static str, PathBuf)>,
    output_folders: Vec<(&'static str, PathBuf)>,
}

impl Io {
    /// Nothing yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// A file read, named by its option.
    pub fn input(mut self, option: &'static str, path: &Path) -> Self {
        self.inputs.push((option, path.to_path_buf()));
        self
    }

    /// The files of the optional inputs that were given, each named by its option.
    pub fn optional_inputs<const N: usize>(
        self,
        options: [(&'static str, Option<&PathBuf>); N],
    ) -> Self {
        options
            .into_iter()
            .filter_map(|(option, path)| Some((option, path?)))
            .fold(self, |io, (option, path)| io.input(option, path))
    }

    /// Files read under one option.
    pub fn inputs(mut self, option: &'static str, paths: &[PathBuf]) -> Self {
        self.inputs
            .extend(paths.iter().map(|p| (option, p.to_path_buf())));
        self
    }

    /// A file written, named by what it is.
    pub fn output(mut self, what: &'static str, path: &Path) -> Self {
        self.outputs.push((what, path.to_path_buf()));
        self
    }

    /// A folder whose files are written (any input inside it could be overwritten).
    pub fn output_folder(mut self, what: &'static str, path: &Path) -> Self {
        self.output_folders.push((what, path.to_path_buf()));
        self
    }

    /// Refuses (exit 2) an output that is one of the inputs, or a folder of outputs that
    /// holds one, two outputs that are one file, an output whose name the file system
    /// cannot hold, and an output whose folder does not exist (unless the command makes it:
    /// the folder of one of its output folders).
    pub fn check(&self) -> Result<(), Failure> {
        self.check_name_lengths()?;
        self.check_output_folders()?;
        for (option, input) in &self.inputs {
            if let Some((what, output)) = self.outputs.iter().find(|(_, o)| same_file(input, o)) {
                return Err(collision(what, output, option, input));
            }
            if let Some((what, folder)) = self.output_folders.iter().find(|(_, f)| within(input, f))
            {
                return Err(collision(what, folder, option, input));
            }
        }
        self.check_outputs_distinct()
    }

    /// A sidecar's name is its output's plus a suffix: a name that fits alone could leave the
    /// output written and its sidecar failing, so every name is checked before any is written.
    fn check_name_lengths(&self) -> Result<(), Failure> {
        let too_long = |(_, p): &&(&str, PathBuf)| file_name_bytes(p) > MAX_FILE_NAME_BYTES;
        match self.outputs.iter().find(too_long) {
            Some((what, path)) => Err(Failure::Usage(anyhow!(
                "the {what} {} has a file name of {} bytes; file systems hold at most {MAX_FILE_NAME_BYTES}: choose a shorter output name",
                path.display(),
                file_name_bytes(path)
            ))),
            None => Ok(()),
        }
    }

    /// Every output file's folder exists, or is one the command creates (it holds, or is, one
    /// of the output folders); checked before any work, so that a long run does not end in
    /// "cannot create".
    fn check_output_folders(&self) -> Result<(), Failure> {
        for (what, path) in &self.outputs {
            let folder = match path.parent() {
                Some(p) if !p.as_os_str().is_empty() => p,
                _ => Path::new("."),
            };
            let made = |(_, f): &(&str, PathBuf)| resolved(f).starts_with(resolved(folder));
            if !folder.is_dir() && !self.output_folders.iter().any(made) {
                return Err(Failure::Usage(anyhow!(
                    "the {what} {}: its folder {} does not exist or is not a folder: create it first, or choose an output in an existing folder",
                    path.display(),
                    folder.display()
                )));
            }
        }
        Ok(())
    }

    fn check_outputs_distinct(&self) -> Result<(), Failure> {
        for (k, (what, a)) in self.outputs.iter().enumerate() {
            if let Some((other, _)) = self.outputs[k + 1..].iter().find(|(_, b)| same_file(a, b)) {
                return Err(Failure::Usage(anyhow!(
                    "{} would be written twice, as the {what} and as the {other}: choose another output name",
                    a.display()
                )));
            }
        }
        Ok(())
    }
}

/// The longest file name (one path component) Linux, macOS and Windows file systems hold, bytes.
pub const MAX_FILE_NAME_BYTES: usize = 255;

fn file_name_bytes(path: &Path) -> usize {
    path.file_name().map_or(0, |n| n.as_encoded_bytes().len())
}

fn collision(what: &str, output: &Path, option: &str, input: &Path) -> Failure {
    Failure::Usage(anyhow!(
        "the {what} {} would overwrite the input {} ({option}): choose an output that is not an input",
        output.display(),
        input.display()
    ))
}

/// The path made absolute and free of `.`, `..` and links as far as it exists: the existing
/// part is canonicalised, the rest appended.
fn resolved(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    match (path.parent(), path.file_name()) {
        (Some(parent), Some(name)) => {
            let parent = if parent.as_os_str().is_empty() {
                Path::new(".")
            } else {
                parent
            };
            resolved(parent).join(name)
        }
        _ => path.to_path_buf(),
    }
}

/// Whether two paths name one file: the same device and inode when both exist, the same
/// resolved path otherwise.
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => file_identity(&x) == file_identity(&y),
        _ => resolved(a) == resolved(b),
    }
}

#[cfg(unix)]
fn file_identity(m: &std::fs::Metadata) -> (u64, u64) {
    use std::os::unix::fs::MetadataExt;
    (m.dev(), m.ino())
}

#[cfg(not(unix))]
fn file_identity(m: &std::fs::Metadata) -> (u64, u64) {
    (m.len(), 0)
}

/// Whether `path` lies inside `folder`.
fn within(path: &Path, folder: &Path) -> bool {
    resolved(path).starts_with(resolved(folder))
}

#[cfg(test)]
mod tests {
    use super::*;

    // The rows of the reliability issue: an output equal to an input by name, by another
    // spelling of the same path, by a hard link, and an input inside a folder of outputs.
    #[test]
    fn an_output_that_is_an_input_is_refused_by_any_name() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("imu.csv");
        std::fs::write(&input, "t_s\n").unwrap();
        let linked = dir.path().join("link.csv");
        std::fs::hard_link(&input, &linked).unwrap();
        let dotted = dir.path().join(".").join("imu.csv");
        for output in [&input, &linked, &dotted] {
            let io = Io::new().input("--imu", &input).output("solution", output);
            assert!(matches!(io.check(), Err(Failure::Usage(_))), "{output:?}");
        }
        let io = Io::new()
            .input("--imu", &input)
            .output_folder("errors", dir.path());
        assert!(io.check().is_err());
        let other = dir.path().join("sol.csv");
        assert!(
            Io::new()
                .input("--imu", &input)
                .output("solution", &other)
                .check()
                .is_ok()
        );
        let twice = Io::new()
            .output("solution", &other)
            .output("states", &other);
        assert!(twice.check().is_err());
    }
}
