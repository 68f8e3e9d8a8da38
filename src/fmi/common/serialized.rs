//! The byte format of serialized FMU states (`fmi2SerializeFMUstate` /
//! `fmi2DeSerializeFMUstate`): an envelope that the glue writes for every model around the
//! model's own bytes ([`crate::fmi::common::model::FmuModel::encode`]), holding what an FMU state has
//! besides the model: the state machine's state ([`Machine`]) and the master's clock
//! ([`Clock`]), both of [`crate::fmi::common::machine`].
//!
//! ```text
//! offset  size  field
//! 0       8     magic "WOUNDFMU"
//! 8       4     format version (u32 LE) = 3 (2 had no input rates)
//! 12      4     payload length in bytes (u32 LE)
//! 16      n     payload (below)
//! 16+n    4     CRC-32 of bytes 0 .. 16+n (u32 LE)
//!
//! payload: model identifier length (u8), model identifier (UTF-8), machine state (u8),
//!          start time, time (f64 LE), has stop time (u8), stop time (f64),
//!          the model's bytes (the rest)
//! ```
//!
//! Decoding checks every length, the magic, the version, the checksum, the model and
//! every value, so truncated, corrupted or foreign bytes are rejected with a reason,
//! never read past. The model checks its own bytes the same way, with [`Reader`].

use crate::fmi::common::machine::{Clock, Machine};

const MAGIC: &[u8; 8] = b"WOUNDFMU";
pub const FORMAT_VERSION: u32 = 3;
const HEADER: usize = 16;

/// Little-endian writer of a serialized state.
pub struct Writer(pub Vec<u8>);

impl Writer {
    pub fn u8(&mut self, v: u8) {
        self.0.push(v);
    }
    pub fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    pub fn f64(&mut self, v: f64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
}

/// The envelope around a model's bytes.
pub fn encode(model_identifier: &str, machine: Machine, clock: &Clock, model: &[u8]) -> Vec<u8> {
    let mut w = Writer(Vec::with_capacity(64 + model.len()));
    w.0.extend_from_slice(MAGIC);
    w.u32(FORMAT_VERSION);
    w.u32(0); // payload length, patched below
    w.u8(model_identifier.len() as u8);
    w.0.extend_from_slice(model_identifier.as_bytes());
    w.u8(machine.code());
    w.f64(clock.start);
    w.f64(clock.time);
    w.u8(clock.stop.is_some() as u8);
    w.f64(clock.stop.unwrap_or(0.0));
    w.0.extend_from_slice(model);
    let payload = (w.0.len() - HEADER) as u32;
    w.0[12..16].copy_from_slice(&payload.to_le_bytes());
    let crc = crc32fast::hash(&w.0);
    w.u32(crc);
    w.0
}

/// Little-endian reader of a serialized state that never reads past the end.
pub struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes, at: 0 }
    }
    /// Whether every byte was read.
    pub fn finish(&self) -> Result<(), String> {
        let left = self.bytes.len() - self.at;
        if left == 0 {
            Ok(())
        } else {
            Err(format!("serialized FMU state has {left} unread bytes"))
        }
    }
    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end =
            end.ok_or_else(|| format!("serialized FMU state is truncated at byte {}", self.at))?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }
    pub fn u8(&mut self) -> Result<u8, String> {
        Ok(self.take(1)?[0])
    }
    pub fn u32(&mut self) -> Result<u32, String> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }
    pub fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
    pub fn finite(&mut self, what: &str) -> Result<f64, String> {
        let v = self.f64()?;
        if v.is_finite() { Ok(v) } else { Err(format!("serialized FMU state has {what} = {v}")) }
    }
    pub fn flag(&mut self, what: &str) -> Result<bool, String> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(format!("serialized FMU state has {what} flag {b} (expected 0 or 1)")),
        }
    }
}

