//! What the wound model builds from its parameters: the tolerance in force, the mesh and the
//! solver, the notes and warnings of the set-up, and the states' nominals.

use super::WoundModel;
use super::codec::SchemeChoice;
use super::variables::MODEL_EXCHANGE_STATES;
use crate::fmi::common::model::Rejected;
use crate::solver::{Settings, Solver, delivered_accuracy};

impl WoundModel {
    /// Report `text` with the current call (a warning status, category logStatusWarning).
    pub(super) fn warn(&self, text: String) {
        self.warning.replace(Some(text));
    }

    /// Report `text` with the current call, whose status stays OK (category
    /// logStatusWarning).
    pub(super) fn note(&self, text: String) {
        self.note.replace(Some(text));
    }

    /// A tolerance below the floor: the run delivers the floor's accuracy, which the
    /// master is told in the log (a note: masters that hand their integrator's tolerance
    /// to the FMU must still be able to run).
    pub(super) fn setup_note(&self) -> Option<String> {
        let tol = self.effective_tolerance();
        let delivered = delivered_accuracy(tol);
        (self.scheme.method == 0 && delivered > tol).then(|| {
            format!("tolerance {tol:e} is below what this FMU can deliver: results are accurate to {delivered:e} of the opening (rounding in the modal transform dominates below)")
        })
    }

    /// A method whose accuracy the tolerance does not control.
    pub(super) fn setup_warning(&self) -> Option<String> {
        let tol = self.effective_tolerance();
        if self.scheme.method != 0 {
            let what = [
                "",
                "TR-BDF2 (method 1)",
                "the paper's scheme (method 2)",
                "the explicit scheme (method 3)",
            ];
            let name = what.get(self.scheme.method as usize).copied().unwrap_or("this method");
            return Some(format!(
                "{name} is for comparison: its error depends on grid_points and internal_step, not on the tolerance {tol:e} (the paper's scheme is off by 10-20 % of the opening at 101 points); method = 0 meets the tolerance"
            ));
        }
        None
    }

    /// The tolerance in force: the experiment's if defined, else the parameter.
    pub(super) fn effective_tolerance(&self) -> f64 {
        self.experiment_tolerance.unwrap_or(self.tolerance)
    }

    /// The mesh the parameters and the tolerance in force give.
    pub(super) fn settings(&self) -> Result<Settings, Rejected> {
        Settings::for_tolerance(&self.params, self.effective_tolerance()).map_err(|e| e.to_string())
    }

    /// A solver at the cut for these parameters, tolerance and scheme choice (the
    /// internal step is in master time, the solver's in units of `T`).
    pub(super) fn build_solver(&self) -> Result<Solver, Rejected> {
        let choice = SchemeChoice {
            internal_step: self.scheme.internal_step / self.scales.time,
            ..self.scheme
        };
        let scheme = choice.scheme(self.settings()?);
        Solver::with_scheme(&self.params, &scheme).map_err(|e| e.to_string())
    }

    pub(super) fn solver(&self) -> &Solver {
        self.solver
            .as_ref()
            .expect("prepare() builds the solver before outputs, steps and derivatives")
    }

    /// The states' nominals under the edge stress `p` (in G).
    pub(super) fn nominals_at(&self, p: f64) -> Vec<f64> {
        let mut n = self.solver.as_ref().and_then(|s| s.ode_nominals(p)).unwrap_or_default();
        let spare = n.iter().copied().fold(0.0, f64::max);
        n.resize(MODEL_EXCHANGE_STATES, if spare > 0.0 { spare } else { 1.0 });
        n
    }

    /// Dimensionless edge stress.
    pub(super) fn p(&self) -> f64 {
        self.edge_stress / self.scales.stress
    }
}
