//! The instance's table of FMU states (`fmi2GetFMUstate` ... `fmi2DeSerializeFMUstate`, and
//! their FMI 3.0 counterparts): snapshots of the state machine, the clock and the model,
//! held by handle. Handles come from the process-wide counter
//! ([`crate::boundary::registry::fresh_handle`]) and are never reused, so a handle that this
//! instance did not hand out is refused with the reason, never dereferenced.

use super::{Call, Instance, Machine, Rejected};
use crate::boundary::registry::fresh_handle;
use crate::fmi::common::machine::Clock;
use crate::fmi::common::model::FmuModel;
use crate::fmi::common::serialized;

/// A saved FMU state, as held in the instance's table of states.
pub(super) struct Snapshot {
    machine: Machine,
    clock: Clock,
    model: Box<dyn FmuModel>,
}

impl Clone for Snapshot {
    fn clone(&self) -> Self {
        Self { machine: self.machine, clock: self.clock, model: self.model.boxed_clone() }
    }
}

impl Instance {
    /// `fmi2GetFMUstate`: save into `handle` if given (it must be ours), else a new one.
    pub fn get_fmu_state(&mut self, handle: Option<u64>) -> Result<u64, Rejected> {
        let snap =
            Snapshot { machine: self.machine, clock: self.clock, model: self.model.boxed_clone() };
        let h = match handle {
            Some(h) => self.snapshot(h).map(|_| h)?,
            None => fresh_handle(),
        };
        self.states.insert(h, snap);
        Ok(h)
    }

    /// A state of this instance. Any other handle is refused with the reason: FMI 2.0
    /// (section 2.1.8) gives an FMU state to the instance that made it; the way to move a
    /// state to another instance is to serialize and deserialize it.
    fn snapshot(&self, handle: u64) -> Result<&Snapshot, Rejected> {
        self.states.get(&handle).ok_or_else(|| {
            format!(
                "FMU state {handle:#x} is unknown to this instance (never allocated by it, or already freed); \
                 a state of another instance cannot be used here: move it with {} and {}",
                self.name_of(Call::SerializeFmuState),
                self.name_of(Call::DeSerializeFmuState)
            )
        })
    }

    pub fn set_fmu_state(&mut self, handle: u64) -> Result<(), Rejected> {
        let snap = self.snapshot(handle)?.clone();
        self.machine = snap.machine;
        self.clock = snap.clock;
        self.model = snap.model;
        Ok(())
    }

    pub fn free_fmu_state(&mut self, handle: u64) -> Result<(), Rejected> {
        self.snapshot(handle)?;
        self.states.remove(&handle);
        Ok(())
    }

    pub fn serialize_fmu_state(&self, handle: u64) -> Result<Vec<u8>, Rejected> {
        let snap = self.snapshot(handle)?;
        let model = snap.model.encode()?;
        Ok(serialized::encode(
            self.description().model_identifier,
            snap.machine,
            &snap.clock,
            &model,
        ))
    }

    /// `fmi2DeSerializeFMUstate`: the bytes must come from an instance of the same model
    /// with the same parameters (a state is a point of one trajectory, not a parameter
    /// set). Into `target` if given (it must be ours), else into a new state.
    pub fn deserialize_fmu_state(
        &mut self,
        bytes: &[u8],
        target: Option<u64>,
    ) -> Result<u64, Rejected> {
        if let Some(h) = target {
            self.snapshot(h)?;
        }
        let (machine, clock, payload) =
            serialized::decode(self.description().model_identifier, bytes)?;
        // Intermediate Update Mode exists only inside a step (no state is saved there),
        // Configuration Mode only in the dialects that have it.
        let transient = machine == Machine::IntermediateUpdate
            || (machine == Machine::ConfigurationMode && !self.dialect.configuration_mode);
        if transient || !machine.belongs_to(self.interface) {
            return Err(format!(
                "serialized FMU state is in state {machine:?}, which this instance ({:?}) is never saved in",
                self.interface
            ));
        }
        let model = self.model.decode(payload)?;
        let handle = target.unwrap_or_else(fresh_handle);
        self.states.insert(handle, Snapshot { machine, clock, model });
        Ok(handle)
    }
}
