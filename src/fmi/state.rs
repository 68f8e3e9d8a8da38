//! FMU states: what `fmi2GetFMUstate` saves, and its byte format for
//! `fmi2SerializeFMUstate` / `fmi2DeSerializeFMUstate`.
//!
//! ```text
//! offset  size  field
//! 0       8     magic "WOUNDFMU"
//! 8       4     format version (u32 LE) = 1
//! 12      4     payload length in bytes (u32 LE)
//! 16      n     payload (below)
//! 16+n    4     CRC-32 of bytes 0 .. 16+n (u32 LE)
//!
//! payload: machine state (u8), lambda, sigma, R_inf (f64 LE), mesh degree, elements (u32),
//!          edge scale, tolerance, edge stress, start time, time (f64),
//!          has experiment tolerance (u8), experiment tolerance (f64), method, grid points (u32),
//!          internal step (f64), has stop time (u8), stop time (f64),
//!          has solver (u8), [solver time (f64), n (u32), n modal coefficients (f64)]
//! ```
//!
//! Decoding checks every length, the magic, the version, the checksum and every value,
//! so truncated, corrupted or foreign bytes are rejected with a reason, never read past.

use crate::solver::{MeshSpec, Params, Scheme, Settings, SolverState};

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

const MAGIC: &[u8; 8] = b"WOUNDFMU";
pub const FORMAT_VERSION: u32 = 1;
const HEADER: usize = 16;
const MAX_COEFFS: usize = 1 << 20;

/// The FMI state machine's states (FMI 2.0 co-simulation, synchronous).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Machine {
    Instantiated,
    InitializationMode,
    StepComplete,
    Terminated,
    /// After an internal failure: only reset, restore or inspection are allowed.
    Error,
}

impl Machine {
    fn code(self) -> u8 {
        self as u8
    }

    fn from_code(c: u8) -> Option<Self> {
        [Self::Instantiated, Self::InitializationMode, Self::StepComplete, Self::Terminated, Self::Error]
            .get(c as usize)
            .copied()
    }
}

/// Everything of an instance that an FMU state saves, in plain values.
#[derive(Debug, Clone, PartialEq)]
pub struct Saved {
    pub machine: Machine,
    pub params: Params,
    pub settings: Settings,
    /// The `tolerance` parameter and the tolerance of `fmi2SetupExperiment`, if defined.
    pub tolerance: f64,
    pub experiment_tolerance: Option<f64>,
    pub scheme: SchemeChoice,
    pub edge_stress: f64,
    pub start_time: f64,
    pub time: f64,
    pub stop_time: Option<f64>,
    pub solver: Option<SolverState>,
}

struct Writer(Vec<u8>);

impl Writer {
    fn u8(&mut self, v: u8) {
        self.0.push(v);
    }
    fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
}

pub fn encode(s: &Saved) -> Vec<u8> {
    let mut w = Writer(Vec::with_capacity(128 + 8 * s.solver.as_ref().map_or(0, |x| x.coeffs.len())));
    w.0.extend_from_slice(MAGIC);
    w.u32(FORMAT_VERSION);
    w.u32(0); // payload length, patched below
    w.u8(s.machine.code());
    for v in [s.params.lambda, s.params.sigma, s.params.r_inf] {
        w.f64(v);
    }
    w.u32(s.settings.mesh.degree as u32);
    w.u32(s.settings.mesh.elements as u32);
    for v in [s.settings.mesh.edge_scale, s.tolerance, s.edge_stress, s.start_time, s.time] {
        w.f64(v);
    }
    w.u8(s.experiment_tolerance.is_some() as u8);
    w.f64(s.experiment_tolerance.unwrap_or(0.0));
    w.u32(s.scheme.method as u32);
    w.u32(s.scheme.grid_points as u32);
    w.f64(s.scheme.internal_step);
    w.u8(s.stop_time.is_some() as u8);
    w.f64(s.stop_time.unwrap_or(0.0));
    w.u8(s.solver.is_some() as u8);
    if let Some(st) = &s.solver {
        w.f64(st.time);
        w.u32(st.coeffs.len() as u32);
        st.coeffs.iter().for_each(|&c| w.f64(c));
    }
    let payload = (w.0.len() - HEADER) as u32;
    w.0[12..16].copy_from_slice(&payload.to_le_bytes());
    let crc = crc32fast::hash(&w.0);
    w.u32(crc);
    w.0
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| format!("serialized FMU state is truncated at byte {}", self.at))?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }
    fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take(1)?[0])
    }
    fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }
    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
    fn finite(&mut self, what: &str) -> Result<f64, String> {
        let v = self.f64()?;
        if v.is_finite() { Ok(v) } else { Err(format!("serialized FMU state has {what} = {v}")) }
    }
    fn flag(&mut self, what: &str) -> Result<bool, String> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("serialized FMU state has {what} flag {b} (expected 0 or 1)")),
        }
    }
}

