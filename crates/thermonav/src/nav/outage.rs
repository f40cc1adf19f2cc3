//! GNSS outages: half-open windows [start, end) in which GNSS updates are withheld and the
//! solution is INS-only.

use crate::time::{Duration, NANOS_PER_SECOND, Timestamp};
use serde::Serialize;

/// One outage window [start, end).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Outage {
    /// First instant without GNSS.
    pub start: Timestamp,
    /// First instant with GNSS again.
    pub end: Timestamp,
}

impl Outage {
    /// Length, s.
    pub fn duration_s(&self) -> f64 {
        self.end.since(self.start).as_seconds()
    }

    /// True when `t` falls inside the window.
    pub fn contains(&self, t: Timestamp) -> bool {
        self.start <= t && t < self.end
    }
}

/// Why an outage list is unusable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OutageError {
    /// Zero or negative length.
    #[error("outage starting at {start_s} s has a non-positive duration")]
    Empty {
        /// Start, s.
        start_s: f64,
    },
    /// Two windows overlap.
    #[error(
        "outages overlap: the one starting at {first_start_s} s ends after {second_start_s} s, where the next begins"
    )]
    Overlap {
        /// Earlier window start, s.
        first_start_s: f64,
        /// Later window start, s.
        second_start_s: f64,
    },
    /// A window lies outside the data.
    #[error(
        "outage {start_s}-{end_s} s is not inside the data ({data_start_s}-{data_end_s} s){}",
        rel_hint(.start_s, .data_start_s)
    )]
    OutsideData {
        /// Window start, s.
        start_s: f64,
        /// Window end, s.
        end_s: f64,
        /// First data time, s.
        data_start_s: f64,
        /// Last data time, s.
        data_end_s: f64,
    },
    /// A specification that does not parse.
    #[error(
        "outage specification \"{spec}\": {reason} (expected START+DURATION[,START+DURATION...], every:FIRST,DURATION,PERIOD,COUNT or spread:COUNT,DURATION, in seconds on the files' t_s scale, or any of them after rel: in seconds from the first IMU sample)"
    )]
    Spec {
        /// The text given.
        spec: String,
        /// What is wrong.
        reason: String,
    },
    /// A time that cannot be represented.
    #[error("outage time {0} s is not a finite number of seconds")]
    Time(f64),
}

/// A sorted list of non-overlapping outages.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize)]
pub struct Outages {
    windows: Vec<Outage>,
}

fn timestamp(seconds: f64) -> Result<Timestamp, OutageError> {
    Timestamp::from_seconds(seconds).map_err(|_| OutageError::Time(seconds))
}

impl Outages {
    /// No outage.
    pub fn none() -> Self {
        Self::default()
    }

    /// Outages from (start, duration) pairs in seconds, in any order.
    ///
    /// # Errors
    /// [`OutageError`] for a non-positive duration or overlapping windows.
    pub fn from_start_duration(pairs: &[(f64, f64)]) -> Result<Self, OutageError> {
        let mut windows = Vec::with_capacity(pairs.len());
        for &(start_s, duration_s) in pairs {
            if duration_s.is_nan() || duration_s <= 0.0 {
                return Err(OutageError::Empty { start_s });
            }
            windows.push(Outage {
                start: timestamp(start_s)?,
                end: timestamp(start_s + duration_s)?,
            });
        }
        windows.sort_by_key(|w| w.start);
        for pair in windows.windows(2) {
            if pair[0].end > pair[1].start {
                return Err(OutageError::Overlap {
                    first_start_s: pair[0].start.as_seconds(),
                    second_start_s: pair[1].start.as_seconds(),
                });
            }
        }
        Ok(Self { windows })
    }

    /// `count` outages of `duration_s` every `period_s` from `first_start_s`.
    ///
    /// # Errors
    /// As [`Outages::from_start_duration`].
    pub fn periodic(
        first_start_s: f64,
        duration_s: f64,
        period_s: f64,
        count: usize,
    ) -> Result<Self, OutageError> {
        let pairs: Vec<_> = (0..count)
            .map(|k| (first_start_s + k as f64 * period_s, duration_s))
            .collect();
        Self::from_start_duration(&pairs)
    }

