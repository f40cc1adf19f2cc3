//! Axes: linear or log₁₀ scales, the data domain an axis shows, its mapping to pixels and its
//! ticks.
//!
//! A log axis shows whole decades, so its decade ticks are equally spaced in pixels; a linear
//! axis shows the data with a margin and ticks at multiples of a 1-2-5 step.

/// Margin added on each side of a fitted linear axis, as a fraction of the data's span.
pub const LINEAR_PADDING: f64 = 0.04;

/// How data values are placed along an axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisScale {
    /// Position proportional to the value.
    Linear,
    /// Position proportional to log₁₀ of the value; values ≤ 0 are not drawn.
    Log10,
}

impl AxisScale {
    /// The value in the axis' linear coordinate, or `None` when it cannot be drawn.
    pub fn transform(self, value: f64) -> Option<f64> {
        match self {
            AxisScale::Linear => value.is_finite().then_some(value),
            AxisScale::Log10 => (value.is_finite() && value > 0.0).then(|| value.log10()),
        }
    }

    /// The data value at a linear coordinate.
    pub fn inverse(self, coordinate: f64) -> f64 {
        match self {
            AxisScale::Linear => coordinate,
            AxisScale::Log10 => 10f64.powf(coordinate),
        }
    }
}

/// One axis of a chart: its label (with the unit), scale and optional fixed range.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Label with the unit, e.g. `averaging time τ (s)`.
    pub label: String,
    /// Linear or logarithmic.
    pub scale: AxisScale,
    /// A fixed data range `(low, high)`; `None` fits the data.
    pub range: Option<(f64, f64)>,
}

impl Axis {
    /// A linear axis fitted to the data.
    pub fn linear(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            scale: AxisScale::Linear,
            range: None,
        }
    }

    /// A log₁₀ axis fitted to the data.
    pub fn log10(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            scale: AxisScale::Log10,
            range: None,
        }
    }

    /// The same axis showing exactly `low..=high` (data units).
    pub fn with_range(self, low: f64, high: f64) -> Self {
        Self {
            range: Some((low, high)),
            ..self
        }
    }
}

/// The part of an axis' linear coordinate that is shown: `low..high` in transformed units
/// (decades on a log axis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// The scale the bounds are expressed in.
    pub scale: AxisScale,
    /// Lower bound, transformed.
    pub low: f64,
    /// Upper bound, transformed, greater than `low`.
    pub high: f64,
    /// Distance between labelled ticks, transformed (one decade on a log axis).
    pub step: f64,
}

/// The domain an axis shows for `values`: its fixed range when it has a usable one, else the
/// data's extent widened to whole decades (log) or padded (linear).
pub fn domain_of(axis: &Axis, values: impl IntoIterator<Item = f64>) -> Domain {
    let scale = axis.scale;
    if let Some(domain) = axis.range.and_then(|range| fixed_domain(scale, range)) {
        return domain;
    }
    let (low, high) = values
        .into_iter()
        .filter_map(|v| scale.transform(v))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        });
    let (low, high) = if low.is_finite() {
        (low, high)
    } else {
        (0.0, 1.0)
    };
    match scale {
        AxisScale::Log10 => whole_decades(low, high),
        AxisScale::Linear => padded(low, high),
    }
}

fn fixed_domain(scale: AxisScale, (low, high): (f64, f64)) -> Option<Domain> {
    let (low, high) = (scale.transform(low)?, scale.transform(high)?);
    let step = match scale {
        AxisScale::Log10 => 1.0,
        AxisScale::Linear => nice_step((high - low) / 5.0),
    };
    (high > low).then_some(Domain {
        scale,
        low,
        high,
        step,
    })
}

fn whole_decades(low: f64, high: f64) -> Domain {
    // Values within a hundredth of a decade of a power of ten count as on it.
    let (low, high) = ((low + 0.01).floor(), (high - 0.01).ceil());
    Domain {
        scale: AxisScale::Log10,
        low,
        high: if high > low { high } else { low + 1.0 },
        step: 1.0,
    }
}

