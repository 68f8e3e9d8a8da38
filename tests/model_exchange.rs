//! FMI 2.0 Model Exchange through the exported functions: the state machine of chapter 3,
//! the states (modal coordinates) against the co-simulation step that integrates the same
//! ODE exactly, refusals, FMU states, and the stiffness an integrator faces.
//! (fmpy's CVode against the exact solution: tests/python/test_model_exchange.py.)

mod common;

use common::fmi::*;
use std::ffi::CString;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::exchange::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::{MODEL_EXCHANGE_STATES as NX, Vr};
use wound_opening::solver::{Params, Settings, Solver};

fn instantiate_me(guid: &str) -> fmi2Component {
    let (name, guid) = (CString::new("me").unwrap(), CString::new(guid).unwrap());
    let callbacks = fmi2CallbackFunctions::NONE;
    let c = unsafe { fmi2Instantiate(name.as_ptr(), FMI2_MODEL_EXCHANGE, guid.as_ptr(), c"".as_ptr(), &callbacks, 0, 0) };
    assert!(!c.is_null());
    c
}

/// An ME instance of WoundOpening in continuous-time mode at t = 0, with `params` set.
fn continuous_time(params: &[(u32, f64)]) -> fmi2Component {
    let c = instantiate_me(WOUND);
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), OK);
        for &(vr, x) in params {
            assert_eq!(fmi2SetReal(c, &vr, 1, &x), OK);
        }
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
        let mut info = fmi2EventInfo {
            newDiscreteStatesNeeded: 1,
            terminateSimulation: 1,
            nominalsOfContinuousStatesChanged: 1,
            valuesOfContinuousStatesChanged: 1,
            nextEventTimeDefined: 1,
            nextEventTime: 1.0,
        };
        assert_eq!(fmi2NewDiscreteStates(c, &mut info), OK);
        assert_eq!((info.newDiscreteStatesNeeded, info.terminateSimulation, info.nextEventTimeDefined), (0, 0, 0));
        assert_eq!(fmi2EnterContinuousTimeMode(c), OK);
    }
    c
}

fn states(c: fmi2Component) -> Vec<f64> {
    let mut x = vec![f64::NAN; NX];
    assert_eq!(unsafe { fmi2GetContinuousStates(c, x.as_mut_ptr(), NX) }, OK);
    x
}

fn derivatives(c: fmi2Component) -> Vec<f64> {
    let mut dx = vec![f64::NAN; NX];
    assert_eq!(unsafe { fmi2GetDerivatives(c, dx.as_mut_ptr(), NX) }, OK);
    dx
}

/// The states of a co-simulation instance after one exact step of `h` are the ME states
/// on the same trajectory: setting them into an ME instance at time h gives the same
/// radius to the last bits, and the ME derivative is the linear ODE's `(g - c) / nu`,
/// which an explicit exponential step reproduces.
#[test]
fn states_are_the_co_simulation_state_and_derivatives_its_ode() {
    let h = 0.3;
    let cs = initialized(WOUND, 0.0, &[(Vr::Lambda as u32, 0.5)]);
    assert_eq!(unsafe { fmi2DoStep(cs, 0.0, h, 1) }, OK);
    let (_, r_cs) = get_real(cs, Vr::WoundRadius as u32);
    let me = continuous_time(&[(Vr::Lambda as u32, 0.5)]);
    let x0 = states(me);
    assert!(x0.iter().all(|&v| v == 0.0), "0 at the cut");
    let (_, r0) = get_real(me, Vr::WoundRadius as u32);
    assert_eq!(r0, 1.0 + 1.0 / 6.0);
    let d0 = derivatives(me);
    assert!(d0.iter().skip(49).all(|&v| v == 0.0), "the spare states are inert");
    let mut x = x0.clone();
    x[0] = 1e-3;
    unsafe {
        assert_eq!(fmi2SetTime(me, h), OK);
        assert_eq!(fmi2SetContinuousStates(me, x.as_ptr(), NX), OK);
    }
    let d1 = derivatives(me);
    // Linear and uncoupled: only mode 0 changes, by -1e-3 / nu_0.
    assert!(d1.iter().zip(&d0).skip(1).all(|(a, b)| a == b));
    let nu0 = -1e-3 / (d1[0] - d0[0]);
    assert!(nu0 > 0.0 && nu0.is_finite());
    // A CS instance refuses the ME getters; its state comes from the solver it wraps.
    let mut x_cs = vec![0.0; NX];
    assert_eq!(unsafe { fmi2GetContinuousStates(cs, x_cs.as_mut_ptr(), NX) }, ERROR, "ME function on a CS instance");
    let params = Params { lambda: 0.5, sigma: 1.0, r_inf: 10.0 };
    let mut solver = Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
    solver.advance(h, 0.0).unwrap();
    let ode = solver.ode(0.0).unwrap();
    let mut x = ode.x.clone();
    x.resize(NX, 0.0);
    assert_eq!(unsafe { fmi2SetContinuousStates(me, x.as_ptr(), NX) }, OK);
    let (_, r_me) = get_real(me, Vr::WoundRadius as u32);
    assert!((r_me - r_cs).abs() < 1e-15, "{r_me} vs {r_cs}");
    let dx = derivatives(me);
    for k in 0..ode.x.len() {
        assert!((dx[k] - ode.rates[k]).abs() <= 1e-15 * ode.rates[k].abs().max(1.0));
    }
    unsafe {
        fmi2FreeInstance(cs);
        fmi2FreeInstance(me);
    }
}

