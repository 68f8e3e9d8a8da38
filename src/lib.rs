//! Wound opening in a thin incompressible Kelvin-Voigt tissue with substrate friction,
//! as a simulation component: a safe solver ([`solver`]) and two C interfaces on top of
//! it, an FMI 2.0 co-simulation FMU ([`fmi`]) and a direct C API ([`capi`]), which share
//! the panic boundary and the handle tables of [`boundary`].

pub mod boundary;
pub mod solver;
pub mod units;
pub mod purse_string;
pub mod models;
pub mod fmi;
pub mod capi;
