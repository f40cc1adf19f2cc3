//! `thermonav compensate`: a record with a bank's thermal calibration taken off.

use crate::args::CompensateArgs;
use crate::failure::{Classify, Failure};
use crate::inputs::read_thermal_calibration;
use crate::report::print_json;
use crate::settings::analysis::json_sidecar;
use crate::settings::paths::Io;
use anyhow::anyhow;
use serde::Serialize;
use std::collections::BTreeMap;
use thermonav::stoch::thermal::check::{ChannelRemoval, compensate_record};
use thermonav_io::{ImuOptions, write_imu_file, write_json_atomically};
use thermonav_plot::figures::DisplayUnits;

/// The sidecar `OUT.csv.json`.
#[derive(Debug, Serialize)]
struct Sidecar {
    input: String,
    bank: String,
    output: String,
    /// The power-on whose offset was taken off; null: the mean offset.
    power_on: Option<u32>,
    /// What stays in the record.
    kept: &'static str,
    samples: usize,
    clamped_samples: usize,
    channels: BTreeMap<&'static str, ChannelRemoval>,
}

/// Runs `compensate`.
pub fn run(args: &CompensateArgs) -> Result<(), Failure> {
    let sidecar_path = json_sidecar(&args.out);
    Io::new()
        .input("RECORD", &args.record)
        .input("--bank", &args.bank)
        .output("compensated record", &args.out)
        .output("sidecar", &sidecar_path)
        .check()?;
    let calibration = read_thermal_calibration(&args.bank)?;
    let mut series = crate::thermal::calibration::sweep_series(
        &args.record,
        args.instance,
        (
            &ImuOptions::default(),
            &crate::settings::imu::topics(&args.topics),
        ),
    )?
    .series;
    let done = compensate_record(&calibration, &mut series, args.power_on)
        .map_err(|e| anyhow!("{}: {e}", args.record.display()))
        .data()?;
    let sidecar = Sidecar {
        input: args.record.display().to_string(),
        bank: args.bank.display().to_string(),
        output: args.out.display().to_string(),
        power_on: done.power_on,
        kept: "gravity, the noise and whatever the calibration does not model; a gyro curve's constant holds the Earth rate's projection of the sweeps it was fitted to, and is taken off with the curve",
        samples: series.len(),
        clamped_samples: done.clamped_samples,
        channels: done
            .channels
            .into_iter()
            .map(|(c, r)| (c.name(), r))
            .collect(),
    };
    write_imu_file(&args.out, &series).data()?;
    write_json_atomically(&sidecar_path, &sidecar).data()?;
    if args.json {
        return print_json(&sidecar);
    }
    print_summary(&sidecar);
    Ok(())
}

fn print_summary(sidecar: &Sidecar) {
    println!(
        "{} -> {} ({} samples)",
        sidecar.input, sidecar.output, sidecar.samples
    );
    for (&name, r) in &sidecar.channels {
        let sensor = thermonav::imu::Channel::from_name(name).map(|c| c.sensor());
        let Some(sensor) = sensor else { continue };
        let show = |si: f64| DisplayUnits::Navigation.rate(sensor, si);
        let lag = r
            .thermal_lag_s
            .map_or(String::new(), |t| format!(", lag {t:.0} s"));
        println!(
            "{name}: order {}{lag}; removed {:.3} .. {:.3} {} (mean {:.3})",
            r.order,
            show(r.removed_min),
            show(r.removed_max),
            DisplayUnits::Navigation.rate_unit(sensor),
            show(r.removed_mean)
        );
    }
    println!(
        "{} samples outside a fitted range (end values used); sidecar {}.json",
        sidecar.clamped_samples, sidecar.output
    );
}
