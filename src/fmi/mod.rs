//! The FMI boundary, shared by every model of the library and knowing none: FMI 2.0 and
//! FMI 3.0, co-simulation and Model Exchange, over one model interface, as the
//! Reference-FMUs do in C with `fmi2Functions.c` and `fmi3Functions.c` over `model.h`.
//!
//! ```text
//! model.rs                  what the glue knows of a model: FmuModel and its Description table
//! wound/, purse/            the models (each: variables.rs table, mod.rs, about.html)
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
//! (each `.fmu` carries a copy named after its `modelIdentifier`). A new model is a folder
//! like `wound/` and one line in [`MODELS`].

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
pub mod purse;
pub mod state;
pub mod types;
pub mod types3;
pub mod wound;
pub mod xml;
pub mod xml3;

use model::{Description, FmuModel};

/// The models of this library: description and a constructor of a fresh model.
pub static MODELS: [(&Description, fn() -> Box<dyn FmuModel>); 2] =
    [(&wound::variables::DESCRIPTION, wound::WoundModel::fresh), (&purse::variables::DESCRIPTION, purse::PurseModel::fresh)];

/// The model whose `modelDescription.xml` has this GUID.
pub fn model_for_guid(guid: &str) -> Option<fn() -> Box<dyn FmuModel>> {
    MODELS.iter().find(|(d, _)| d.guid == guid).map(|(_, fresh)| *fresh)
}
