//! Integration tests of the thermonav-io file formats: readers, writers and atomic output.

mod atomic;
mod chunked;
mod dataflash;
mod fuzz_corpus;
mod gnss;
mod gzip_bounds;
mod imu_errors;
mod imu_units;
mod kf_gins;
mod nmea;
mod non_finite;
mod outside_solution;
mod parallel;
mod raw_imu;
mod ros;
mod ros_bounds;
mod round_trip;
mod rtklib_pos;
mod spare;
mod support;
mod thermal_parameters;
mod trajectory;
mod ulog;
mod ulog_built;
mod ulog_writer;