pub fn decode(bytes: &[u8]) -> Result<Saved, String> {
    if bytes.len() < HEADER + 4 {
        return Err(format!("serialized FMU state is {} bytes, shorter than its header", bytes.len()));
    }
    if &bytes[..8] != MAGIC {
        return Err("serialized FMU state does not start with \"WOUNDFMU\": not a WoundOpening state".into());
    }
    let mut r = Reader { bytes, at: 8 };
    let version = r.u32()?;
    if version != FORMAT_VERSION {
        return Err(format!(
            "serialized FMU state has format version {version}; this FMU reads version {FORMAT_VERSION}"
        ));
    }
    let payload = r.u32()? as usize;
    if bytes.len() != HEADER + payload + 4 {
        return Err(format!(
            "serialized FMU state is {} bytes but its header announces {}",
            bytes.len(),
            HEADER + payload + 4
        ));
    }
    let stored = u32::from_le_bytes(bytes[HEADER + payload..].try_into().expect("4 bytes"));
    let actual = crc32fast::hash(&bytes[..HEADER + payload]);
    if stored != actual {
        return Err(format!("serialized FMU state is corrupted: checksum {actual:08x}, expected {stored:08x}"));
    }
    let code = r.u8()?;
    let machine = Machine::from_code(code).ok_or_else(|| format!("serialized FMU state has machine state {code}"))?;
    let params = Params { lambda: r.f64()?, sigma: r.f64()?, r_inf: r.f64()? };
    params.validate().map_err(|e| format!("serialized FMU state: {e}"))?;
    let degree = r.u32()? as usize;
    let elements = r.u32()? as usize;
    let edge_scale = r.finite("edge scale")?;
    let settings = Settings { mesh: MeshSpec { degree, elements, edge_scale } };
    let tolerance = r.finite("tolerance")?;
    let edge_stress = r.finite("edge_stress")?;
    let start_time = r.finite("start time")?;
    let time = r.finite("time")?;
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
    let scheme = SchemeChoice { method: method as i32, grid_points: grid_points as i32, internal_step };
    let has_stop = r.flag("stop time")?;
    let stop = r.finite("stop time")?;
    let solver = if r.flag("solver")? {
        let st = r.finite("solver time")?;
        let n = r.u32()? as usize;
        if n > MAX_COEFFS {
            return Err(format!("serialized FMU state has {n} modal coefficients (at most {MAX_COEFFS})"));
        }
        let coeffs = (0..n).map(|_| r.finite("a modal coefficient")).collect::<Result<_, _>>()?;
        Some(SolverState { time: st, coeffs })
    } else {
        None
    };
    if r.at != HEADER + payload {
        return Err(format!("serialized FMU state has {} unread payload bytes", HEADER + payload - r.at));
    }
    Ok(Saved {
        machine,
        params,
        settings,
        tolerance,
        experiment_tolerance,
        scheme,
        edge_stress,
        start_time,
        time,
        stop_time: has_stop.then_some(stop),
        solver,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Saved {
        Saved {
            machine: Machine::StepComplete,
            params: Params { lambda: 0.1, sigma: 1.0, r_inf: 10.0 },
            settings: Settings::default(),
            tolerance: 1e-10,
            experiment_tolerance: Some(1e-6),
            scheme: SchemeChoice { method: 2, grid_points: 101, internal_step: 1e-3 },
            edge_stress: 0.25,
            start_time: 0.0,
            time: 1.5,
            stop_time: Some(10.0),
            solver: Some(SolverState { time: 1.5, coeffs: vec![0.5, -1.25, 3.0] }),
        }
    }

    #[test]
    fn round_trips() {
        let s = sample();
        assert_eq!(decode(&encode(&s)).unwrap(), s);
        let none = Saved { solver: None, stop_time: None, ..sample() };
        assert_eq!(decode(&encode(&none)).unwrap(), none);
    }

    #[test]
    fn rejects_every_truncation_and_every_single_bit_flip() {
        let bytes = encode(&sample());
        for n in 0..bytes.len() {
            assert!(decode(&bytes[..n]).is_err(), "truncated to {n}");
        }
        for i in 0..bytes.len() {
            for bit in 0..8 {
                let mut b = bytes.clone();
                b[i] ^= 1 << bit;
                assert!(decode(&b).is_err(), "bit {bit} of byte {i}");
            }
        }
    }

    #[test]
    fn names_a_foreign_version() {
        let mut bytes = encode(&sample());
        bytes[8] = 2;
        let n = bytes.len() - 4;
        let crc = crc32fast::hash(&bytes[..n]);
        bytes[n..].copy_from_slice(&crc.to_le_bytes());
        assert!(decode(&bytes).unwrap_err().contains("format version 2"));
    }
}