/// The state machine of chapter 3 and the interface split: CS functions on an ME
/// instance and ME functions out of their states are refused; wrong counts, NaN states,
/// times before startTime and the stepping schemes are refused with fmi2Error.
#[test]
fn refuses_what_model_exchange_does_not_allow() {
    let c = continuous_time(&[]);
    unsafe {
        assert_eq!(fmi2DoStep(c, 0.0, 0.1, 1), ERROR, "fmi2DoStep on ME");
        let mut x = vec![0.0; NX];
        assert_eq!(fmi2SetContinuousStates(c, x.as_ptr(), NX - 1), ERROR, "nx");
        x[3] = f64::NAN;
        assert_eq!(fmi2SetContinuousStates(c, x.as_ptr(), NX), ERROR, "NaN");
        assert_eq!(fmi2SetTime(c, -1.0), ERROR, "before startTime");
        assert_eq!(fmi2GetEventIndicators(c, std::ptr::null_mut(), 0), OK);
        assert_eq!(fmi2GetEventIndicators(c, x.as_mut_ptr(), 1), ERROR, "no event indicators");
        let (mut enter, mut term) = (1, 1);
        assert_eq!(fmi2CompletedIntegratorStep(c, 1, &mut enter, &mut term), OK);
        assert_eq!((enter, term), (0, 0));
        assert_eq!(fmi2NewDiscreteStates(c, &mut std::mem::zeroed()), ERROR, "not in event mode");
        assert_eq!(fmi2EnterEventMode(c), OK);
        assert_eq!(fmi2SetContinuousStates(c, vec![0.0; NX].as_ptr(), NX), ERROR, "states only in continuous-time mode");
        let one = 1.0;
        let state_vr = 13u32;
        assert_eq!(fmi2SetReal(c, &state_vr, 1, &one), ERROR, "nor by fmi2SetReal in event mode");
        let (s, v) = get_real(c, state_vr);
        assert_eq!((s, v), (OK, 0.0), "but read by fmi2GetReal");
        assert_eq!(fmi2Terminate(c), OK);
        fmi2FreeInstance(c);
    }
    // method 1 (TR-BDF2) is a stepping scheme: no ODE to hand over.
    let c = instantiate_me(WOUND);
    unsafe {
        let (vr, one) = (Vr::Method as u32, 1);
        assert_eq!(fmi2SetInteger(c, &vr, 1, &one), OK);
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), ERROR, "ME with method = 1");
        fmi2FreeInstance(c);
    }
    // A CS instance refuses the ME functions.
    let cs = initialized(WOUND, 0.0, &[]);
    unsafe {
        assert_eq!(fmi2SetTime(cs, 0.0), ERROR);
        assert_eq!(fmi2EnterEventMode(cs), ERROR);
        fmi2FreeInstance(cs);
    }
}

