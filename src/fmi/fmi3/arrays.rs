//! FMI 3.0 variables beyond the FMI 2.0 ones, on the shared [`Instance`]: the independent
//! variable `time`, and the arrays sized by a structural parameter ([`Arrays`]), read and
//! written as FMI 3.0 does: one value reference per array, its values concatenated in
//! the order of the references, `nValues` the total. The structural parameter is set
//! only in Configuration Mode (FMI 3.0, section 2.3); parameter arrays then have its
//! length.
#![forbid(unsafe_code)]

use crate::fmi::common::instance::{Instance, Rejected};
use crate::fmi::common::machine::Machine;
use crate::fmi::common::model::{Arrays, Causality, Kind, Named};
use crate::fmi::fmi3::xml::time_reference;

/// What an FMI 3.0-only value reference names.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Extra {
    Time,
    Length,
    Array(usize),
}

impl Instance {
    fn arrays(&self) -> Option<Arrays> {
        self.description().arrays
    }

    fn extra(&self, vr: u32) -> Option<Extra> {
        let time = time_reference(self.description());
        let arrays = self.arrays();
        match vr.checked_sub(time)? {
            0 => Some(Extra::Time),
            1 if arrays.is_some() => Some(Extra::Length),
            k => arrays
                .filter(|a| ((k - 2) as usize) < a.arrays.len())
                .map(|_| Extra::Array((k - 2) as usize)),
        }
    }

    /// `fmi3GetFloat64`: scalars as in FMI 2.0, `time`, and whole arrays; the total count
    /// must be `n_values`.
    pub fn get_float64(&mut self, vrs: &[u32], n_values: usize) -> Result<Vec<f64>, Rejected> {
        let mut out = Vec::with_capacity(n_values);
        for &vr in vrs {
            match self.extra(vr) {
                Some(Extra::Time) => out.push(self.clock.time),
                Some(Extra::Array(j)) => {
                    let is_output =
                        self.arrays().is_some_and(|a| a.arrays[j].causality == Causality::Output);
                    if is_output {
                        if self.before_initialization() {
                            return Err(format!(
                                "{} is an output: it has no value before fmi3EnterInitializationMode",
                                self.arrays().map_or("", |a| a.arrays[j].name)
                            ));
                        }
                        self.prepare()?;
                    }
                    out.extend(self.model.get_array(j, self.clock.since_start())?);
                }
                Some(Extra::Length) => {
                    return Err(format!(
                        "value reference {vr} is a UInt64 (the structural parameter), not a Float64"
                    ));
                }
                None => {
                    let d = self.description();
                    let computed = match d.named(Kind::Real, vr)? {
                        Named::Table(v) => v.causality == Causality::Output,
                        _ => true,
                    };
                    if computed && self.before_initialization() {
                        return Err(format!(
                            "value reference {vr} is computed: it has no value before fmi3EnterInitializationMode"
                        ));
                    }
                    let mut x = [0.0];
                    self.get_real(&[vr], &mut x)?;
                    out.push(x[0]);
                }
            }
            if out.len() > n_values {
                break;
            }
        }
        if out.len() != n_values {
            return Err(format!(
                "nValues = {n_values} but the variables named have {} values",
                out.len()
            ));
        }
        Ok(out)
    }

    /// `fmi3SetFloat64`: scalars as in FMI 2.0 and whole parameter arrays (of the current
    /// length); all checked before any is set. Nothing but structural parameters in
    /// Configuration Mode.
    pub fn set_float64(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), Rejected> {
        if self.machine == Machine::ConfigurationMode {
            return Err("only the structural parameter can be set in Configuration Mode".into());
        }
        let length = self.model.array_length() as usize;
        let (mut at, mut arrays, mut scalars) = (0, Vec::new(), Vec::new());
        for &vr in vrs {
            match self.extra(vr) {
                Some(Extra::Array(j)) => {
                    let a = self.arrays().expect("an array value reference").arrays[j];
                    if a.causality != Causality::Parameter {
                        return Err(format!(
                            "{} (value reference {vr}) is an output and cannot be set",
                            a.name
                        ));
                    }
                    if !matches!(self.machine, Machine::Instantiated | Machine::InitializationMode)
                    {
                        return Err(format!(
                            "{} is a fixed parameter: it can only be set before fmi3ExitInitializationMode",
                            a.name
                        ));
                    }
                    let part = values
                        .get(at..at + length)
                        .ok_or_else(|| format!("too few values for {} ({length} each)", a.name))?;
                    self.model.check_array(j, part)?;
                    arrays.push((j, part.to_vec()));
                    at += length;
                }
                Some(_) => {
                    return Err(format!("value reference {vr} cannot be set with fmi3SetFloat64"));
                }
                None => {
                    let x = *values.get(at).ok_or("too few values")?;
                    scalars.push((vr, x));
                    at += 1;
                }
            }
        }
        if at != values.len() {
            return Err(format!("nValues = {} but the variables named take {at}", values.len()));
        }
        let (svrs, sxs): (Vec<u32>, Vec<f64>) = scalars.into_iter().unzip();
        self.set_real(&svrs, &sxs)?;
        arrays.into_iter().for_each(|(j, v)| self.model.set_array(j, &v));
        Ok(())
    }

    /// `fmi3GetUInt64`: the structural parameter.
    pub fn get_uint64(&mut self, vrs: &[u32]) -> Result<Vec<u64>, Rejected> {
        vrs.iter()
            .map(|&vr| match self.extra(vr) {
                Some(Extra::Length) => Ok(self.model.array_length()),
                _ => Err(format!("no UInt64 variable has value reference {vr}")),
            })
            .collect()
    }

    /// `fmi3SetUInt64`: the structural parameter, in Configuration Mode, in `1 ..= max`.
    pub fn set_uint64(&mut self, vrs: &[u32], values: &[u64]) -> Result<(), Rejected> {
        let Some(a) = self.arrays() else {
            return match vrs.first() {
                None => Ok(()),
                Some(vr) => Err(format!("no UInt64 variable has value reference {vr}")),
            };
        };
        for (&vr, &n) in vrs.iter().zip(values) {
            if self.extra(vr) != Some(Extra::Length) {
                return Err(format!("no UInt64 variable has value reference {vr}"));
            }
            if self.machine != Machine::ConfigurationMode {
                return Err(format!(
                    "{} is a structural parameter: set it in Configuration Mode (fmi3EnterConfigurationMode)",
                    a.length_name
                ));
            }
            if !(1..=a.length_max).contains(&n) {
                return Err(format!(
                    "{} = {n} is invalid: it must be in 1 ..= {}",
                    a.length_name, a.length_max
                ));
            }
        }
        values.iter().for_each(|&n| self.model.set_array_length(n));
        Ok(())
    }

    pub fn enter_configuration_mode(&mut self) -> Result<(), Rejected> {
        if self.arrays().is_none() {
            return Err("this model has no structural parameters".into());
        }
        self.machine = Machine::ConfigurationMode;
        Ok(())
    }

    pub fn exit_configuration_mode(&mut self) -> Result<(), Rejected> {
        self.machine = Machine::Instantiated;
        Ok(())
    }
}
