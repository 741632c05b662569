//! Text forms of a bounce for the headless commands: a readable table, JSON and CSV.

pub mod csv;
pub mod json;
pub mod table;
