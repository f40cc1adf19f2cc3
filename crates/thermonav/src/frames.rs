//! Frames in the type system: vectors and rotations that know which frame they live in.
//!
//! `Vector<F>` is a 3-vector resolved in frame `F`; `Rotation<From, To>` maps `From`
//! coordinates to `To` coordinates (it is the direction cosine matrix C_From^To). Rotations
//! compose only when the frames match, so mixing up body and navigation axes does not build:
//!
//! ```compile_fail
//! use thermonav::frames::{Body, Ned, Rotation, Vector};
//! let c_b_n: Rotation<Body, Ned> = Rotation::identity();
//! let v_n: Vector<Ned> = Vector::new(1.0, 0.0, 0.0);
//! let wrong = c_b_n * v_n; // a navigation vector cannot be rotated from body to navigation
//! ```
//!
//! ```
//! use thermonav::frames::{Body, Ned, Rotation, Vector};
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.0, 0.0, std::f64::consts::FRAC_PI_2);
//! let forward: Vector<Body> = Vector::new(1.0, 0.0, 0.0);
//! let v = c_b_n * forward; // heading 90°: forward points east
//! assert!((v.y() - 1.0).abs() < 1e-15);
//! ```
//!
//! Conventions (CONVENTIONS.md): Hamilton quaternions, scalar first; Euler angles ZYX with
//! C_b^n = R_z(yaw) R_y(pitch) R_x(roll).
//!
//! ## Mix-ups that do not build
//!
//! Each example that must not compile is followed by the same code written correctly, which
//! does, so that the first fails for the frame mix-up and not for a typo.
//!
//! Vectors add, subtract, dot and cross only within one frame. A lever arm measured on the
//! vehicle (body axes) cannot be added to a navigation-frame offset as it stands:
//!
//! ```compile_fail
//! use thermonav::frames::{Body, Ned, Vector};
//! let lever_arm_b: Vector<Body> = Vector::new(0.3, 0.0, -2.5);
//! let offset_n: Vector<Ned> = Vector::new(10.0, 0.0, 0.0);
//! let antenna_n = offset_n + lever_arm_b; // body components added to north-east-down ones
//! ```
//!
//! ```
//! use thermonav::frames::{Body, Ned, Rotation, Vector};
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.0, 0.0, std::f64::consts::PI);
//! let lever_arm_b: Vector<Body> = Vector::new(0.3, 0.0, -2.5);
//! let offset_n: Vector<Ned> = Vector::new(10.0, 0.0, 0.0);
//! let antenna_n = offset_n + c_b_n * lever_arm_b; // rotated into NED first
//! assert!((antenna_n.x() - 9.7).abs() < 1e-12 && (antenna_n.z() + 2.5).abs() < 1e-12);
//! ```
//!
//! The speed along the vehicle's forward axis needs the velocity in body axes, not its NED
//! components:
//!
//! ```compile_fail
//! use thermonav::frames::{Body, Ned, Rotation, Vector};
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.0, 0.0, 0.5);
//! let velocity_n: Vector<Ned> = Vector::new(3.0, 4.0, 0.0);
//! let forward_b: Vector<Body> = Vector::new(1.0, 0.0, 0.0);
//! let speed = velocity_n.dot(&forward_b); // a dot product across frames
//! ```
//!
//! ```
//! use thermonav::frames::{Body, Ned, Rotation, Vector};
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.0, 0.0, 0.5);
//! let velocity_n: Vector<Ned> = Vector::new(3.0, 4.0, 0.0);
//! let forward_b: Vector<Body> = Vector::new(1.0, 0.0, 0.0);
//! let speed = (c_b_n.inverse() * velocity_n).dot(&forward_b);
//! assert!((speed - (3.0 * 0.5f64.cos() + 4.0 * 0.5f64.sin())).abs() < 1e-12);
//! ```
//!
//! Rotations compose only when the inner frames meet: C_b^e = C_n^e C_b^n, never
//! C_b^n C_n^e.
//!
//! ```compile_fail
//! use thermonav::frames::{Body, Ecef, Ned, Rotation};
//! use thermonav::geo::position::Geodetic;
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.1, -0.2, 1.0);
//! let c_n_e: Rotation<Ned, Ecef> = Geodetic::from_degrees(44.6, -63.6, 5.0).ned_to_ecef();
//! let c_b_e: Rotation<Body, Ecef> = c_b_n * c_n_e; // the product in the wrong order
//! ```
//!
//! ```
//! use thermonav::frames::{Body, Ecef, Ned, Rotation, Vector};
//! use thermonav::geo::position::Geodetic;
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.1, -0.2, 1.0);
//! let c_n_e: Rotation<Ned, Ecef> = Geodetic::from_degrees(44.6, -63.6, 5.0).ned_to_ecef();
//! let c_b_e: Rotation<Body, Ecef> = c_n_e * c_b_n;
//! let v_b: Vector<Body> = Vector::new(1.0, 2.0, 3.0);
//! assert!((c_b_e * v_b - c_n_e * (c_b_n * v_b)).norm() < 1e-12);
//! ```
//!
//! Roll, pitch and yaw describe the body relative to the local level frame only; other
//! rotations are built from quaternions:
//!
//! ```compile_fail
//! use thermonav::frames::{Ecef, Ned, Rotation};
//! let c_n_e = Rotation::<Ned, Ecef>::from_euler_zyx(0.0, 0.0, 0.3); // not an attitude
//! ```
//!
//! ```
//! use thermonav::frames::{Body, Ned, Rotation};
//! let c_b_n = Rotation::<Body, Ned>::from_euler_zyx(0.0, 0.0, 0.3);
//! assert!((c_b_n.euler_zyx().2 - 0.3).abs() < 1e-15);
//! ```
//!
//! A position moves by a NED offset ([`crate::geo::position::Geodetic::displaced`]); an offset
//! in body axes must be rotated first (this is how the IMU position follows from the
//! antenna's):
//!
//! ```compile_fail
//! use thermonav::frames::{Body, Vector};
//! use thermonav::geo::position::Geodetic;
//! let antenna = Geodetic::from_degrees(44.6, -63.6, 5.0);
//! let lever_arm_b: Vector<Body> = Vector::new(0.3, 0.0, -2.5);
//! let imu = antenna.displaced(&(-lever_arm_b)); // body axes taken for north, east, down
//! ```
//!
//! ```
//! use thermonav::frames::{Body, Ned, Rotation, Vector};
//! use thermonav::geo::position::Geodetic;
//! let antenna = Geodetic::from_degrees(44.6, -63.6, 5.0);
//! let lever_arm_b: Vector<Body> = Vector::new(0.3, 0.0, -2.5);
//! let c_b_n: Rotation<Body, Ned> = Rotation::from_euler_zyx(0.0, 0.0, 0.0);
//! let imu = antenna.displaced(&(-(c_b_n * lever_arm_b)));
//! assert!((antenna.height_m - imu.height_m - 2.5).abs() < 1e-9);
//! ```

