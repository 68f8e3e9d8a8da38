//! FMI 2.0: its C types, the exported `fmi2*` functions (co-simulation and Model
//! Exchange) as thin shims over [`super::common`], and its `modelDescription.xml`.
//!
//! ```text
//! types.rs       fmi2TypesPlatform.h, fmi2FunctionTypes.h as Rust declarations
//! functions.rs   the common and co-simulation functions
//! status.rs      the fmi2Get*Status functions
//! names.rs       its Dialect: the functions' names (safe Rust)
//! exchange.rs    the Model Exchange functions
//! xml.rs         modelDescription.xml (fmi2ModelDescription.xsd)
//! ```

pub mod exchange;
pub mod functions;
pub mod names;
pub mod status;
pub mod types;
pub mod xml;
