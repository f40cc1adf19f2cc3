//! Allan deviation per channel on log-log axes: one panel per sensor (their units differ), a
//! line per channel, its confidence band, and the IEEE 952 noise terms as markers where each
//! term's asymptote is read.

use super::{DisplayUnits, channel_color, sensor_title};
use crate::chart::{Chart, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;
use thermonav::imu::{Channel, Sensor};
use thermonav::stoch::allan::DeviationKind;
use thermonav::stoch::bank::{ChannelModel, TemperatureEntry};
use thermonav::stoch::gmwm::{Term, terms_from_parameters};
use thermonav::stoch::noise_terms::BIAS_INSTABILITY_FACTOR;

/// A deviation curve of one channel (Allan or another kind of the family), SI (rad/s or m/s²;
/// times seconds for the time deviation).
#[derive(Debug, Clone, PartialEq)]
pub struct AllanCurve {
    /// The channel.
    pub channel: Channel,
    /// Averaging times, s.
    pub tau_s: Vec<f64>,
    /// The deviation at each τ (the figure's kind).
    pub deviation: Vec<f64>,
    /// Confidence limits, when known.
    pub confidence: Option<ConfidenceBand>,
    /// Noise terms read off the curve.
    pub terms: Vec<NoiseTermReading>,
    /// A composite model's implied curve, when one was fitted.
    pub model: Option<ImpliedCurve>,
}

/// The Allan deviation a fitted composite implies at the curve's τ: each process and their
/// sum (σ²_A = Σ 2 ν²_k(2m), [`thermonav::stoch::gmwm::Term::allan_variance`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ImpliedCurve {
    /// The composite (`wn+rw+2gm`).
    pub name: String,
    /// Each process: its label (`WN`, `GM1`, ...) and its deviation at each τ.
    pub components: Vec<(String, Vec<f64>)>,
    /// The sum's deviation at each τ.
    pub total: Vec<f64>,
    /// The shortest τ the model was fitted at, s (it is drawn from there on).
    pub from_tau_s: f64,
}

impl ImpliedCurve {
    /// The curve of `terms` (sampled every `dt_s`) at averaging times `tau_s`.
    pub fn of(name: &str, terms: &[Term], dt_s: f64, tau_s: &[f64]) -> Self {
        let deviation = |term: &Term| {
            tau_s
                .iter()
                .map(|&t| term.allan_variance(t / dt_s).sqrt())
                .collect::<Vec<f64>>()
        };
        let mut gm = 0;
        let components: Vec<(String, Vec<f64>)> = terms
            .iter()
            .map(|term| {
                let label = match term {
                    Term::GaussMarkov { .. } => {
                        gm += 1;
                        format!("GM{gm}")
                    }
                    _ => term.label().to_owned(),
                };
                (label, deviation(term))
            })
            .collect();
        let total = (0..tau_s.len())
            .map(|i| {
                components
                    .iter()
                    .map(|(_, d)| d[i] * d[i])
                    .sum::<f64>()
                    .sqrt()
            })
            .collect();
        ImpliedCurve {
            name: name.to_owned(),
            components,
            total,
            from_tau_s: tau_s.first().copied().unwrap_or(0.0),
        }
    }
}

/// Confidence limits of an Allan curve, one pair per τ.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfidenceBand {
    /// Confidence level, in (0, 1).
    pub level: f64,
    /// Lower limits.
    pub low: Vec<f64>,
    /// Upper limits.
    pub high: Vec<f64>,
}

/// The IEEE Std 952 noise terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseTerm {
    /// Quantisation Q: σ = √3 Q / τ.
    Quantization,
    /// Angle / velocity random walk N: σ = N / √τ.
    RandomWalk,
    /// Bias instability B: σ = 0.664 B at the flat minimum.
    BiasInstability,
    /// Rate random walk K: σ = K √(τ/3).
    RateRandomWalk,
    /// Rate ramp R: σ = R τ / √2.
    RateRamp,
}

