//! Shared by the accuracy tests: exact answers and case generators.

pub mod cases;
pub mod exact;
