//! The purse-string closure model ([`crate::purse_string`]) behind the FMI glue: no state
//! but the clock and the input, so a step only moves time (and the input along its rate,
//! after `fmi2SetRealInputDerivatives`).

pub mod variables;

use crate::fmi::common::model::{Description, FmuModel, Rejected};
use crate::fmi::common::serialized::{Reader, Writer, same_parameters};
use crate::purse_string::{MAX_TENSION, PurseString, THICKNESS, check_radius, check_time};
use variables::{DESCRIPTION, Vr};

#[derive(Debug, Clone)]
pub struct PurseModel {
    purse: PurseString,
    /// The input, micrometres.
    wound_radius: f64,
    /// Its rate in um/s (0: held).
    radius_rate: f64,
}

impl PurseModel {
    /// A model with the start values of the variable table.
    pub fn fresh() -> Box<dyn FmuModel> {
        let start = |vr: Vr| vr.var().start.unwrap_or(0.0);
        Box::new(Self {
            purse: PurseString {
                max_tension: start(Vr::MaxTension),
                assembly_time: start(Vr::AssemblyTime),
                delay: start(Vr::Delay),
                thickness: start(Vr::Thickness),
            },
            wound_radius: start(Vr::WoundRadius),
            radius_rate: 0.0,
        })
    }

    fn parameters(&self) -> [f64; 4] {
        let p = &self.purse;
        [p.max_tension, p.assembly_time, p.delay, p.thickness]
    }
}

impl FmuModel for PurseModel {
    fn description(&self) -> &'static Description {
        &DESCRIPTION
    }

    fn boxed_clone(&self) -> Box<dyn FmuModel> {
        Box::new(self.clone())
    }

    fn check(&self, vr: u32, x: f64) -> Result<f64, Rejected> {
        match Vr::from_u32(vr) {
            Some(Vr::WoundRadius) => check_radius(x),
            Some(Vr::MaxTension) => MAX_TENSION.check("T_max", x),
            Some(v @ (Vr::AssemblyTime | Vr::Delay)) => check_time(v.var().name, x),
            Some(Vr::Thickness) => THICKNESS.check("thickness", x),
            _ => Err(format!("value reference {vr} is not a parameter or input")),
        }
    }

    fn set(&mut self, vr: u32, x: f64) {
        let p = &mut self.purse;
        match Vr::from_u32(vr) {
            Some(Vr::MaxTension) => p.max_tension = x,
            Some(Vr::AssemblyTime) => p.assembly_time = x,
            Some(Vr::Delay) => p.delay = x,
            Some(Vr::Thickness) => p.thickness = x,
            Some(Vr::WoundRadius) => (self.wound_radius, self.radius_rate) = (x, 0.0),
            _ => {}
        }
    }

    /// Closed form in time: nothing to resolve, so no tolerance to honour.
    fn set_experiment_tolerance(&mut self, _tolerance: Option<f64>) {}

    fn prepare(&mut self) -> Result<Option<String>, Rejected> {
        Ok(None)
    }

    fn get(&self, vr: u32, time: f64) -> f64 {
        let p = &self.purse;
        match Vr::from_u32(vr) {
            Some(Vr::MaxTension) => p.max_tension,
            Some(Vr::AssemblyTime) => p.assembly_time,
            Some(Vr::Delay) => p.delay,
            Some(Vr::Thickness) => p.thickness,
            Some(Vr::WoundRadius) => self.wound_radius,
            Some(Vr::EdgeStress) => p.edge_stress(time, self.wound_radius),
            Some(Vr::LineTension) => p.tension(time),
            None => f64::NAN,
        }
    }

    /// The input moves along its rate; the end value must be an accepted radius.
    fn step(&mut self, _time: f64, h: f64) -> Result<(), Rejected> {
        if self.radius_rate != 0.0 {
            self.wound_radius = check_radius(self.wound_radius + self.radius_rate * h)?;
        }
        Ok(())
    }

    fn check_input_rate(&self, vr: u32, _rate: f64) -> Result<(), Rejected> {
        match Vr::from_u32(vr) {
            Some(Vr::WoundRadius) => Ok(()),
            _ => Err(format!("value reference {vr} is not wound_radius")),
        }
    }

    fn set_input_rate(&mut self, _vr: u32, rate: f64) {
        self.radius_rate = rate;
    }

    fn partial(&self, output: u32, input: u32, time: f64) -> Result<f64, Rejected> {
        Ok(match (Vr::from_u32(output), Vr::from_u32(input)) {
            (Some(Vr::EdgeStress), Some(Vr::WoundRadius)) => {
                self.purse.edge_stress_slope(time, self.wound_radius)
            }
            _ => 0.0,
        })
    }

    /// `T_max, t_assembly, t_delay, thickness, wound_radius, its rate` (f64 LE).
    fn encode(&self) -> Result<Vec<u8>, Rejected> {
        let mut w = Writer(Vec::with_capacity(48));
        self.parameters()
            .into_iter()
            .chain([self.wound_radius, self.radius_rate])
            .for_each(|v| w.f64(v));
        Ok(w.0)
    }

    fn decode(&self, bytes: &[u8]) -> Result<Box<dyn FmuModel>, Rejected> {
        let mut r = Reader::new(bytes);
        let theirs = [r.f64()?, r.f64()?, r.f64()?, r.f64()?];
        let radius = r.f64()?;
        let radius_rate = r.finite("radius rate")?;
        r.finish()?;
        let pairs: Vec<(&str, f64, f64)> = Vr::ALL
            .iter()
            .zip(self.parameters())
            .zip(theirs)
            .map(|((vr, a), b)| (vr.var().name, a, b))
            .collect();
        same_parameters(&pairs)?;
        let wound_radius =
            check_radius(radius).map_err(|e| format!("serialized FMU state: {e}"))?;
        Ok(Box::new(Self { purse: self.purse, wound_radius, radius_rate }))
    }
}