/// A noise term's value (SI of the curve's rate unit per its power of time) and the τ range
/// it was read over, when known.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NoiseTermReading {
    /// Which term.
    pub term: NoiseTerm,
    /// Its coefficient, SI.
    pub value_si: f64,
    /// Shortest and longest τ of the region it was read over, s.
    pub tau_range_s: Option<(f64, f64)>,
}

impl NoiseTerm {
    /// The term's asymptote σ(τ) for coefficient `value`.
    pub fn asymptote(self, value: f64, tau_s: f64) -> f64 {
        match self {
            NoiseTerm::Quantization => 3f64.sqrt() * value / tau_s,
            NoiseTerm::RandomWalk => value / tau_s.sqrt(),
            NoiseTerm::BiasInstability => BIAS_INSTABILITY_FACTOR * value,
            NoiseTerm::RateRandomWalk => value * (tau_s / 3.0).sqrt(),
            NoiseTerm::RateRamp => value * tau_s / 2f64.sqrt(),
        }
    }

    /// Where the coefficient is read on its asymptote (the slope's textbook reading point):
    /// τ = √3, 1, 3 and √2 s for Q, N, K and R; `minimum_tau_s` for B.
    pub fn reading_tau_s(self, minimum_tau_s: f64) -> f64 {
        match self {
            NoiseTerm::Quantization => 3f64.sqrt(),
            NoiseTerm::RandomWalk => 1.0,
            NoiseTerm::BiasInstability => minimum_tau_s,
            NoiseTerm::RateRandomWalk => 3.0,
            NoiseTerm::RateRamp => 2f64.sqrt(),
        }
    }

    fn shape(self) -> Shape {
        match self {
            NoiseTerm::Quantization | NoiseTerm::RateRamp => Shape::Diamond,
            NoiseTerm::RandomWalk => Shape::Circle,
            NoiseTerm::BiasInstability => Shape::Square,
            NoiseTerm::RateRandomWalk => Shape::Triangle,
        }
    }

    fn legend(self) -> &'static str {
        match self {
            NoiseTerm::Quantization => "Q: quantisation (τ = √3 s)",
            NoiseTerm::RandomWalk => "N: random walk (τ = 1 s)",
            NoiseTerm::BiasInstability => "B: bias instability (0.664 B)",
            NoiseTerm::RateRandomWalk => "K: rate random walk (τ = 3 s)",
            NoiseTerm::RateRamp => "R: rate ramp (τ = √2 s)",
        }
    }
}

/// The figure of the overlapping Allan deviation: [`deviation_figure`] of
/// [`DeviationKind::Adev`].
pub fn allan_deviation_figure(title: &str, curves: &[AllanCurve], units: DisplayUnits) -> String {
    deviation_figure(title, DeviationKind::Adev, curves, units)
}

/// The name of a deviation kind as a figure states it, e.g. "Modified Allan deviation".
pub fn deviation_name(kind: DeviationKind) -> &'static str {
    match kind {
        DeviationKind::Adev => "Allan deviation",
        DeviationKind::Mdev => "Modified Allan deviation",
        DeviationKind::Hdev => "Hadamard deviation",
        DeviationKind::Ohdev => "Overlapping Hadamard deviation",
        DeviationKind::Tdev => "Time deviation",
        DeviationKind::Totdev => "Total deviation",
    }
}

/// The y-axis label of `kind` in the display unit of a rate `rate_unit`: the name, its symbol,
/// and the unit (the rate's times seconds for the time deviation).
fn deviation_axis_label(kind: DeviationKind, rate_unit: &str) -> String {
    let (symbol, unit) = match kind {
        DeviationKind::Adev => ("σ(τ)", rate_unit.to_owned()),
        DeviationKind::Mdev => ("mod σ(τ)", rate_unit.to_owned()),
        DeviationKind::Hdev | DeviationKind::Ohdev => ("Hσ(τ)", rate_unit.to_owned()),
        DeviationKind::Tdev => ("σx(τ)", format!("{rate_unit}·s")),
        DeviationKind::Totdev => ("σtotal(τ)", rate_unit.to_owned()),
    };
    format!("{} {symbol} ({unit})", deviation_name(kind))
}

