//! The FMI 2.0 boundary (co-simulation and Model Exchange), shared by every model of the library: the model
//! interface ([`model`]), a safe instance with its state machine ([`instance`], [`call`]),
//! logging ([`log`]) and FMU states ([`state`]), and the `unsafe` code of the FMI side:
//! the C types ([`types`]), the frame of every call (the table of live instances and their
//! locks, [`frame`]) and the exported functions ([`ffi`]). (The direct C API,
//! [`crate::capi`], is the other `unsafe` part; both share [`crate::boundary`].)
//!
//! One shared object serves both FMUs: `fmi2Instantiate` picks the model by the GUID the
//! master passes (each `.fmu` carries a copy named after its `modelIdentifier`).

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
