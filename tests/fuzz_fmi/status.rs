//! The fuzzer's status queries (`fmi2Get*Status`, any kind, NULL or not) and the calls
//! this FMU refuses or answers partly (derivatives, `fmi2CancelStep`).

use super::*;

impl World {
    pub(super) fn status(&mut self) {
        let i = self.target();
        let c = self.component(i);
        let kind = if self.rng.chance(0.8) {
            self.rng.below(4) as i32
        } else {
            self.rng.next_u64() as i32
        };
        let (mut st, mut r, mut n, mut s) = (0, 0.0, 0, std::ptr::null());
        let null = self.rng.chance(0.1);
        let (name, status) = match self.rng.below(5) {
            0 => ("fmi2GetStatus", unsafe {
                fmi2GetStatus(c, kind, if null { std::ptr::null_mut() } else { &mut st })
            }),
            1 => ("fmi2GetRealStatus", unsafe {
                fmi2GetRealStatus(c, kind, if null { std::ptr::null_mut() } else { &mut r })
            }),
            2 => ("fmi2GetIntegerStatus", unsafe {
                fmi2GetIntegerStatus(c, kind, if null { std::ptr::null_mut() } else { &mut n })
            }),
            3 => ("fmi2GetBooleanStatus", unsafe {
                fmi2GetBooleanStatus(c, kind, if null { std::ptr::null_mut() } else { &mut n })
            }),
            _ => ("fmi2GetStringStatus", unsafe {
                fmi2GetStringStatus(c, kind, if null { std::ptr::null_mut() } else { &mut s })
            }),
        };
        self.record(name, status);
    }

    pub(super) fn unsupported(&mut self) {
        let i = self.target();
        let c = self.component(i);
        let (vr, order, mut x) = ([3u32], [1i32], [0.5f64]);
        let (name, s) = match self.rng.below(4) {
            0 => {
                // Random unknowns and knowns (any role, or out of range), random seeds.
                let (nu, nk) = (self.rng.below(4), self.rng.below(4));
                let unknowns: Vec<u32> = (0..nu).map(|_| self.value_reference()).collect();
                let knowns: Vec<u32> = (0..nk).map(|_| self.value_reference()).collect();
                let seed: Vec<f64> = (0..nk).map(|_| self.rng.real()).collect();
                let mut out = vec![0.0; nu];
                let s = unsafe {
                    fmi2GetDirectionalDerivative(
                        c,
                        unknowns.as_ptr(),
                        nu,
                        knowns.as_ptr(),
                        nk,
                        seed.as_ptr(),
                        out.as_mut_ptr(),
                    )
                };
                if s == 0 {
                    assert!(
                        out.iter().all(|v| v.is_finite()),
                        "a derivative accepted with OK is finite: {out:?}"
                    );
                }
                ("fmi2GetDirectionalDerivative", s)
            }
            1 => ("fmi2SetRealInputDerivatives", unsafe {
                fmi2SetRealInputDerivatives(c, vr.as_ptr(), 1, order.as_ptr(), x.as_ptr())
            }),
            2 => ("fmi2GetRealOutputDerivatives", unsafe {
                fmi2GetRealOutputDerivatives(c, vr.as_ptr(), 1, order.as_ptr(), x.as_mut_ptr())
            }),
            _ => ("fmi2CancelStep", unsafe { fmi2CancelStep(c) }),
        };
        self.record(name, s);
    }
}