    /// `count` outages of `duration_s` spread evenly over the data [first, last]: equal gaps g
    /// before each outage and g/2 after the last, so count·(g + duration) + g/2 = span (the
    /// arrangement of the paper's Figure 6, with time to converge before the first).
    ///
    /// # Errors
    /// [`OutageError::Spec`] when they do not fit; otherwise as
    /// [`Outages::from_start_duration`].
    pub fn spread(
        first: Timestamp,
        last: Timestamp,
        count: usize,
        duration_s: f64,
    ) -> Result<Self, OutageError> {
        let span = last.since(first).as_seconds();
        let gap = (span - count as f64 * duration_s) / (count as f64 + 0.5);
        if count == 0 || gap.is_nan() || gap <= 0.0 {
            return Err(OutageError::Spec {
                spec: format!("spread:{count},{duration_s}"),
                reason: format!(
                    "{count} outages of {duration_s} s do not fit in {span:.1} s of data"
                ),
            });
        }
        let start = first.as_seconds() + gap;
        Self::periodic(start, duration_s, gap + duration_s, count)
    }

    /// Every window moved by exactly `offset`.
    pub fn offset(&self, offset: Duration) -> Self {
        let windows = self
            .windows
            .iter()
            .map(|w| Outage {
                start: w.start + offset,
                end: w.end + offset,
            })
            .collect();
        Self { windows }
    }

    /// Every window moved by `offset_s`.
    ///
    /// # Errors
    /// As [`Outages::from_start_duration`].
    pub fn shifted(&self, offset_s: f64) -> Result<Self, OutageError> {
        let pairs: Vec<(f64, f64)> = self
            .windows
            .iter()
            .map(|w| (w.start.as_seconds() + offset_s, w.duration_s()))
            .collect();
        Self::from_start_duration(&pairs)
    }

    /// Parses a specification and lays it over the data span `data`: see [`OutageSpec`].
    ///
    /// # Errors
    /// [`OutageError::Spec`] for text that does not parse; otherwise as
    /// [`OutageSpec::resolve`].
    pub fn from_spec(spec: &str, data: (Timestamp, Timestamp)) -> Result<Self, OutageError> {
        spec.parse::<OutageSpec>()?.resolve(data)
    }

    /// Checks that every window lies within [first, last] of the data.
    ///
    /// # Errors
    /// [`OutageError::OutsideData`] for the first window that does not.
    pub fn check_within(&self, first: Timestamp, last: Timestamp) -> Result<(), OutageError> {
        match self
            .windows
            .iter()
            .find(|w| w.start < first || w.end > last)
        {
            Some(w) => Err(OutageError::OutsideData {
                start_s: w.start.as_seconds(),
                end_s: w.end.as_seconds(),
                data_start_s: first.as_seconds(),
                data_end_s: last.as_seconds(),
            }),
            None => Ok(()),
        }
    }

    /// True when `t` is inside an outage.
    pub fn contains(&self, t: Timestamp) -> bool {
        let k = self.windows.partition_point(|w| w.start <= t);
        k > 0 && self.windows[k - 1].contains(t)
    }

    /// The windows, sorted.
    pub fn windows(&self) -> &[Outage] {
        &self.windows
    }
}

/// An outage specification as written, checked for form but not yet laid over any data.
///
/// Text forms (seconds on the data's time scale): `none`; a list
/// `START+DURATION[,START+DURATION...]`; a periodic generator
/// `every:FIRST,DURATION,PERIOD,COUNT`; or `spread:COUNT,DURATION`, spread over the data span
/// as [`Outages::spread`] does. Any of them after `rel:` counts its seconds from the first data
/// time instead (`rel:60+30` starts 60 s after the first IMU sample, whatever the files' time
/// scale, e.g. GPST seconds). Parsing needs no data, so a command can refuse a bad
/// specification before it reads a file.
#[derive(Debug, Clone, PartialEq)]
pub enum OutageSpec {
    /// No outage.
    None,
    /// Explicit windows, (start, duration) in seconds.
    List(Vec<(f64, f64)>),
    /// `count` windows of `duration_s` every `period_s` from `first_start_s`.
    Every {
        /// Start of the first window, s.
        first_start_s: f64,
        /// Length of each window, s.
        duration_s: f64,
        /// Start-to-start period, s.
        period_s: f64,
        /// Number of windows.
        count: usize,
    },
    /// `count` windows of `duration_s` spread over the data.
    Spread {
        /// Number of windows.
        count: usize,
        /// Length of each window, s.
        duration_s: f64,
    },
    /// Another form in seconds from the first data time (`rel:`).
    FromStart(Box<OutageSpec>),
}

