//! What the integration tests share, as modules (each test crate declares `mod common;`):
//!
//! ```text
//! fmi.rs    drive the exported FMI 2.0 functions from Rust as a C master would
//! fuzz.rs   the fuzz harnesses' seeded generator, time budget and state mutations
//! ```
//!
//! Each test crate uses part of them; the rest is dead code there.
#![allow(dead_code)]

pub mod fmi;
pub mod fuzz;
