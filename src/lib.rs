//! Wound opening in a thin incompressible Kelvin-Voigt tissue with substrate friction,
//! as a simulation component: a safe solver ([`solver`]) and an FMI 2.0 co-simulation
//! boundary on top of it.

pub mod solver;
pub mod units;
pub mod closure;
pub mod fmi;
pub mod capi;
