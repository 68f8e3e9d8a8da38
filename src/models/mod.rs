//! The models this library packages as FMUs, each in its own folder: its variable table
//! (value references, units, start values, descriptions), its documentation page
//! (`about.html`) and its [`FmuModel`] implementation over a physics module of the crate.
//!
//! ```text
//! wound/            WoundOpening: the wound-opening solver (crate::solver) in physical units
//! purse_string/     PurseString: the actin purse-string closure model (crate::purse_string)
//! ```
//!
//! A new model is a folder like these and one line in [`MODELS`]; the FMI glue
//! ([`crate::fmi`]) knows none of them.
#![forbid(unsafe_code)]

pub mod purse_string;
pub mod wound;

use crate::fmi::common::model::{Description, FmuModel};

/// A constructor of a fresh model.
pub type Fresh = fn() -> Box<dyn FmuModel>;

/// The models of this library: description and a constructor of a fresh model.
pub static MODELS: [(&Description, Fresh); 2] = [
    (&wound::variables::DESCRIPTION, wound::WoundModel::fresh),
    (&purse_string::variables::DESCRIPTION, purse_string::PurseModel::fresh),
];
