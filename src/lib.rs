//! Wound opening in a thin incompressible Kelvin-Voigt tissue with substrate friction
//! (G. M. Carvalho, N. A. M. Araujo, P. Patricio, "Wound opening in a thin incompressible
//! viscoelastic tissue"), as a simulation component. The crate reads from the physics to the
//! C boundary:
//!
//! ```text
//! solver        the wound-opening physics: a safe solver, no FMI, no C
//! purse_string  the purse-string closure physics, to couple with
//! units         physical scales and material constants
//! models        the FMU models over that physics, one folder each, and the model list
//! fmi           the FMI glue, knowing no model: a safe core, then FMI 2.0 and FMI 3.0
//!               (co-simulation and Model Exchange)
//! capi          the direct C API (wo_*)
//! boundary      what both C interfaces share: panic boundary, handle tables
//! ```

pub mod boundary;
pub mod capi;
pub mod fmi;
pub mod models;
pub mod purse_string;
pub mod solver;
pub mod units;
