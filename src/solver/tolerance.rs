//! From a tolerance to the cheapest mesh that meets it.
//!
//! The error measure is the one every accuracy claim of this project uses: the largest
//! `|R(t) - R_exact(t)|` over `t >= 0.01`, relative to the opening amplitude
//! `R_final - R1`. It is independent of sigma (the problem is linear in sigma) and, with
//! exact time integration, has no time-step part.
//!
//! Elements are uniform in `xi = ln(1 + (r - 1) / ell)` (see [`super::mesh`]), so a mesh is
//! characterised by its degree `p`, its grading length `ell` and its element width `dxi`
//! in `xi`. A scan against the exact Laplace-domain solution found `p = 8`, `ell = 0.1` the
//! cheapest family, with an error governed by `dxi` and nearly independent of lambda (the
//! worst case is lambda -> 0):
//!
//! ```text
//! dxi     0.60    0.75    0.86    0.99    1.15    1.32    1.53    1.84    2.30    3.07
//! error   1.4e-12 1.1e-11 1.0e-10 8.2e-10 9.2e-09 6.4e-08 5.1e-07 7.4e-06 8.7e-05 3.7e-03
//! ```
//!
//! The number of elements is then `E = ceil(ln(1 + (R_inf - 1) / ell) / dxi)`, growing only
//! logarithmically with `R_inf`: 49 unknowns at tolerance 1e-10 and `R_inf = 10`, 97 at
//! `1e3`, 169 at `1e6`.
//!
//! [`MAX_DXI`] is verified over the whole accepted domain (lambda in {0, 1e-3, 1e-2, 0.1,
//! 1, 10, 1e3, 1e4, 1e6} x R_inf in {1.001, 1.01, 1.1, 2, 3, 10, 50, 100, 150, 200, 1e3, 1e4,
//! 1e5, 1e6}, times
//! from 0.01 to 1e16 T, `cargo run --release --example accuracy_scan -- TOL` against
//! `python python/bench/accuracy_scan.py`): the worst error at each tolerance is
//!
//! ```text
//! tolerance  1e-2    1e-3    1e-4    1e-5    1e-6    1e-7    1e-8    1e-9    1e-10    1e-11
//! worst      4.1e-3  1.3e-4  3.0e-5  2.8e-6  2.9e-7  2.0e-8  1.4e-9  1.4e-10 1.6e-11  5.4e-12
//! ```
//!
//! Below [`FINEST_TOLERANCE`] = 1e-11 rounding in the modal transform dominates: smaller
//! tolerances get the 1e-11 mesh, and the FMU answers with a warning that names the
//! accuracy delivered ([`delivered_accuracy`]).

use super::{MeshSpec, Params, Settings, SolverError};

/// `(tolerance, largest element width dxi)` pairs, tolerance decreasing.
const MAX_DXI: [(f64, f64); 10] = [
    (1e-2, 3.2),
    (1e-3, 2.5),
    (1e-4, 2.2),
    (1e-5, 1.75),
    (1e-6, 1.5),
    (1e-7, 1.25),
    (1e-8, 1.05),
    (1e-9, 0.9),
    (1e-10, 0.8),
    (1e-11, 0.6),
];

/// Polynomial degree of the tolerance-driven meshes.
pub const DEGREE: usize = 8;
/// Grading length of the tolerance-driven meshes (R0).
pub const EDGE_SCALE: f64 = 0.1;
/// The smallest tolerance the rule distinguishes; smaller ones get this mesh.
pub const FINEST_TOLERANCE: f64 = 1e-11;

/// The accuracy that a request of `tol` gets: `tol` itself down to [`FINEST_TOLERANCE`].
pub fn delivered_accuracy(tol: f64) -> f64 {
    tol.max(FINEST_TOLERANCE)
}

/// The smallest `|sigma|` but 0 whose wound radius meets the tolerance `tol` (requested;
/// the contract is [`delivered_accuracy`]): `6 eps / tol`, 1.3e-5 at the default 1e-10.
///
/// The wound radius `R = 1 + u(1)` (in R0) is a double near 1, rounded once when formed and
/// once when scaled to um: at most one unit in the last place, `eps R` (eps = 2.2e-16), for
/// any `R < 2`. The opening it is measured against, `R_final - R1 = sigma (2 R_inf^2 /
/// (3 (R_inf^2 - 1)) - 1/6)`, exceeds `|sigma| / 2`, so the rounding is at most
/// `2 eps / |sigma|` of it (measured: 2.2e-16 / |sigma| to 3.8e-16 / |sigma| at lambda = 1,
/// R_inf = 10, whatever the mesh). Below `6 eps / tol` it would take more than a third of
/// the tolerance, which the mesh's own error (up to 0.54 tol, the table above) needs; no
/// double can do better, so such a sigma is refused rather than answered inaccurately.
/// `sigma = 0` is exact: the tissue stays at rest (`R = 1`), or moves only by the edge
/// stress, whose opening is then the scale.
pub fn sigma_floor(tol: f64) -> f64 {
    6.0 * f64::EPSILON / delivered_accuracy(tol)
}