/// The data's extent padded by [`LINEAR_PADDING`] of its span on each side (a constant
/// series gets a span of its own), with a 1-2-5 tick step.
fn padded(low: f64, high: f64) -> Domain {
    let (low, high) = if high > low {
        (low, high)
    } else {
        let half = (low.abs() * 0.1).max(0.5);
        (low - half, high + half)
    };
    let pad = (high - low) * LINEAR_PADDING;
    let (low, high) = (low - pad, high + pad);
    Domain {
        scale: AxisScale::Linear,
        low,
        high,
        step: nice_step((high - low) / 5.0),
    }
}

/// The 1, 2 or 5 × 10ᵏ step nearest to `raw` (on a log scale).
pub fn nice_step(raw: f64) -> f64 {
    let raw = if raw > 0.0 && raw.is_finite() {
        raw
    } else {
        1.0
    };
    let power = 10f64.powf(raw.log10().floor());
    let fraction = raw / power;
    let nice = if fraction < 2f64.sqrt() {
        1.0
    } else if fraction < 10f64.sqrt() {
        2.0
    } else if fraction < 50f64.sqrt() {
        5.0
    } else {
        10.0
    };
    nice * power
}

/// The pixel interval a domain is drawn on. `start` is where `domain.low` lands, so a
/// vertical axis has `start` below `end` on screen (larger pixel value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mapping {
    /// The shown domain.
    pub domain: Domain,
    /// Pixel of the lower bound.
    pub start: f64,
    /// Pixel of the upper bound.
    pub end: f64,
}

impl Mapping {
    /// The pixel of a data value, or `None` when the scale cannot place it (log of v ≤ 0).
    /// Values outside the domain map outside `start..end`.
    pub fn pixel(&self, value: f64) -> Option<f64> {
        let t = self.domain.scale.transform(value)?;
        Some(self.pixel_of_coordinate(t))
    }

    /// The pixel of a transformed coordinate.
    pub fn pixel_of_coordinate(&self, t: f64) -> f64 {
        let fraction = (t - self.domain.low) / (self.domain.high - self.domain.low);
        self.start + fraction * (self.end - self.start)
    }
}

/// A tick: its data value and its label.
#[derive(Debug, Clone, PartialEq)]
pub struct Tick {
    /// Data value.
    pub value: f64,
    /// Label text.
    pub label: TickLabel,
}

/// How a tick is labelled.
#[derive(Debug, Clone, PartialEq)]
pub enum TickLabel {
    /// A plain number.
    Plain(String),
    /// 10 to this power.
    PowerOfTen(i32),
}

/// Labelled ticks: each decade of a log domain, or every 1-2-5 step of a linear one.
pub fn major_ticks(domain: &Domain) -> Vec<Tick> {
    match domain.scale {
        AxisScale::Log10 => decade_exponents(domain)
            .map(|k| Tick {
                value: 10f64.powi(k),
                label: TickLabel::PowerOfTen(k),
            })
            .collect(),
        AxisScale::Linear => {
            let step = domain.step;
            let first = (domain.low / step - 1e-9).ceil() as i64;
            let last = (domain.high / step + 1e-9).floor() as i64;
            (first..=last)
                .map(|i| {
                    let value = i as f64 * step;
                    Tick {
                        value,
                        label: TickLabel::Plain(plain_number(value, step)),
                    }
                })
                .collect()
        }
    }
}

/// Unlabelled ticks at 2..9 × 10ᵏ inside a log domain (none on a linear axis).
pub fn minor_ticks(domain: &Domain) -> Vec<f64> {
    if domain.scale != AxisScale::Log10 || domain.high - domain.low > 6.0 {
        return Vec::new();
    }
    let first = domain.low.floor() as i32;
    let last = domain.high.ceil() as i32;
    (first..last)
        .flat_map(|k| (2..10).map(move |m| f64::from(m) * 10f64.powi(k)))
        .filter(|v| (domain.low..=domain.high).contains(&v.log10()))
        .collect()
}

fn decade_exponents(domain: &Domain) -> impl Iterator<Item = i32> {
    let first = (domain.low - 1e-9).ceil() as i32;
    let last = (domain.high + 1e-9).floor() as i32;
    first..=last
}

