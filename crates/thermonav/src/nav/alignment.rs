//! Initial alignment: coarse levelling from the mean specific force, heading from a
//! dual-antenna baseline or from the GNSS course, position and velocity from the first fixes,
//! and the initial covariance.
//!
//! Levelling (Groves 2013 §5.6.2): at rest the accelerometers sense f^b = −C_n^b g^n, so
//! roll φ = atan2(−f_y, −f_z) and pitch θ = atan2(f_x, √(f_y² + f_z²)). On a moving vehicle
//! the mean over a short span still levels to within the mean horizontal acceleration over g;
//! the initial attitude uncertainty should say so.

use super::error_state::{Estimate, SensorCorrection};
use super::measurement::AntennaGeometry;
use crate::frames::{Body, Rotation, Vector};
use crate::geo::position::Geodetic;
use crate::gnss::{GnssFix, HeadingObservation};
use crate::ins::error_model::{STATES, SystemMatrix, block};
use crate::ins::state::{Increment, NavState};
use crate::time::Duration;
use serde::Serialize;

/// Shortest course baseline, m: the distance the vehicle must cover in a straight line before
/// its course is taken for the initial heading.
pub const MIN_COURSE_BASELINE_M: f64 = 2.0;

/// A course baseline is also at least this many horizontal position standard deviations long:
/// the course of two fixes σ apart in each axis and d apart errs by about √2·σ/d rad, so 16 σ
/// keeps it near 5°, the initial heading uncertainty of [`InitialUncertainty::default`].
pub const COURSE_BASELINE_IN_SD: f64 = 16.0;

/// Longest time a course baseline may span, s: slower than that, the vehicle is waited for.
pub const MAX_COURSE_BASELINE_S: f64 = 20.0;

/// Fewest fixes on a course baseline: with three or more, a fix that is off (a multipath jump, a
/// wrong RTK fix) stands out as a residual from the straight line through the others.
pub const MIN_COURSE_FIXES: usize = 3;

/// A dense, noisy stretch (many fixes, each metres off) also ends as soon as its fitted
/// course's sd is this small, rad (2°), and its fitted line is [`MIN_COURSE_BASELINE_M`] long:
/// 20 Hz fixes 0.7 m off give a rover at 0.4 m/s that sd in about 12 s, while 16 sds (11.2 m)
/// take it 28 s, more than [`MAX_COURSE_BASELINE_S`]. Without this the stretch ended only
/// where the noise threw a fix 16 sds away, a choice made by the noise (issue 38 row 14).
pub const COURSE_SD_ENOUGH_RAD: f64 = 2.0 * std::f64::consts::PI / 180.0;

/// A stretch whose halves' courses differ by more than this many sds of the difference ...
pub const BEND_TEST_SD: f64 = 3.0;

/// ... and by more than this, rad (5°, the default initial heading sd), holds a turn: its mean
/// course is not the heading at its start, and it is no baseline.
pub const BEND_TOLERANCE_RAD: f64 = 5.0 * std::f64::consts::PI / 180.0;

/// Horizontal position standard deviation assumed for a fix that states none, m (code GNSS).
pub const UNSTATED_POSITION_SD_M: f64 = 1.0;

/// The straight, evenly driven stretch of fixes the initial course was taken from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CourseBaseline {
    /// Distance from the first fix to the last, horizontal, m.
    pub distance_m: f64,
    /// Time from the first fix to the last, s.
    pub duration_s: f64,
    /// Fixes on it.
    pub fixes: usize,
    /// Standard deviation of the fitted course, rad (from the stated position noise).
    pub course_sd_rad: f64,
    /// Largest horizontal distance of a fix from the fitted constant-velocity line, m.
    pub largest_residual_m: f64,
    /// Mean velocity over it, north/east/down, m/s.
    pub velocity_ned_m_s: [f64; 3],
}

/// Roll and pitch (rad) from a mean specific force in body axes (m/s²).
pub fn level(mean_specific_force_b: [f64; 3]) -> (f64, f64) {
    let [fx, fy, fz] = mean_specific_force_b;
    ((-fy).atan2(-fz), fx.atan2(fy.hypot(fz)))
}

/// Where the initial heading came from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadingSource {
    /// The first fix's dual-antenna heading.
    DualAntenna,
    /// The course over ground along a straight baseline of fixes.
    Course(CourseBaseline),
}