/// Largest element width in `xi` for a tolerance, interpolated linearly in `log10(tol)`.
fn max_dxi(tol: f64) -> f64 {
    let (first, last) = (MAX_DXI[0], MAX_DXI[MAX_DXI.len() - 1]);
    if tol >= first.0 {
        return first.1;
    }
    if tol <= last.0 {
        return last.1;
    }
    let k =
        MAX_DXI.windows(2).position(|w| tol <= w[0].0 && tol >= w[1].0).expect("inside the table");
    let ((t0, d0), (t1, d1)) = (MAX_DXI[k], MAX_DXI[k + 1]);
    let s = (tol.log10() - t0.log10()) / (t1.log10() - t0.log10());
    d0 + s * (d1 - d0)
}

impl Settings {
    /// The cheapest mesh of the rule above whose error stays below `tol` (relative to the
    /// opening amplitude, for t >= 0.01), for these parameters.
    pub fn for_tolerance(params: &Params, tol: f64) -> Result<Settings, SolverError> {
        params.validate()?;
        if !(tol.is_finite() && tol > 0.0) {
            return Err(SolverError::Tolerance(tol));
        }
        let floor = sigma_floor(tol);
        if params.sigma != 0.0 && params.sigma.abs() < floor {
            return Err(SolverError::Unresolved { sigma: params.sigma, tolerance: tol, floor });
        }
        let span = (1.0 + (params.r_inf - 1.0) / EDGE_SCALE).ln();
        let elements = ((span / max_dxi(tol)).ceil() as usize).max(1);
        Ok(Settings { mesh: MeshSpec { degree: DEGREE, elements, edge_scale: EDGE_SCALE } })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn elements(r_inf: f64, tol: f64) -> usize {
        let params = Params { lambda: 1.0, sigma: 1.0, r_inf };
        Settings::for_tolerance(&params, tol).unwrap().mesh.elements
    }

    #[test]
    fn finer_tolerances_and_larger_domains_get_more_elements() {
        assert_eq!(elements(10.0, 1e-9), 6); // ln(91) / 0.9 = 5.01
        assert_eq!(elements(100.0, 1e-10), 9); // ln(991) / 0.8 = 8.6
        for r_inf in [1.001, 2.0, 10.0, 1e3, 1e6] {
            let counts: Vec<usize> = [1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
                .iter()
                .map(|&t| elements(r_inf, t))
                .collect();
            assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{r_inf}: {counts:?}");
            assert!(counts[0] >= 1);
        }
    }

    #[test]
    fn interpolation_hits_the_table_and_stays_between_its_rows() {
        for (tol, dxi) in MAX_DXI {
            assert!((max_dxi(tol) - dxi).abs() < 1e-12);
        }
        let mid = max_dxi(10f64.powf(-8.5));
        assert!(mid > 0.9 && mid < 1.05);
        assert_eq!(max_dxi(1.0), 3.2);
        assert_eq!(max_dxi(1e-15), 0.6);
    }

    #[test]
    fn a_sigma_below_the_rounding_floor_is_refused_with_the_range() {
        let at = |sigma, tol| Settings::for_tolerance(&Params { sigma, ..Params::default() }, tol);
        assert!((sigma_floor(1e-10) - 1.33e-5).abs() < 1e-7);
        assert_eq!(
            sigma_floor(1e-13),
            sigma_floor(1e-11),
            "the floor follows the delivered accuracy"
        );
        for (sigma, tol) in [(1e-6, 1e-10), (-1e-6, 1e-10), (1e-12, 1e-3), (1.3e-5, 1e-10)] {
            let msg = at(sigma, tol).unwrap_err().to_string();
            assert!(msg.contains("accepted: sigma = 0 or |sigma| >= 1.3"), "{msg}");
        }
        for (sigma, tol) in
            [(0.0, 1e-10), (1.34e-5, 1e-10), (-1.34e-5, 1e-10), (1e-12, 1e-2), (2e-9, 1e-6)]
        {
            assert!(at(sigma, tol).is_ok(), "{sigma} {tol}");
        }
    }

    #[test]
    fn rejects_bad_tolerances() {
        let p = Params::default();
        for tol in [0.0, -1e-6, f64::NAN, f64::INFINITY] {
            assert!(Settings::for_tolerance(&p, tol).is_err(), "{tol}");
        }
    }
}