use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};
use std::marker::PhantomData;
use std::ops::{Add, Mul, Neg, Sub};

/// The body frame: forward, right, down, fixed to the IMU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Body;
/// The IMU's own measurement axes (the sensor frame `s`, as printed on its case), which the
/// mounting ([`crate::mounting::Mounting`]) turns into body axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorAxes;
/// The local-level navigation frame: north, east, down.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ned;
/// The Earth-centred Earth-fixed frame (WGS84).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ecef;

/// A 3-vector resolved in frame `F`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vector<F> {
    v: Vector3<f64>,
    frame: PhantomData<F>,
}

impl<F> Vector<F> {
    /// The vector (x, y, z) in frame `F`.
    pub fn new(x: f64, y: f64, z: f64) -> Self {
        Self::from_raw(Vector3::new(x, y, z))
    }

    /// The zero vector.
    pub fn zeros() -> Self {
        Self::from_raw(Vector3::zeros())
    }

    /// Wraps raw components declared to be in frame `F`.
    pub fn from_raw(v: Vector3<f64>) -> Self {
        Self {
            v,
            frame: PhantomData,
        }
    }

    /// From an array [x, y, z].
    pub fn from_array(a: [f64; 3]) -> Self {
        Self::new(a[0], a[1], a[2])
    }

    /// The raw components (for filter kernels that mix frames deliberately).
    pub fn raw(&self) -> Vector3<f64> {
        self.v
    }

    /// Components as an array.
    pub fn to_array(&self) -> [f64; 3] {
        [self.v.x, self.v.y, self.v.z]
    }

    /// First component.
    pub fn x(&self) -> f64 {
        self.v.x
    }

    /// Second component.
    pub fn y(&self) -> f64 {
        self.v.y
    }

    /// Third component.
    pub fn z(&self) -> f64 {
        self.v.z
    }

    /// Euclidean norm.
    pub fn norm(&self) -> f64 {
        self.v.norm()
    }

