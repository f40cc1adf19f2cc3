//! The report page (`report.html`) and the figure data read back from files thermonav wrote.

pub mod figure_data;
pub mod ranking;
pub mod report;
pub mod summary;
pub mod temperature;