/// `value` with as many decimals as `step` needs; in exponent form (`1.4e6`) when the step is
/// below 10⁻³ or above 10⁴.
pub fn plain_number(value: f64, step: f64) -> String {
    let step_magnitude = step.abs().log10().floor();
    if (value / step).abs() < 0.5 {
        return "0".to_owned();
    }
    if !(-3.0..=4.0).contains(&step_magnitude) {
        let digits = (value.abs().log10().floor() - step_magnitude).max(0.0) as usize;
        return format!("{value:.digits$e}");
    }
    let decimals = (-step_magnitude).max(0.0) as usize;
    format!("{value:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_log_domain_covers_whole_decades_around_the_data() {
        let d = domain_of(&Axis::log10("τ (s)"), [0.013, 4.0, 650.0, -1.0, 0.0]);
        let on_decades = domain_of(&Axis::log10("τ (s)"), [0.009_999_9, 1_000.000_1]);
        assert_eq!((on_decades.low, on_decades.high), (-2.0, 3.0));
        assert_eq!((d.low, d.high), (-2.0, 3.0));
        let values: Vec<f64> = major_ticks(&d).iter().map(|t| t.value).collect();
        assert_eq!(values, [0.01, 0.1, 1.0, 10.0, 100.0, 1000.0]);
    }

    #[test]
    fn a_linear_domain_pads_the_data_and_ticks_inside_it() {
        let d = domain_of(&Axis::linear("T (°C)"), [-38.0, 61.0]);
        let pad = 99.0 * LINEAR_PADDING;
        assert!((d.low - (-38.0 - pad)).abs() < 1e-12 && (d.high - (61.0 + pad)).abs() < 1e-12);
        let labels: Vec<TickLabel> = major_ticks(&d).into_iter().map(|t| t.label).collect();
        assert_eq!(labels.first(), Some(&TickLabel::Plain("-40".into())));
        assert_eq!(labels.last(), Some(&TickLabel::Plain("60".into())));
        assert_eq!(labels.len(), 6);
    }

    #[test]
    fn a_fixed_range_is_kept_and_a_constant_series_still_gets_a_span() {
        let d = domain_of(&Axis::linear("x").with_range(2.0, 3.0), [0.0, 100.0]);
        assert_eq!((d.low, d.high), (2.0, 3.0));
        let flat = domain_of(&Axis::linear("x"), [5.0, 5.0]);
        assert!(flat.low < 5.0 && flat.high > 5.0);
        let empty = domain_of(&Axis::log10("x"), []);
        assert!(empty.high > empty.low);
    }

    #[test]
    fn the_mapping_is_affine_in_the_transformed_value() {
        let m = Mapping {
            domain: Domain {
                scale: AxisScale::Log10,
                low: -1.0,
                high: 2.0,
                step: 1.0,
            },
            start: 400.0,
            end: 100.0,
        };
        assert_eq!(m.pixel(0.1), Some(400.0));
        assert_eq!(m.pixel(100.0), Some(100.0));
        assert!((m.pixel(10f64.sqrt()).unwrap() - 250.0).abs() < 1e-9);
        assert_eq!(m.pixel(0.0), None);
    }

    #[test]
    fn steps_are_one_two_or_five_times_a_power_of_ten() {
        assert_eq!(nice_step(0.3), 0.2);
        assert_eq!(nice_step(0.4), 0.5);
        assert_eq!(nice_step(13.0), 10.0);
        assert_eq!(nice_step(2.0), 2.0);
        assert!((nice_step(0.00071) - 0.001).abs() < 1e-15);
        assert_eq!(plain_number(0.30000000000000004, 0.1), "0.3");
        assert_eq!(plain_number(-0.0, 0.5), "0");
        assert_eq!(plain_number(1_400_000.000_000_1, 200_000.0), "1.4e6");
        assert_eq!(plain_number(-0.000_35, 0.000_05), "-3.5e-4");
        assert_eq!(plain_number(25.0, 5.0), "25");
    }
}
