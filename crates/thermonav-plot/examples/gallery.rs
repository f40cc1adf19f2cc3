//! Every figure of thermonav-plot on synthetic data, as SVG and PNG, and one HTML page holding
//! them: `cargo run --release -p thermonav-plot --example gallery -- OUT_DIR`.

use std::f64::consts::PI;
use std::path::Path;
use thermonav::imu::Channel;
use thermonav_plot::figures::DisplayUnits;
use thermonav_plot::figures::allan::{
    AllanCurve, ConfidenceBand, NoiseTerm, NoiseTermReading, allan_deviation_figure,
};
use thermonav_plot::figures::autocorrelation::{
    Autocovariance, GaussMarkovFit, autocorrelation_figure,
};
use thermonav_plot::figures::correlation::{
    CorrelationTimePoint, CorrelationTimeSeries, correlation_time_figure,
};
use thermonav_plot::figures::navigation::{
    Innovations, ModelErrors, RmsSeries, Trajectory, innovations_figure, outage_errors_figure,
    rms_versus_temperature_figure, trajectory_figure,
};
use thermonav_plot::html::{Block, InlineFigure, Page, Section, Table, render_page};
use thermonav_plot::png::svg_to_png;

const TEMPERATURES_C: [f64; 6] = [-40.0, -20.0, 0.0, 20.0, 40.0, 60.0];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "out/gallery".into());
    let out = Path::new(&out);
    std::fs::create_dir_all(out)?;
    let figures = [
        ("allan", "Allan deviation", allan()),
        ("correlation-time", "Correlation time", correlation()),
        ("autocorrelation", "Autocovariance", autocorrelation()),
        ("outage-errors", "INS-only errors", outage_errors()),
        ("rms", "RMS versus temperature", rms()),
        ("innovations", "Innovations", innovations()),
        ("trajectory", "Trajectory", trajectory()),
    ];
    let mut blocks = vec![Block::Table(Table {
        caption: "Figures".into(),
        header: vec!["file".into(), "SVG bytes".into()],
        rows: figures
            .iter()
            .map(|(name, _, svg)| vec![format!("{name}.svg"), svg.len().to_string()])
            .collect(),
    })];
    for (name, caption, svg) in figures {
        std::fs::write(out.join(format!("{name}.svg")), &svg)?;
        std::fs::write(out.join(format!("{name}.png")), svg_to_png(&svg)?)?;
        blocks.push(Block::Figure(InlineFigure {
            svg,
            caption: caption.into(),
        }));
    }
    let page = Page {
        summary: Vec::new(),
        title: "thermonav-plot gallery".into(),
        sections: vec![Section {
            heading: "Synthetic data".into(),
            blocks,
        }],
    };
    std::fs::write(out.join("gallery.html"), render_page(&page))?;
    println!("wrote {}", out.display());
    Ok(())
}

fn allan() -> String {
    let curve = |channel: Channel, n: f64, b: f64| {
        let tau_s: Vec<f64> = (0..17).map(|k| 0.01 * 2f64.powi(k)).collect();
        let adev: Vec<f64> = tau_s
            .iter()
            .map(|t| (n * n / t + (0.664 * b).powi(2)).sqrt())
            .collect();
        AllanCurve {
            channel,
            model: None,
            confidence: Some(ConfidenceBand {
                level: 0.683,
                low: adev.iter().map(|a| a * 0.9).collect(),
                high: adev.iter().map(|a| a * 1.1).collect(),
            }),
            terms: vec![
                NoiseTermReading {
                    term: NoiseTerm::RandomWalk,
                    value_si: n,
                    tau_range_s: Some((0.01, 5.0)),
                },
                NoiseTermReading {
                    term: NoiseTerm::BiasInstability,
                    value_si: b,
                    tau_range_s: None,
                },
            ],
            tau_s,
            deviation: adev,
        }
    };
    let curves = [
        curve(Channel::Gx, 6e-4, 9e-5),
        curve(Channel::Gy, 7e-4, 8e-5),
        curve(Channel::Gz, 5e-4, 1e-4),
        curve(Channel::Ax, 2e-3, 1e-3),
        curve(Channel::Ay, 2.5e-3, 9e-4),
        curve(Channel::Az, 1.8e-3, 1.2e-3),
    ];
    allan_deviation_figure("Allan deviation", &curves, DisplayUnits::Navigation)
}