/// A model's state belongs to one parameter set: each `(name, this instance's value, the
/// state's value)` must agree to the bit.
pub fn same_parameters(pairs: &[(&str, f64, f64)]) -> Result<(), String> {
    match pairs.iter().find(|(_, mine, theirs)| mine.to_bits() != theirs.to_bits()) {
        Some((name, mine, theirs)) => Err(format!(
            "serialized FMU state has {name} = {theirs} but this instance has {name} = {mine}"
        )),
        None => Ok(()),
    }
}

/// Open the envelope: the machine state, the clock and the model's bytes, checked to come
/// from the model `model_identifier`.
pub fn decode<'a>(
    model_identifier: &str,
    bytes: &'a [u8],
) -> Result<(Machine, Clock, &'a [u8]), String> {
    if bytes.len() < HEADER + 4 {
        return Err(format!(
            "serialized FMU state is {} bytes, shorter than its header",
            bytes.len()
        ));
    }
    if &bytes[..8] != MAGIC {
        return Err(
            "serialized FMU state does not start with \"WOUNDFMU\": not a state of this library"
                .into(),
        );
    }
    let mut r = Reader { bytes: &bytes[..bytes.len().saturating_sub(4)], at: 8 };
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
        return Err(format!(
            "serialized FMU state is corrupted: checksum {actual:08x}, expected {stored:08x}"
        ));
    }
    let n = r.u8()? as usize;
    let theirs = String::from_utf8_lossy(r.take(n)?).into_owned();
    if theirs != model_identifier {
        return Err(format!(
            "serialized FMU state is of model {theirs:?} but this instance is {model_identifier:?}"
        ));
    }
    let code = r.u8()?;
    let machine = Machine::from_code(code)
        .ok_or_else(|| format!("serialized FMU state has machine state {code}"))?;
    let start = r.finite("start time")?;
    let time = r.finite("time")?;
    let has_stop = r.flag("stop time")?;
    let stop = r.finite("stop time")?;
    let stop = has_stop.then_some(stop);
    if time < start || stop.is_some_and(|s| s < start) {
        return Err(format!(
            "serialized FMU state has start time {start}, time {time}, stop time {stop:?}"
        ));
    }
    Ok((machine, Clock { start, stop, time }, &r.bytes[r.at..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    const CLOCK: Clock = Clock { start: 0.0, stop: Some(10.0), time: 1.5 };
    const MODEL: &[u8] = &[1, 2, 3, 4, 5];

    fn sample() -> Vec<u8> {
        encode("ModelA", Machine::StepComplete, &CLOCK, MODEL)
    }

    #[test]
    fn round_trips() {
        assert_eq!(decode("ModelA", &sample()).unwrap(), (Machine::StepComplete, CLOCK, MODEL));
        let open = Clock { stop: None, ..CLOCK };
        let bytes = encode("ModelB", Machine::Terminated, &open, &[]);
        assert_eq!(decode("ModelB", &bytes).unwrap(), (Machine::Terminated, open, &[][..]));
    }

    #[test]
    fn rejects_every_truncation_and_every_single_bit_flip() {
        let bytes = sample();
        for n in 0..bytes.len() {
            assert!(decode("ModelA", &bytes[..n]).is_err(), "truncated to {n}");
        }
        for i in 0..bytes.len() {
            for bit in 0..8 {
                let mut b = bytes.clone();
                b[i] ^= 1 << bit;
                assert!(decode("ModelA", &b).is_err(), "bit {bit} of byte {i}");
            }
        }
    }

    #[test]
    fn names_a_foreign_version_and_a_foreign_model() {
        let mut bytes = sample();
        bytes[8] = 1;
        let n = bytes.len() - 4;
        let crc = crc32fast::hash(&bytes[..n]);
        bytes[n..].copy_from_slice(&crc.to_le_bytes());
        assert!(decode("ModelA", &bytes).unwrap_err().contains("format version 1"));
        let err = decode("ModelB", &sample()).unwrap_err();
        assert!(err.contains("of model \"ModelA\" but this instance is \"ModelB\""), "{err}");
    }
}