/// The figure of curves of deviation `kind`: a log-log panel per sensor present in `curves`.
pub fn deviation_figure(
    title: &str,
    kind: DeviationKind,
    curves: &[AllanCurve],
    units: DisplayUnits,
) -> String {
    let panels = [Sensor::Gyro, Sensor::Accelerometer]
        .into_iter()
        .filter_map(|sensor| {
            let of_sensor: Vec<&AllanCurve> = curves
                .iter()
                .filter(|c| c.channel.sensor() == sensor)
                .collect();
            (!of_sensor.is_empty()).then(|| allan_panel(sensor, kind, &of_sensor, units))
        })
        .collect();
    Figure::stacked(title, panels).to_svg()
}

fn allan_panel(
    sensor: Sensor,
    kind: DeviationKind,
    curves: &[&AllanCurve],
    units: DisplayUnits,
) -> Chart {
    let shown = |v: f64| units.rate(sensor, v);
    let mut bands = Vec::new();
    let mut lines = Vec::new();
    let mut terms = Vec::new();
    for curve in curves {
        let color = channel_color(curve.channel);
        if let Some(band) = &curve.confidence {
            bands.push(Layer::Band {
                name: format!("{:.1} % confidence", band.level * 100.0),
                x: curve.tau_s.clone(),
                low: band.low.iter().map(|&v| shown(v)).collect(),
                high: band.high.iter().map(|&v| shown(v)).collect(),
                fill: color,
            });
        }
        lines.push(Layer::Line {
            name: curve.channel.name().to_owned(),
            points: curve
                .tau_s
                .iter()
                .zip(&curve.deviation)
                .map(|(&t, &a)| (t, shown(a)))
                .collect(),
            stroke: Stroke::solid(color),
        });
        terms.extend(term_layers(curve, &shown));
        terms.extend(model_layers(curve, &shown));
    }
    Chart {
        title: sensor_title(sensor).to_owned(),
        x: Axis::log10("averaging time τ (s)"),
        y: Axis::log10(deviation_axis_label(kind, units.rate_unit(sensor))),
        layers: bands.into_iter().chain(lines).chain(terms).collect(),
    }
}

/// The implied curve of the composite: its sum dashed in the channel's colour, each process
/// a thin dashed grey line where it is within a factor 30 of the data's lowest point (a
/// process far below the curve would only stretch the axis).
fn model_layers(curve: &AllanCurve, shown: &impl Fn(f64) -> f64) -> Vec<Layer> {
    let Some(model) = &curve.model else {
        return Vec::new();
    };
    let floor = curve
        .deviation
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min)
        / 30.0;
    let line = |name: String, values: &[f64], stroke: Stroke| Layer::Line {
        name,
        points: curve
            .tau_s
            .iter()
            .zip(values)
            .filter(|(t, v)| **t >= model.from_tau_s && v.is_finite() && **v >= floor)
            .map(|(&t, &v)| (t, shown(v)))
            .collect(),
        stroke,
    };
    let thin = Stroke {
        width: 0.8,
        ..Stroke::dashed(palette::MUTED)
    };
    let mut layers = vec![line(
        format!("{} model ({})", curve.channel.name(), model.name),
        &model.total,
        Stroke::dashed(channel_color(curve.channel)),
    )];
    layers.extend(
        model
            .components
            .iter()
            .map(|(_, values)| line(PROCESSES_LEGEND.to_owned(), values, thin))
            .filter(|layer| matches!(layer, Layer::Line { points, .. } if points.len() > 1)),
    );
    layers
}

/// The legend entry of a composite's processes (one for all of them).
const PROCESSES_LEGEND: &str = "each process of the model";

