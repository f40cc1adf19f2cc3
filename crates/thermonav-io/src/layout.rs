//! From a header line to what each column holds: a slot in the row's value array and the unit
//! to convert from.

use crate::error::ReadErrorKind;
use thermonav::units;

/// Name of the time column of every format.
pub(crate) const TIME_COLUMN: &str = "t_s";

/// Most values one row can hold.
pub(crate) const MAX_SLOTS: usize = 16;

/// Unit of a column in a file; every value is converted to SI once, as it is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Unit {
    /// Already SI (rad, rad/s, m, m/s, m/s², °C).
    Si,
    /// Degrees (angles) to rad.
    Deg,
    /// deg/s to rad/s.
    DegPerS,
    /// deg/h to rad/s.
    DegPerH,
    /// Standard gravities to m/s².
    G,
    /// Milli-g to m/s².
    MilliG,
}

impl Unit {
    /// The value in SI.
    #[inline]
    pub(crate) fn to_si(self, value: f64) -> f64 {
        match self {
            Unit::Si => value,
            Unit::Deg | Unit::DegPerS => units::deg_to_rad(value),
            Unit::DegPerH => units::deg_per_h_to_rad_per_s(value),
            Unit::G => units::g_to_m_per_s2(value),
            Unit::MilliG => units::mg_to_m_per_s2(value),
        }
    }
}

/// One accepted header name.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ColumnSpec {
    /// Header name, unit suffix included.
    pub(crate) name: &'static str,
    /// Where the converted value goes in the row's array.
    pub(crate) slot: usize,
    /// Unit of the values in the file.
    pub(crate) unit: Unit,
}

/// A file format's accepted columns (besides `t_s`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Schema {
    /// Every accepted name.
    pub(crate) columns: &'static [ColumnSpec],
    /// The accepted names as told to the user.
    pub(crate) expected: &'static str,
    /// What may stand in for a missing `t_s`, as ` (or …)`, or empty.
    pub(crate) time_alternatives: &'static str,
}

/// What one column of a file holds.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Target {
    /// The time, in seconds.
    Time,
    /// A value for `slot`, in `unit`.
    Value {
        /// Index in the row's value array.
        slot: usize,
        /// Unit in the file.
        unit: Unit,
    },
}

/// The value slots of `targets` in order when the first is the time and every other a value in
/// SI ([`Layout::si_value_slots`]).
fn si_value_slots(targets: &[Target]) -> Option<Vec<usize>> {
    let (Target::Time, values) = targets.split_first()? else {
        return None;
    };
    (values.iter())
        .map(|target| match *target {
            Target::Value {
                slot,
                unit: Unit::Si,
            } => Some(slot),
            _ => None,
        })
        .collect()
}

/// The columns of one file, in file order.
#[derive(Debug, Clone)]
pub(crate) struct Layout {
    /// The header line as read.
    pub(crate) header: String,
    /// Header names, in file order.
    pub(crate) names: Vec<String>,
    /// What each column holds, in file order.
    pub(crate) targets: Vec<Target>,
    /// For each slot, the file column that fills it.
    slot_columns: [Option<usize>; MAX_SLOTS],
    /// When the time comes first and every other column holds a value already in SI (the
    /// canonical files), the slots of those values in file order: the row decoder then walks
    /// them without looking at each column's target and unit.
    pub(crate) si_value_slots: Option<Vec<usize>>,
}

impl Layout {
    /// Maps each header name to its target; unknown and repeated names are errors, and so is a
    /// missing `t_s` (or, with `rate_hz`, a present one: the times come from one source).
    /// Names are trimmed of surrounding spaces.
    pub(crate) fn from_header(
        header: &str,
        schema: &Schema,
        rate_hz: Option<f64>,
    ) -> Result<Self, ReadErrorKind> {
        let mut layout = Layout {
            header: header.to_owned(),
            names: Vec::new(),
            targets: Vec::new(),
            slot_columns: [None; MAX_SLOTS],
            si_value_slots: None,
        };
        let mut time_column = None;
        for name in header.split(',').map(str::trim) {
            let index = layout.names.len();
            let target = target_of(name, schema).map_err(|e| with_kind_hint(e, header, schema))?;
            let claimed = match target {
                Target::Time => &mut time_column,
                Target::Value { slot, .. } => &mut layout.slot_columns[slot],
            };
            if let Some(first) = claimed.replace(index) {
                return Err(ReadErrorKind::DuplicateColumn {
                    first: layout.names[first].clone(),
                    second: name.to_owned(),
                });
            }
            layout.names.push(name.to_owned());
            layout.targets.push(target);
        }
        layout.si_value_slots = si_value_slots(&layout.targets);
        match (time_column, rate_hz) {
            (None, None) => Err(missing(TIME_COLUMN, schema.time_alternatives)),
            (Some(_), Some(rate_hz)) => Err(ReadErrorKind::TimeColumnWithRate { rate_hz }),
            _ => Ok(layout),
        }
    }

