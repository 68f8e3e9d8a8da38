//! The wound model's part of a serialized FMU state (inside the envelope of
//! [`crate::fmi::common::serialized`]).
//!
//! ```text
//! lambda, sigma, R_inf, R0, T, G (f64 LE), mesh degree, elements (u32), edge scale,
//! tolerance, edge stress (f64), has experiment tolerance (u8), experiment tolerance (f64),
//! method, grid points (u32), internal step (f64),
//! has solver (u8), [solver time (f64), n (u32), n modal coefficients (f64)],
//! edge stress rate (f64, Pa/s; 0 unless fmi2SetRealInputDerivatives set one)
//!
//! (The FMI 3.0 probe radii are not in it: they say where the field is read, not where
//! the trajectory is; a restored state reads at the instance's own radii.)
//! ```

use crate::fmi::common::serialized::{Reader, Writer};
use crate::solver::{MeshSpec, Params, Scheme, Settings, SolverState};
use crate::units::Scales;

const MAX_COEFFS: usize = 1 << 20;

/// The FMU's `method`, `grid_points` and `internal_step` parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SchemeChoice {
    pub method: i32,
    pub grid_points: i32,
    pub internal_step: f64,
}

impl SchemeChoice {
    /// The solver scheme: 0 modal on `mesh`, 1 TR-BDF2 on `mesh`, 2 the paper's, 3 explicit
    /// (values were range-checked when set).
    pub fn scheme(&self, settings: Settings) -> Scheme {
        let (points, max_step) = (self.grid_points.max(3) as usize, self.internal_step);
        match self.method {
            1 => Scheme::TrBdf2 { mesh: settings.mesh, max_step },
            2 => Scheme::Paper { points, max_step },
            3 => Scheme::Explicit { points, max_step },
            _ => Scheme::Modal(settings),
        }
    }
}

/// Everything of the wound model that an FMU state saves, in plain values.
#[derive(Debug, Clone, PartialEq)]
pub struct Saved {
    pub params: Params,
    pub scales: Scales,
    pub settings: Settings,
    /// The `tolerance` parameter and the tolerance of `fmi2SetupExperiment`, if defined.
    pub tolerance: f64,
    pub experiment_tolerance: Option<f64>,
    pub scheme: SchemeChoice,
    pub edge_stress: f64,
    pub edge_stress_rate: f64,
    pub solver: Option<SolverState>,
}

pub fn encode(s: &Saved) -> Vec<u8> {
    let mut w =
        Writer(Vec::with_capacity(128 + 8 * s.solver.as_ref().map_or(0, |x| x.coeffs.len())));
    let (p, k) = (s.params, s.scales);
    for v in [p.lambda, p.sigma, p.r_inf, k.length, k.time, k.stress] {
        w.f64(v);
    }
    w.u32(s.settings.mesh.degree as u32);
    w.u32(s.settings.mesh.elements as u32);
    for v in [s.settings.mesh.edge_scale, s.tolerance, s.edge_stress] {
        w.f64(v);
    }
    w.u8(s.experiment_tolerance.is_some() as u8);
    w.f64(s.experiment_tolerance.unwrap_or(0.0));
    w.u32(s.scheme.method as u32);
    w.u32(s.scheme.grid_points as u32);
    w.f64(s.scheme.internal_step);
    w.u8(s.solver.is_some() as u8);
    if let Some(st) = &s.solver {
        w.f64(st.time);
        w.u32(st.coeffs.len() as u32);
        st.coeffs.iter().for_each(|&c| w.f64(c));
    }
    w.f64(s.edge_stress_rate);
    w.0
}

pub fn decode(bytes: &[u8]) -> Result<Saved, String> {
    let mut r = Reader::new(bytes);
    let params = Params { lambda: r.f64()?, sigma: r.f64()?, r_inf: r.f64()? };
    params.validate().map_err(|e| format!("serialized FMU state: {e}"))?;
    let scales = Scales { length: r.f64()?, time: r.f64()?, stress: r.f64()? };
    scales.validate().map_err(|e| format!("serialized FMU state: {e}"))?;
    let degree = r.u32()? as usize;
    let elements = r.u32()? as usize;
    let edge_scale = r.finite("edge scale")?;
    let settings = Settings { mesh: MeshSpec { degree, elements, edge_scale } };
    let tolerance = r.finite("tolerance")?;
    let edge_stress = r.finite("edge_stress")?;
    let has_experiment_tolerance = r.flag("experiment tolerance")?;
    let experiment_tolerance = r.finite("experiment tolerance")?;
    let experiment_tolerance = has_experiment_tolerance.then_some(experiment_tolerance);
    for tol in std::iter::once(tolerance).chain(experiment_tolerance) {
        if tol <= 0.0 {
            return Err(format!("serialized FMU state has tolerance = {tol}"));
        }
    }
    let (method, grid_points) = (r.u32()?, r.u32()?);
    let internal_step = r.finite("internal_step")?;
    if method > 3 || !(3..=100_000).contains(&grid_points) || internal_step <= 0.0 {
        return Err(format!(
            "serialized FMU state has method {method}, grid_points {grid_points}, internal_step {internal_step}"
        ));
    }
    let scheme =
        SchemeChoice { method: method as i32, grid_points: grid_points as i32, internal_step };
    let solver = if r.flag("solver")? {
        let st = r.finite("solver time")?;
        let n = r.u32()? as usize;
        if n > MAX_COEFFS {
            return Err(format!(
                "serialized FMU state has {n} modal coefficients (at most {MAX_COEFFS})"
            ));
        }
        let coeffs = (0..n).map(|_| r.finite("a modal coefficient")).collect::<Result<_, _>>()?;
        Some(SolverState { time: st, coeffs })
    } else {
        None
    };
    let edge_stress_rate = r.finite("edge stress rate")?;
    r.finish()?;
    Ok(Saved {
        params,
        scales,
        settings,
        tolerance,
        experiment_tolerance,
        scheme,
        edge_stress,
        edge_stress_rate,
        solver,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Saved {
        Saved {
            params: Params { lambda: 0.1, sigma: 1.0, r_inf: 10.0 },
            scales: Scales { length: 10.0, time: 10.0, stress: 100.0 },
            settings: Settings::default(),
            tolerance: 1e-10,
            experiment_tolerance: Some(1e-6),
            scheme: SchemeChoice { method: 2, grid_points: 101, internal_step: 1e-3 },
            edge_stress: 0.25,
            edge_stress_rate: -1.5,
            solver: Some(SolverState { time: 1.5, coeffs: vec![0.5, -1.25, 3.0] }),
        }
    }

    #[test]
    fn round_trips() {
        let s = sample();
        assert_eq!(decode(&encode(&s)).unwrap(), s);
        let none = Saved { solver: None, experiment_tolerance: None, ..sample() };
        assert_eq!(decode(&encode(&none)).unwrap(), none);
    }

    #[test]
    fn rejects_every_truncation_and_trailing_bytes() {
        let bytes = encode(&sample());
        for n in 0..bytes.len() {
            assert!(decode(&bytes[..n]).is_err(), "truncated to {n}");
        }
        let mut long = bytes.clone();
        long.push(0);
        assert!(decode(&long).unwrap_err().contains("1 unread bytes"));
    }

    #[test]
    fn rejects_invalid_scales() {
        let bad = Saved { scales: Scales { time: 0.0, ..sample().scales }, ..sample() };
        assert!(decode(&encode(&bad)).unwrap_err().contains("T = 0 is invalid"));
    }
}