impl std::str::FromStr for OutageSpec {
    type Err = OutageError;

    fn from_str(spec: &str) -> Result<Self, OutageError> {
        let text = spec.trim();
        if let Some(rest) = text.strip_prefix("rel:") {
            return relative_spec(spec, rest);
        }
        let parsed = if text.eq_ignore_ascii_case("none") || text.is_empty() {
            Ok(Self::None)
        } else if let Some(rest) = text.strip_prefix("spread:") {
            parse_spread(rest)
        } else if let Some(rest) = text.strip_prefix("every:") {
            parse_every(rest)
        } else {
            text.split(',')
                .map(parse_start_duration)
                .collect::<Result<Vec<_>, String>>()
                .map(Self::List)
        };
        let spec = parsed.map_err(|reason| OutageError::Spec {
            spec: spec.to_owned(),
            reason,
        })?;
        spec.check_durations()?;
        Ok(spec)
    }
}

/// The `rel:` form: another form, not itself relative.
fn relative_spec(spec: &str, rest: &str) -> Result<OutageSpec, OutageError> {
    if rest.trim().starts_with("rel:") {
        return Err(OutageError::Spec {
            spec: spec.to_owned(),
            reason: "rel: is given twice".into(),
        });
    }
    Ok(OutageSpec::FromStart(Box::new(rest.parse()?)))
}

impl std::fmt::Display for OutageSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::None => write!(f, "none"),
            Self::List(pairs) => {
                let items: Vec<String> = pairs.iter().map(|(s, d)| format!("{s}+{d}")).collect();
                write!(f, "{}", items.join(","))
            }
            Self::Every {
                first_start_s,
                duration_s,
                period_s,
                count,
            } => write!(f, "every:{first_start_s},{duration_s},{period_s},{count}"),
            Self::Spread { count, duration_s } => write!(f, "spread:{count},{duration_s}"),
            Self::FromStart(inner) => write!(f, "rel:{inner}"),
        }
    }
}

fn finite_number(text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| format!("\"{}\" is not a finite number", text.trim()))
}

fn whole_number(text: &str) -> Result<usize, String> {
    text.trim()
        .parse()
        .map_err(|_| format!("count \"{}\" is not a whole number", text.trim()))
}

fn parse_spread(rest: &str) -> Result<OutageSpec, String> {
    let (count, duration) = rest
        .split_once(',')
        .ok_or_else(|| "spread: takes two values".to_string())?;
    Ok(OutageSpec::Spread {
        count: whole_number(count)?,
        duration_s: finite_number(duration)?,
    })
}

fn parse_every(rest: &str) -> Result<OutageSpec, String> {
    let fields: Vec<&str> = rest.split(',').collect();
    let [first, duration, period, count] = fields[..] else {
        return Err("every: takes four values".into());
    };
    Ok(OutageSpec::Every {
        first_start_s: finite_number(first)?,
        duration_s: finite_number(duration)?,
        period_s: finite_number(period)?,
        count: whole_number(count)?,
    })
}

fn parse_start_duration(item: &str) -> Result<(f64, f64), String> {
    let (start, duration) = item
        .split_once('+')
        .ok_or_else(|| format!("\"{}\" is not START+DURATION", item.trim()))?;
    Ok((finite_number(start)?, finite_number(duration)?))
}

/// For a window before data whose times do not start near 0 (a clock's seconds, Unix or GPS
/// time): the hint to count from the first IMU sample with `rel:`.
fn rel_hint(start_s: &f64, data_start_s: &f64) -> String {
    if *start_s >= *data_start_s || *data_start_s < REL_HINT_AFTER_S {
        return String::new();
    }
    format!(
        ": the data's t_s start at {data_start_s} s, not near 0: to count seconds from the first IMU sample, put rel: before the specification (rel:every:..., rel:START+DURATION)"
    )
}

/// Data that start later than this, s, are on a clock's scale (not seconds from the start).
const REL_HINT_AFTER_S: f64 = 1.0e5;

