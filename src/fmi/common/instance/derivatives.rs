//! The derivatives of an [`Instance`]: the Jacobian of outputs (and, in Model Exchange,
//! state derivatives) with respect to inputs (and states), and the directional and adjoint
//! derivatives made of it, each refused with the reason when an argument names the wrong
//! kind of variable or a seed is not finite.

use super::Instance;
use crate::fmi::common::machine::Interface;
use crate::fmi::common::model::{Causality, Kind, Named, Rejected};

impl Instance {
    /// The Jacobian `J[i][j] = d unknown_i / d known_j` (row-major) at the current time:
    /// unknowns are outputs or (Model Exchange) state derivatives, knowns inputs or (Model
    /// Exchange) states; `seed` (the vector it multiplies) must be finite.
    fn jacobian(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
    ) -> Result<Vec<f64>, Rejected> {
        let d = self.description();
        let exchange = self.interface == Interface::ModelExchange;
        let role = |v: u32, want: Causality, state: bool, what: &str| -> Result<(), Rejected> {
            match d.named(Kind::Real, v)? {
                Named::Table(var) if var.causality == want => Ok(()),
                Named::State(_) if state && exchange => Ok(()),
                Named::Derivative(_) if !state && exchange => Ok(()),
                named => {
                    let role = match named {
                        Named::Table(var) => var.causality.as_str(),
                        Named::State(_) => "state",
                        Named::Derivative(_) => "state derivative",
                    };
                    let article =
                        if role.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
                    let also = match (exchange, state) {
                        (false, _) => "",
                        (true, true) => " or a continuous state",
                        (true, false) => " or a state derivative",
                    };
                    Err(format!(
                        "{} (value reference {v}) is {article} {role} but {} {what} must be a Real {}{also}",
                        d.state_name(named),
                        if what.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" },
                        want.as_str()
                    ))
                }
            }
        };
        let [unknown, known, seed_name] = self.dialect.derivative_arguments;
        unknowns
            .iter()
            .try_for_each(|&v| role(v, Causality::Output, false, &format!("{unknown} entry")))?;
        knowns
            .iter()
            .try_for_each(|&v| role(v, Causality::Input, true, &format!("{known} entry")))?;
        if let Some(x) = seed.iter().find(|x| !x.is_finite()) {
            return Err(format!("{seed_name} = {x} is invalid: it must be finite"));
        }
        self.prepare()?;
        self.model.jacobian(unknowns, knowns, self.clock.since_start())
    }

    /// `fmi2GetDirectionalDerivative` / `fmi3GetDirectionalDerivative`: `J seed`
    /// ([`Instance::jacobian`]), one value per unknown.
    pub fn directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
    ) -> Result<Vec<f64>, Rejected> {
        let j = self.jacobian(unknowns, knowns, seed)?;
        let got: Vec<f64> = (0..unknowns.len())
            .map(|i| (0..knowns.len()).map(|k| j[i * knowns.len() + k] * seed[k]).sum())
            .collect();
        self.overflow(&got, unknowns)
    }

    /// `fmi3GetAdjointDerivative`: `seed^T J` (`seed` per unknown), one value per known.
    pub fn adjoint_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
    ) -> Result<Vec<f64>, Rejected> {
        let j = self.jacobian(unknowns, knowns, seed)?;
        let got: Vec<f64> = (0..knowns.len())
            .map(|k| (0..unknowns.len()).map(|i| seed[i] * j[i * knowns.len() + k]).sum())
            .collect();
        self.overflow(&got, knowns)
    }

    fn overflow(&self, got: &[f64], names: &[u32]) -> Result<Vec<f64>, Rejected> {
        let d = self.description();
        match got.iter().position(|x| !x.is_finite()) {
            Some(i) => {
                let name = d
                    .named(Kind::Real, names[i])
                    .map_or_else(|_| names[i].to_string(), |n| d.state_name(n));
                Err(format!(
                    "the derivative of {name} overflows for this {}",
                    self.dialect.derivative_arguments[2]
                ))
            }
            None => Ok(got.to_vec()),
        }
    }
}