/// Why the alignment failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AlignmentError {
    /// Fewer than two GNSS fixes at or after the first IMU sample.
    #[error(
        "alignment needs two GNSS fixes at or after the first IMU sample ({imu_start_s:.3} s); the GNSS file has {fixes}, {after_imu_start} of them from then on{}",
        span_note(*first_fix_s, *last_fix_s)
    )]
    TooFewFixes {
        /// Fixes in the file.
        fixes: usize,
        /// Fixes at or after the first IMU sample.
        after_imu_start: usize,
        /// Time of the first IMU sample, s (NaN without IMU data).
        imu_start_s: f64,
        /// Time of the first fix, s.
        first_fix_s: Option<f64>,
        /// Time of the last fix, s.
        last_fix_s: Option<f64>,
    },
    /// No IMU data in the levelling span.
    #[error("no IMU sample in the {0} s after the first GNSS fix to level with")]
    NoImu(f64),
    /// Neither a dual-antenna heading nor a straight baseline for a course.
    #[error(
        "no initial heading: no fix during the IMU record has a dual-antenna heading, and the fixes never cover a straight baseline for the course ({MIN_COURSE_BASELINE_M} m and {COURSE_BASELINE_IN_SD} position sds or more, within {MAX_COURSE_BASELINE_S} s, {MIN_COURSE_FIXES} fixes or more, each close to the line through them); fastest speed between fixes {speed_m_s:.2} m/s"
    )]
    NoHeading {
        /// Largest speed between consecutive fixes.
        speed_m_s: f64,
    },
}

/// " (fixes from A to B s: check that both files share one time scale)", or nothing.
fn span_note(first_fix_s: Option<f64>, last_fix_s: Option<f64>) -> String {
    match (first_fix_s, last_fix_s) {
        (Some(a), Some(b)) => {
            format!(" (fixes from {a:.3} to {b:.3} s: check that both files share one time scale)")
        }
        _ => String::new(),
    }
}

/// The aligned initial state and how its heading was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Alignment {
    /// The initial state at the first fix's time.
    pub nav: NavState,
    /// Heading source.
    pub heading_source: HeadingSource,
}

/// The fix's position.
pub(crate) fn geodetic_of(fix: &GnssFix) -> Geodetic {
    Geodetic {
        latitude_rad: fix.latitude_rad,
        longitude_rad: fix.longitude_rad,
        height_m: fix.height_m,
    }
}

