//! PurseString's domain: every parameter and input value it accepts gives finite outputs
//! and derivatives (`edge_stress = T_c / (h R)` and `-T_c / (h R^2)`); values outside it
//! are refused at `fmi2SetReal`. The edges of the domain are probed, not only its centre.

mod common;

use common::fmi::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::models::purse_string::variables::Vr;

/// `edge_stress`, `line_tension` and d edge_stress / d wound_radius after one step past
/// the delay, for these values (set before initialization; the radius after it).
fn outputs_at(t_max: f64, thickness: f64, radius: f64) -> [f64; 3] {
    let params = [
        (Vr::MaxTension as u32, t_max),
        (Vr::Thickness as u32, thickness),
        (Vr::AssemblyTime as u32, 0.0),
    ];
    let c = initialized(PURSE, 0.0, &params);
    assert_eq!(set_real(c, Vr::WoundRadius as u32, radius), OK, "wound_radius = {radius}");
    assert_eq!(unsafe { fmi2DoStep(c, 0.0, 100.0, 1) }, OK);
    let (unknown, known, seed) = (Vr::EdgeStress as u32, Vr::WoundRadius as u32, 1.0);
    let mut d = f64::NAN;
    assert_eq!(
        unsafe { fmi2GetDirectionalDerivative(c, &unknown, 1, &known, 1, &seed, &mut d) },
        OK
    );
    let out = [get_real(c, Vr::EdgeStress as u32).1, get_real(c, Vr::LineTension as u32).1, d];
    unsafe { fmi2FreeInstance(c) };
    out
}

/// Guards against `fmi2OK` with an infinite edge stress (thickness or radius 5e-324 gave
/// inf): the extreme accepted values give finite outputs, exactly T_c / (h R).
#[test]
fn the_bounds_themselves_are_accepted_with_finite_outputs() {
    for (t_max, h, r) in [
        (1e9, 1e-6, 1e-6),
        (0.0, 1e-6, 1e-6),
        (1e9, 1e6, 1e9),
        (1e9, 1e-6, 1e9),
        (6500.0, 5.0, 10.0),
    ] {
        let [p, tc, d] = outputs_at(t_max, h, r);
        assert!(
            p.is_finite() && tc.is_finite() && d.is_finite(),
            "T_max {t_max}, h {h}, R {r}: {p} {tc} {d}"
        );
        assert_eq!(tc, t_max);
        assert_eq!(p, t_max / (h * r));
    }
}

/// Guards against accepting values outside the domain: below and above each bound,
/// non-finite, at `fmi2SetReal`, with nothing changed.
#[test]
fn values_outside_the_bounds_are_refused() {
    let cases: [(Vr, &[f64]); 5] = [
        (Vr::Thickness, &[1e-7, 5e-324, 0.0, 1.1e6, f64::INFINITY, f64::NAN]),
        (Vr::MaxTension, &[-1.0, 1.1e9, f64::INFINITY, f64::NAN]),
        (Vr::WoundRadius, &[9e-7, 5e-324, 0.0, -1.0, 1.1e9, f64::INFINITY, f64::NAN]),
        (Vr::AssemblyTime, &[-1.0, f64::INFINITY, f64::NAN]),
        (Vr::Delay, &[-1.0, f64::INFINITY, f64::NAN]),
    ];
    let c = instantiate(PURSE, "bounds");
    for (vr, bad) in cases {
        for &x in bad {
            assert_eq!(set_real(c, vr as u32, x), ERROR, "{} = {x}", vr.var().name);
        }
    }
    unsafe {
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        for vr in Vr::ALL.iter().filter(|v| v.var().start.is_some()) {
            assert_eq!(
                get_real(c, *vr as u32),
                (OK, vr.var().start.unwrap()),
                "{} unchanged",
                vr.var().name
            );
        }
        fmi2FreeInstance(c);
    }
}

#[derive(Default)]
struct Collect(std::sync::Mutex<Vec<String>>);

impl wound_opening::fmi::common::instance::Logger for Collect {
    fn log(
        &self,
        _status: wound_opening::fmi::common::instance::Status,
        _category: &str,
        message: &str,
    ) {
        self.0.lock().unwrap().push(message.into());
    }
}

/// Guards against a refusal that does not say what is accepted: the message names the
/// variable, the value, and the range with its unit.
#[test]
fn a_refusal_names_the_accepted_range() {
    use wound_opening::fmi::common::instance::{Call, Instance};
    let log = std::sync::Arc::new(Collect::default());
    let mut i = Instance::new(
        wound_opening::models::purse_string::PurseModel::fresh,
        "purse",
        log.clone(),
        false,
    );
    let cases = [
        (Vr::Thickness, 1e-7, "thickness = 0.0000001 is invalid: it must be in [1e-6, 1e6] um"),
        (Vr::MaxTension, 2e9, "T_max = 2000000000 is invalid: it must be in [0, 1e9] pN"),
        (
            Vr::WoundRadius,
            1e10,
            "wound_radius = 10000000000 is invalid: it must be in [1e-6, 1e9] um",
        ),
        (
            Vr::WoundRadius,
            0.0,
            "wound_radius = 0 is invalid: it must be in [1e-6, 1e9] um (the purse-string stress",
        ),
    ];
    for (vr, x, want) in cases {
        assert!(i.call(Call::Set, String::new, |i| i.set_real(&[vr as u32], &[x])).is_err());
        let last = log.0.lock().unwrap().last().cloned().unwrap();
        assert!(last.starts_with(&format!("fmi2Set*: {want}")), "{last}");
    }
}