fn correlation() -> String {
    let series = |channel: Channel, family: &str, scale: f64| CorrelationTimeSeries {
        channel,
        family: family.into(),
        points: TEMPERATURES_C
            .iter()
            .map(|&t| {
                let tc = scale * (100.0 + 2.0 * (t + 40.0));
                CorrelationTimePoint {
                    temperature_c: t,
                    correlation_time_s: tc,
                    ci95_s: [Some(tc / 2.0), (t < 50.0).then_some(tc * 3.0)],
                }
            })
            .collect(),
    };
    let all: Vec<CorrelationTimeSeries> = Channel::ALL
        .into_iter()
        .flat_map(|c| [series(c, "exact ML", 1.0), series(c, "AR(1)-based", 0.01)])
        .collect();
    correlation_time_figure("Correlation time versus temperature", &all)
}

fn autocorrelation() -> String {
    let fit = GaussMarkovFit {
        sigma: 1.5e-4,
        correlation_time_s: 60.0,
    };
    let lag_s: Vec<f64> = (0..=300).map(f64::from).collect();
    let value = lag_s
        .iter()
        .map(|&l| fit.autocovariance(l) * (1.0 + 0.05 * (l / 7.0).sin()))
        .collect();
    let data = Autocovariance {
        channel: Channel::Gz,
        lag_s,
        value,
        fit: Some(fit),
    };
    autocorrelation_figure("Autocovariance", &data, DisplayUnits::Navigation)
}

fn outage_errors() -> String {
    let time_s: Vec<f64> = (0..=120).map(|k| 600.0 + f64::from(k)).collect();
    let model = |name: &str, growth: f64| ModelErrors {
        model: name.into(),
        north_m: time_s
            .iter()
            .map(|t| growth * (t - 600.0).powi(2) / 100.0)
            .collect(),
        east_m: time_s
            .iter()
            .map(|t| -growth * (t - 600.0).powi(2) / 150.0)
            .collect(),
        heading_deg: time_s
            .iter()
            .map(|t| growth * (t - 600.0) / 200.0)
            .collect(),
        time_s: time_s.clone(),
    };
    outage_errors_figure(
        "INS-only errors during a 120 s outage",
        &[model("model of 20 °C", 1.0), model("model of -40 °C", 1.8)],
        Some((600.0, 720.0)),
    )
}

fn rms() -> String {
    let model = |name: &str, base: f64| RmsSeries {
        model: name.into(),
        temperature_c: TEMPERATURES_C.to_vec(),
        rms: TEMPERATURES_C
            .iter()
            .map(|t| base * (1.0 + (t - 20.0).abs() / 40.0))
            .collect(),
    };
    rms_versus_temperature_figure(
        "RMS north error per model",
        "north",
        "m",
        &[model("AR-based", 12.0), model("exact ML", 8.0)],
    )
}

fn innovations() -> String {
    let time_s: Vec<f64> = (0..300).map(f64::from).collect();
    let component = |name: &str, unit: &str, sigma: f64| Innovations {
        name: name.into(),
        unit: unit.into(),
        innovation: time_s
            .iter()
            .map(|t| sigma * 1.3 * (t * 1.7).sin() * (t * 0.31).cos())
            .collect(),
        sigma: time_s
            .iter()
            .map(|t| sigma * (1.0 + 1.0 / (1.0 + t)))
            .collect(),
        time_s: time_s.clone(),
    };
    innovations_figure(
        "Innovations",
        &[
            component("north position", "m", 1.2),
            component("heading", "deg", 0.3),
        ],
    )
}

fn trajectory() -> String {
    let time_s: Vec<f64> = (0..=1800).map(f64::from).collect();
    let east_m = time_s
        .iter()
        .map(|t| 800.0 * (2.0 * PI * t / 1800.0).sin())
        .collect();
    let north_m = time_s
        .iter()
        .map(|t| 300.0 * (4.0 * PI * t / 1800.0).sin())
        .collect();
    trajectory_figure(
        "Vessel survey",
        &Trajectory {
            time_s,
            east_m,
            north_m,
        },
        &[(300.0, 420.0), (1200.0, 1320.0)],
    )
}
