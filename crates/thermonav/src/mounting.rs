//! The IMU's mounting: how its own axes (the sensor frame `s`, as printed on its case) sit in
//! the body frame (FRD, CONVENTIONS.md).
//!
//! A [`Mounting`] is the rotation C_s^b with v^b = C_s^b v^s, given either as an axis mapping
//! (`-y,x,z`: body x is the IMU's −y, body y its x, body z its z) or as the roll, pitch and
//! yaw of the IMU relative to the body (`rpy:0,0,90`), ZYX like every attitude:
//! C_s^b = R_z(yaw) R_y(pitch) R_x(roll). Gyro and accelerometer vectors, and their increments,
//! turn by the same C_s^b; the temperature does not. An axis mapping is applied exactly (each
//! body component is one IMU component, negated or not).
//!
//! ```
//! use thermonav::mounting::Mounting;
//! let mapping: Mounting = "-y,x,z".parse()?;
//! assert_eq!(mapping.to_body([1.0, 2.0, 3.0]), [-2.0, 1.0, 3.0]);
//! let yawed: Mounting = "rpy:0,0,90".parse()?; // the same mounting as angles
//! let v = yawed.to_body([1.0, 2.0, 3.0]);
//! assert!((v[0] + 2.0).abs() < 1e-15 && (v[1] - 1.0).abs() < 1e-15);
//! # Ok::<(), thermonav::mounting::MountingError>(())
//! ```

use crate::frames::{Body, Rotation, SensorAxes};
use crate::imu::{ImuSample, ImuSeries};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion};
use std::fmt;
use std::str::FromStr;

/// Prefix of the angle form, `rpy:ROLL,PITCH,YAW` (degrees).
pub const ANGLES_PREFIX: &str = "rpy:";

/// One IMU axis, perhaps negated: a component of an axis mapping.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SignedAxis {
    /// The IMU axis, 0 (x), 1 (y) or 2 (z).
    pub axis: usize,
    /// Whether the body axis points along the IMU axis's negative direction.
    pub negated: bool,
}

/// How the IMU is mounted in the body: the rotation C_s^b from its axes to the body's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mounting {
    /// Body axis i is the signed IMU axis `axes[i]`: a proper signed permutation (a rotation,
    /// never a reflection).
    Axes([SignedAxis; 3]),
    /// Roll, pitch and yaw of the IMU relative to the body, degrees (ZYX).
    Angles {
        /// Rotation about x, deg.
        roll_deg: f64,
        /// Rotation about y, deg.
        pitch_deg: f64,
        /// Rotation about z, deg.
        yaw_deg: f64,
    },
}

/// Why a mounting text is refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MountingError {
    /// Not three comma-separated parts.
    #[error(
        "expected three comma-separated parts (an axis mapping such as -y,x,z, or rpy:ROLL,PITCH,YAW in degrees), found {found}"
    )]
    PartCount {
        /// Number of parts found.
        found: usize,
    },
    /// A part of an axis mapping that is not an axis.
    #[error("{found:?} is not an IMU axis: expected x, y or z, optionally signed (-y, +x)")]
    NotAnAxis {
        /// The part as given.
        found: String,
    },
    /// An IMU axis used twice: the mapping is no permutation.
    #[error(
        "IMU axis {axis} appears twice: each body axis must be a different IMU axis (a signed permutation of x, y, z)"
    )]
    RepeatedAxis {
        /// The axis name.
        axis: char,
    },
    /// A signed permutation with determinant −1.
    #[error(
        "{mapping} is a reflection, not a rotation (it turns right-handed axes into left-handed ones): negate one more axis, or swap two"
    )]
    Reflection {
        /// The mapping as given.
        mapping: String,
    },
    /// An angle that is not a finite number.
    #[error("{found:?} is not a finite angle in degrees")]
    NotAnAngle {
        /// The part as given.
        found: String,
    },
}

const AXIS_NAMES: [char; 3] = ['x', 'y', 'z'];