/// FMU states work in ME as in CS; a serialized CS state (in StepComplete) does not
/// deserialize into an ME instance, whose machine never is in that state.
#[test]
fn fmu_states_round_trip_and_stay_with_their_interface() {
    let c = continuous_time(&[]);
    let mut x = vec![0.0; NX];
    x[..3].copy_from_slice(&[0.1, -0.2, 0.3]);
    unsafe {
        assert_eq!(fmi2SetTime(c, 0.5), OK);
        assert_eq!(fmi2SetContinuousStates(c, x.as_ptr(), NX), OK);
    }
    let (s, state) = get_state(c);
    assert_eq!(s, OK);
    let mut size = 0usize;
    assert_eq!(unsafe { fmi2SerializedFMUstateSize(c, state, &mut size) }, OK);
    let mut bytes = vec![0i8; size];
    assert_eq!(unsafe { fmi2SerializeFMUstate(c, state, bytes.as_mut_ptr(), size) }, OK);
    unsafe {
        assert_eq!(fmi2SetContinuousStates(c, vec![0.0; NX].as_ptr(), NX), OK);
        let mut back: fmi2FMUstate = std::ptr::null_mut();
        assert_eq!(fmi2DeSerializeFMUstate(c, bytes.as_ptr(), size, &mut back), OK);
        assert_eq!(fmi2SetFMUstate(c, back), OK);
    }
    assert_eq!(&states(c)[..3], &[0.1, -0.2, 0.3]);
    let cs = initialized(WOUND, 0.0, &[]);
    let (_, cs_state) = get_state(cs);
    let mut size = 0usize;
    assert_eq!(unsafe { fmi2SerializedFMUstateSize(cs, cs_state, &mut size) }, OK);
    let mut bytes = vec![0i8; size];
    assert_eq!(unsafe { fmi2SerializeFMUstate(cs, cs_state, bytes.as_mut_ptr(), size) }, OK);
    let mut into: fmi2FMUstate = std::ptr::null_mut();
    assert_eq!(unsafe { fmi2DeSerializeFMUstate(c, bytes.as_ptr(), size, &mut into) }, ERROR, "CS state into ME");
    unsafe {
        fmi2FreeInstance(c);
        fmi2FreeInstance(cs);
    }
}

/// PurseString has no states: nx = 0, and its outputs follow fmi2SetTime.
#[test]
fn purse_string_runs_as_model_exchange_without_states() {
    let c = instantiate_me(PURSE);
    unsafe {
        assert_eq!(fmi2SetupExperiment(c, 0, 0.0, 0.0, 0, 0.0), OK);
        assert_eq!(fmi2EnterInitializationMode(c), OK);
        assert_eq!(fmi2ExitInitializationMode(c), OK);
        assert_eq!(fmi2EnterContinuousTimeMode(c), OK);
        assert_eq!(fmi2GetDerivatives(c, std::ptr::null_mut(), 0), OK);
        assert_eq!(fmi2SetTime(c, 50.0), OK);
        // T_c(50) = 6500 (1 - exp(-(50 - 20) / 30)) pN.
        let (s, t) = get_real(c, 6);
        assert_eq!(s, OK);
        assert!((t - 6500.0 * (1.0 - (-1.0f64).exp())).abs() < 1e-9, "{t}");
        fmi2FreeInstance(c);
    }
}