impl OutageSpec {
    /// Every window must last a positive time.
    fn check_durations(&self) -> Result<(), OutageError> {
        let (start_s, duration_s) = match self {
            Self::None => return Ok(()),
            Self::List(pairs) => match pairs.iter().find(|(_, d)| *d <= 0.0) {
                Some(&pair) => pair,
                None => return Ok(()),
            },
            Self::Every {
                first_start_s,
                duration_s,
                ..
            } => (*first_start_s, *duration_s),
            Self::Spread { duration_s, .. } => (0.0, *duration_s),
            Self::FromStart(inner) => return inner.check_durations(),
        };
        if duration_s > 0.0 {
            Ok(())
        } else {
            Err(OutageError::Empty { start_s })
        }
    }

    /// The windows over the data span `data`, each inside it.
    ///
    /// A periodic list whose last window would end after the data is refused from its closed
    /// form before any window is made, so the memory used is bounded by the data, never by the
    /// count asked for.
    ///
    /// # Errors
    /// [`OutageError::OutsideData`] for a window outside the data, [`OutageError::Spec`] for
    /// spread outages that do not fit, and otherwise as [`Outages::from_start_duration`].
    pub fn resolve(&self, data: (Timestamp, Timestamp)) -> Result<Outages, OutageError> {
        let outages = match self {
            Self::FromStart(inner) => {
                let zero = Timestamp::from_nanos(0);
                let relative = inner.resolve((zero, zero + (data.1 - data.0)))?;
                return Ok(relative.offset(data.0 - zero));
            }
            Self::None => Outages::none(),
            Self::List(pairs) => Outages::from_start_duration(pairs)?,
            Self::Every {
                first_start_s,
                duration_s,
                period_s,
                count,
            } => {
                check_periodic_fits(*first_start_s, *duration_s, *period_s, *count, data)?;
                Outages::periodic(*first_start_s, *duration_s, *period_s, *count)?
            }
            Self::Spread { count, duration_s } => {
                Outages::spread(data.0, data.1, *count, *duration_s)?
            }
        };
        outages.check_within(data.0, data.1)?;
        Ok(outages)
    }
}

/// Refuses a periodic list whose first or last window leaves the data, from the closed form
/// of the last window (no list is built).
fn check_periodic_fits(
    first_start_s: f64,
    duration_s: f64,
    period_s: f64,
    count: usize,
    data: (Timestamp, Timestamp),
) -> Result<(), OutageError> {
    let Some(last_index) = count.checked_sub(1) else {
        return Ok(());
    };
    if last_index > 0 && period_s.abs() < duration_s {
        return Err(OutageError::Overlap {
            first_start_s,
            second_start_s: first_start_s + period_s,
        });
    }
    let last_start_s = first_start_s + last_index as f64 * period_s;
    let (lo, hi) = (data.0.as_seconds(), data.1.as_seconds());
    let outside = |start_s: f64| start_s < lo || start_s + duration_s > hi;
    for start_s in [first_start_s, last_start_s] {
        if outside(start_s) {
            return Err(OutageError::OutsideData {
                start_s,
                end_s: start_s + duration_s,
                data_start_s: lo,
                data_end_s: hi,
            });
        }
    }
    Ok(())
}

/// Whole seconds as a timestamp (for tests and generators).
pub fn seconds(s: i64) -> Timestamp {
    Timestamp::from_nanos(s * NANOS_PER_SECOND)
}

#[cfg(test)]
mod tests {
    use super::*;

