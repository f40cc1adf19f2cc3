//! Production-lot manifests as TOML: the units of a lot and their chamber records.
//!
//! ```toml
//! name = "ADIS16364 lot 2026-11"
//!
//! [defaults]                      # all optional
//! temperatures_c = [0.0, 20.0]    # default: each file's temp_c mean
//! cutoff_hz = 0.4                 # conditioning before AR modelling, as `characterize`
//! transition_hz = 0.2
//! modelling_rate_hz = 1.0
//!
//! [[unit]]
//! serial = "SN0001"
//! files = ["SN0001/chamber_0C.csv", "SN0001/chamber_20C.csv"]
//! # temperatures_c = [0.1, 19.8]  # overrides the default for this unit
//! ```
//! Paths are relative to the manifest's folder (absolute paths are kept). A serial names the
//! unit's output folder, so it may hold only letters, digits, `.`, `_` and `-`, and may not
//! start with a dot. Unknown keys are errors.

use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use toml::Spanned;

/// Why a manifest cannot be used. Displays as `path:line: what` when tied to a line.
#[derive(Debug, thiserror::Error)]
pub enum ManifestError {
    /// The file cannot be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Not valid TOML for the schema (the parser's message carries line and column).
    #[error("{path}: {message}")]
    Parse {
        /// File.
        path: String,
        /// The parser's message.
        message: String,
    },
    /// A value the schema accepts but a lot cannot use.
    #[error("{path}:{line}: {message}")]
    Invalid {
        /// File.
        path: String,
        /// 1-based line of the offending value.
        line: usize,
        /// What is wrong and what was expected.
        message: String,
    },
}

/// A lot: its name, the conditioning shared by its units, and the units.
#[derive(Debug, Clone, PartialEq)]
pub struct LotManifest {
    /// Name of the lot.
    pub name: String,
    /// Conditioning settings given in `[defaults]` (`None`: the command's own).
    pub conditioning: Conditioning,
    /// The units, in file order.
    pub units: Vec<LotUnit>,
}

/// Conditioning settings of a lot; `None` leaves the command's value.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Conditioning {
    /// Kaiser cut-off before AR modelling, Hz.
    pub cutoff_hz: Option<f64>,
    /// Kaiser transition width, Hz.
    pub transition_hz: Option<f64>,
    /// Rate of the conditioned series, Hz.
    pub modelling_rate_hz: Option<f64>,
}