    /// Cross product in the same frame.
    pub fn cross(&self, other: &Self) -> Self {
        Self::from_raw(self.v.cross(&other.v))
    }

    /// Dot product.
    pub fn dot(&self, other: &Self) -> f64 {
        self.v.dot(&other.v)
    }

    /// Scaled by `k`.
    pub fn scale(&self, k: f64) -> Self {
        Self::from_raw(self.v * k)
    }
}

impl<F> Add for Vector<F> {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self::from_raw(self.v + rhs.v)
    }
}

impl<F> Sub for Vector<F> {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Self::from_raw(self.v - rhs.v)
    }
}

impl<F> Neg for Vector<F> {
    type Output = Self;
    fn neg(self) -> Self {
        Self::from_raw(-self.v)
    }
}

/// A rotation taking `From` coordinates to `To` coordinates (C_From^To), held as a unit
/// quaternion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotation<From, To> {
    q: UnitQuaternion<f64>,
    frames: PhantomData<(From, To)>,
}

impl<From, To> Rotation<From, To> {
    /// The identity (the two frames coincide).
    pub fn identity() -> Self {
        Self::from_unit_quaternion(UnitQuaternion::identity())
    }

    /// From a unit quaternion q with v_To = q ⊗ v_From ⊗ q*.
    pub fn from_unit_quaternion(q: UnitQuaternion<f64>) -> Self {
        Self {
            q,
            frames: PhantomData,
        }
    }

    /// From quaternion components [w, x, y, z] (normalised here).
    pub fn from_wxyz(q: [f64; 4]) -> Self {
        Self::from_unit_quaternion(UnitQuaternion::from_quaternion(Quaternion::new(
            q[0], q[1], q[2], q[3],
        )))
    }

    /// Quaternion components [w, x, y, z] with w ≥ 0.
    pub fn to_wxyz(&self) -> [f64; 4] {
        let q = self.q.quaternion();
        let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
        [sign * q.w, sign * q.i, sign * q.j, sign * q.k]
    }

    /// The underlying unit quaternion.
    pub fn unit_quaternion(&self) -> UnitQuaternion<f64> {
        self.q
    }

    /// The direction cosine matrix C_From^To as a matrix.
    pub fn to_matrix3(&self) -> Matrix3<f64> {
        self.q.to_rotation_matrix().into_inner()
    }

    /// The direction cosine matrix C_From^To as rows.
    pub fn matrix(&self) -> [[f64; 3]; 3] {
        let m = self.q.to_rotation_matrix();
        std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]))
    }

    /// The inverse rotation, C_To^From.
    pub fn inverse(&self) -> Rotation<To, From> {
        Rotation::from_unit_quaternion(self.q.inverse())
    }

    /// Angle of the rotation that takes `self` to `other`, rad.
    pub fn angle_to(&self, other: &Self) -> f64 {
        self.q.angle_to(&other.q)
    }
}

impl Rotation<Body, Ned> {
    /// C_b^n from Euler angles ZYX (roll φ, pitch θ, yaw ψ), rad.
    pub fn from_euler_zyx(roll_rad: f64, pitch_rad: f64, yaw_rad: f64) -> Self {
        Self::from_unit_quaternion(UnitQuaternion::from_euler_angles(
            roll_rad, pitch_rad, yaw_rad,
        ))
    }

    /// Euler angles (roll, pitch, yaw), rad; yaw in (−π, π].
    pub fn euler_zyx(&self) -> (f64, f64, f64) {
        self.q.euler_angles()
    }
}

impl<A, B> Rotation<A, B> {
    /// Post-multiplies by the rotation of the `A` axes through the rotation vector `phi`
    /// (expressed in `A`): C_A'^B = C_A^B · exp([φ×]). This is how a body attitude is advanced
    /// by a gyro increment.
    pub fn rotated_by_rotation_vector(&self, phi: Vector3<f64>) -> Self {
        Self::from_unit_quaternion(self.q * UnitQuaternion::from_scaled_axis(phi))
    }

    /// Pre-multiplies by the rotation of the `B` axes through −`phi` (expressed in `B`):
    /// C_A^B' = exp(−[φ×]) · C_A^B. This is how the navigation frame's own rotation is
    /// removed.
    pub fn frame_rotated_by_rotation_vector(&self, phi: Vector3<f64>) -> Self {
        Self::from_unit_quaternion(UnitQuaternion::from_scaled_axis(-phi) * self.q)
    }
}

