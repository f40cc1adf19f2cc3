//! ROS 2 bag folders, as `ros2 bag record` writes them: a folder holding `metadata.yaml` and
//! the storage files it lists under `relative_file_paths`, in recording order, all of the
//! storage `storage_identifier` names (`sqlite3`: `.db3`; `mcap`). A bag split by size or
//! duration is several files; their messages are read one file after the other, in the order
//! the metadata lists them.
//!
//! `metadata.yaml` is read minimally: at most [`MAX_METADATA_BYTES`], and of the mapping
//! `rosbag2_bagfile_information` only the keys at its own indentation that are needed
//! (`version`, `storage_identifier`, `relative_file_paths`, `compression_format`), as rosbag2
//! (yaml-cpp) and rosbags write them: plain, single- or double-quoted scalars, and a block or
//! one-line flow list. Nested mappings (the topics, their QoS strings) are skipped unread.
//! A path is relative to the bag folder (to its parent for metadata versions 1 to 3, as
//! rosbag2 resolves them); an absolute one is kept.

use super::BagFormat;
use crate::error::{ReadError, ReadErrorKind};
use std::path::{Path, PathBuf};

/// The name of a bag folder's metadata file.
pub const METADATA_FILE: &str = "metadata.yaml";

/// The largest `metadata.yaml` read, bytes (1 MiB: a bag of thousands of topics and files
/// takes a few hundred KiB).
pub const MAX_METADATA_BYTES: u64 = 1 << 20;

/// A ROS 2 bag folder: its storage and its storage files, in the order the metadata lists them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BagFolder {
    /// The storage of every file.
    pub format: BagFormat,
    /// The storage files, in order.
    pub files: Vec<PathBuf>,
}

/// The bag folder `dir`, told by its `metadata.yaml`.
///
/// # Errors
/// [`ReadErrorKind::Unusable`] naming the folder when it holds no `metadata.yaml` (with the
/// bag files it holds, if any); naming `metadata.yaml` (and its line) when it cannot be read,
/// is larger than [`MAX_METADATA_BYTES`], is not UTF-8, lacks the keys above, names another
/// storage than `sqlite3` or `mcap`, a compression, no file, or a file that is not there.
pub fn read_bag_folder(dir: &Path) -> Result<BagFolder, ReadError> {
    let path = dir.join(METADATA_FILE);
    let input = path.display().to_string();
    if !path.is_file() {
        return Err(no_metadata(dir));
    }
    let text = read_metadata_text(&path, &input)?;
    let metadata = parse_metadata(&text, &input)?;
    folder_of(dir, metadata, &input)
}

/// The error for a folder without `metadata.yaml`, naming the bag files it holds.
fn no_metadata(dir: &Path) -> ReadError {
    let bag_files = bag_files_in(dir);
    let hint = match bag_files.is_empty() {
        true => String::new(),
        false => format!(
            "; it holds {}: give one of them, or restore the bag's metadata.yaml (ros2 bag \
             reindex)",
            bag_files.join(", ")
        ),
    };
    unusable(
        &dir.display().to_string(),
        format!(
            "a folder without {METADATA_FILE}: expected a ROS 2 bag folder (metadata.yaml and \
             the .db3 or .mcap files it lists, as ros2 bag record writes it) or a file{hint}"
        ),
    )
}

/// The names of the `.db3`, `.mcap` and `.bag` files in `dir`, sorted (at most 8).
fn bag_files_in(dir: &Path) -> Vec<String> {
    let is_bag = |name: &str| [".db3", ".mcap", ".bag"].iter().any(|e| name.ends_with(e));
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|entry| entry.file_name().into_string().ok())
        .filter(|name| is_bag(name))
        .collect();
    names.sort();
    names.truncate(8);
    names
}

/// The text of `metadata.yaml` at `path`, at most [`MAX_METADATA_BYTES`].
fn read_metadata_text(path: &Path, input: &str) -> Result<String, ReadError> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|file| file.take(MAX_METADATA_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| ReadError::new(input, None, ReadErrorKind::Read(e)))?;
    if bytes.len() as u64 > MAX_METADATA_BYTES {
        return Err(unusable(
            input,
            format!(
                "larger than {MAX_METADATA_BYTES} bytes: not the metadata of a ROS 2 bag \
                 (expected a short YAML file)"
            ),
        ));
    }
    String::from_utf8(bytes)
        .map_err(|_| unusable(input, "not UTF-8 text (expected YAML)".to_string()))
}

/// A `ReadErrorKind::Unusable` about `input`.
fn unusable(input: &str, what: String) -> ReadError {
    ReadError::new(input, None, ReadErrorKind::Unusable(what))
}

