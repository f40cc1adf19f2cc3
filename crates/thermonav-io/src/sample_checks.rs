//! The value checks every reader applies to a decoded sample, whatever the file it came from.
//!
//! The CSV readers check each value as they parse it: finite, at most [`MAX_SI_MAGNITUDE`] in
//! SI, a temperature inside [`crate::SENSOR_TEMPERATURE_RANGE_C`]. The binary readers (ROS bags,
//! DataFlash, ULog) decode numbers from bytes; they pass each sample through the same checks
//! here, so that a record refused as a CSV is refused as a bag, and the message names the place
//! (the caller prefixes the file and the message index or time).

use crate::SENSOR_TEMPERATURE_RANGE_C;

/// The largest magnitude of an inertial value in SI (rad/s, m/s², rad, m/s) that a reader
/// accepts: the bound of the strict CSV reader.
pub const MAX_SI_MAGNITUDE: f64 = crate::rows::MAX_MAGNITUDE;

/// Kelvin minus degrees Celsius at the same temperature.
const KELVIN_OFFSET: f64 = 273.15;

/// `None` when every value of `values` (named by `names`) is finite and at most
/// [`MAX_SI_MAGNITUDE`], else what is wrong with the first that is not, in words.
#[must_use]
pub fn inertial_values_problem(names: &[&str], values: &[f64]) -> Option<String> {
    names.iter().zip(values).find_map(|(name, &v)| match v {
        v if !v.is_finite() => Some(format!("{name} is {v}, not a finite number")),
        v if v.abs() > MAX_SI_MAGNITUDE => Some(format!(
            "{name} is {v:e} in SI, beyond the {MAX_SI_MAGNITUDE:e} any sensor reading stays within"
        )),
        _ => None,
    })
}

/// `None` for a temperature inside [`SENSOR_TEMPERATURE_RANGE_C`], else what is wrong with it,
/// with a hint when it reads as kelvin.
#[must_use]
pub fn temperature_problem(temperature_c: f64) -> Option<String> {
    let [low, high] = SENSOR_TEMPERATURE_RANGE_C;
    if (low..=high).contains(&temperature_c) {
        return None;
    }
    let as_celsius = temperature_c - KELVIN_OFFSET;
    let hint = match (low..=high).contains(&as_celsius) {
        true => format!(" (in kelvin? {temperature_c} K is {as_celsius:.2} °C)"),
        false => String::new(),
    };
    Some(format!(
        "temperature {temperature_c} °C is outside {low}..{high} °C, the range of a sensor's temperature{hint}"
    ))
}

/// [`inertial_values_problem`] of a gyro and accelerometer triple (`gx`..`az`), then
/// [`temperature_problem`] of the temperature when there is one.
#[must_use]
pub fn imu_sample_problem(
    gyro: [f64; 3],
    accel: [f64; 3],
    temperature_c: Option<f64>,
) -> Option<String> {
    let values = [gyro[0], gyro[1], gyro[2], accel[0], accel[1], accel[2]];
    inertial_values_problem(&["gx", "gy", "gz", "ax", "ay", "az"], &values)
        .or_else(|| temperature_c.and_then(temperature_problem))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_csv_bounds_hold_for_decoded_samples() {
        let level = ([0.001, -0.002, 0.0], [0.0, 0.0, -9.81]);
        assert_eq!(imu_sample_problem(level.0, level.1, Some(25.0)), None);
        assert_eq!(imu_sample_problem(level.0, level.1, None), None);
        let huge = imu_sample_problem(level.0, [0.0, -1e300, 0.0], None).unwrap();
        assert!(huge.starts_with("ay is -1e300"), "{huge}");
        let nan = imu_sample_problem([f64::NAN, 0.0, 0.0], level.1, None).unwrap();
        assert!(nan.starts_with("gx is NaN"), "{nan}");
        // Exactly the bound passes, the next float above it does not.
        assert_eq!(inertial_values_problem(&["x"], &[MAX_SI_MAGNITUDE]), None);
        assert!(inertial_values_problem(&["x"], &[MAX_SI_MAGNITUDE.next_up()]).is_some());
    }

    #[test]
    fn a_temperature_in_kelvin_gets_a_hint_and_the_range_ends_pass() {
        assert_eq!(temperature_problem(-80.0), None);
        assert_eq!(temperature_problem(150.0), None);
        let kelvin = temperature_problem(298.15).unwrap();
        assert!(
            kelvin.contains("in kelvin? 298.15 K is 25.00 °C"),
            "{kelvin}"
        );
        let absurd = temperature_problem(1e30).unwrap();
        assert!(
            absurd.contains("outside -80..150") && !absurd.contains("kelvin"),
            "{absurd}"
        );
        assert!(temperature_problem(f64::NAN).is_some());
    }
}