/// A dashed asymptote over the term's region (when known) and a marker at its reading point.
fn term_layers(curve: &AllanCurve, shown: &impl Fn(f64) -> f64) -> Vec<Layer> {
    let color = channel_color(curve.channel);
    let minimum_tau_s = curve
        .tau_s
        .iter()
        .zip(&curve.deviation)
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map_or(1.0, |(&t, _)| t);
    let mut layers = Vec::new();
    for reading in &curve.terms {
        let (term, value) = (reading.term, reading.value_si);
        if let Some((from, to)) = reading.tau_range_s {
            layers.push(Layer::Line {
                name: String::new(),
                points: vec![
                    (from, shown(term.asymptote(value, from))),
                    (to, shown(term.asymptote(value, to))),
                ],
                stroke: Stroke::dashed(color),
            });
        }
        let tau = match (term, reading.tau_range_s) {
            (NoiseTerm::BiasInstability, Some((from, _))) => from,
            _ => term.reading_tau_s(minimum_tau_s),
        };
        layers.push(Layer::Markers {
            name: term.legend().to_owned(),
            points: vec![(tau, shown(term.asymptote(value, tau)))],
            marker: Marker {
                shape: term.shape(),
                radius: 4.5,
                stroke: palette::INK,
                fill: None,
            },
        });
    }
    layers
}

/// The Allan curves stored in one bank entry, with the terms the bank keeps (N, B, K).
pub fn allan_curves_of_entry(entry: &TemperatureEntry) -> Vec<AllanCurve> {
    entry
        .channels
        .iter()
        .map(|(&channel, model)| {
            let summary = &model.allan;
            let terms = [
                (NoiseTerm::RandomWalk, summary.white_noise_density),
                (NoiseTerm::BiasInstability, summary.bias_instability),
                (NoiseTerm::RateRandomWalk, summary.rate_random_walk),
            ]
            .into_iter()
            .filter_map(|(term, value)| {
                value.map(|value_si| NoiseTermReading {
                    term,
                    value_si,
                    tau_range_s: None,
                })
            })
            .collect();
            AllanCurve {
                channel,
                model: implied_of_model(model, entry.preprocessing.input_rate_hz, &summary.tau_s),
                tau_s: summary.tau_s.clone(),
                deviation: summary.adev.clone(),
                confidence: None,
                terms,
            }
        })
        .collect()
}