/// Aligns at the first GNSS fix during the IMU record that has a dual-antenna heading or that
/// starts a straight course baseline ([`course_baseline`]; a vehicle parked at the start is
/// waited for): attitude levelled from the IMU samples in `levelling_s` after it, heading
/// from its dual-antenna heading or the baseline's course, velocity from its velocity or the
/// baseline's mean velocity, position at the IMU (the antenna position less the lever arm).
///
/// # Errors
/// [`AlignmentError`] when the data cannot give one of these.
pub fn align_from_gnss(
    imu: &[Increment],
    gnss: &[GnssFix],
    geometry: &AntennaGeometry,
    levelling_s: f64,
) -> Result<Alignment, AlignmentError> {
    let imu_start = imu.first().map(|i| i.time);
    let usable: Vec<&[GnssFix]> = gnss
        .windows(2)
        .filter(|w| imu_start.is_some_and(|t| w[0].time >= t))
        .collect();
    if usable.is_empty() {
        let start = imu_start.map_or(f64::NAN, |t| t.as_seconds());
        return Err(AlignmentError::TooFewFixes {
            fixes: gnss.len(),
            after_imu_start: gnss
                .iter()
                .filter(|f| imu_start.is_some_and(|t| f.time >= t))
                .count(),
            imu_start_s: start,
            first_fix_s: gnss.first().map(|f| f.time.as_seconds()),
            last_fix_s: gnss.last().map(|f| f.time.as_seconds()),
        });
    }
    let course_of = |w: &[GnssFix]| {
        let dt = w[1].time.since(w[0].time).as_seconds();
        geodetic_of(&w[1])
            .ned_from(&geodetic_of(&w[0]))
            .scale(1.0 / dt)
    };
    let speed = |w: &[GnssFix]| {
        let c = course_of(w);
        c.x().hypot(c.y())
    };
    let starts = gnss.len() - usable.len() - 1;
    let found = (starts..gnss.len()).find_map(|i| match gnss[i].heading {
        Some(h) => Some((i, HeadingFrom::Antenna(h))),
        None => course_baseline(&gnss[i..]).map(|c| (i, HeadingFrom::Course(c))),
    });
    let Some((index, heading_from)) = found else {
        let fastest = usable.iter().map(|w| speed(w)).fold(0.0, f64::max);
        return Err(AlignmentError::NoHeading { speed_m_s: fastest });
    };
    let index = match &heading_from {
        HeadingFrom::Course(c) => index + nearest_to_mean_time(&gnss[index..index + c.fixes]),
        HeadingFrom::Antenna(_) => index,
    };
    let pair = &gnss[index..(index + 2).min(gnss.len())];
    let first = &pair[0];
    let span: Vec<_> = imu
        .iter()
        .filter(|i| i.time > first.time && i.time.since(first.time).as_seconds() <= levelling_s)
        .collect();
    let total_dt: Duration = span.iter().map(|i| i.dt).sum();
    if span.is_empty() || !total_dt.is_positive() {
        return Err(AlignmentError::NoImu(levelling_s));
    }
    let mean_force = span
        .iter()
        .fold(Vector::<Body>::zeros(), |acc, i| acc + i.delta_velocity)
        .scale(1.0 / total_dt.as_seconds());
    let (roll, pitch) = level(mean_force.to_array());
    let p0 = geodetic_of(first);
    let (yaw, heading_source, course) = match heading_from {
        HeadingFrom::Antenna(h) => {
            let b = geometry.baseline_body;
            let course = match pair.len() {
                2 => course_of(pair),
                _ => Vector::zeros(),
            };
            (
                h.heading_rad - b[1].atan2(b[0]),
                HeadingSource::DualAntenna,
                course,
            )
        }
        HeadingFrom::Course(c) => {
            let [vn, ve, _] = c.velocity_ned_m_s;
            let velocity = Vector::from_array(c.velocity_ned_m_s);
            (ve.atan2(vn), HeadingSource::Course(c), velocity)
        }
    };
    let attitude = Rotation::from_euler_zyx(roll, pitch, yaw);
    let lever = attitude * Vector::<Body>::from_array(geometry.lever_arm_body_m);
    let velocity = first
        .velocity_ned_m_s
        .map(Vector::from_array)
        .unwrap_or(course);
    Ok(Alignment {
        nav: NavState {
            time: first.time,
            position: p0.displaced(&(-lever)),
            velocity,
            attitude,
        },
        heading_source,
    })
}

/// The index of the fix nearest the fixes' mean time: a constant-velocity line fitted through
/// them has the velocity (and so the course) of the vehicle at that time, exactly when it
/// accelerates evenly, and to first order in the turn rate when it curves gently. A rover that
/// pulls away from rest inside the stretch is slower at its first fix than the line says.
fn nearest_to_mean_time(fixes: &[GnssFix]) -> usize {
    let Some(first) = fixes.first() else {
        return 0;
    };
    let offset = |f: &GnssFix| f.time.since(first.time).as_seconds();
    let mean = fixes.iter().map(offset).sum::<f64>() / fixes.len() as f64;
    (0..fixes.len())
        .min_by(|&a, &b| {
            let (da, db) = (
                (offset(&fixes[a]) - mean).abs(),
                (offset(&fixes[b]) - mean).abs(),
            );
            da.total_cmp(&db)
        })
        .unwrap_or(0)
}

/// What the initial heading is taken from at the alignment fix.
enum HeadingFrom {
    Antenna(HeadingObservation),
    Course(CourseBaseline),
}

/// The course baseline that starts at `fixes[0]`, if there is one: the first fixes up to the
/// first one at least [`MIN_COURSE_BASELINE_M`] and [`COURSE_BASELINE_IN_SD`] horizontal
/// position sds away, or up to the first at which the fitted course's sd is
/// [`COURSE_SD_ENOUGH_RAD`] or less over a fitted line [`MIN_COURSE_BASELINE_M`] long (at least
/// [`MIN_COURSE_FIXES`] fixes, within [`MAX_COURSE_BASELINE_S`]), fitted by least squares with a
/// constant velocity; `None` when the stretch is too slow, too short in fixes, or bent or
/// broken: a fix farther from the fitted line than 4 sds or 5 % of the baseline (a turn of
/// radius R bows a chord d by d²/8R: 5 % is a radius of 2.5 d), or halves whose courses differ
/// by more than [`BEND_TEST_SD`] sds and [`BEND_TOLERANCE_RAD`] (a turn inside a long stretch
/// of noisy fixes, which bows it by less than 4 sds).
pub fn course_baseline(fixes: &[GnssFix]) -> Option<CourseBaseline> {
    let first = fixes.first()?;
    let sd = horizontal_sd_m(first);
    let needed = MIN_COURSE_BASELINE_M.max(COURSE_BASELINE_IN_SD * sd);
    let origin = geodetic_of(first);
    let mut points = Vec::new();
    let mut sums = LineSums::default();
    for fix in fixes {
        let t = fix.time.since(first.time).as_seconds();
        if t > MAX_COURSE_BASELINE_S {
            return None;
        }
        let offset = geodetic_of(fix).ned_from(&origin).to_array();
        points.push((t, offset));
        sums.add(t, offset);
        let distance = offset[0].hypot(offset[1]);
        if distance >= needed || sums.course_known(sd) {
            if points.len() < MIN_COURSE_FIXES {
                return None;
            }
            return straight_line_course(&points, distance, sd);
        }
    }
    None
}

