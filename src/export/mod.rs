//! Text forms of a bounce for the headless commands: a readable table, JSON and CSV; and figures as SVG.

pub mod csv;
pub mod json;
pub mod shot;
pub mod svg;
pub mod table;
pub mod uncertainty;
