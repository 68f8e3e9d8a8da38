//! The FMI boundary, shared by every model of the library and knowing none: FMI 2.0 and
//! FMI 3.0, co-simulation and Model Exchange, over one model interface, as the
//! Reference-FMUs do in C with `fmi2Functions.c` and `fmi3Functions.c` over `model.h`.
//!
//! ```text
//! model.rs                  what the glue knows of a model: FmuModel and its Description table
//! instance.rs               one instance in safe Rust: calls, variables, FMU states, logging
//! machine.rs, call.rs       the state machines and which call is allowed where
//! exchange.rs, arrays.rs    Model Exchange; FMI 3.0 time, arrays and Configuration Mode
//! state.rs, log.rs          serialized FMU states; logging and categories
//! xml.rs, xml3.rs           modelDescription.xml generated from the tables (FMI 2.0, 3.0)
//! frame.rs                  the `unsafe` frame of every call: handle table, lock, panic boundary
//! ffi*.rs, types*.rs        the exported C functions and C types (ffi3*: FMI 3.0)
//! ```
//!
//! One shared object serves every model and version: `fmi2Instantiate` and
//! `fmi3Instantiate*` pick the model by the GUID / instantiation token the master passes
//! (each `.fmu` carries a copy named after its `modelIdentifier`), from the list of
//! [`crate::models`]. The glue names no model.

pub mod arrays;
pub mod call;
pub mod exchange;
pub mod ffi;
pub mod ffi_exchange;
pub mod ffi3;
pub mod ffi3_exchange;
pub mod ffi3_other;
pub mod frame;
pub mod instance;
pub mod intermediate;
pub mod log;
pub mod machine;
pub mod model;
pub mod state;
pub mod types;
pub mod types3;
pub mod xml;
pub mod xml3;

use crate::models::MODELS;
use model::FmuModel;

/// The model whose `modelDescription.xml` has this GUID (FMI 2.0) or instantiation token
/// (FMI 3.0, `what` names which); otherwise the message for the importer's log, naming
/// every model's.
pub fn model_for_guid(guid: Option<&str>, what: &str) -> Result<fn() -> Box<dyn FmuModel>, String> {
    if let Some((_, fresh)) = MODELS.iter().find(|(d, _)| Some(d.guid) == guid) {
        return Ok(*fresh);
    }
    let known: Vec<String> = MODELS.iter().map(|(d, _)| format!("{} ({})", d.guid, d.model_identifier)).collect();
    Err(format!("Expected {what} {} but was {}", known.join(" or "), guid.unwrap_or("NULL")))
}