impl Mounting {
    /// The direction cosine matrix C_s^b, as rows.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        match self {
            Mounting::Axes(axes) => std::array::from_fn(|row| {
                std::array::from_fn(|column| match axes[row] {
                    SignedAxis { axis, negated } if axis == column => sign(negated),
                    _ => 0.0,
                })
            }),
            Mounting::Angles {
                roll_deg,
                pitch_deg,
                yaw_deg,
            } => {
                let m = Rotation3::from_euler_angles(
                    roll_deg.to_radians(),
                    pitch_deg.to_radians(),
                    yaw_deg.to_radians(),
                );
                std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]))
            }
        }
    }

    /// C_s^b as a frame-typed rotation.
    pub fn rotation(&self) -> Rotation<SensorAxes, Body> {
        let m = Matrix3::from_fn(|r, c| self.matrix()[r][c]);
        let r = Rotation3::from_matrix_unchecked(m);
        Rotation::from_unit_quaternion(UnitQuaternion::from_rotation_matrix(&r))
    }

    /// The IMU-axes vector `v` in body axes, C_s^b v: exact for an axis mapping.
    pub fn to_body(&self, v: [f64; 3]) -> [f64; 3] {
        match self {
            Mounting::Axes(axes) => axes.map(|a| if a.negated { -v[a.axis] } else { v[a.axis] }),
            Mounting::Angles { .. } => {
                let m = self.matrix();
                m.map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
            }
        }
    }

    /// The sample with its gyro and accelerometer vectors (rates or increments) in body axes.
    pub fn sample_to_body(&self, sample: ImuSample) -> ImuSample {
        ImuSample {
            gyro: self.to_body(sample.gyro),
            accel: self.to_body(sample.accel),
            ..sample
        }
    }

    /// Turns every sample of `series` into body axes: the gyro columns and the accelerometer
    /// columns each by C_s^b, as [`Mounting::sample_to_body`] does sample by sample.
    pub fn series_to_body(&self, series: &mut ImuSeries) {
        for first in [0, 3] {
            for k in 0..series.len() {
                let v = std::array::from_fn(|i| series.channels[first + i][k]);
                for (i, value) in self.to_body(v).into_iter().enumerate() {
                    series.channels[first + i][k] = value;
                }
            }
        }
    }

    /// For an axis mapping, where each IMU axis goes: `Some(body axis)` of IMU axis i (the
    /// channel a present IMU column fills); `None` for angles, which mix the axes.
    pub fn body_axis_of(&self, imu_axis: usize) -> Option<usize> {
        match self {
            Mounting::Axes(axes) => axes.iter().position(|a| a.axis == imu_axis),
            Mounting::Angles { .. } => None,
        }
    }
}

fn sign(negated: bool) -> f64 {
    if negated { -1.0 } else { 1.0 }
}

impl FromStr for Mounting {
    type Err = MountingError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let text = text.trim();
        match text.strip_prefix(ANGLES_PREFIX) {
            Some(angles) => parse_angles(angles),
            None => parse_axes(text),
        }
    }
}

fn parts(text: &str) -> Result<[&str; 3], MountingError> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    <[&str; 3]>::try_from(parts.as_slice())
        .map_err(|_| MountingError::PartCount { found: parts.len() })
}

fn parse_angles(text: &str) -> Result<Mounting, MountingError> {
    let angle = |part: &str| match part.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        _ => Err(MountingError::NotAnAngle {
            found: part.to_owned(),
        }),
    };
    let [roll, pitch, yaw] = parts(text)?;
    Ok(Mounting::Angles {
        roll_deg: angle(roll)?,
        pitch_deg: angle(pitch)?,
        yaw_deg: angle(yaw)?,
    })
}

fn parse_axis(part: &str) -> Result<SignedAxis, MountingError> {
    let (negated, name) = match part.as_bytes().first() {
        Some(b'-') => (true, &part[1..]),
        Some(b'+') => (false, &part[1..]),
        _ => (false, part),
    };
    let lower = name.to_ascii_lowercase();
    let axis = AXIS_NAMES
        .iter()
        .position(|&c| lower.len() == 1 && lower.starts_with(c));
    axis.map(|axis| SignedAxis { axis, negated })
        .ok_or_else(|| MountingError::NotAnAxis {
            found: part.to_owned(),
        })
}

fn parse_axes(text: &str) -> Result<Mounting, MountingError> {
    let [a, b, c] = parts(text)?;
    let axes = [parse_axis(a)?, parse_axis(b)?, parse_axis(c)?];
    for (i, first) in axes.iter().enumerate() {
        if axes[i + 1..].iter().any(|other| other.axis == first.axis) {
            return Err(MountingError::RepeatedAxis {
                axis: AXIS_NAMES[first.axis],
            });
        }
    }
    if determinant(&axes) < 0.0 {
        return Err(MountingError::Reflection {
            mapping: text.to_owned(),
        });
    }
    Ok(Mounting::Axes(axes))
}

/// Determinant of a signed permutation: the permutation's parity times the signs.
fn determinant(axes: &[SignedAxis; 3]) -> f64 {
    let inversions = (0..3)
        .flat_map(|i| (i + 1..3).map(move |j| (i, j)))
        .filter(|&(i, j)| axes[i].axis > axes[j].axis)
        .count();
    let parity = if inversions % 2 == 0 { 1.0 } else { -1.0 };
    axes.iter().fold(parity, |d, a| d * sign(a.negated))
}