/// Running sums of a constant-velocity least-squares line through horizontal points, so that
/// the fitted course's sd is known at every fix of a stretch without refitting it.
#[derive(Debug, Clone, Copy, Default)]
struct LineSums {
    n: f64,
    t: f64,
    tt: f64,
    x: [f64; 2],
    tx: [f64; 2],
    /// The last point's time (the first is at 0), s.
    last_t: f64,
}

impl LineSums {
    fn add(&mut self, t: f64, offset: [f64; 3]) {
        self.n += 1.0;
        self.t += t;
        self.tt += t * t;
        self.last_t = t;
        for ((x, tx), o) in self.x.iter_mut().zip(&mut self.tx).zip(offset) {
            *x += o;
            *tx += t * o;
        }
    }

    /// Whether the fitted course's sd is [`COURSE_SD_ENOUGH_RAD`] or less and the fitted line
    /// covers [`MIN_COURSE_BASELINE_M`] (its speed times the time spanned).
    fn course_known(&self, sd_m: f64) -> bool {
        if self.n < MIN_COURSE_FIXES as f64 {
            return false;
        }
        let spread = self.tt - self.t * self.t / self.n;
        let slope = |k: usize| (self.tx[k] - self.t * self.x[k] / self.n) / spread;
        let speed = slope(0).hypot(slope(1));
        let course_sd = sd_m / spread.sqrt() / speed;
        course_sd <= COURSE_SD_ENOUGH_RAD && speed * self.last_t >= MIN_COURSE_BASELINE_M
    }
}
/// The larger of a fix's stated north and east sds, or [`UNSTATED_POSITION_SD_M`].
pub(crate) fn horizontal_sd_m(fix: &GnssFix) -> f64 {
    fix.position_sd_ned_m
        .map(|[n, e, _]| n.max(e))
        .filter(|sd| sd.is_finite() && *sd > 0.0)
        .unwrap_or(UNSTATED_POSITION_SD_M)
}

/// The constant-velocity least-squares line through `(t, NED offset)` points, as a
/// baseline, or `None` when a point is off it (see [`course_baseline`]).
fn straight_line_course(
    points: &[(f64, [f64; 3])],
    distance_m: f64,
    sd_m: f64,
) -> Option<CourseBaseline> {
    let (lines, spread) = fitted_line(points);
    let largest_residual_m = points
        .iter()
        .map(|(t, p)| {
            let off = |axis: usize| p[axis] - (lines[axis].0 + lines[axis].1 * t);
            off(0).hypot(off(1))
        })
        .fold(0.0, f64::max);
    if largest_residual_m > (4.0 * sd_m).max(0.05 * distance_m) || bent(points, sd_m) {
        return None;
    }
    let velocity_ned_m_s = [lines[0].1, lines[1].1, lines[2].1];
    let speed = velocity_ned_m_s[0].hypot(velocity_ned_m_s[1]);
    let course_sd_rad = sd_m / spread.sqrt() / speed;
    if !course_sd_rad.is_finite() {
        return None;
    }
    Some(CourseBaseline {
        distance_m,
        duration_s: points.last()?.0,
        fixes: points.len(),
        course_sd_rad,
        largest_residual_m,
        velocity_ned_m_s,
    })
}