/// The keys of `rosbag2_bagfile_information` that are read.
#[derive(Debug, Default, PartialEq, Eq)]
struct Metadata {
    version: Option<u32>,
    storage: Option<String>,
    compression: Option<String>,
    files: Option<Vec<String>>,
}

/// One line of the file that holds something: its 1-based number, indentation and text
/// (trailing spaces off).
#[derive(Debug, Clone, Copy)]
struct Line<'a> {
    number: u64,
    indent: usize,
    text: &'a str,
}

/// The lines of `text` that hold something (not blank, not a comment, not a document marker).
fn content_lines(text: &str) -> Vec<Line<'_>> {
    text.lines()
        .enumerate()
        .filter_map(|(k, raw)| {
            let body = raw.trim_end();
            let text = body.trim_start_matches(' ');
            let marker = text.starts_with('#') || text == "---" || text == "...";
            (!text.is_empty() && !marker).then_some(Line {
                number: k as u64 + 1,
                indent: body.len() - text.len(),
                text,
            })
        })
        .collect()
}

/// The error about line `line` of `input`.
fn at_line(input: &str, line: u64, what: String) -> ReadError {
    ReadError::new(input, Some(line), ReadErrorKind::Unusable(what))
}

/// The keys read from the text of a `metadata.yaml`.
fn parse_metadata(text: &str, input: &str) -> Result<Metadata, ReadError> {
    let lines = content_lines(text);
    match lines.first() {
        Some(root)
            if root.indent == 0
                && key_value(root.text) == Some(("rosbag2_bagfile_information", "")) => {}
        _ => {
            return Err(unusable(
                input,
                "expected the mapping rosbag2_bagfile_information: on its first line (not the \
                 metadata of a ROS 2 bag)"
                    .to_string(),
            ));
        }
    }
    let body = &lines[1..];
    let child = body.first().map_or(0, |l| l.indent);
    let mut metadata = Metadata::default();
    for (k, line) in body.iter().enumerate() {
        if line.indent == 0 {
            break;
        }
        if line.indent != child {
            continue;
        }
        if let Some((key, value)) = key_value(line.text) {
            read_key(&mut metadata, (key, value), (*line, &body[k + 1..]), input)?;
        }
    }
    Ok(metadata)
}

/// `key: value` (value possibly empty) when `text` is a mapping entry with a plain key.
fn key_value(text: &str) -> Option<(&str, &str)> {
    let (key, value) = text.split_once(':')?;
    let plain = !key.is_empty() && !key.starts_with(['-', '"', '\'', '[', '{', '?']);
    let separated = value.is_empty() || value.starts_with(' ');
    (plain && separated).then(|| (key.trim_end(), value.trim_start()))
}

/// Records the entry `key: value` of `line` (the lines after it: a block list's items).
fn read_key(
    metadata: &mut Metadata,
    (key, value): (&str, &str),
    (line, after): (Line<'_>, &[Line<'_>]),
    input: &str,
) -> Result<(), ReadError> {
    let scalar = || scalar(value, line.number, input);
    match key {
        "version" => {
            let text = scalar()?;
            let version = text.parse().map_err(|_| {
                at_line(
                    input,
                    line.number,
                    format!("version {text:?}: expected a whole number"),
                )
            })?;
            metadata.version = Some(version);
        }
        "storage_identifier" => metadata.storage = Some(scalar()?),
        "compression_format" => metadata.compression = Some(scalar()?),
        "relative_file_paths" => {
            metadata.files = Some(match value.is_empty() {
                true => block_list(line, after, input)?,
                false => flow_list(value, line.number, input)?,
            });
        }
        _ => {}
    }
    Ok(())
}

/// The items of the block list under `key` (`- item` lines at its indentation or deeper).
fn block_list(key: Line<'_>, after: &[Line<'_>], input: &str) -> Result<Vec<String>, ReadError> {
    after
        .iter()
        .take_while(|l| l.indent >= key.indent && (l.text == "-" || l.text.starts_with("- ")))
        .map(|l| scalar(l.text[1..].trim_start(), l.number, input))
        .collect()
}

/// The items of a one-line flow list `[a, b]`.
fn flow_list(value: &str, line: u64, input: &str) -> Result<Vec<String>, ReadError> {
    let inner = value
        .strip_prefix('[')
        .and_then(|v| without_comment(v).strip_suffix(']'))
        .ok_or_else(|| {
            at_line(
                input,
                line,
                format!(
                    "relative_file_paths {value:?}: expected a list of file names ([a, b] on \
                     one line, or - items on the lines below)"
                ),
            )
        })?;
    split_items(inner)
        .into_iter()
        .filter(|item| !item.trim().is_empty())
        .map(|item| scalar(item.trim(), line, input))
        .collect()
}

