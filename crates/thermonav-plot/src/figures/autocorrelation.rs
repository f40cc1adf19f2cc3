//! The sample autocovariance of a channel with the fitted first-order Gauss-Markov curve
//! σ² exp(−τ/Tc) (the paper's Figure 1).

use super::DisplayUnits;
use crate::chart::{Chart, Figure, Layer, Marker, Shape, Stroke};
use crate::palette;
use crate::scale::Axis;
use thermonav::imu::Channel;

/// Points on the fitted curve.
const CURVE_POINTS: usize = 200;

/// A first-order Gauss-Markov model, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussMarkovFit {
    /// Standard deviation σ (rad/s or m/s²).
    pub sigma: f64,
    /// Correlation time Tc, s.
    pub correlation_time_s: f64,
}

impl GaussMarkovFit {
    /// Its autocovariance σ² exp(−|τ|/Tc).
    pub fn autocovariance(&self, lag_s: f64) -> f64 {
        self.sigma * self.sigma * (-lag_s.abs() / self.correlation_time_s).exp()
    }
}

/// The sample autocovariance of one channel, SI squared (rad²/s² or m²/s⁴).
#[derive(Debug, Clone, PartialEq)]
pub struct Autocovariance {
    /// The channel.
    pub channel: Channel,
    /// Lags, s.
    pub lag_s: Vec<f64>,
    /// Autocovariance at each lag.
    pub value: Vec<f64>,
    /// The fitted model, when there is one.
    pub fit: Option<GaussMarkovFit>,
}

/// The figure: sample autocovariance, the fitted curve, and a marker at τ = Tc where the curve
/// has fallen to σ²/e.
pub fn autocorrelation_figure(title: &str, data: &Autocovariance, units: DisplayUnits) -> String {
    let sensor = data.channel.sensor();
    let scale = units.rate(sensor, 1.0).powi(2);
    let mut layers = vec![Layer::Line {
        name: format!("sample autocovariance of {}", data.channel.name()),
        points: data
            .lag_s
            .iter()
            .zip(&data.value)
            .map(|(&lag, &v)| (lag, v * scale))
            .collect(),
        stroke: Stroke::solid(palette::series_color(0)),
    }];
    if let Some(fit) = data.fit {
        let last = data.lag_s.iter().copied().fold(0.0, f64::max);
        let curve = (0..=CURVE_POINTS)
            .map(|i| {
                let lag = last * i as f64 / CURVE_POINTS as f64;
                (lag, fit.autocovariance(lag) * scale)
            })
            .collect();
        layers.push(Layer::Line {
            name: "fitted σ² exp(−τ/Tc)".into(),
            points: curve,
            stroke: Stroke::dashed(palette::series_color(3)),
        });
        let tc = fit.correlation_time_s;
        layers.push(Layer::Markers {
            name: "τ = Tc: σ²/e".into(),
            points: vec![(tc, fit.autocovariance(tc) * scale)],
            marker: Marker {
                shape: Shape::Circle,
                radius: 4.5,
                stroke: palette::series_color(3),
                fill: None,
            },
        });
    }
    let unit = units.rate_unit(sensor);
    let panel_title = match data.fit {
        Some(fit) => format!(
            "{}: Tc = {} s, σ = {} {unit}",
            data.channel.name(),
            significant(fit.correlation_time_s),
            significant(units.rate(sensor, fit.sigma)),
        ),
        None => format!("{}: no Gauss-Markov fit", data.channel.name()),
    };
    let chart = Chart {
        title: panel_title,
        x: Axis::linear("lag τ (s)"),
        y: Axis::linear(format!("autocovariance (({unit})²)")),
        layers,
    };
    Figure::stacked(title, vec![chart]).to_svg()
}

/// `value` with three significant digits.
fn significant(value: f64) -> String {
    let magnitude = value.abs().log10().floor();
    let decimals = (2.0 - magnitude).clamp(0.0, 12.0) as usize;
    format!("{value:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parsed_svg::{
        ParsedSvg, assert_complete_figure, grid_mapping, number, polyline_points,
    };
    use thermonav::units::rad_per_s_to_deg_per_h;

    #[test]
    fn the_fitted_curve_starts_at_sigma_squared_and_falls_to_one_over_e_at_tc() {
        let fit = GaussMarkovFit {
            sigma: 2e-4,
            correlation_time_s: 30.0,
        };
        let lag_s: Vec<f64> = (0..=120).map(f64::from).collect();
        let value = lag_s.iter().map(|&l| fit.autocovariance(l) * 1.1).collect();
        let data = Autocovariance {
            channel: Channel::Gy,
            lag_s,
            value,
            fit: Some(fit),
        };
        let text = autocorrelation_figure("ACF", &data, DisplayUnits::Navigation);
        let svg = ParsedSvg::parse(&text);
        assert_complete_figure(&svg);
        assert_eq!(svg.texts("axis-label y"), ["autocovariance ((deg/h)²)"]);
        assert_eq!(
            svg.texts("panel-title"),
            ["gy: Tc = 30.0 s, σ = 41.3 deg/h"]
        );
        let x_of = grid_mapping(&svg, 0, "x", false);
        let y_of = grid_mapping(&svg, 0, "y", false);
        let sigma2 = rad_per_s_to_deg_per_h(2e-4).powi(2);
        let curve = polyline_points(&svg.with_class("series")[1]);
        assert!((curve[0].0 - x_of(0.0)).abs() < 0.02);
        assert!((curve[0].1 - y_of(sigma2)).abs() < 0.02);
        let marker = svg.with_class("marker")[0];
        assert!((number(&marker, "cx") - x_of(30.0)).abs() < 0.02);
        assert!((number(&marker, "cy") - y_of(sigma2 / std::f64::consts::E)).abs() < 0.02);
    }
}