/// One unit of a lot.
#[derive(Debug, Clone, PartialEq)]
pub struct LotUnit {
    /// Serial number (also the name of its output folder).
    pub serial: String,
    /// Chamber records, one per temperature, resolved against the manifest's folder.
    pub files: Vec<PathBuf>,
    /// Temperatures of the files, °C, when given (the unit's own, else the defaults').
    pub temperatures_c: Option<Vec<f64>>,
    /// Line of the unit's serial in the manifest.
    pub line: usize,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ManifestFile {
    name: String,
    #[serde(default)]
    defaults: DefaultsFile,
    #[serde(default)]
    unit: Vec<UnitFile>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct DefaultsFile {
    temperatures_c: Option<Spanned<Vec<f64>>>,
    cutoff_hz: Option<Spanned<f64>>,
    transition_hz: Option<Spanned<f64>>,
    modelling_rate_hz: Option<Spanned<f64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct UnitFile {
    serial: Spanned<String>,
    files: Spanned<Vec<String>>,
    temperatures_c: Option<Spanned<Vec<f64>>>,
}

/// Most units of one lot: a thousand times a production batch. A manifest of 10^5 units
/// (6 MB) is read in 0.7 s and 250 MB, most of it the TOML parser's tree.
pub const MAX_LOT_UNITS: usize = 100_000;

/// Largest manifest text, bytes: room for [`MAX_LOT_UNITS`] units of a few files each, checked
/// before parsing so that the parser's tree (about 40 bytes per byte of text) stays bounded.
pub const MAX_MANIFEST_BYTES: usize = 8 << 20;

/// Reads and validates a manifest file.
///
/// # Errors
/// [`ManifestError`]: unreadable file, invalid TOML or unknown keys, no units, a repeated or
/// unusable serial, a unit without files, temperatures that do not match the files, or a
/// conditioning value that is not a positive number.
pub fn read_manifest(path: &Path) -> Result<LotManifest, ManifestError> {
    let name = path.display().to_string();
    let text = crate::read_document_text(path).map_err(|source| ManifestError::Read {
        path: name.clone(),
        source,
    })?;
    let folder = path.parent().unwrap_or(Path::new(""));
    parse_manifest(&text, &name, folder)
}

/// Parses manifest text; `name` names it in errors and relative paths resolve against `folder`.
///
/// # Errors
/// As [`read_manifest`].
pub fn parse_manifest(text: &str, name: &str, folder: &Path) -> Result<LotManifest, ManifestError> {
    if text.len() > MAX_MANIFEST_BYTES {
        return Err(ManifestError::Invalid {
            path: name.to_string(),
            line: 1,
            message: format!(
                "the manifest holds {} bytes, more than the {} MiB of a lot of {MAX_LOT_UNITS} units (split the lot)",
                text.len(),
                MAX_MANIFEST_BYTES >> 20
            ),
        });
    }
    let file: ManifestFile = toml::from_str(text).map_err(|e| ManifestError::Parse {
        path: name.to_string(),
        message: e.to_string(),
    })?;
    let invalid = |span: std::ops::Range<usize>, message: String| ManifestError::Invalid {
        path: name.to_string(),
        line: line_of(text, span.start),
        message,
    };
    if file.unit.is_empty() {
        return Err(invalid(
            0..0,
            "no [[unit]] entries (expected at least one unit)".into(),
        ));
    }
    if file.unit.len() > MAX_LOT_UNITS {
        let n = file.unit.len();
        return Err(invalid(
            file.unit[MAX_LOT_UNITS].serial.span(),
            format!("{n} units, more than the {MAX_LOT_UNITS} a lot may hold (split the lot)"),
        ));
    }
    let conditioning = conditioning_of(&file.defaults, &invalid)?;
    // Lines and serials indexed once: a lot of 10^5 units is read in time linear in its size.
    let lines = LineIndex::of(text);
    let mut first_line_of_serial: HashMap<&str, usize> = HashMap::with_capacity(file.unit.len());
    let mut units: Vec<LotUnit> = Vec::with_capacity(file.unit.len());
    for unit in &file.unit {
        let line = lines.line_of(unit.serial.span().start);
        let lot_unit = unit_of(
            unit,
            file.defaults.temperatures_c.as_ref(),
            folder,
            line,
            &invalid,
        )?;
        if let Some(first) = first_line_of_serial.insert(unit.serial.get_ref(), line) {
            return Err(invalid(
                unit.serial.span(),
                format!(
                    "serial \"{}\" already names the unit on line {first} (serials must be unique)",
                    lot_unit.serial
                ),
            ));
        }
        units.push(lot_unit);
    }
    Ok(LotManifest {
        name: file.name,
        conditioning,
        units,
    })
}

/// The 1-based line holding byte `offset` of `text`.
fn line_of(text: &str, offset: usize) -> usize {
    LineIndex::of(text).line_of(offset)
}

/// The byte offsets of a text's line ends, for line numbers by binary search.
struct LineIndex(Vec<usize>);

impl LineIndex {
    /// The index of `text`.
    fn of(text: &str) -> Self {
        Self(memchr::memchr_iter(b'\n', text.as_bytes()).collect())
    }

    /// The 1-based line holding byte `offset`: one more than the line ends before it.
    fn line_of(&self, offset: usize) -> usize {
        self.0.partition_point(|&end| end < offset) + 1
    }
}

/// The `[defaults]` conditioning, each value checked to be a positive number.
fn conditioning_of(
    defaults: &DefaultsFile,
    invalid: &impl Fn(std::ops::Range<usize>, String) -> ManifestError,
) -> Result<Conditioning, ManifestError> {
    let positive = |value: &Option<Spanned<f64>>, key: &str| match value {
        Some(v) if !(v.get_ref().is_finite() && *v.get_ref() > 0.0) => Err(invalid(
            v.span(),
            format!("{key} = {}: expected a positive number", v.get_ref()),
        )),
        _ => Ok(value.as_ref().map(|v| *v.get_ref())),
    };
    Ok(Conditioning {
        cutoff_hz: positive(&defaults.cutoff_hz, "cutoff_hz")?,
        transition_hz: positive(&defaults.transition_hz, "transition_hz")?,
        modelling_rate_hz: positive(&defaults.modelling_rate_hz, "modelling_rate_hz")?,
    })
}

/// One `[[unit]]`, validated, with its paths resolved.
fn unit_of(
    unit: &UnitFile,
    default_temperatures: Option<&Spanned<Vec<f64>>>,
    folder: &Path,
    line: usize,
    invalid: &impl Fn(std::ops::Range<usize>, String) -> ManifestError,
) -> Result<LotUnit, ManifestError> {
    let serial = unit.serial.get_ref();
    if !is_usable_serial(serial) {
        return Err(invalid(
            unit.serial.span(),
            format!(
                "serial \"{serial}\": expected letters, digits, '.', '_' or '-', not starting with '.' (it names the unit's output folder)"
            ),
        ));
    }
    let files = unit.files.get_ref();
    if files.is_empty() {
        return Err(invalid(
            unit.files.span(),
            format!("unit {serial}: files is empty (expected one chamber record per temperature)"),
        ));
    }
    let temperatures = unit.temperatures_c.as_ref().or(default_temperatures);
    if let Some(t) = temperatures {
        check_temperatures(serial, t, files.len(), invalid)?;
    }
    Ok(LotUnit {
        serial: serial.clone(),
        files: files.iter().map(|f| folder.join(f)).collect(),
        temperatures_c: temperatures.map(|t| t.get_ref().clone()),
        line,
    })
}

/// One finite temperature per file.
fn check_temperatures(
    serial: &str,
    temperatures: &Spanned<Vec<f64>>,
    file_count: usize,
    invalid: &impl Fn(std::ops::Range<usize>, String) -> ManifestError,
) -> Result<(), ManifestError> {
    let values = temperatures.get_ref();
    if values.len() != file_count {
        return Err(invalid(
            temperatures.span(),
            format!(
                "unit {serial}: {} temperatures for {file_count} files (expected one per file)",
                values.len()
            ),
        ));
    }
    match values.iter().find(|t| !t.is_finite()) {
        Some(t) => Err(invalid(
            temperatures.span(),
            format!("unit {serial}: temperature {t} is not a finite number of °C"),
        )),
        None => Ok(()),
    }
}

/// Letters, digits, `.`, `_`, `-`; not empty, not starting with a dot.
fn is_usable_serial(serial: &str) -> bool {
    !serial.is_empty()
        && !serial.starts_with('.')
        && serial
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'))
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"name = "lot A"

[defaults]
cutoff_hz = 0.5

[[unit]]
serial = "SN1"
files = ["a/0.csv", "a/20.csv"]
temperatures_c = [0.0, 20.0]

[[unit]]
serial = "SN2"
files = ["/abs/0.csv"]
"#;

    #[test]
    fn a_manifest_resolves_paths_against_its_folder() {
        let m = parse_manifest(GOOD, "lot.toml", Path::new("/data/lot")).unwrap();
        assert_eq!(m.name, "lot A");
        assert_eq!(m.conditioning.cutoff_hz, Some(0.5));
        assert_eq!(m.conditioning.transition_hz, None);
        assert_eq!(m.units.len(), 2);
        assert_eq!(m.units[0].files[1], PathBuf::from("/data/lot/a/20.csv"));
        assert_eq!(m.units[0].temperatures_c, Some(vec![0.0, 20.0]));
        assert_eq!(m.units[0].line, 7);
        assert_eq!(m.units[1].files[0], PathBuf::from("/abs/0.csv"));
        assert_eq!(m.units[1].temperatures_c, None);
    }

    #[test]
    fn a_lot_beyond_its_bounds_is_refused_before_it_is_parsed_or_run() {
        let unit = |k: usize| format!("[[unit]]\nserial = \"S{k}\"\nfiles = [\"a.csv\"]\n");
        let many: String =
            "name = \"big\"\n".to_string() + &(0..=MAX_LOT_UNITS).map(unit).collect::<String>();
        let e = parse_manifest(&many, "lot.toml", Path::new("")).unwrap_err();
        // Line 1 names the lot; unit k's serial is on line 3k + 3.
        let expected = format!(
            "lot.toml:{}: 100001 units, more than the 100000",
            3 * MAX_LOT_UNITS + 3
        );
        assert!(e.to_string().starts_with(&expected), "{e}");
        let long = format!("name = \"{}\"\n", "x".repeat(MAX_MANIFEST_BYTES));
        let e = parse_manifest(&long, "lot.toml", Path::new("")).unwrap_err();
        assert!(e.to_string().contains("more than the 8 MiB"), "{e}");
    }

    #[test]
    fn line_numbers_count_the_line_ends_before_the_offset() {
        let text = "a\nbc\n\nd";
        let lines: Vec<usize> = (0..text.len()).map(|k| line_of(text, k)).collect();
        assert_eq!(lines, [1, 1, 2, 2, 2, 3, 4]);
    }

    #[test]
    fn bad_manifests_name_the_line_and_what_was_expected() {
        let repeated = GOOD.replace("\"SN2\"", "\"SN1\"");
        let e = parse_manifest(&repeated, "lot.toml", Path::new("")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "lot.toml:12: serial \"SN1\" already names the unit on line 7 (serials must be unique)"
        );
        let unknown = GOOD.replace("cutoff_hz", "cutof_hz");
        let e = parse_manifest(&unknown, "lot.toml", Path::new("")).unwrap_err();
        assert!(e.to_string().contains("line 4"), "{e}");
        assert!(e.to_string().contains("cutof_hz"), "{e}");
        let short = GOOD.replace("[0.0, 20.0]", "[0.0]");
        let e = parse_manifest(&short, "lot.toml", Path::new("")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("lot.toml:9: unit SN1: 1 temperatures for 2 files"),
            "{e}"
        );
        let slash = GOOD.replace("\"SN1\"", "\"../x\"");
        let e = parse_manifest(&slash, "lot.toml", Path::new("")).unwrap_err();
        assert!(
            e.to_string().starts_with("lot.toml:7: serial \"../x\""),
            "{e}"
        );
        let negative = GOOD.replace("0.5", "-1");
        let e = parse_manifest(&negative, "lot.toml", Path::new("")).unwrap_err();
        assert!(
            e.to_string().starts_with("lot.toml:4: cutoff_hz = -1"),
            "{e}"
        );
        let e = parse_manifest("name = \"x\"\n", "lot.toml", Path::new("")).unwrap_err();
        assert!(e.to_string().contains("no [[unit]]"), "{e}");
    }
}
