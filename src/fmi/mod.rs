//! The FMI 2.0 co-simulation boundary: the variable table ([`variables`]), a safe
//! instance with its state machine ([`instance`]) and FMU states ([`state`]), and the
//! only `unsafe` code of the crate: the C types, the panic boundary and the exported
//! functions.

pub mod boundary;
pub mod ffi;
pub mod instance;
pub mod state;
pub mod types;
pub mod variables;