/// The implied curve of a channel's GMWM composite in the bank, at `tau_s`, drawn from the
/// first fitted scale on (Allan τ = m dt at wavelet scale 2m).
fn implied_of_model(model: &ChannelModel, rate_hz: f64, tau_s: &[f64]) -> Option<ImpliedCurve> {
    let gmwm = model.gmwm.as_ref()?;
    let dt_s = 1.0 / rate_hz;
    let terms = terms_from_parameters(&gmwm.parameters, dt_s)?;
    let from_tau_s = gmwm.first_scale_s / 2.0;
    Some(ImpliedCurve {
        from_tau_s,
        ..ImpliedCurve::of(&gmwm.model, &terms, dt_s, tau_s)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parsed_svg::{
        ParsedSvg, assert_complete_figure, layers_named, number, polyline_points,
    };

    /// Pure white noise of density n: σ(τ) = n/√τ on an octave grid from 0.01 s.
    fn white(channel: Channel, n: f64) -> AllanCurve {
        let tau_s: Vec<f64> = (0..15).map(|k| 0.01 * 2f64.powi(k)).collect();
        let adev: Vec<f64> = tau_s.iter().map(|t| n / t.sqrt()).collect();
        AllanCurve {
            channel,
            confidence: Some(ConfidenceBand {
                level: 0.683,
                low: adev.iter().map(|a| a * 0.9).collect(),
                high: adev.iter().map(|a| a * 1.1).collect(),
            }),
            terms: vec![NoiseTermReading {
                term: NoiseTerm::RandomWalk,
                value_si: n,
                tau_range_s: Some((tau_s[0], tau_s[14])),
            }],
            tau_s,
            deviation: adev,
            model: None,
        }
    }

    fn figure(units: DisplayUnits) -> String {
        let curves = [
            white(Channel::Gx, 1e-3),
            white(Channel::Gy, 2e-3),
            white(Channel::Ax, 5e-3),
        ];
        allan_deviation_figure("Allan deviation", &curves, units)
    }

    #[test]
    fn gyros_and_accelerometers_get_panels_with_their_units() {
        let text = figure(DisplayUnits::Navigation);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        assert_eq!(
            svg.texts("axis-label y"),
            ["Allan deviation σ(τ) (deg/h)", "Allan deviation σ(τ) (mg)"]
        );
        assert_eq!(svg.texts("axis-label x")[0], "averaging time τ (s)");
        let legend = svg.texts("legend-entry");
        for entry in [
            "gx",
            "gy",
            "ax",
            "68.3 % confidence",
            "N: random walk (τ = 1 s)",
        ] {
            assert!(legend.iter().any(|e| e == entry), "{entry} in {legend:?}");
        }
        let si = figure(DisplayUnits::Si);
        assert!(si.contains("(rad/s)") && si.contains("(m/s²)"));
    }

    // A white-noise composite implies σ(τ) = N/√τ (IEEE 952), which is the curve itself: the
    // model's sum and its one process are drawn exactly over the data, point for point.
    #[test]
    fn the_implied_curve_of_white_noise_lies_on_the_white_noise_curve() {
        let dt_s = 0.01;
        let mut curve = white(Channel::Gx, 1e-3);
        let terms = [Term::white_from_density(1e-3, dt_s)];
        curve.model = Some(ImpliedCurve::of("wn", &terms, dt_s, &curve.tau_s));
        let text = allan_deviation_figure("Allan deviation", &[curve], DisplayUnits::Si);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        let points = |name: &str| {
            polyline_points(&layers_named(&svg, name)[0].first_element_child().unwrap())
        };
        let data = points("gx");
        for name in ["gx model (wn)", PROCESSES_LEGEND] {
            let model = points(name);
            assert_eq!(model.len(), data.len(), "{name}");
            for (m, d) in model.iter().zip(&data) {
                assert!(
                    (m.0 - d.0).abs() < 0.01 && (m.1 - d.1).abs() < 0.01,
                    "{name}"
                );
            }
        }
    }

    #[test]
    fn the_random_walk_marker_sits_on_a_white_noise_curve_at_one_second() {
        let text = figure(DisplayUnits::Navigation);
        let svg = ParsedSvg::parse(&text);
        // The gx curve passes through τ = 0.01·2^k; τ = 1.28 s is on it, and τ = 1 s lies on
        // the straight (log-log) segment between 0.64 and 1.28 s.
        let curve = polyline_points(&layers_named(&svg, "gx")[0].first_element_child().unwrap());
        let (a, b) = (curve[6], curve[7]);
        let markers: Vec<(f64, f64)> = layers_named(&svg, "N: random walk (τ = 1 s)")
            .iter()
            .map(|layer| {
                let m = layer.first_element_child().unwrap();
                (number(&m, "cx"), number(&m, "cy"))
            })
            .collect();
        let (x, y) = markers[0];
        assert!(a.0 < x && x < b.0);
        let on_segment = a.1 + (x - a.0) / (b.0 - a.0) * (b.1 - a.1);
        assert!((y - on_segment).abs() < 0.05, "{y} vs {on_segment}");
    }

    #[test]
    fn bias_instability_is_marked_at_0_664_b_at_the_curve_minimum() {
        let mut curve = white(Channel::Gz, 1e-3);
        curve.confidence = None;
        let minimum = curve.deviation[14];
        curve.terms = vec![NoiseTermReading {
            term: NoiseTerm::BiasInstability,
            value_si: minimum / BIAS_INSTABILITY_FACTOR,
            tau_range_s: None,
        }];
        let text = allan_deviation_figure("B", &[curve], DisplayUnits::Si);
        let svg = ParsedSvg::parse(&text);
        let marker = svg.with_class("marker")[0];
        let points: Vec<f64> = marker
            .attribute("points")
            .unwrap()
            .split([' ', ','])
            .map(|v| v.parse().unwrap())
            .collect();
        let centre_x = points.iter().step_by(2).sum::<f64>() / 4.0;
        let centre_y = points.iter().skip(1).step_by(2).sum::<f64>() / 4.0;
        let last = *polyline_points(&svg.with_class("series")[0])
            .last()
            .unwrap();
        assert!((centre_x - last.0).abs() < 0.02 && (centre_y - last.1).abs() < 0.02);
    }
}
