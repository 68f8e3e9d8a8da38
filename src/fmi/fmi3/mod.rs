//! FMI 3.0: its C types, the exported `fmi3*` functions (co-simulation and Model
//! Exchange) as thin shims over [`super::common`], the functions every FMU exports but
//! this one does not provide, and its `modelDescription.xml`.
//!
//! ```text
//! types.rs         fmi3PlatformTypes.h, fmi3FunctionTypes.h as Rust declarations
//! functions.rs     the common and co-simulation functions
//! values.rs        the get and set functions of Float64, UInt64 and Int32
//! derivatives.rs   the directional and adjoint derivatives
//! intermediate.rs  Intermediate Update Mode inside a step (safe Rust)
//! names.rs         its Dialect: the functions' names, each written out (safe Rust)
//! states.rs        the FMU-state functions
//! arrays.rs        time, arrays and Configuration Mode on an instance (safe Rust)
//! exchange.rs      the Model Exchange functions
//! unsupported.rs   clocks, scheduled execution, output derivatives, other variable types: refused
//! xml.rs           modelDescription.xml (fmi3ModelDescription.xsd)
//! ```

pub mod arrays;
pub mod derivatives;
pub mod exchange;
pub mod functions;
pub mod intermediate;
pub mod names;
pub mod states;
pub mod types;
pub mod unsupported;
pub mod values;
pub mod xml;
