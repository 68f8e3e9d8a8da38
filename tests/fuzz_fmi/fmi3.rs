//! The fuzzer's FMI 3.0 calls: the functions whose arguments differ from FMI 2.0's, on
//! the same instances (one handle table for both versions).

use super::*;

impl World {
    /// FMI 3.0 functions on the same instances (one handle table for both versions): the
    /// calls whose arguments differ from FMI 2.0's, with random counts and values, and an
    /// FMI 3.0 instantiation now and then.
    pub(super) fn fmi3(&mut self) {
        use wound_opening::fmi::fmi3::exchange::*;
        use wound_opening::fmi::fmi3::functions::*;
        use wound_opening::fmi::fmi3::unsupported::*;
        if self.rng.chance(0.1) && self.live.len() < 6 {
            let guid = CString::new(MODELS[self.rng.below(MODELS.len())].0.guid).unwrap();
            let c = if self.rng.chance(0.5) {
                unsafe {
                    fmi3InstantiateModelExchange(
                        c"f3".as_ptr(),
                        guid.as_ptr(),
                        std::ptr::null(),
                        0,
                        0,
                        std::ptr::null_mut(),
                        None,
                    )
                }
            } else {
                let event = self.rng.below(2) as u8;
                unsafe {
                    fmi3InstantiateCoSimulation(
                        c"f3".as_ptr(),
                        guid.as_ptr(),
                        std::ptr::null(),
                        0,
                        0,
                        event,
                        0,
                        std::ptr::null(),
                        0,
                        std::ptr::null_mut(),
                        None,
                        None,
                    )
                }
            };
            self.record("fmi3Instantiate*", if c.is_null() { 3 } else { 0 });
            if !c.is_null() {
                self.live.push(Live { c, states: Vec::new(), freed: Vec::new() });
            }
            return;
        }
        let i = self.target();
        let c = self.component(i);
        let nvr = self.rng.below(4);
        // The FMI 3.0-only references too: time (447), n_probes (448), probe_radii,
        // displacement, velocity (449..451), and the states and derivatives (13..446).
        let vrs: Vec<u32> = (0..nvr)
            .map(|_| {
                if self.rng.chance(0.5) {
                    440 + self.rng.below(14) as u32
                } else {
                    self.value_reference()
                }
            })
            .collect();
        let n_values = if self.rng.chance(0.8) { nvr } else { self.rng.below(6) };
        let x: Vec<f64> = (0..n_values.max(nvr)).map(|_| self.rng.real()).collect();
        let mut k: Vec<i32> = (0..n_values.max(nvr)).map(|_| self.rng.next_u64() as i32).collect();
        let (mut b, mut t) = ([0u8; 5], 0.0);
        let mut big: Vec<u64> =
            (0..n_values.max(nvr))
                .map(|_| {
                    if self.rng.chance(0.8) {
                        self.rng.below(12) as u64
                    } else {
                        self.rng.next_u64()
                    }
                })
                .collect();
        let (name, s) = match self.rng.below(12) {
            8 => ("fmi3EnterConfigurationMode", unsafe { fmi3EnterConfigurationMode(c) }),
            9 => ("fmi3ExitConfigurationMode", unsafe { fmi3ExitConfigurationMode(c) }),
            10 => ("fmi3SetUInt64", unsafe {
                fmi3SetUInt64(c, vrs.as_ptr(), nvr, big.as_ptr(), n_values)
            }),
            11 => ("fmi3GetUInt64", unsafe {
                fmi3GetUInt64(c, vrs.as_ptr(), nvr, big.as_mut_ptr(), n_values)
            }),
            0 => {
                // Arrays take up to 1000 values each: a buffer that large, nValues as chosen.
                let mut out = vec![0.0; 4000];
                let n = if self.rng.chance(0.5) { n_values } else { self.rng.below(30) };
                ("fmi3GetFloat64", unsafe {
                    fmi3GetFloat64(c, vrs.as_ptr(), nvr, out.as_mut_ptr(), n)
                })
            }
            1 => ("fmi3SetFloat64", unsafe {
                fmi3SetFloat64(c, vrs.as_ptr(), nvr, x.as_ptr(), n_values)
            }),
            2 => ("fmi3GetInt32", unsafe {
                fmi3GetInt32(c, vrs.as_ptr(), nvr, k.as_mut_ptr(), n_values)
            }),
            3 => ("fmi3SetInt32", unsafe {
                fmi3SetInt32(c, vrs.as_ptr(), nvr, k.as_ptr(), n_values)
            }),
            4 => {
                let (tol, stop) = (self.rng.real(), self.rng.real());
                let tol_defined = self.rng.below(2) as u8;
                ("fmi3EnterInitializationMode", unsafe {
                    fmi3EnterInitializationMode(
                        c,
                        tol_defined,
                        tol,
                        0.0,
                        self.rng.below(2) as u8,
                        stop,
                    )
                })
            }
            5 => {
                let (mut now, h) = (0.0, self.rng.unit() * 10.0);
                let _ = unsafe { fmi2GetRealStatus(c, FMI2_LAST_SUCCESSFUL_TIME, &mut now) };
                let [e, f, g, ..] = &mut b;
                ("fmi3DoStep", unsafe { fmi3DoStep(c, now, h, 0, e, f, g, &mut t) })
            }
            6 => {
                let [p, q, r, u, v] = &mut b;
                ("fmi3UpdateDiscreteStates", unsafe {
                    fmi3UpdateDiscreteStates(c, p, q, r, u, v, &mut t)
                })
            }
            _ => ("fmi3GetClock", unsafe { fmi3GetClock(c, vrs.as_ptr(), nvr, b.as_mut_ptr()) }),
        };
        self.record(name, s);
    }
}
