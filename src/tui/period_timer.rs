//! The period timer's logic, now in [`crate::measure::period`] (beside the other measuring
//! tools); kept under this name for the code that found it here.

pub use crate::measure::period::*;