    // Issue 16: `rel:` counts from the first data time, exactly (integer nanoseconds): on a
    // GPST-like scale starting at 1 400 000 000.25 s, rel:60+30 is the window starting
    // 60 s after it, and a relative window past the data's length is refused in relative
    // seconds, the user's own numbers.
    #[test]
    fn relative_outages_count_from_the_first_data_time() {
        let first = Timestamp::from_nanos(1_400_000_000_250_000_000);
        let data = (first, first + Duration::from_nanos(240 * NANOS_PER_SECOND));
        let o = Outages::from_spec("rel:60+30,150+30", data).unwrap();
        let after = |s: i64| first + Duration::from_nanos(s * NANOS_PER_SECOND);
        assert_eq!(
            o.windows()[0],
            Outage {
                start: after(60),
                end: after(90)
            }
        );
        assert_eq!(
            o.windows()[1],
            Outage {
                start: after(150),
                end: after(180)
            }
        );
        let every = Outages::from_spec("rel:every:60,30,90,2", data).unwrap();
        assert_eq!(every, o);
        let spec: OutageSpec = "rel:60+30".parse().unwrap();
        assert_eq!(spec.to_string(), "rel:60+30");
        let error = Outages::from_spec("rel:230+30", data).unwrap_err();
        assert!(
            error
                .to_string()
                .contains("outage 230-260 s is not inside the data (0-240 s)"),
            "{error}"
        );
        assert!(matches!(
            "rel:rel:1+2".parse::<OutageSpec>(),
            Err(OutageError::Spec { .. })
        ));
        assert!(matches!(
            "rel:5+0".parse::<OutageSpec>(),
            Err(OutageError::Empty { .. })
        ));
    }

    #[test]
    fn membership_is_half_open_and_overlaps_are_refused() {
        let o = Outages::periodic(100.0, 30.0, 60.0, 3).unwrap();
        assert!(!o.contains(seconds(99)) && o.contains(seconds(100)) && o.contains(seconds(129)));
        assert!(!o.contains(seconds(130)) && o.contains(seconds(160)) && !o.contains(seconds(250)));
        assert!(matches!(
            Outages::from_start_duration(&[(10.0, 20.0), (25.0, 5.0)]),
            Err(OutageError::Overlap { .. })
        ));
        assert!(matches!(
            Outages::from_start_duration(&[(10.0, 0.0)]),
            Err(OutageError::Empty { .. })
        ));
        assert!(o.check_within(seconds(0), seconds(400)).is_ok());
        let data = (seconds(0), seconds(1000));
        assert_eq!(Outages::from_spec("every:100,30,60,3", data).unwrap(), o);
        assert_eq!(
            Outages::from_spec("160+30, 100+30,220+30", data).unwrap(),
            o
        );
        assert_eq!(Outages::from_spec("none", data).unwrap(), Outages::none());
        for bad in [
            "100",
            "100+x",
            "every:1,2,3",
            "every:1,2,3,-1",
            "5+nan",
            "spread:20,100",
        ] {
            assert!(
                matches!(Outages::from_spec(bad, data), Err(OutageError::Spec { .. })),
                "{bad}"
            );
        }
        // Spread: 1700 s of data, 8 × 100 s: gap (1700 − 800) / 8.5 ≈ 105.9 s.
        let spread = Outages::from_spec("spread:8,100", (seconds(100), seconds(1800))).unwrap();
        let gap = 900.0 / 8.5;
        let w = spread.windows();
        assert_eq!(w.len(), 8);
        assert!((w[0].start.as_seconds() - (100.0 + gap)).abs() < 1e-6);
        assert!((1800.0 - w[7].end.as_seconds() - gap / 2.0).abs() < 1e-6);
        assert_eq!(o.shifted(5.0).unwrap().windows()[0].start, seconds(105));
        assert!(o.check_within(seconds(0), seconds(200)).is_err());
    }

    // A specification parses without data; laying it over the data refuses windows outside
    // it. A periodic list that cannot fit is refused from the closed form of its last window:
    // 1e12 windows would need 16 TB if they were built first.
    #[test]
    fn specifications_parse_alone_and_huge_periodic_lists_are_refused_unbuilt() {
        let spec: OutageSpec = "every:100,30,60,3".parse().unwrap();
        assert_eq!(spec.to_string(), "every:100,30,60,3");
        let data = (seconds(0), seconds(1000));
        assert_eq!(spec.resolve(data).unwrap().windows().len(), 3);
        for huge in ["every:10,5,20,1000000000000", "every:10,5,0,1000000000000"] {
            let spec: OutageSpec = huge.parse().unwrap();
            assert!(spec.resolve(data).is_err(), "{huge}");
        }
        assert!(matches!(
            "spread:2,0".parse::<OutageSpec>(),
            Err(OutageError::Empty { .. })
        ));
        assert!(matches!(
            "bogus".parse::<OutageSpec>(),
            Err(OutageError::Spec { .. })
        ));
        assert!(matches!(
            "990+20".parse::<OutageSpec>().unwrap().resolve(data),
            Err(OutageError::OutsideData { .. })
        ));
    }
}
