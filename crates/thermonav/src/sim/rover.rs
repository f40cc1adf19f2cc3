//! A slow ground rover (issue 38, rows 13-14): a still start, a gentle pull-away, then square
//! loops of straight legs and 90° turns at a walking or planetary-rover speed, level and
//! without waves. At 0.4 m/s a metre-level fix moves the antenna less than the fix's own
//! noise in seconds, so heading and the IMU-GNSS time offset are weakly observable: the case
//! `simulate vessel --speed-m-s` makes for testing that the filter and the time-offset search
//! say so.

use super::motion::{MotionDefinition, MotionSegment, PitchModel, StartPoint, WaveMotion};

/// Length of the still start, s (long enough for a static alignment).
pub const ROVER_STILL_START_S: f64 = 20.0;
/// Time the rover takes to reach its speed, s.
pub const ROVER_PULL_AWAY_S: f64 = 5.0;
/// Length of each straight leg, s.
pub const ROVER_LEG_S: f64 = 30.0;
/// Turn rate of each 90° turn, deg/s (a turn takes 15 s).
pub const ROVER_TURN_RATE_DEG_S: f64 = 6.0;

/// The rover's motion of `duration_s` at `speed_m_s`: [`ROVER_STILL_START_S`] still, a
/// pull-away over [`ROVER_PULL_AWAY_S`], then legs of [`ROVER_LEG_S`] joined by 90° turns to
/// starboard at [`ROVER_TURN_RATE_DEG_S`], the last segment cut at `duration_s`.
pub fn rover_loops(duration_s: f64, speed_m_s: f64) -> MotionDefinition {
    let segment = |duration_s: f64, acceleration_m_s2: f64, turn_deg_s: f64| MotionSegment {
        duration_s,
        acceleration_m_s2,
        turn_rate_rad_s: turn_deg_s.to_radians(),
        climb_rate_m_s: 0.0,
    };
    let turn_s = 90.0 / ROVER_TURN_RATE_DEG_S;
    let mut plan = vec![
        segment(ROVER_STILL_START_S, 0.0, 0.0),
        segment(ROVER_PULL_AWAY_S, speed_m_s / ROVER_PULL_AWAY_S, 0.0),
    ];
    let mut turn = false;
    while total_s(&plan) < duration_s {
        plan.push(match turn {
            false => segment(ROVER_LEG_S, 0.0, 0.0),
            true => segment(turn_s, 0.0, ROVER_TURN_RATE_DEG_S),
        });
        turn = !turn;
    }
    MotionDefinition {
        start: StartPoint {
            lat_deg: 28.5,
            lon_deg: -80.6,
            h_m: 3.0,
        },
        initial_speed_m_s: 0.0,
        initial_heading_rad: 30f64.to_radians(),
        segments: cut_at(plan, duration_s),
        waves: WaveMotion::default(),
        pitch: PitchModel::Level,
    }
}

/// The summed length of `segments`, s.
fn total_s(segments: &[MotionSegment]) -> f64 {
    segments.iter().map(|s| s.duration_s).sum()
}

/// `segments` up to `duration_s`: later ones dropped, the one across it shortened (a
/// duration shorter than the first segment leaves that segment shortened).
fn cut_at(segments: Vec<MotionSegment>, duration_s: f64) -> Vec<MotionSegment> {
    let mut kept = Vec::new();
    let mut start_s = 0.0;
    for mut segment in segments {
        if start_s >= duration_s {
            break;
        }
        segment.duration_s = segment.duration_s.min(duration_s - start_s);
        start_s += segment.duration_s;
        kept.push(segment);
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed forms: the still start, the pull-away's acceleration v/5 s, and a total of
    // exactly the requested duration with the last leg cut.
    #[test]
    fn the_loops_start_still_reach_the_speed_and_end_at_the_duration() {
        let m = rover_loops(100.0, 0.4);
        assert_eq!(m.initial_speed_m_s, 0.0);
        assert_eq!(m.segments[0].acceleration_m_s2, 0.0);
        assert!((m.segments[1].acceleration_m_s2 - 0.08).abs() < 1e-15);
        assert!((m.duration_s() - 100.0).abs() < 1e-12, "{}", m.duration_s());
        // 20 still + 5 pull-away + 30 leg + 15 turn + 30 leg = 100.
        assert_eq!(m.segments.len(), 5);
        assert!((m.segments[3].turn_rate_rad_s - 6f64.to_radians()).abs() < 1e-15);
    }
}
