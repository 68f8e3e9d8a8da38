//! `fmi3GetDirectionalDerivative` and `fmi3GetAdjointDerivative`: `nSeed` and
//! `nSensitivity` checked against the scalar variables named, then the same Jacobian as
//! FMI 2.0's ([`crate::fmi::common::instance::Instance::directional_derivative`]).
#![allow(non_snake_case, clippy::missing_safety_doc)]

use crate::fmi::common::instance::Call;
use crate::fmi::fmi3::types::*;
use crate::fmi::frame::{slice, slice_mut, with_instance};

const OK: Result<crate::fmi::common::instance::Status, String> =
    Ok(crate::fmi::common::instance::Status::Ok);

/// `fmi3GetDirectionalDerivative` (`adjoint = false`: sensitivity = J seed) and
/// `fmi3GetAdjointDerivative` (`true`: sensitivity = seed^T J).
unsafe fn derivative_of(
    instance: fmi3Instance,
    name: &'static str,
    adjoint: bool,
    (unknowns, n_unknowns): (*const fmi3ValueReference, usize),
    (knowns, n_knowns): (*const fmi3ValueReference, usize),
    (seed, n_seed): (*const fmi3Float64, usize),
    (sensitivity, n_sensitivity): (*mut fmi3Float64, usize),
) -> fmi3Status {
    unsafe {
        with_instance(
            instance,
            Call::GetDirectionalDerivative,
            || format!("{name}(nUnknowns={n_unknowns}, nKnowns={n_knowns})"),
            |i| {
                let (seeds, sensitivities) =
                    if adjoint { (n_unknowns, n_knowns) } else { (n_knowns, n_unknowns) };
                if n_seed != seeds || n_sensitivity != sensitivities {
                    let (a, b) =
                        if adjoint { ("nUnknowns", "nKnowns") } else { ("nKnowns", "nUnknowns") };
                    return Err(format!(
                        "nSeed = {n_seed} and nSensitivity = {n_sensitivity} must equal {a} = {seeds} and {b} = {sensitivities} (scalar variables)"
                    ));
                }
                let u = slice(unknowns, n_unknowns, "unknowns")?;
                let k = slice(knowns, n_knowns, "knowns")?;
                let s = slice(seed, n_seed, "seed")?;
                let out = slice_mut(sensitivity, n_sensitivity, "sensitivity")?;
                let got = if adjoint {
                    i.adjoint_derivative(u, k, s)?
                } else {
                    i.directional_derivative(u, k, s)?
                };
                out.copy_from_slice(&got);
                OK
            },
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetDirectionalDerivative(
    instance: fmi3Instance,
    unknowns: *const fmi3ValueReference,
    nUnknowns: usize,
    knowns: *const fmi3ValueReference,
    nKnowns: usize,
    seed: *const fmi3Float64,
    nSeed: usize,
    sensitivity: *mut fmi3Float64,
    nSensitivity: usize,
) -> fmi3Status {
    let args =
        ((unknowns, nUnknowns), (knowns, nKnowns), (seed, nSeed), (sensitivity, nSensitivity));
    unsafe {
        derivative_of(
            instance,
            "fmi3GetDirectionalDerivative",
            false,
            args.0,
            args.1,
            args.2,
            args.3,
        )
    }
}

#[unsafe(no_mangle)]
pub unsafe extern "C" fn fmi3GetAdjointDerivative(
    instance: fmi3Instance,
    unknowns: *const fmi3ValueReference,
    nUnknowns: usize,
    knowns: *const fmi3ValueReference,
    nKnowns: usize,
    seed: *const fmi3Float64,
    nSeed: usize,
    sensitivity: *mut fmi3Float64,
    nSensitivity: usize,
) -> fmi3Status {
    let args =
        ((unknowns, nUnknowns), (knowns, nKnowns), (seed, nSeed), (sensitivity, nSensitivity));
    unsafe {
        derivative_of(instance, "fmi3GetAdjointDerivative", true, args.0, args.1, args.2, args.3)
    }
}