/// The stiffness a Model Exchange integrator faces: the relaxation times nu_k = mu_k +
/// lambda^2 of the default mesh (R_inf = 10, tolerance 1e-10, 49 modes), in T. Measured:
///
/// ```text
/// lambda   fastest      slowest    ratio
/// 0        4.54e-6 T    23.9 T     5.3e6
/// 0.1      1.00e-2 T    23.9 T     2.4e3
/// 1        1.00    T    24.9 T     25
/// 10       100     T    124  T     1.2
/// ```
///
/// At small lambda an explicit integrator needs steps below the fastest time (the mesh's
/// edge element at lambda = 0), so use an implicit one (BDF, e.g. CVode). Printed with
/// `--nocapture`; the bounds (a factor 2 around the measured fastest time at lambda = 0,
/// lambda^2 plus at most 1e-5 elsewhere) fail if the mesh or the basis changes.
#[test]
fn stiffness_of_the_default_mesh() {
    for lambda in [0.0, 0.1, 1.0, 10.0] {
        let params = Params { lambda, sigma: 1.0, r_inf: 10.0 };
        let solver = Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
        let nu = solver.ode(0.0).unwrap().relaxation_times;
        let (fast, slow) = nu.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
        println!("lambda = {lambda}: {} modes, fastest relaxation time {fast:.3e} T, slowest {slow:.3e} T, ratio {:.1e}", nu.len(), slow / fast);
        if lambda == 0.0 {
            assert!((2.2e-6..9.1e-6).contains(&fast), "{fast}");
        } else {
            assert!(fast >= lambda * lambda && fast <= lambda * lambda + 1e-5, "{fast}");
        }
        assert!(slow > fast);
    }
}

/// The nominals are one scale per parameter set, the edge-stress scale max(|sigma|, |p|)
/// in G: the coordinates are proportional to sigma - p, so an absolute tolerance
/// `rtol nominal` is the same fraction of the opening whatever sigma (the accuracy this
/// gives CVode, BDF and Radau: tests/python/test_masters.py, docs/fmi.md).
#[test]
fn nominals_scale_with_the_edge_stress() {
    for (sigma, p, want) in [(1.0, 0.0, 1.0), (2e-5, 0.0, 2e-5), (-5.0, 0.0, 5.0), (1e-4, 2e-4, 2e-4), (0.0, 0.0, 1.0)] {
        let c = continuous_time(&[(Vr::Sigma as u32, sigma), (Vr::EdgeStress as u32, p)]);
        let mut n = vec![f64::NAN; NX];
        assert_eq!(unsafe { fmi2GetNominalsOfContinuousStates(c, n.as_mut_ptr(), NX) }, OK);
        assert!(n.iter().all(|&v| v == want), "sigma {sigma} p {p}: {:?}", &n[..3]);
        unsafe {
            fmi2Terminate(c);
            fmi2FreeInstance(c);
        }
    }
}

/// Outputs are functions of the states, inputs and parameters: the edge velocity at t = 0
/// with the cut's states x = 0 is the closed-form initial velocity however often the
/// states are set, and a state set alone with fmi2SetReal in continuous-time mode moves
/// only its own derivative.
#[test]
fn edge_velocity_is_a_function_of_the_states_and_states_can_be_set_one_by_one() {
    for lambda in [1e-4, 1e-3] {
        let c = continuous_time(&[(Vr::Lambda as u32, lambda)]);
        unsafe {
            let first = get_real(c, Vr::EdgeVelocity as u32);
            for _ in 0..2 {
                assert_eq!(fmi2SetTime(c, 0.0), OK);
                assert_eq!(fmi2SetContinuousStates(c, vec![0.0; NX].as_ptr(), NX), OK);
                assert_eq!(get_real(c, Vr::EdgeVelocity as u32), first, "lambda {lambda}");
            }
            // -1/(4 lambda) (sigma - p) to leading order in lambda (p = 0, sigma = 1):
            // 2500 and 250; the Bessel closed form to 1e-7: tests/python/test_masters.py.
            let lead = 1.0 / (4.0 * lambda);
            assert!((first.1 - lead).abs() < 2e-2 * lead, "lambda {lambda}: {first:?}");
            let d0 = derivatives(c);
            let (vr, x) = (14u32, 1e-3);
            let k = (vr - 13) as usize;
            assert_eq!(fmi2SetReal(c, &vr, 1, &x), OK);
            assert_eq!(states(c)[k], x);
            let d1 = derivatives(c);
            for i in 0..NX {
                if i != k {
                    assert_eq!(d1[i], d0[i], "state {i}");
                }
            }
            fmi2Terminate(c);
            fmi2FreeInstance(c);
        }
    }
}
