//! The wound model's FMU state: what [`WoundModel`] saves into the bytes of
//! [`codec`] and how saved bytes become a model again, refused with the reason when they
//! come from an instance with other parameters, scales, tolerance or scheme, or were forged.

use super::{WoundModel, codec};
use crate::fmi::common::model::Rejected;
use crate::fmi::common::serialized::same_parameters;
use crate::solver::{Solver, check_edge_stress};
use std::cell::RefCell;

impl WoundModel {
    /// The bytes of the model's FMU state ([`codec::encode`]).
    pub(super) fn saved(&self) -> Result<Vec<u8>, Rejected> {
        Ok(codec::encode(&codec::Saved {
            params: self.params,
            scales: self.scales,
            settings: self.settings()?,
            tolerance: self.tolerance,
            experiment_tolerance: self.experiment_tolerance,
            scheme: self.scheme,
            edge_stress: self.edge_stress,
            edge_stress_rate: self.edge_stress_rate,
            solver: self.solver.as_ref().map(Solver::state),
        }))
    }

    /// The bytes must come from an instance with the same parameters, scales, tolerance
    /// and scheme (a state is a point of one trajectory, not a parameter set).
    pub(super) fn restored(&self, bytes: &[u8]) -> Result<Self, Rejected> {
        let saved = codec::decode(bytes)?;
        let (mine, theirs) = (self.params, saved.params);
        let (a, b) = (self.scales, saved.scales);
        same_parameters(&[
            ("lambda", mine.lambda, theirs.lambda),
            ("sigma", mine.sigma, theirs.sigma),
            ("R_inf", mine.r_inf, theirs.r_inf),
            ("R0", a.length, b.length),
            ("T", a.time, b.time),
            ("G", a.stress, b.stress),
            (
                "tolerance",
                self.effective_tolerance(),
                saved.experiment_tolerance.unwrap_or(saved.tolerance),
            ),
        ])?;
        if saved.scheme != self.scheme {
            return Err(format!(
                "serialized FMU state has {:?} but this instance has {:?}",
                saved.scheme, self.scheme
            ));
        }
        // The mesh follows from parameters and tolerance (checked equal to ours above):
        // bytes that claim another are forged.
        let expected = self.settings()?;
        if saved.settings != expected {
            return Err(format!(
                "serialized FMU state has mesh {:?} but its parameters and tolerance give {:?}",
                saved.settings.mesh, expected.mesh
            ));
        }
        check_edge_stress(saved.edge_stress / saved.scales.stress)
            .map_err(|e| format!("serialized FMU state: {e}"))?;
        let mut model = Self {
            params: saved.params,
            scales: saved.scales,
            tolerance: saved.tolerance,
            experiment_tolerance: saved.experiment_tolerance,
            scheme: saved.scheme,
            edge_stress: saved.edge_stress,
            edge_stress_rate: saved.edge_stress_rate,
            solver: None,
            warning: RefCell::new(None),
            note: RefCell::new(None),
            exchange: self.exchange.clone(),
            probe_radii: self.probe_radii.clone(),
            validity_warning: self.validity_warning,
        };
        if let Some(st) = &saved.solver {
            // Same parameters, tolerance and scheme: a clone of our own solver shares its operator.
            let mut s = match &self.solver {
                Some(own) => own.clone(),
                None => model.build_solver()?,
            };
            s.restore(st).map_err(|e| format!("serialized FMU state: {e}"))?;
            model.solver = Some(s);
        }
        Ok(model)
    }
}
