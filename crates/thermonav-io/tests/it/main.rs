//! Integration tests of the thermonav-io file formats: readers, writers and atomic output.

mod atomic;
mod gnss;
mod imu_errors;
mod imu_units;
mod parallel;
mod round_trip;
mod support;
mod trajectory;
