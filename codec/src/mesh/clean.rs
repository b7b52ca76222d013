//! placeholder
pub struct CleanOptions;
pub struct CleanReport;
pub struct Cleaned;
pub fn clean() {}
