//! FMI 2.0 Model Exchange through the exported functions: the state machine of chapter 3,
//! the states (the modal coordinates' departure from their response to the edge stress
//! held) against the co-simulation step that integrates the same ODE exactly, the exact
//! Jacobian, refusals, FMU states, and the stiffness an integrator faces.
//! (fmpy's CVode against the exact solution: tests/python/test_model_exchange.py.)

mod common;

use common::fmi::*;
use std::ffi::CString;
use wound_opening::fmi::fmi2::exchange::*;
use wound_opening::fmi::fmi2::functions::*;
use wound_opening::fmi::fmi2::types::*;
use wound_opening::models::wound::variables::{MODEL_EXCHANGE_STATES as NX, Vr};
use wound_opening::solver::{Params, Settings, Solver};

fn instantiate_me(guid: &str) -> fmi2Component {
    let (name, guid) = (CString::new("me").unwrap(), CString::new(guid).unwrap());
    let callbacks = fmi2CallbackFunctions::NONE;
    let c = unsafe {
        fmi2Instantiate(
            name.as_ptr(),
            FMI2_MODEL_EXCHANGE,
            guid.as_ptr(),
            c"".as_ptr(),
            &callbacks,
            0,
            0,
        )
    };
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
        assert_eq!(
            (info.newDiscreteStatesNeeded, info.terminateSimulation, info.nextEventTimeDefined),
            (0, 0, 0)
        );
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

/// A co-simulation step of `h` with lambda = 0.5, and the solver it wraps: the ODE the
/// ME states depart from ([`wound_opening::solver::Ode`]: physical coordinates, rates,
/// relaxation times, edge values).
fn co_simulation_reference(lambda: f64, h: f64) -> (f64, wound_opening::solver::Ode) {
    let cs = initialized(WOUND, 0.0, &[(Vr::Lambda as u32, lambda)]);
    assert_eq!(unsafe { fmi2DoStep(cs, 0.0, h, 1) }, OK);
    let (_, r_cs) = get_real(cs, Vr::WoundRadius as u32);
    let mut x_cs = vec![0.0; NX];
    assert_eq!(
        unsafe { fmi2GetContinuousStates(cs, x_cs.as_mut_ptr(), NX) },
        ERROR,
        "ME function on a CS instance"
    );
    unsafe { fmi2FreeInstance(cs) };
    let params = Params { lambda, sigma: 1.0, r_inf: 10.0 };
    let mut solver =
        Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
    solver.advance(h, 0.0).unwrap();
    (r_cs, solver.ode(0.0).unwrap())
}

/// The states are the departure `y = c - c0(t)` of the modal coordinates from their
/// closed-form response `c0` to the edge stress held from the cut
/// (src/models/wound/exchange.rs): 0 at the cut and at every time while the edge stress
/// is held, where fmi2SetTime alone moves the radius along the exact solution (that of a
/// co-simulation step, to the last bits). A departure set relaxes at its own rate
/// `-y_k / nu_k`, and a changed edge stress drives every mode: the derivative is the
/// physical ODE's `(g_k(p) - c_k) / nu_k` minus `c0_k'`.
#[test]
fn states_depart_from_the_held_response_and_derivatives_are_its_ode() {
    let (h, lambda) = (0.3, 0.5);
    let (r_cs, ode) = co_simulation_reference(lambda, h);
    let me = continuous_time(&[(Vr::Lambda as u32, lambda)]);
    assert!(states(me).iter().all(|&v| v == 0.0), "0 at the cut");
    let (_, r0) = get_real(me, Vr::WoundRadius as u32);
    assert_eq!(r0, 1.0 + 1.0 / 6.0);
    assert!(
        derivatives(me).iter().all(|&v| v == 0.0),
        "no departure while the edge stress is held"
    );
    assert_eq!(unsafe { fmi2SetTime(me, h) }, OK);
    let (_, r_h) = get_real(me, Vr::WoundRadius as u32);
    assert!((r_h - r_cs).abs() < 1e-15, "fmi2SetTime follows the exact solution: {r_h} vs {r_cs}");
    assert!(states(me).iter().all(|&v| v == 0.0));
    let mut x = vec![0.0; NX];
    x[0] = 1e-3;
    assert_eq!(unsafe { fmi2SetContinuousStates(me, x.as_ptr(), NX) }, OK);
    let (_, r_x) = get_real(me, Vr::WoundRadius as u32);
    assert!((r_x - (r_cs + 1e-3 * ode.loads[0])).abs() < 1e-15, "R = R(c0) + X_0 y_0");
    let d1 = derivatives(me);
    assert!(
        ((d1[0] + 1e-3 / ode.relaxation_times[0]) / d1[0]).abs() < 1e-14,
        "{} vs {}",
        d1[0],
        -1e-3 / ode.relaxation_times[0]
    );
    assert!(d1.iter().skip(1).all(|&v| v == 0.0), "uncoupled");
    // A changed edge stress: y' = c' - c0', with c' the physical ODE's rate at c = c0 + y.
    let p = 0.2;
    assert_eq!(set_real(me, Vr::EdgeStress as u32, p), OK);
    let d2 = derivatives(me);
    let params = Params { lambda, sigma: 1.0, r_inf: 10.0 };
    let mut solver =
        Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
    let mut c = ode.x.clone();
    c[0] += 1e-3;
    solver.set_ode_state(h, &c, p).unwrap();
    let physical = solver.ode(p).unwrap();
    for (k, &got) in d2.iter().enumerate().take(ode.x.len()) {
        let (x0, nu) = (ode.loads[k], ode.relaxation_times[k]);
        let held_rate = x0 * (-h / nu).exp() / nu;
        let want = physical.rates[k] - held_rate;
        assert!(
            (got - want).abs() <= 1e-12 * physical.rates[k].abs().max(held_rate.abs()).max(1e-300),
            "mode {k}: {got} vs {want}"
        );
    }
    assert!(d2.iter().skip(ode.x.len()).all(|&v| v == 0.0), "the spare states are inert");
    unsafe { fmi2FreeInstance(me) };
}

/// The first state's value reference: after the rows numbered by position (rows added
/// later, such as `validity_warning`, come after the derivatives).
fn first_state() -> usize {
    wound_opening::models::wound::variables::DESCRIPTION.first_state() as usize
}

fn state_vr(k: usize) -> u32 {
    (first_state() + k) as u32
}

fn derivative_vr(k: usize) -> u32 {
    (first_state() + NX + k) as u32
}

fn directional(
    c: fmi2Component,
    unknowns: &[u32],
    knowns: &[u32],
    seed: &[f64],
) -> (fmi2Status, Vec<f64>) {
    let mut out = vec![f64::NAN; unknowns.len()];
    let s = unsafe {
        fmi2GetDirectionalDerivative(
            c,
            unknowns.as_ptr(),
            unknowns.len(),
            knowns.as_ptr(),
            knowns.len(),
            seed.as_ptr(),
            out.as_mut_ptr(),
        )
    };
    (s, out)
}

/// The exact Jacobian of fmi2GetDirectionalDerivative (providesDirectionalDerivative):
/// `J v` over every state equals `A v` with `A = diag(-1 / nu_k)` of the solver's
/// relaxation times (0 on the spare states), and finite differences of
/// fmi2GetDerivatives and of the wound radius in the states and in the edge stress (the
/// system is linear: differences are exact up to rounding). Refused on a co-simulation
/// instance and for a parameter as known.
#[test]
fn directional_derivatives_are_the_exact_jacobian() {
    let lambda = 0.0;
    let me = continuous_time(&[(Vr::Lambda as u32, lambda)]);
    let (_, ode) = co_simulation_reference(lambda, 0.1);
    let n = ode.x.len();
    let mut x: Vec<f64> = (0..NX).map(|k| 1e-3 * ((k as f64) * 0.7).sin()).collect();
    unsafe {
        assert_eq!(fmi2SetTime(me, 0.1), OK);
        assert_eq!(fmi2SetContinuousStates(me, x.as_ptr(), NX), OK);
    }
    let (ders, sts): (Vec<u32>, Vec<u32>) =
        ((0..NX).map(derivative_vr).collect(), (0..NX).map(state_vr).collect());
    let v: Vec<f64> = (0..NX).map(|k| ((k as f64) * 1.3).cos()).collect();
    let (s, jv) = directional(me, &ders, &sts, &v);
    assert_eq!(s, OK);
    for k in 0..NX {
        let want = if k < n { -v[k] / ode.relaxation_times[k] } else { 0.0 };
        assert!((jv[k] - want).abs() <= 1e-15 * want.abs(), "state {k}: {} vs {want}", jv[k]);
    }
    // Finite differences of the derivatives along v.
    let f0 = derivatives(me);
    let e = 1e-6;
    let shifted: Vec<f64> = x.iter().zip(&v).map(|(a, b)| a + e * b).collect();
    assert_eq!(unsafe { fmi2SetContinuousStates(me, shifted.as_ptr(), NX) }, OK);
    let f1 = derivatives(me);
    let (_, r1) = get_real(me, Vr::WoundRadius as u32);
    assert_eq!(unsafe { fmi2SetContinuousStates(me, x.as_ptr(), NX) }, OK);
    let (_, r0) = get_real(me, Vr::WoundRadius as u32);
    for k in 0..NX {
        let fd = (f1[k] - f0[k]) / e;
        assert!(
            (fd - jv[k]).abs() <= 1e-6 * jv[k].abs().max(1.0),
            "state {k}: FD {fd} vs {}",
            jv[k]
        );
    }
    let (s, dr) = directional(me, &[Vr::WoundRadius as u32], &sts, &v);
    assert_eq!(s, OK);
    assert!(
        ((r1 - r0) / e - dr[0]).abs() <= 1e-6 * dr[0].abs(),
        "radius: FD {} vs {}",
        (r1 - r0) / e,
        dr[0]
    );
    // The edge stress drives every mode.
    let edge = [Vr::EdgeStress as u32];
    let (s, jp) = directional(me, &ders, &edge, &[1.0]);
    assert_eq!(s, OK);
    assert_eq!(set_real(me, Vr::EdgeStress as u32, e), OK);
    let fp = derivatives(me);
    for k in 0..NX {
        let want = if k < n { -ode.loads[k] / ode.relaxation_times[k] } else { 0.0 };
        assert!((jp[k] - want).abs() <= 1e-15 * want.abs(), "mode {k}: {} vs {want}", jp[k]);
        assert!(((fp[k] - f0[k]) / e - want).abs() <= 1e-6 * want.abs().max(1.0), "mode {k}: FD");
    }
    // Refusals: a parameter is no known, a state no unknown; CS has no states to differentiate.
    assert_eq!(directional(me, &ders[..1], &[Vr::Lambda as u32], &[1.0]).0, ERROR);
    assert_eq!(directional(me, &sts[..1], &sts[..1], &[1.0]).0, ERROR);
    x[0] = f64::NAN;
    assert_eq!(directional(me, &ders[..1], &sts[..1], &x[..1]).0, ERROR, "NaN seed");
    unsafe { fmi2FreeInstance(me) };
    let cs = initialized(WOUND, 0.0, &[]);
    assert_eq!(
        directional(cs, &[Vr::WoundRadius as u32], &sts[..1], &[1.0]).0,
        ERROR,
        "no states in CS"
    );
    assert_eq!(directional(cs, &[Vr::EdgeVelocity as u32], &edge, &[1.0]).0, OK);
    unsafe { fmi2FreeInstance(cs) };
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
        assert_eq!(
            fmi2SetContinuousStates(c, vec![0.0; NX].as_ptr(), NX),
            ERROR,
            "states only in continuous-time mode"
        );
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
    assert_eq!(
        unsafe { fmi2DeSerializeFMUstate(c, bytes.as_ptr(), size, &mut into) },
        ERROR,
        "CS state into ME"
    );
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
        let solver =
            Solver::new(&params, &Settings::for_tolerance(&params, 1e-10).unwrap()).unwrap();
        let nu = solver.ode(0.0).unwrap().relaxation_times;
        let (fast, slow) =
            nu.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
        println!(
            "lambda = {lambda}: {} modes, fastest relaxation time {fast:.3e} T, slowest {slow:.3e} T, ratio {:.1e}",
            nu.len(),
            slow / fast
        );
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
    for (sigma, p, want) in
        [(1.0, 0.0, 1.0), (2e-5, 0.0, 2e-5), (-5.0, 0.0, 5.0), (1e-4, 2e-4, 2e-4), (0.0, 0.0, 1.0)]
    {
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