/// The constant-velocity least-squares line through `(t, NED offset)` points: (intercept,
/// slope) per axis, and Σ (t − t̄)².
fn fitted_line(points: &[(f64, [f64; 3])]) -> ([(f64, f64); 3], f64) {
    let n = points.len() as f64;
    let t_mean = points.iter().map(|p| p.0).sum::<f64>() / n;
    let spread: f64 = points.iter().map(|p| (p.0 - t_mean).powi(2)).sum();
    let fit = |axis: usize| {
        let mean = points.iter().map(|p| p.1[axis]).sum::<f64>() / n;
        let slope = points
            .iter()
            .map(|p| (p.0 - t_mean) * (p.1[axis] - mean))
            .sum::<f64>()
            / spread;
        (mean - slope * t_mean, slope)
    };
    ([fit(0), fit(1), fit(2)], spread)
}

/// Whether the courses fitted to the stretch's first and second halves differ by more than
/// [`BEND_TEST_SD`] sds of their difference and by more than [`BEND_TOLERANCE_RAD`]. Halves
/// of fewer than [`MIN_COURSE_FIXES`] fixes, or one standing still (no course), are no evidence
/// of a turn.
fn bent(points: &[(f64, [f64; 3])], sd_m: f64) -> bool {
    let (first, second) = points.split_at(points.len() / 2);
    if first.len() < MIN_COURSE_FIXES || second.len() < MIN_COURSE_FIXES {
        return false;
    }
    let course = |half: &[(f64, [f64; 3])]| {
        let (lines, spread) = fitted_line(half);
        let (vn, ve) = (lines[0].1, lines[1].1);
        (ve.atan2(vn), sd_m / spread.sqrt() / vn.hypot(ve))
    };
    let ((a, sd_a), (b, sd_b)) = (course(first), course(second));
    let turn = crate::units::wrap_pi(b - a).abs();
    let sd = sd_a.hypot(sd_b);
    sd.is_finite() && turn > (BEND_TEST_SD * sd).max(BEND_TOLERANCE_RAD)
}

/// Initial standard deviations of the 21 error states.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InitialUncertainty {
    /// Position, north/east/down, m.
    pub position_sd_m: [f64; 3],
    /// Velocity, north/east/down, m/s.
    pub velocity_sd_m_s: [f64; 3],
    /// Attitude error about north/east/down (≈ roll, pitch, heading when level), rad.
    pub attitude_sd_rad: [f64; 3],
    /// Gyro bias x, y, z, rad/s (the turn-on bias: see [`InitialBiasSource`]).
    pub gyro_bias_sd_rad_s: [f64; 3],
    /// Accelerometer bias x, y, z, m/s².
    pub accel_bias_sd_m_s2: [f64; 3],
    /// Gyro scale-factor error (dimensionless).
    pub gyro_scale_sd: f64,
    /// Accelerometer scale-factor error (dimensionless).
    pub accel_scale_sd: f64,
}

impl Default for InitialUncertainty {
    /// A consumer MEMS IMU aligned on a moving vehicle with code GNSS: 2 m, 0.5 m/s, 2° in
    /// roll and pitch, 5° in heading, 1 °/s and 10 mg turn-on biases (ADIS16364 data sheet:
    /// ±3 °/s, ±8 mg), 1000 ppm scale factors.
    fn default() -> Self {
        Self {
            position_sd_m: [2.0, 2.0, 3.0],
            velocity_sd_m_s: [0.5; 3],
            attitude_sd_rad: [2f64.to_radians(), 2f64.to_radians(), 5f64.to_radians()],
            gyro_bias_sd_rad_s: [1f64.to_radians(); 3],
            accel_bias_sd_m_s2: [0.01 * crate::units::STANDARD_GRAVITY_M_S2; 3],
            gyro_scale_sd: 1e-3,
            accel_scale_sd: 1e-3,
        }
    }
}

impl InitialUncertainty {
    /// The diagonal initial covariance.
    pub fn covariance(&self) -> SystemMatrix {
        let mut sd = [0.0; STATES];
        let mut put = |start: usize, v: [f64; 3]| sd[start..start + 3].copy_from_slice(&v);
        put(block::POSITION, self.position_sd_m);
        put(block::VELOCITY, self.velocity_sd_m_s);
        put(block::ATTITUDE, self.attitude_sd_rad);
        put(block::GYRO_BIAS, self.gyro_bias_sd_rad_s);
        put(block::ACCEL_BIAS, self.accel_bias_sd_m_s2);
        put(block::GYRO_SCALE, [self.gyro_scale_sd; 3]);
        put(block::ACCEL_SCALE, [self.accel_scale_sd; 3]);
        SystemMatrix::from_diagonal(&nalgebra::SVector::from(sd.map(|s| s * s)))
    }
}

