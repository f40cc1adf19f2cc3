//! Outside solutions read from bytes (`read_solution`, the fuzz target's entry point) on the
//! hand-written seeds of `fuzz/corpus/outside_solution`: each format reads its own seed, the
//! `.pos` heading is the course over ground atan2(ve, vn) (a closed form, compared exactly: the
//! same one libm call on the same two parsed numbers), and a `.pos` without velocity is refused.

use std::io::Cursor;
use thermonav_io::Strictness;
use thermonav_io::outside_solution::{SolutionFormat, read_solution};

fn seed(name: &str) -> Vec<u8> {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/outside_solution");
    std::fs::read(dir.join(name)).unwrap()
}

fn read(
    name: &str,
    format: SolutionFormat,
) -> Result<Vec<thermonav::trajectory::TrajectoryPoint>, String> {
    read_solution(Cursor::new(seed(name)), name, format, Strictness::Strict)
        .map_err(|e| e.to_string())
}

#[test]
fn each_format_reads_its_seed_and_a_pos_heading_is_its_course() {
    assert_eq!(
        read("trajectory.csv", SolutionFormat::Csv).unwrap().len(),
        2
    );
    let nav = read("kfgins.nav", SolutionFormat::KfGinsNav).unwrap();
    assert_eq!(nav.len(), 2);
    let pos = read("rtk.pos", SolutionFormat::RtklibPos).unwrap();
    assert_eq!(pos.len(), 2);
    assert_eq!(pos[0].yaw_rad, 0.5_f64.atan2(1.0));
    assert_eq!((pos[0].roll_rad, pos[0].pitch_rad), (0.0, 0.0));
    assert_eq!(pos[1].velocity_ned_m_s, [1.0, 0.5, 0.1]);
    let err = read("no_velocity.pos", SolutionFormat::RtklibPos).unwrap_err();
    assert!(
        err.contains("no_velocity.pos") && err.contains("vn(m/s)"),
        "{err}"
    );
    assert!(read("rtk.pos", SolutionFormat::Csv).is_err());
}