/// `text` cut at the commas outside quotes.
fn split_items(text: &str) -> Vec<&str> {
    let (mut items, mut start, mut quote) = (Vec::new(), 0, None);
    for (k, c) in text.char_indices() {
        match (quote, c) {
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), _) if c == q => quote = None,
            (None, ',') => {
                items.push(&text[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    items.push(&text[start..]);
    items
}

/// A plain scalar without its trailing ` # comment`.
fn without_comment(text: &str) -> &str {
    text.find(" #").map_or(text, |k| &text[..k]).trim_end()
}

/// The value of a scalar: plain, single- or double-quoted (on one line).
fn scalar(text: &str, line: u64, input: &str) -> Result<String, ReadError> {
    let unclosed = || {
        at_line(
            input,
            line,
            format!("{text}: a quoted value not closed on its line"),
        )
    };
    if let Some(rest) = text.strip_prefix('"') {
        return double_quoted(rest).ok_or_else(unclosed);
    }
    if let Some(rest) = text.strip_prefix('\'') {
        return single_quoted(rest).ok_or_else(unclosed);
    }
    let plain = without_comment(text);
    Ok(match plain {
        "~" | "null" => String::new(),
        _ => plain.to_string(),
    })
}

/// The value of a double-quoted scalar whose opening quote is gone (`None`: not closed).
fn double_quoted(rest: &str) -> Option<String> {
    let mut out = String::new();
    let mut chars = rest.chars();
    while let Some(c) = chars.next() {
        match c {
            '"' => return Some(out),
            '\\' => out.push(match chars.next()? {
                'n' => '\n',
                't' => '\t',
                '0' => '\0',
                other => other,
            }),
            _ => out.push(c),
        }
    }
    None
}

/// The value of a single-quoted scalar whose opening quote is gone (`None`: not closed).
fn single_quoted(rest: &str) -> Option<String> {
    let mut out = String::new();
    let mut chars = rest.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, chars.peek()) {
            ('\'', Some('\'')) => {
                out.push('\'');
                chars.next();
            }
            ('\'', _) => return Some(out),
            _ => out.push(c),
        }
    }
    None
}

/// The bag folder `dir` of the keys read from its `metadata.yaml` (named `input`).
fn folder_of(dir: &Path, metadata: Metadata, input: &str) -> Result<BagFolder, ReadError> {
    let format = storage_format(metadata.storage.as_deref(), input)?;
    if let Some(compression) = metadata.compression.filter(|c| !c.is_empty()) {
        return Err(unusable(
            input,
            format!(
                "compression_format {compression}: the bag's files or messages are compressed \
                 by rosbag2, which is not read (write an uncompressed copy with ros2 bag \
                 convert, or record with --storage mcap and its chunk compression)"
            ),
        ));
    }
    let names = metadata.files.unwrap_or_default();
    if names.is_empty() {
        return Err(unusable(
            input,
            "relative_file_paths lists no file (expected the bag's storage files)".to_string(),
        ));
    }
    // rosbag2 before metadata version 4 wrote the paths with the bag folder's name in front.
    let base = match metadata.version {
        Some(v) if v < 4 => dir.parent().unwrap_or(dir),
        _ => dir,
    };
    let files = names.iter().map(|name| base.join(name)).collect::<Vec<_>>();
    if let Some((name, _)) = names.iter().zip(&files).find(|(_, f)| !f.is_file()) {
        return Err(unusable(
            input,
            format!(
                "relative_file_paths lists {name}, which is not a file in {} (a bag folder \
                 copied in part?)",
                base.display()
            ),
        ));
    }
    Ok(BagFolder { format, files })
}

/// The bag format of a `storage_identifier`.
fn storage_format(storage: Option<&str>, input: &str) -> Result<BagFormat, ReadError> {
    match storage {
        Some("sqlite3") => Ok(BagFormat::Ros2Db3),
        Some("mcap") => Ok(BagFormat::Ros2Mcap),
        Some(other) => Err(unusable(
            input,
            format!("storage_identifier {other:?}: expected sqlite3 or mcap"),
        )),
        None => Err(unusable(
            input,
            "no storage_identifier under rosbag2_bagfile_information (expected sqlite3 or mcap)"
                .to_string(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// As rosbag2 (yaml-cpp) writes it: list items indented under their key, a QoS string
    /// spanning lines, nested mappings holding keys of the same names.
    const ROSBAG2: &str = "rosbag2_bagfile_information:
  version: 5
  storage_identifier: sqlite3
  duration:
    nanoseconds: 2503055613
  topics_with_message_count:
    - topic_metadata:
        name: /imu
        type: sensor_msgs/msg/Imu
        serialization_format: cdr
        offered_qos_profiles: \"- history: 3\\n  depth: 0\\n  reliability: 1\\n  durability:\\
          \\ 2\\n\"
      message_count: 250
  compression_format: \"\"
  compression_mode: \"\"
  relative_file_paths:
    - run_0.db3
    - 'run_1.db3'
  files:
    - path: run_0.db3
      message_count: 125
";

    /// As rosbags (ruamel) writes it: list items at their key's indentation.
    const ROSBAGS: &str = "rosbag2_bagfile_information:
  version: 8
  storage_identifier: mcap
  relative_file_paths:
  - a.mcap
  - \"b.mcap\"  
  starting_time:
    nanoseconds_since_epoch: 1
  compression_format: ''
  files:
  - path: a.mcap
";

    fn parse(text: &str) -> Result<Metadata, String> {
        parse_metadata(text, "metadata.yaml").map_err(|e| e.to_string())
    }

    #[test]
    fn the_keys_of_both_writers_are_read_and_nested_ones_skipped() {
        let m = parse(ROSBAG2).unwrap();
        assert_eq!(m.version, Some(5));
        assert_eq!(m.storage.as_deref(), Some("sqlite3"));
        assert_eq!(m.compression.as_deref(), Some(""));
        assert_eq!(m.files.unwrap(), ["run_0.db3", "run_1.db3"]);
        let m = parse(ROSBAGS).unwrap();
        assert_eq!(m.storage.as_deref(), Some("mcap"));
        assert_eq!(m.files.unwrap(), ["a.mcap", "b.mcap"]);
        let flow = "rosbag2_bagfile_information:\n  storage_identifier: mcap # x\n  relative_file_paths: [a.mcap, 'b,c.mcap']\n";
        let m = parse(flow).unwrap();
        assert_eq!(m.storage.as_deref(), Some("mcap"));
        assert_eq!(m.files.unwrap(), ["a.mcap", "b,c.mcap"]);
    }

    #[test]
    fn text_that_is_not_bag_metadata_is_refused_in_words_never_a_panic() {
        let err = parse("imu: [1, 2]\n").unwrap_err();
        assert!(
            err.contains("expected the mapping rosbag2_bagfile_information"),
            "{err}"
        );
        let err = parse("").unwrap_err();
        assert!(err.contains("rosbag2_bagfile_information"), "{err}");
        let err = parse("rosbag2_bagfile_information:\n  version: five\n").unwrap_err();
        assert_eq!(
            err,
            "metadata.yaml:2: version \"five\": expected a whole number"
        );
        let err =
            parse("rosbag2_bagfile_information:\n  relative_file_paths: [a.db3\n").unwrap_err();
        assert!(
            err.contains("metadata.yaml:2: relative_file_paths"),
            "{err}"
        );
        let err =
            parse("rosbag2_bagfile_information:\n  storage_identifier: \"mcap\n").unwrap_err();
        assert!(err.contains("not closed"), "{err}");
        // Odd bytes and indentation anywhere: an answer, never a panic.
        for text in [
            "rosbag2_bagfile_information:\n- -\n  :\n\t\"\\",
            "é:\n  é: 'é",
            ":",
        ] {
            let _ = parse(text);
        }
    }

    #[test]
    fn a_storage_compression_or_empty_list_is_refused_naming_the_key() {
        let dir = Path::new("/nowhere");
        let of = |m: Metadata| folder_of(dir, m, "metadata.yaml").map_err(|e| e.to_string());
        let err = of(Metadata {
            storage: Some("rosbag_v2".into()),
            ..Metadata::default()
        })
        .unwrap_err();
        assert!(err.contains("storage_identifier \"rosbag_v2\": expected sqlite3 or mcap"));
        let err = of(Metadata {
            storage: Some("mcap".into()),
            compression: Some("zstd".into()),
            ..Metadata::default()
        })
        .unwrap_err();
        assert!(err.contains("compression_format zstd"), "{err}");
        let err = of(Metadata {
            storage: Some("mcap".into()),
            files: Some(vec![]),
            ..Metadata::default()
        })
        .unwrap_err();
        assert!(err.contains("lists no file"), "{err}");
        let err = of(Metadata {
            storage: Some("mcap".into()),
            files: Some(vec!["a.mcap".into()]),
            ..Metadata::default()
        })
        .unwrap_err();
        assert!(
            err.contains("lists a.mcap, which is not a file in /nowhere"),
            "{err}"
        );
    }
}