impl<A, B, C> Mul<Rotation<A, B>> for Rotation<B, C> {
    type Output = Rotation<A, C>;
    fn mul(self, rhs: Rotation<A, B>) -> Rotation<A, C> {
        Rotation::from_unit_quaternion(self.q * rhs.q)
    }
}

impl<A, B> Mul<Vector<A>> for Rotation<A, B> {
    type Output = Vector<B>;
    fn mul(self, rhs: Vector<A>) -> Vector<B> {
        Vector::from_raw(self.q * rhs.v)
    }
}

/// The skew-symmetric matrix [v×] with [v×] w = v × w.
pub fn skew_matrix(v: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rx(a: f64) -> [[f64; 3]; 3] {
        let (s, c) = a.sin_cos();
        [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]]
    }
    fn ry(a: f64) -> [[f64; 3]; 3] {
        let (s, c) = a.sin_cos();
        [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]
    }
    fn rz(a: f64) -> [[f64; 3]; 3] {
        let (s, c) = a.sin_cos();
        [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
    }
    fn matmul(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
        std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| a[r][k] * b[k][c]).sum()))
    }

    #[test]
    fn euler_zyx_is_rz_ry_rx_written_by_hand() {
        let (roll, pitch, yaw) = (0.3, -0.7, 2.5);
        let expected = matmul(rz(yaw), matmul(ry(pitch), rx(roll)));
        let m = Rotation::<Body, Ned>::from_euler_zyx(roll, pitch, yaw).matrix();
        for r in 0..3 {
            for c in 0..3 {
                assert!((m[r][c] - expected[r][c]).abs() < 1e-15, "({r},{c})");
            }
        }
    }

    #[test]
    fn euler_round_trip_and_quaternion_sign() {
        let c = Rotation::<Body, Ned>::from_euler_zyx(-1.2, 0.4, -3.0);
        let (r, p, y) = c.euler_zyx();
        assert!((r + 1.2).abs() < 1e-12 && (p - 0.4).abs() < 1e-12 && (y + 3.0).abs() < 1e-12);
        let q = c.to_wxyz();
        assert!(q[0] >= 0.0);
        let back = Rotation::<Body, Ned>::from_wxyz(q);
        assert!(back.angle_to(&c) < 1e-12);
    }

    #[test]
    fn quaternion_matches_the_closed_form_dcm() {
        // C = [[1-2(y²+z²), 2(xy-wz), 2(xz+wy)], ...] for q = [w, x, y, z] (Hamilton).
        let raw = [0.5_f64, -0.1, 0.7, 0.2];
        let n = raw.iter().map(|v| v * v).sum::<f64>().sqrt();
        let [w, x, y, z] = raw.map(|v| v / n);
        let expected = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - w * z),
                2.0 * (x * z + w * y),
            ],
            [
                2.0 * (x * y + w * z),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - w * x),
            ],
            [
                2.0 * (x * z - w * y),
                2.0 * (y * z + w * x),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        let m = Rotation::<Body, Ned>::from_wxyz(raw).matrix();
        for r in 0..3 {
            for c in 0..3 {
                assert!((m[r][c] - expected[r][c]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn composition_and_inverse_follow_the_frames() {
        let c_b_n = Rotation::<Body, Ned>::from_euler_zyx(0.1, 0.2, 0.3);
        let c_n_e: Rotation<Ned, Ecef> = Rotation::from_wxyz([0.9, 0.1, -0.3, 0.2]);
        let v_b = Vector::<Body>::new(1.0, -2.0, 0.5);
        let direct = (c_n_e * c_b_n) * v_b;
        let stepwise = c_n_e * (c_b_n * v_b);
        assert!((direct - stepwise).norm() < 1e-14);
        let back = c_b_n.inverse() * (c_b_n * v_b);
        assert!((back - v_b).norm() < 1e-14);
    }

    #[test]
    fn rotation_vector_updates_match_small_axis_rotations() {
        // Rotating the body by +90° about its z axis turns a north-facing IMU to face east.
        let c = Rotation::<Body, Ned>::identity().rotated_by_rotation_vector(Vector3::new(
            0.0,
            0.0,
            std::f64::consts::FRAC_PI_2,
        ));
        let (_, _, yaw) = c.euler_zyx();
        assert!((yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        // Rotating the navigation axes by +90° about down makes the same body face 90° less.
        let c2 = Rotation::<Body, Ned>::identity().frame_rotated_by_rotation_vector(Vector3::new(
            0.0,
            0.0,
            std::f64::consts::FRAC_PI_2,
        ));
        assert!((c2.euler_zyx().2 + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }
}
