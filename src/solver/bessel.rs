//! Exponentially scaled modified Bessel functions of orders 0 and 1,
//!
//! ```text
//! ive(n, x) = I_n(x) exp(-x),     kve(n, x) = K_n(x) exp(x),     x > 0,
//! ```
//!
//! which stay finite where `I_n` overflows and `K_n` underflows (`x` beyond ~700, i.e.
//! `lambda` below ~1e-3 in the viscous-layer solution of [`super::exact`]).
//!
//! For `x < 20` they are puruspe's `In`, `Kn` times the exponential. For `x >= 20` the
//! asymptotic (Hankel) expansions
//!
//! ```text
//! ive(n, x) = sum_k (-1)^k a_k(n) / x^k / sqrt(2 pi x),   kve(n, x) = sum_k a_k(n) / x^k sqrt(pi / (2 x)),
//! a_k(n) = prod_{j=1..k} (4 n^2 - (2 j - 1)^2) / (k! 8^k)
//! ```
//!
//! are summed until the terms fall below `1e-17` of the sum: at `x = 20` the smallest term
//! is ~`exp(-2x)` ~ `4e-18`, so the truncation is below double rounding (the `ive`
//! expansion omits an exponentially small `exp(-2x)` term of the same size).

use puruspe::{In, Kn};
use std::f64::consts::PI;

const ASYMPTOTIC_FROM: f64 = 20.0;

/// `sum_k s^k a_k(n) / x^k` with `s = -1` (for I) or `+1` (for K).
fn hankel_sum(n: u32, x: f64, sign: f64) -> f64 {
    let mu = 4.0 * f64::from(n * n);
    let (mut term, mut sum) = (1.0f64, 1.0f64);
    for k in 1..60 {
        let odd = (2 * k - 1) as f64;
        term *= sign * (mu - odd * odd) / (k as f64 * 8.0 * x);
        sum += term;
        if term.abs() < 1e-17 * sum.abs() {
            break;
        }
    }
    sum
}

/// `I_n(x) exp(-x)` for `n` in {0, 1}, `x > 0`.
pub fn ive(n: u32, x: f64) -> f64 {
    if x < ASYMPTOTIC_FROM {
        In(n, x) * (-x).exp()
    } else {
        hankel_sum(n, x, -1.0) / (2.0 * PI * x).sqrt()
    }
}

/// `K_n(x) exp(x)` for `n` in {0, 1}, `x > 0`.
pub fn kve(n: u32, x: f64) -> f64 {
    if x < ASYMPTOTIC_FROM {
        Kn(n, x) * x.exp()
    } else {
        hankel_sum(n, x, 1.0) * (PI / (2.0 * x)).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SciPy `special.ive` / `special.kve` (Cephes/AMOS), printed with 17 digits (kept as
    /// printed, not rounded to what a double holds).
    #[allow(clippy::excessive_precision)]
    const SCIPY: [(f64, f64, f64, f64, f64); 6] = [
        // x, ive(0), ive(1), kve(0), kve(1)
        (
            1e-06,
            0.99999900000075004,
            4.9999950000031305e-07,
            13.931456005075455,
            1000000.9999932843,
        ),
        (0.5, 0.6450352704491501, 0.15642080318487167, 1.5241093857739092, 2.7310097082117855),
        (5.0, 0.18354081260932834, 0.16397226694454237, 0.54780756431351896, 0.60027385878831252),
        (
            19.999,
            0.089782586060965341,
            0.087508323480178438,
            0.27855175753249345,
            0.28543288788183335,
        ),
        (
            20.0,
            0.089780311884825992,
            0.087506222183288643,
            0.27854487665718219,
            0.28542549694072644,
        ),
        (
            1000.0,
            0.012617240455891255,
            0.012610930256928629,
            0.039628321600754218,
            0.03964813081296021,
        ),
    ];

    #[test]
    fn agree_with_scipy_on_both_sides_of_the_switch() {
        for (x, i0, i1, k0, k1) in SCIPY {
            for (got, want, what) in [
                (ive(0, x), i0, "ive0"),
                (ive(1, x), i1, "ive1"),
                (kve(0, x), k0, "kve0"),
                (kve(1, x), k1, "kve1"),
            ] {
                assert!(
                    (got - want).abs() < 1e-13 * want.abs(),
                    "{what}({x}) = {got:e}, scipy {want:e}"
                );
            }
        }
    }
}
