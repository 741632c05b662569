//! snapback: a ball bouncing obliquely off a surface with tangential compliance (Rod Cross, "Impact of a
//! ball on a surface with tangential compliance", Am. J. Phys. 78, 2010).
//!
//! [`model`] is the simulation core; everything else (the command line, the exports, the [`tui`] explorer)
//! calls its API.

pub mod analysis;
pub mod cli;
pub mod config;
pub mod export;
pub mod input;
pub mod model;
pub mod output;
pub mod scenario;
pub mod shot;
pub mod tui;