/// Where the initial bias uncertainty came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum InitialBiasSource {
    /// [`InitialUncertainty::default`]'s 1 °/s and 10 mg: nothing better is known (a bank
    /// without a thermal calibration, or a record not compensated with it).
    Default,
    /// A sensor profile: its unit-to-unit (turn-on) bias and power-on offset sds, with the
    /// Gauss-Markov bias σ at the run's temperature, added in quadrature.
    ProfileTurnOn,
    /// A bank whose thermal calibration was subtracted: that calibration's spread between
    /// power-ons (the unit's own bias curve is known) with the Gauss-Markov bias σ, added in
    /// quadrature; channels whose calibration separated no power-ons keep the default.
    BankPowerOnSpread,
}

/// The initial bias sd of one axis: √(Σ parts²), the parts independent.
pub fn bias_sd_in_quadrature(parts: &[f64]) -> f64 {
    parts.iter().map(|p| p * p).sum::<f64>().sqrt()
}

/// An estimate with no sensor correction at a navigation state.
pub fn uncorrected(nav: NavState) -> Estimate {
    Estimate {
        nav,
        sensors: SensorCorrection::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geo::gravity::normal_gravity_m_s2;

    // Closed form: a body at roll φ, pitch θ under gravity g senses
    // f = (g sin θ, −g sin φ cos θ, −g cos φ cos θ); levelling must return (φ, θ).
    #[test]
    fn levelling_recovers_roll_and_pitch() {
        let g = normal_gravity_m_s2(0.8, 0.0);
        for (roll, pitch) in [(0.0, 0.0), (0.2, -0.1), (-1.0, 0.7), (2.5, 0.3)] {
            let f = [
                g * f64::sin(pitch),
                -g * f64::sin(roll) * f64::cos(pitch),
                -g * f64::cos(roll) * f64::cos(pitch),
            ];
            let (r, p) = level(f);
            assert!((r - roll).abs() < 1e-12 && (p - pitch).abs() < 1e-12);
        }
    }

    /// Fixes every `dt_s` from t = 0 along `offsets` (NED from a point at 40° N), each with
    /// a stated horizontal sd of `sd_m`.
    fn fixes_along(offsets: &[[f64; 3]], dt_s: f64, sd_m: f64) -> Vec<GnssFix> {
        let origin = Geodetic {
            latitude_rad: 40f64.to_radians(),
            longitude_rad: -105f64.to_radians(),
            height_m: 1600.0,
        };
        offsets
            .iter()
            .enumerate()
            .map(|(k, o)| {
                let p = origin.displaced(&Vector::from_array(*o));
                GnssFix {
                    time: crate::time::Timestamp::from_nanos((k as f64 * dt_s * 1e9) as i64),
                    latitude_rad: p.latitude_rad,
                    longitude_rad: p.longitude_rad,
                    height_m: p.height_m,
                    position_sd_ned_m: Some([sd_m, sd_m, 2.0 * sd_m]),
                    velocity_ned_m_s: None,
                    heading: None,
                }
            })
            .collect()
    }

    // Closed form: fixes every 0.25 s along a straight line at 1.2 m/s on a course of 30°,
    // stated at 1 cm: the baseline ends at the first fix 2 m or more away (2 m = max(2 m,
    // 16 x 1 cm)), i.e. the 7th step (2.1 m, 1.75 s, 8 fixes), with the exact course and velocity (noise-free
    // fixes; the 1e-6 rad allows for the NED offsets of the displaced/ned_from round trip),
    // and a course sd of σ/(speed √Σ(t − t̄)²).
    #[test]
    fn a_straight_baseline_gives_the_course_and_its_sd() {
        let course = 30f64.to_radians();
        let offsets: Vec<_> = (0..40)
            .map(|k| {
                let d = 1.2 * 0.25 * k as f64;
                [d * course.cos(), d * course.sin(), 0.0]
            })
            .collect();
        let fixes = fixes_along(&offsets, 0.25, 0.01);
        let c = course_baseline(&fixes).unwrap();
        assert_eq!(c.fixes, 8);
        assert!((c.duration_s - 1.75).abs() < 1e-9 && (c.distance_m - 2.1).abs() < 1e-6);
        let [vn, ve, vd] = c.velocity_ned_m_s;
        assert!((ve.atan2(vn) - course).abs() < 1e-6 && (vn.hypot(ve) - 1.2).abs() < 1e-6);
        assert!(vd.abs() < 1e-6 && c.largest_residual_m < 1e-6);
        let spread: f64 = (0..8).map(|k| (0.25 * k as f64 - 0.875).powi(2)).sum();
        assert!((c.course_sd_rad - 0.01 / 1.2 / spread.sqrt()).abs() < 1e-9);
    }

    // A fix 5 m off the line breaks the baseline through it; a vehicle at 5 cm/s never covers
    // 2 m within 20 s; a turn of radius 1 m bows the 2 m chord by far more than 5 %.
    #[test]
    fn a_broken_slow_or_bent_stretch_gives_no_baseline() {
        let straight: Vec<_> = (0..20).map(|k| [0.3 * k as f64, 0.0, 0.0]).collect();
        let mut broken = straight.clone();
        broken[3][1] += 5.0;
        assert!(course_baseline(&fixes_along(&straight, 0.25, 0.01)).is_some());
        assert!(course_baseline(&fixes_along(&broken, 0.25, 0.01)).is_none());
        let slow: Vec<_> = (0..200).map(|k| [0.0125 * k as f64, 0.0, 0.0]).collect();
        assert!(course_baseline(&fixes_along(&slow, 0.25, 0.01)).is_none());
        let turn: Vec<_> = (0..40)
            .map(|k| {
                let a = 0.25 * k as f64;
                [a.sin(), 1.0 - a.cos(), 0.0]
            })
            .collect();
        assert!(course_baseline(&fixes_along(&turn, 0.25, 0.01)).is_none());
    }

    // A car parked for 10 s at 4 Hz with one fix thrown 20 m away (the pair through it looks
    // like 80 m/s), then driving north-east at 2 m/s: the alignment waits for the drive and
    // takes its course, not the jump's.
    #[test]
    fn the_alignment_waits_past_a_displaced_fix_for_the_drive() {
        let mut offsets: Vec<[f64; 3]> = (0..40).map(|_| [0.0; 3]).collect();
        offsets[20] = [0.0, 20.0, 0.0];
        let step = 2.0 * 0.25 / 2f64.sqrt();
        offsets.extend((1..40).map(|k| [step * k as f64, step * k as f64, 0.0]));
        let fixes = fixes_along(&offsets, 0.25, 0.01);
        let end = fixes.last().unwrap().time;
        let imu: Vec<Increment> = (0..=2000)
            .map(|k| {
                let time = crate::time::Timestamp::from_nanos(k * 10_000_000);
                let dt = Duration::from_nanos(10_000_000);
                Increment::from_rates(time, dt, [0.0; 3], [0.0, 0.0, -9.8])
            })
            .filter(|i| i.time <= end)
            .collect();
        let a = align_from_gnss(&imu, &fixes, &AntennaGeometry::default(), 1.0).unwrap();
        let HeadingSource::Course(c) = a.heading_source else {
            panic!("a course was expected");
        };
        // The baseline runs from the last parked fix (39, at 9.75 s) to the first 2 m away
        // (43, or 44 where the geodetic round trip leaves 43 a hair short); the run starts at
        // the fix nearest its middle time, evenly spaced fixes' mean time: within half a fix
        // interval (0.125 s) of it.
        assert!(c.duration_s <= 1.25 + 1e-9, "{c:?}");
        let middle_s = 9.75 + c.duration_s / 2.0;
        let start_s = a.nav.time.as_seconds();
        assert!((start_s - middle_s).abs() <= 0.125 + 1e-9, "{start_s} s");
        let yaw = a.nav.attitude.euler_zyx().2;
        assert!((yaw - 45f64.to_radians()).abs() < 0.02, "yaw {yaw}");
        let v = a.nav.velocity.to_array();
        assert!((v[0] - 2f64.sqrt()).abs() < 1e-6 && (v[1] - 2f64.sqrt()).abs() < 1e-6);
        assert!(c.distance_m >= MIN_COURSE_BASELINE_M && c.fixes >= MIN_COURSE_FIXES);
    }

    /// `(t, NED offset)` points every 0.05 s (20 Hz) for `seconds` along the path `at(t)`.
    fn points_along(seconds: f64, at: impl Fn(f64) -> [f64; 3]) -> Vec<(f64, [f64; 3])> {
        let n = (seconds / 0.05).round() as usize;
        (0..=n)
            .map(|k| (0.05 * k as f64, at(0.05 * k as f64)))
            .collect()
    }

    // Issue 38 row 14. A rover at 0.4 m/s on a course of 30°, 20 Hz fixes stated at 0.7 m:
    // 16 sds are 11.2 m, 28 s of driving, past the 20 s a baseline may take, so only a fix
    // thrown that far by the noise ended one. The fitted course's sd, σ/(v √Σ(t − t̄)²), is 2°
    // or less from the n-th fix on, n found here by summing Σ(t − t̄)² afresh for each n
    // (noise-free fixes: the fit is exact, the sd is the stated noise's).
    #[test]
    fn dense_noisy_fixes_end_the_baseline_once_the_course_is_known() {
        let (speed, course, sd) = (0.4, 30f64.to_radians(), 0.7);
        let offsets: Vec<_> = points_along(30.0, |t| {
            let d = speed * t;
            [d * course.cos(), d * course.sin(), 0.0]
        })
        .into_iter()
        .map(|p| p.1)
        .collect();
        let fixes = fixes_along(&offsets, 0.05, sd);
        let course_sd = |n: usize| {
            let times: Vec<f64> = (0..n).map(|k| 0.05 * k as f64).collect();
            let mean = times.iter().sum::<f64>() / n as f64;
            let spread: f64 = times.iter().map(|t| (t - mean).powi(2)).sum();
            sd / spread.sqrt() / speed
        };
        let expected = (3..offsets.len())
            .find(|&n| course_sd(n) <= 2f64.to_radians())
            .unwrap();
        let c = course_baseline(&fixes).unwrap();
        assert_eq!(c.fixes, expected, "{c:?}");
        // 1e-6 relative: the fitted speed carries the geodetic round trip's 1e-7 m.
        assert!(
            (c.course_sd_rad / course_sd(expected) - 1.0).abs() < 1e-6,
            "{c:?}"
        );
        let [vn, ve, _] = c.velocity_ned_m_s;
        assert!((ve.atan2(vn) - course).abs() < 1e-6, "{c:?}");
        assert!(c.duration_s < MAX_COURSE_BASELINE_S && c.distance_m < 16.0 * sd);
    }

    // Issue 38 row 14 (seeds 6, 18 and 20 of bench/slow_rover.py): 12 s at 0.4 m/s through a
    // 90° turn, fixes stated at 0.7 m. The arc (radius v/ω = 3.06 m) bows its chord by
    // R (1 − cos 45°) = 0.90 m, well inside the 4 sds (2.8 m) the residual check allows, but its
    // halves' courses differ by 45°, 3 sds of that difference being 23° (each half's course sd
    // σ/(v √Σ(t − t̄)²) is 5.4° over its 6 s): it is bent. The same 12 s driven straight is a
    // baseline.
    #[test]
    fn a_turn_inside_a_long_noisy_stretch_is_no_baseline() {
        let (speed, rate, sd) = (0.4, 90f64.to_radians() / 12.0, 0.7);
        let radius = speed / rate;
        let turn = points_along(12.0, |t| {
            let a = rate * t;
            [radius * a.sin(), radius * (1.0 - a.cos()), 0.0]
        });
        let chord = 2.0 * radius * 45f64.to_radians().sin();
        let bow = radius * (1.0 - 45f64.to_radians().cos());
        assert!(bow < 4.0 * sd && bow > 0.05 * chord, "bow {bow} m");
        assert!(straight_line_course(&turn, chord, sd).is_none());
        let straight = points_along(12.0, |t| [speed * t, 0.0, 0.0]);
        assert!(straight_line_course(&straight, 12.0 * speed, sd).is_some());
    }

    // The start is the fix nearest the fixes' mean time, not the middle one by count.
    #[test]
    fn the_start_is_the_fix_nearest_the_mean_time() {
        let at = |times: &[f64]| {
            let mut fixes = fixes_along(&vec![[0.0; 3]; times.len()], 1.0, 1.0);
            for (f, t) in fixes.iter_mut().zip(times) {
                f.time = crate::time::Timestamp::from_nanos((t * 1e9) as i64);
            }
            nearest_to_mean_time(&fixes)
        };
        assert_eq!(at(&[0.0, 1.0, 2.0, 3.0, 4.0]), 2);
        // Mean 6.8 s: the fix at 7 s (the second), not the middle one at 8 s.
        assert_eq!(at(&[0.0, 7.0, 8.0, 9.0, 10.0]), 1);
        assert_eq!(at(&[0.0]), 0);
    }
}
