//! A claim's paired comparisons: the lead of the claimed model over each rival (mean of the
//! rival's error minus the claimed model's, over paired replicates) with its 95 % interval,
//! against the rival's temperature, and the zero line a lead must clear.

use crate::chart::{Bound, Chart, ErrorBar, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;

/// One paired comparison: the rival's temperature, the lead and its 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lead {
    /// The temperature the rival model stands for, °C.
    pub rival_temperature_c: f64,
    /// Mean of the rival's error minus the claimed model's, m (positive: the claim's model leads).
    pub lead_m: f64,
    /// 95 % interval of that mean, m, when there is a test.
    pub ci95_m: Option<[f64; 2]>,
}

/// The comparisons of one claimed model against one kind of rival (legend text and leads).
#[derive(Debug, Clone, PartialEq)]
pub struct LeadSeries {
    /// Legend text.
    pub name: String,
    /// The comparisons.
    pub leads: Vec<Lead>,
}

/// Leads with their 95 % intervals against the rival's temperature, one marker family per
/// series (shifted apart where they share a temperature), with the zero line.
pub fn paired_leads_figure(title: &str, y_label: &str, series: &[LeadSeries]) -> String {
    let mut layers = vec![zero_line(series)];
    let shapes = [
        Shape::Circle,
        Shape::Square,
        Shape::Diamond,
        Shape::Triangle,
    ];
    for (i, s) in series.iter().enumerate() {
        let color = palette::series_color(i);
        layers.push(Layer::ErrorBars {
            name: s.name.clone(),
            bars: s.leads.iter().map(error_bar).collect(),
            marker: Marker::filled(shapes[i % shapes.len()], color),
            stroke: Stroke::solid(color),
            offset_px: 7.0 * i as f64,
        });
    }
    let chart = Chart {
        title: "Paired lead with its 95 % interval".into(),
        x: Axis::linear("rival model's temperature (°C)"),
        y: Axis::linear(y_label),
        layers,
    };
    Figure::stacked(title, vec![chart]).to_svg()
}

/// A lead as an error bar at the rival's temperature.
fn error_bar(lead: &Lead) -> ErrorBar {
    ErrorBar {
        x: lead.rival_temperature_c,
        y: lead.lead_m,
        interval: lead
            .ci95_m
            .map(|[low, high]| [Bound::At(low), Bound::At(high)]),
    }
}

/// The zero line across the rivals' temperatures (10 °C beyond each end).
fn zero_line(series: &[LeadSeries]) -> Layer {
    let temperatures = series
        .iter()
        .flat_map(|s| s.leads.iter().map(|l| l.rival_temperature_c));
    let (low, high) = temperatures.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
        (lo.min(t), hi.max(t))
    });
    let (low, high) = if low <= high { (low, high) } else { (0.0, 0.0) };
    Layer::Line {
        name: "no lead".into(),
        points: vec![(low - 10.0, 0.0), (high + 10.0, 0.0)],
        stroke: Stroke::dashed(palette::MUTED),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_lead_and_the_zero_line_are_drawn_with_a_legend() {
        let series = [
            LeadSeries {
                name: "against fixed models".into(),
                leads: vec![
                    Lead {
                        rival_temperature_c: -40.0,
                        lead_m: 66.0,
                        ci95_m: Some([31.7, 100.2]),
                    },
                    Lead {
                        rival_temperature_c: 60.0,
                        lead_m: 62.5,
                        ci95_m: None,
                    },
                ],
            },
            LeadSeries {
                name: "against fixed + compensation".into(),
                leads: vec![Lead {
                    rival_temperature_c: 20.0,
                    lead_m: -3.0,
                    ci95_m: Some([-9.0, 3.0]),
                }],
            },
        ];
        let svg = paired_leads_figure("Claim (b)", "lead (m)", &series);
        assert!(svg.starts_with("<svg") && svg.contains("viewBox"));
        for text in [
            "against fixed models",
            "against fixed + compensation",
            "no lead",
        ] {
            assert!(svg.contains(text), "{text}");
        }
    }
}
