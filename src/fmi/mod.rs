//! The FMI boundary, shared by every model of the library and knowing none: FMI 2.0 and
//! FMI 3.0, co-simulation and Model Exchange, over one model interface, as the
//! Reference-FMUs do in C with `fmi2Functions.c` and `fmi3Functions.c` over `model.h`.
//!
//! ```text
//! common/   the version-independent core in safe Rust (no `unsafe`, enforced): the model
//!           interface, one instance's calls, state machine, FMU states, Model Exchange,
//!           logging; a version's names and rules come from its Dialect
//! fmi2/     FMI 2.0: C types, exported functions, its Dialect, modelDescription.xml
//! fmi3/     FMI 3.0: the same, and its own calls (arrays, intermediate update)
//! frame.rs  what every exported function of both versions runs in: the instance table,
//!           the instance's lock, the panic boundary, C strings and the importer's logger
//! shims.rs  the bodies of the functions whose C signatures both versions share
//! ```
//!
//! One shared object serves every model and version: `fmi2Instantiate` and
//! `fmi3Instantiate*` pick the model by the GUID / instantiation token the master passes
//! (each `.fmu` carries a copy named after its `modelIdentifier`), from the list of
//! [`crate::models`]. The glue names no model.

pub mod common;
pub mod fmi2;
pub mod fmi3;
pub mod frame;
pub mod shims;

use crate::models::MODELS;
use common::model::FmuModel;

/// The model whose `modelDescription.xml` has this GUID (FMI 2.0) or instantiation token
/// (FMI 3.0, `what` names which); otherwise the message for the importer's log, naming
/// every model's.
pub fn model_for_guid(guid: Option<&str>, what: &str) -> Result<fn() -> Box<dyn FmuModel>, String> {
    if let Some((_, fresh)) = MODELS.iter().find(|(d, _)| Some(d.guid) == guid) {
        return Ok(*fresh);
    }
    let known: Vec<String> =
        MODELS.iter().map(|(d, _)| format!("{} ({})", d.guid, d.model_identifier)).collect();
    Err(format!("Expected {what} {} but was {}", known.join(" or "), guid.unwrap_or("NULL")))
}