impl fmt::Display for Mounting {
    /// The text that parses back to the same mounting (`-y,x,z`, `rpy:0,0,90`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Mounting::Axes(axes) => {
                let names: Vec<String> = axes
                    .iter()
                    .map(|a| format!("{}{}", if a.negated { "-" } else { "" }, AXIS_NAMES[a.axis]))
                    .collect();
                write!(f, "{}", names.join(","))
            }
            Mounting::Angles {
                roll_deg,
                pitch_deg,
                yaw_deg,
            } => write!(f, "{ANGLES_PREFIX}{roll_deg},{pitch_deg},{yaw_deg}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mounting(text: &str) -> Mounting {
        text.parse().unwrap()
    }

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-14)
    }

    #[test]
    fn an_axis_mapping_takes_each_body_component_from_its_signed_imu_axis() {
        assert_eq!(
            mounting("-y,x,z").to_body([1.0, 2.0, 3.0]),
            [-2.0, 1.0, 3.0]
        );
        assert_eq!(
            mounting("x,-y,-z").to_body([1.0, 2.0, 3.0]),
            [1.0, -2.0, -3.0]
        );
        assert_eq!(
            mounting(" +Z , x , y ").to_body([1.0, 2.0, 3.0]),
            [3.0, 1.0, 2.0]
        );
    }

    /// Elementary rotations written out (C_s^b = R_z(ψ) R_y(θ) R_x(φ)), against which the
    /// angle form is checked on known vectors.
    #[test]
    fn angles_rotate_known_vectors_as_the_closed_forms_say() {
        let (phi, theta, psi) = (
            30_f64.to_radians(),
            (-20_f64).to_radians(),
            70_f64.to_radians(),
        );
        let roll = mounting("rpy:30,0,0").to_body([0.0, 1.0, 0.0]);
        assert!(close(roll, [0.0, phi.cos(), phi.sin()]), "{roll:?}");
        let pitch = mounting("rpy:0,-20,0").to_body([1.0, 0.0, 0.0]);
        assert!(close(pitch, [theta.cos(), 0.0, -theta.sin()]), "{pitch:?}");
        let yaw = mounting("rpy:0,0,70").to_body([1.0, 0.0, 0.0]);
        assert!(close(yaw, [psi.cos(), psi.sin(), 0.0]), "{yaw:?}");
        // All three: z of the IMU goes to the third column of R_z R_y R_x.
        let all = mounting("rpy:30,-20,70").to_body([0.0, 0.0, 1.0]);
        let column = [
            psi.cos() * theta.sin() * phi.cos() + psi.sin() * phi.sin(),
            psi.sin() * theta.sin() * phi.cos() - psi.cos() * phi.sin(),
            theta.cos() * phi.cos(),
        ];
        assert!(close(all, column), "{all:?} against {column:?}");
    }

    #[test]
    fn axis_mappings_equal_their_angles() {
        for (axes, angles) in [
            ("-y,x,z", "rpy:0,0,90"),
            ("x,-y,-z", "rpy:180,0,0"),
            ("-x,-y,z", "rpy:0,0,180"),
            ("z,y,-x", "rpy:0,90,0"),
        ] {
            let (a, b) = (mounting(axes).matrix(), mounting(angles).matrix());
            for (ra, rb) in a.iter().zip(&b) {
                assert!(close(*ra, *rb), "{axes} against {angles}: {a:?} {b:?}");
            }
            let angle = mounting(axes)
                .rotation()
                .angle_to(&mounting(angles).rotation());
            assert!(angle < 1e-12, "{axes} against {angles}: {angle}");
        }
    }

    #[test]
    fn a_mapping_that_is_no_rotation_is_refused_with_the_reason() {
        let error = |text: &str| text.parse::<Mounting>().unwrap_err();
        assert_eq!(error("x,x,z"), MountingError::RepeatedAxis { axis: 'x' });
        assert!(matches!(error("x,y,-z"), MountingError::Reflection { .. }));
        assert!(matches!(error("y,x,z"), MountingError::Reflection { .. }));
        assert_eq!(error("x,y"), MountingError::PartCount { found: 2 });
        assert!(matches!(error("x,w,z"), MountingError::NotAnAxis { .. }));
        assert!(matches!(
            error("rpy:0,nan,0"),
            MountingError::NotAnAngle { .. }
        ));
        assert!(error("x,y,-z").to_string().contains("reflection"));
    }

    #[test]
    fn the_text_reads_back_to_the_same_mounting() {
        for text in ["-y,x,z", "z,-x,-y", "rpy:1.5,-2,90"] {
            assert_eq!(mounting(text).to_string(), text);
            assert_eq!(mounting(&mounting(text).to_string()), mounting(text));
        }
    }

    #[test]
    fn every_proper_signed_permutation_is_a_rotation() {
        let mut proper = 0;
        for p in [
            [0, 1, 2],
            [0, 2, 1],
            [1, 0, 2],
            [1, 2, 0],
            [2, 0, 1],
            [2, 1, 0],
        ] {
            for signs in 0..8 {
                let axes = p.map(|axis| axis);
                let text: Vec<String> = (0..3)
                    .map(|i| {
                        format!(
                            "{}{}",
                            if signs >> i & 1 == 1 { "-" } else { "" },
                            AXIS_NAMES[axes[i]]
                        )
                    })
                    .collect();
                if let Ok(m) = text.join(",").parse::<Mounting>() {
                    proper += 1;
                    let r = m.rotation().to_matrix3();
                    let exact = Matrix3::from_fn(|i, j| m.matrix()[i][j]);
                    assert!((r - exact).abs().max() < 1e-15);
                    assert!((exact.determinant() - 1.0).abs() < 1e-15);
                }
            }
        }
        assert_eq!(proper, 24, "the 24 rotations of the cube");
    }
}
