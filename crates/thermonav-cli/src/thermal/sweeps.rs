//! A thermal calibration from temperature sweeps alone: each sweep's pieces cut into blocks,
//! gravity taken off along each sweep's measured specific force, legs found within each piece,
//! and each channel's model chosen on held-out legs (`stoch::thermal::sweep_model`).

use crate::failure::Failure;
use crate::thermal::calibration::{Sweep, ThermalInputs, common_devices, sweep_series};
use anyhow::anyhow;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use thermonav::geo::gravity::normal_gravity_m_s2;
use thermonav::imu::{Channel, ImuSeries, SampleKind};
use thermonav::stoch::thermal::check::gravity_signal;
use thermonav::stoch::thermal::sweep_model::{
    SweepBlock, SweepLeg, SweepPiece, calibrate_from_sweeps, default_block_s, sweep_blocks,
};
use thermonav::stoch::thermal::{PowerOnRecord, ScaleFactorCalibration, ThermalCalibration};

/// The calibration of `inputs.sweeps`, each sweep a power-on numbered from 1.
///
/// # Errors
/// A sweep that cannot be read, a bad sweep (named with its file), or a failed fit.
pub fn calibrate_sweeps_alone(inputs: &ThermalInputs) -> Result<ThermalCalibration, Failure> {
    let gravity = normal_gravity_m_s2(inputs.site.latitude_rad, inputs.site.height_m);
    let mut blocks = Vec::new();
    let mut legs = Vec::new();
    let mut devices = Vec::new();
    let mut first_signal = BTreeMap::new();
    for (k, files) in inputs.sweeps.iter().enumerate() {
        let power_on = k as u32 + 1;
        let sweeps: Vec<Sweep> = files
            .iter()
            .map(|f| read_sweep(f, inputs))
            .collect::<Result<_, _>>()?;
        devices.extend(sweeps.iter().filter_map(|s| s.devices));
        let signal = gravity_along_specific_force(&sweeps, gravity);
        if k == 0 {
            first_signal = signal.clone();
        }
        for (file, sweep) in files.iter().zip(&sweeps) {
            let first_leg = legs.len() as u32 + 1;
            let (b, l) = piece_blocks(file, &sweep.series, (power_on, first_leg), &signal, inputs)?;
            blocks.extend(b);
            legs.extend(l);
        }
    }
    let channels = calibrate_from_sweeps(&blocks)
        .map_err(|e| Failure::Data(anyhow!("thermal calibration from the sweeps: {e}")))?;
    let files: Vec<PathBuf> = inputs.sweeps.iter().flatten().cloned().collect();
    Ok(ThermalCalibration {
        channels,
        power_ons: inputs.sweeps.len(),
        scale_factor: ScaleFactorCalibration::static_sweeps(),
        removed_signal: first_signal,
        observations: observations_of(&blocks),
        devices: common_devices(&devices, &files)?,
        legs,
        sweep_blocks: blocks,
    })
}

/// A sweep piece read, with a temperature column and rates (not increments).
fn read_sweep(path: &Path, inputs: &ThermalInputs) -> Result<Sweep, Failure> {
    let sweep = sweep_series(path, inputs.sweep_instance, (&inputs.imu, &inputs.topics))?;
    if sweep.series.temperature_c.is_none() {
        return Err(Failure::Data(anyhow!(
            "{}: a temperature sweep needs a temp_c column",
            path.display()
        )));
    }
    if sweep.series.kind == Some(SampleKind::Increments) {
        return Err(Failure::Data(anyhow!(
            "{}: a temperature sweep is fitted from rates (rad/s, m/s²), and this record holds increments",
            path.display()
        )));
    }
    if sweep.series.len() < 2 {
        return Err(Failure::Data(anyhow!(
            "{}: fewer than two samples",
            path.display()
        )));
    }
    Ok(sweep)
}

/// Per accelerometer channel, the gravity a still unit reads along its mean specific force
/// over every piece of one sweep (any orientation, not only level).
fn gravity_along_specific_force(sweeps: &[Sweep], gravity_m_s2: f64) -> BTreeMap<Channel, f64> {
    let series: Vec<&ImuSeries> = sweeps.iter().map(|s| &s.series).collect();
    gravity_signal(&series, gravity_m_s2)
}

/// The blocks and legs of one piece; errors name the file.
fn piece_blocks(
    path: &Path,
    series: &ImuSeries,
    (power_on, first_leg): (u32, u32),
    signal: &BTreeMap<Channel, f64>,
    inputs: &ThermalInputs,
) -> Result<(Vec<SweepBlock>, Vec<SweepLeg>), Failure> {
    let time: Vec<f64> = series.time.iter().map(|t| t.as_seconds()).collect();
    let temperatures = series.temperature_c.as_deref().unwrap_or_default();
    let present = series.present_channels();
    let columns: Vec<(Channel, &[f64], f64)> = present
        .iter()
        .map(|&c| (c, series.channel(c), signal.get(&c).copied().unwrap_or(0.0)))
        .collect();
    let piece = SweepPiece {
        time_s: &time,
        temperature_c: temperatures,
        channels: &columns,
    };
    let block_s = inputs
        .sweep_block_s
        .unwrap_or_else(|| default_block_s(&time, temperatures));
    let (blocks, legs) = sweep_blocks(piece, power_on, first_leg, block_s)
        .map_err(|e| Failure::Data(anyhow!("{}: {e}", path.display())))?;
    let source = path.display().to_string();
    let legs = legs
        .iter()
        .enumerate()
        .map(|(j, l)| SweepLeg {
            leg: first_leg + j as u32,
            power_on,
            source: source.clone(),
            t_s: [time[l.start], time[l.end - 1]],
            temperature_c: l.temperature_c,
            span_c: l.span_c,
            direction: l.direction,
        })
        .collect();
    Ok((blocks, legs))
}

/// The blocks as per-channel observations (plots and `bank show` read these).
fn observations_of(blocks: &[SweepBlock]) -> BTreeMap<Channel, Vec<PowerOnRecord>> {
    let mut out: BTreeMap<Channel, Vec<PowerOnRecord>> = BTreeMap::new();
    for b in blocks {
        for (&c, &value) in &b.values {
            out.entry(c).or_default().push(PowerOnRecord {
                power_on: b.power_on,
                temperature_c: b.temperature_c,
                value,
            });
        }
    }
    out
}