    /// Header name of the column filling `slot`, if any.
    pub(crate) fn name_of(&self, slot: usize) -> Option<&str> {
        self.slot_columns[slot].map(|column| self.names[column].as_str())
    }

    /// Whether some column fills `slot`.
    pub(crate) fn has(&self, slot: usize) -> bool {
        self.slot_columns[slot].is_some()
    }

    /// Fails with [`ReadErrorKind::MissingColumn`] unless `slot` is filled.
    pub(crate) fn require(
        &self,
        slot: usize,
        name: &'static str,
        alternatives: &'static str,
    ) -> Result<(), ReadErrorKind> {
        match self.has(slot) {
            true => Ok(()),
            false => Err(missing(name, alternatives)),
        }
    }

    /// Whether an all-or-nothing group of `(slot, name)` columns is present; a partial group is
    /// an error.
    pub(crate) fn group_presence(
        &self,
        group: &'static str,
        members: &[(usize, &'static str)],
    ) -> Result<Presence, ReadErrorKind> {
        let present = members.iter().find_map(|&(slot, _)| self.name_of(slot));
        let absent = members.iter().find(|&&(slot, _)| !self.has(slot));
        match (present, absent) {
            (None, _) => Ok(Presence::Absent),
            (Some(_), None) => Ok(Presence::Present),
            (Some(present), Some(&(_, missing))) => Err(ReadErrorKind::PartialGroup {
                group,
                present: present.to_owned(),
                missing,
            }),
        }
    }
}

/// Whether an optional group of columns is in a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Presence {
    /// Every column of the group is there.
    Present,
    /// No column of the group is there.
    Absent,
}

fn target_of(name: &str, schema: &Schema) -> Result<Target, ReadErrorKind> {
    if name == TIME_COLUMN {
        return Ok(Target::Time);
    }
    schema
        .columns
        .iter()
        .find(|spec| spec.name == name)
        .map(|spec| Target::Value {
            slot: spec.slot,
            unit: spec.unit,
        })
        .ok_or_else(|| ReadErrorKind::UnknownColumn {
            name: name.to_owned(),
            expected: schema.expected,
            hint: String::new(),
        })
}

/// A kind of CSV our readers take: its name, a test of a column only it has, and the option
/// that takes it on `integrate` and `evaluate`.
type CsvKind = (&'static str, fn(&str) -> bool, &'static str);

/// The kinds, in the order they are recognised (a trajectory has lat_deg too).
const CSV_KINDS: [CsvKind; 3] = [
    (
        "an IMU CSV",
        |name| {
            ["gx_", "gy_", "gz_", "ax_", "ay_", "az_"]
                .iter()
                .any(|p| name.starts_with(p))
        },
        "--imu",
    ),
    (
        "a trajectory CSV (a reference or a solution)",
        |name| matches!(name, "roll_deg" | "pitch_deg" | "yaw_deg"),
        "--reference",
    ),
    (
        "a GNSS CSV",
        |name| name == "lat_deg" || name.starts_with("sd_"),
        "--gnss",
    ),
];

/// The kind whose column is among `names`, if any.
fn kind_of<'a>(names: impl Iterator<Item = &'a str> + Clone) -> Option<&'static CsvKind> {
    CSV_KINDS.iter().find(|(_, has, _)| names.clone().any(has))
}

/// An unknown column's error with a hint when the header is another kind of our CSVs than
/// the reader's (files given to the wrong option).
fn with_kind_hint(error: ReadErrorKind, header: &str, schema: &Schema) -> ReadErrorKind {
    let ReadErrorKind::UnknownColumn { name, expected, .. } = error else {
        return error;
    };
    let found = kind_of(header.split(',').map(str::trim));
    let own = kind_of(schema.columns.iter().map(|c| c.name));
    let hint = match (found, own) {
        (Some(found), own) if own.map(|o| o.0) != Some(found.0) => {
            format!(
                ": this looks like {}: was it meant for {}?",
                found.0, found.2
            )
        }
        _ => String::new(),
    };
    ReadErrorKind::UnknownColumn {
        name,
        expected,
        hint,
    }
}

fn missing(name: &'static str, alternatives: &'static str) -> ReadErrorKind {
    ReadErrorKind::MissingColumn { name, alternatives }
}
