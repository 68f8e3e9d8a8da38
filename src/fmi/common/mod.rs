//! The version-independent glue: everything an FMU instance is, in safe Rust, for any model
//! and for FMI 2.0 and 3.0 alike. It knows nothing of C: the shims of [`super::fmi2`] and
//! [`super::fmi3`] convert pointers, and the compiler holds every `unsafe` to them.
//!
//! ```text
//! model.rs          what the glue knows of a model: the FmuModel trait and its Description table
//! model/fmu_model.rs  the FmuModel trait itself
//! instance.rs       one instance: calls, variables, logging
//! instance/derivatives.rs  its Jacobian, directional and adjoint derivatives
//! instance/fmu_states.rs  its table of saved FMU states (get, set, free, serialize)
//! machine.rs        the state machine's states and the master's clock
//! call.rs           the calls, and in which state each is allowed
//! exchange.rs       Model Exchange on an instance
//! serialized.rs     the byte format of serialized FMU states
//! log.rs            status, logger trait, log categories
//! xml.rs            what both modelDescription.xml writers share
//! ```
#![forbid(unsafe_code)]

pub mod call;
pub mod exchange;
pub mod instance;
pub mod log;
pub mod machine;
pub mod model;
pub mod serialized;
pub mod xml;
