//! The fuzzer's Model Exchange calls: random counts, states and times on instances of
//! either interface.

use super::*;

impl World {
    /// The Model Exchange functions with random counts, states and times, on instances of
    /// either interface (a CS instance refuses them all).
    pub(super) fn exchange(&mut self) {
        let i = self.target();
        let c = self.component(i);
        let nx = if self.rng.chance(0.7) { 217 } else { self.rng.below(300) };
        let mut x: Vec<f64> = (0..nx)
            .map(|_| if self.rng.chance(0.8) { self.rng.unit() - 0.5 } else { self.rng.real() })
            .collect();
        let (mut a, mut b) = (0, 0);
        let (name, s) = match self.rng.below(9) {
            0 => ("fmi2EnterEventMode", unsafe { fmi2EnterEventMode(c) }),
            1 => ("fmi2NewDiscreteStates", unsafe {
                fmi2NewDiscreteStates(c, &mut std::mem::zeroed())
            }),
            2 => ("fmi2EnterContinuousTimeMode", unsafe { fmi2EnterContinuousTimeMode(c) }),
            3 => ("fmi2CompletedIntegratorStep", unsafe {
                fmi2CompletedIntegratorStep(c, 1, &mut a, &mut b)
            }),
            4 => ("fmi2SetTime", unsafe {
                fmi2SetTime(
                    c,
                    if self.rng.chance(0.7) { self.rng.unit() * 10.0 } else { self.rng.real() },
                )
            }),
            5 => ("fmi2SetContinuousStates", unsafe { fmi2SetContinuousStates(c, x.as_ptr(), nx) }),
            6 => {
                let s = unsafe { fmi2GetDerivatives(c, x.as_mut_ptr(), nx) };
                if s == 0 {
                    assert!(
                        x.iter().all(|v| v.is_finite()),
                        "derivatives accepted with OK are finite"
                    );
                }
                ("fmi2GetDerivatives", s)
            }
            7 => ("fmi2GetContinuousStates", unsafe {
                fmi2GetContinuousStates(c, x.as_mut_ptr(), nx)
            }),
            _ => ("fmi2GetNominalsOfContinuousStates", unsafe {
                fmi2GetNominalsOfContinuousStates(c, x.as_mut_ptr(), nx)
            }),
        };
        self.record(name, s);
    }
}
