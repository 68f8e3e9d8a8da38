"""The threshold of delta chi^2 for a 95 % profile interval where lambda may sit on its bound 0.

Away from bounds, delta chi^2 at the true value is chi^2(1) (95 %: 3.84), or F(1, dof)
with the noise estimated. R(t) and the velocities depend on lambda through psi = lambda^2
only, and psi >= 0; near psi = 0 the likelihood is regular in psi (lambda's column of the
Jacobian vanishes there, psi's does not), and the local Gaussian model is

    (theta_hat, psi_hat) ~ N((theta, psi), C),   psi >= 0,   corr(theta_hat, psi_hat) = rho.

lambda's own profile. With the truth on the bound (psi = 0) the likelihood ratio is the
chi-bar-squared mixture 1/2 chi^2_0 + 1/2 chi^2_1 (Self & Liang 1987, case 1): psi_hat = 0
half of the time (LR = 0), else LR = Z^2. Its 95 % point is chi^2_1's 90 % point, 2.71
(F(1, dof)'s 90 % point with the noise estimated). More generally, at a truth psi = a se,
LR = Z^2 where Z > -a and a^2 where the fit hits the bound, whose 95 % point c(a) is 2.71
for a <= 1.645, a^2 up to 1.96 and 3.84 beyond: inverting this exact test, a fit with
psi_hat = 0 has the interval [0, 1.645 se], which is the crossing of delta = 2.71. So the
mixture's threshold is used for lambda's profile where lambda's estimate is 0; with
lambda_hat > 0 the ordinary 3.84 (which then only makes the lower end conservative:
LR <= Z^2 there, never larger). A threshold below 3.84 shortens the interval: it is used
only where the bound makes the LR stochastically smaller, and restores 95 % from above.

Other parameters while lambda may be 0 (Self & Liang 1987, a parameter of interest with a
nuisance on its boundary). With psi = 0 true, whitened (x, y) ~ N(0, I), theta_hat = x,
psi_hat = rho x + sqrt(1 - rho^2) y, and psi* = psi_hat - rho theta_hat the nuisance's fit
at theta held at its truth:

    psi_hat >= 0, psi* >= 0:  LR = x^2
    psi_hat >= 0, psi* <  0:  LR = x^2 + psi*^2 / (1 - rho^2)         (> x^2)
    psi_hat <  0, psi* >= 0:  LR = x^2 - psi_hat^2                   (< x^2)
    psi_hat <  0, psi* <  0:  LR = (x - rho psi_hat)^2 / (1 - rho^2)

LR is homogeneous of degree 2 in (x, y) = R (cos w, sin w): LR = R^2 g(w) with R^2 ~
chi^2_2 independent of the uniform angle w, so

    P(LR > c) = (1 / 2 pi) integral over w of exp(-c / (2 g(w)))   (where g(w) > 0),

and the 95 % point q(rho) solves P(LR > q) = 0.05: 3.84 at rho = 0, rising slowly with
|rho| (3.92 at 0.9, 4.00 at 0.95, 4.13 at 0.99). At a truth just off the bound (a > 0) the
95 % point falls below 3.84 (to ~3.0 at rho = 0.95, a = 0.5: a Monte Carlo of this model)
and returns to 3.84 for large a, so q(rho) is the largest over the truths the data allow:
it is used, for a parameter whose estimate has correlation rho with psi_hat (from the
Jacobian with psi's column), wherever lambda's interval reaches 0; with the noise estimated
it is scaled by F(1, dof)'s 95 % point over chi^2_1's. The bound can thus only widen these
intervals, and only by a few per cent: an under-coverage larger than that is not the bound's.

Two valleys. Next to the bound the radius data can allow a second local optimum (one valley
at lambda = 0, one at lambda ~ 0.4 in the friction regime), and then the truth lies in one
while the minimum is in the other in a fair share of draws: delta chi^2 at the truth is the
valleys' gap plus its own chi^2_1 (95 % point 5.5 for R0 at lambda = 0.05, measured), which
no single-valley law gives. Where a free fit from the estimate moved to lambda = 0, or
another optimum of the fit, lies within VALLEYS thresholds, the threshold is the larger of
q(rho) and the law of the several valleys' local Gaussian model (valley_law.py).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize, special

from .._native import SolverError
from .intervals import BETTER, BetterOptimum
from .local import local_fit
from .valley_law import correlation, padded, psi_jacobian, valley_thresholds

#: Angles of the quadrature of P(LR > c) (the integrand is smooth between the four cones).
ANGLES = 20000
#: Valleys further than this many regular thresholds above the minimum are left out of the
#: several valleys' law: the fit's minimum is never there.
VALLEYS = 3.0
#: Evaluations of the free fit that looks for a valley next to lambda = 0: one converges in
#: ~20 where there is one (the friction regime, radius only); on the flat valley of
#: plateau-only data (R0 -> 0.1 um, 12 ms a solve) it would crawl for its 200.
FREE_NFEV = 40


def quantile(p: float, noise_given: bool, dof: int) -> float:
    """The p quantile of chi^2_1, or of F(1, dof) with the noise estimated (scipy.special's
    inverse distribution functions: scipy.stats costs more to import than a fit)."""
    return float(special.chdtri(1, 1 - p)) if noise_given else float(special.fdtri(1, dof, p))


def regular(noise_given: bool, dof: int) -> float:
    """chi^2_1's 95 % point, or F(1, dof)'s with the noise estimated."""
    return quantile(0.95, noise_given, dof)


def mixture(noise_given: bool, dof: int) -> float:
    """The 95 % point of 1/2 chi^2_0 + 1/2 chi^2_1 (chi^2_1's 90 %), or of F likewise."""
    return quantile(0.90, noise_given, dof)


def exceedance(c: float, rho: float) -> float:
    """P(LR > c) for a parameter whose estimate has correlation rho with psi_hat, psi = 0."""
    return _tail(c, _gains(rho))


def _gains(rho: float) -> np.ndarray:
    """g(w) at ANGLES angles w (module docstring: LR = R^2 g(w)), 0 where g <= 0."""
    w = (np.arange(ANGLES) + 0.5) * (2 * math.pi / ANGLES)
    x, y = np.cos(w), np.sin(w)
    s = math.sqrt(max(1 - rho * rho, 1e-12))
    psi = rho * x + s * y
    star = psi - rho * x
    g = np.where(
        psi >= 0,
        np.where(star >= 0, x * x, x * x + star**2 / s**2),
        np.where(star >= 0, x * x - psi**2, (x - rho * psi) ** 2 / s**2),
    )
    return g[g > 0]


def _tail(c: float, g: np.ndarray) -> float:
    """(1 / 2 pi) integral of exp(-c / (2 g(w))) over the angles where g > 0."""
    with np.errstate(under="ignore"):
        return float(np.sum(np.exp(-c / (2 * g)))) / ANGLES


def nuisance_quantile(rho: float) -> float:
    """q(rho): the 95 % point of the LR with lambda's truth on its bound (module docstring);
    g(w) is computed once, the root found on it."""
    g = _gains(float(np.clip(rho, -0.999999, 0.999999)))
    return float(optimize.brentq(lambda c: _tail(c, g) - 0.05, 1.0, 50.0, xtol=1e-6))


def psi_correlations(problem, z, gradients: dict) -> dict:
    """corr(estimate, psi_hat) of each quantity whose gradient in z is given (name ->
    d quantity / d z over coordinates 0, 1, 3), from the Jacobian with lambda's column
    replaced by psi = lambda^2's: dr/dpsi = (dr/dlambda) / (2 lambda), or at lambda = 0 the
    difference (r(PSI_STEP) - r(0)) / PSI_STEP^2 (exact to O(PSI_STEP^2): r is even in
    lambda). Coordinates the problem holds fixed are left out."""
    z = np.asarray(z, float)
    if z[2] > 1e-6:
        jac = problem.jacobian(z)
        jac[:, 2] = jac[:, 2] / (2 * z[2])
    else:
        jac = psi_jacobian(problem, z, zero=1e-6)[1]
    free = [i for i in range(len(z)) if i not in problem.fixed]
    if 2 not in free:
        return {}
    try:
        cov = np.linalg.inv(jac[:, free].T @ jac[:, free])
    except np.linalg.LinAlgError:
        return {}
    out = {}
    for name, grad in gradients.items():
        rho = correlation(cov, free.index(2), padded(grad, len(z))[free])
        if rho is not None:
            out[name] = rho
    return out


#: d quantity / d z of the quantities whose threshold follows q(rho): the parameters other
#: than lambda and ln zeta/G = ln 4 - 2 ln R0 + ln T (tau and the viscous length involve
#: lambda itself: at lambda = 0 they are 0 and not profiled).
GRADIENTS = {
    "R0_um": (1.0, 0.0, 0.0, 0.0),
    "sigma": (0.0, 1.0, 0.0, 0.0),
    "T_s": (0.0, 0.0, 0.0, 1.0),
    "zeta_over_G_s_per_um2": (-2.0, 0.0, 0.0, 1.0),
}


def thresholds(
    problem,
    z,
    chi2_min: float,
    loss: str,
    noise_given: bool,
    dof: int,
    others=(),
    restart: bool = False,
) -> tuple[dict, list]:
    """name -> the threshold of its 95 % interval where it is not `regular` (module
    docstring): lambda's where its estimate is 0; the others' q(rho) wherever lambda's
    interval reaches 0 (its estimate 0, or delta chi^2 at lambda = 0 below the regular
    threshold, one constrained fit). Where delta chi^2 at lambda = 0 is below VALLEYS
    thresholds and a second valley lies there (a free fit from that constrained fit, and
    `others`: the fit's other optima, (z, delta chi^2)), the larger of that and the several
    valleys' law (valley_law.py; least squares only). Nothing with lambda held fixed or
    bounded above 0 by the user (the bound is then the user's). Returns (the thresholds,
    the valleys found beyond `others`: (z, delta chi^2), for the walks to start from).
    With `restart`, either fit landing BETTER or more below chi2_min raises BetterOptimum,
    as a profile walk's does (intervals.Walk.below): the fit settles again from there."""
    if 2 in problem.fixed or problem.bounds()[0][2] > 0:
        return {}, []
    base = regular(noise_given, dof)
    out = {}
    start = None  # where a second valley is looked for: lambda's profile at 0
    if z[2] <= 1e-8:
        out["lambda"] = mixture(noise_given, dof)
        reaches = True
    else:
        try:
            start, held, res = local_fit(
                problem, z, fixed=2, value=0.0, loss=loss, tol=1e-7, max_nfev=100
            )
        except SolverError:
            start, held, res = None, chi2_min, None
        if restart and held < chi2_min - BETTER:  # lambda = 0 fits better than the optimum
            raise BetterOptimum(start, held)
        reaches = held - chi2_min < base or res is None or res.status == 0  # unsure: reached
        if not reaches and held - chi2_min >= VALLEYS * base:
            return out, []
    scale = base / quantile(0.95, True, 0)
    if reaches:
        for name, rho in psi_correlations(problem, z, GRADIENTS).items():
            out[name] = scale * nuisance_quantile(rho)
    if loss != "linear":
        return out, []
    found = _free_valley(problem, start, chi2_min)
    if restart and found and found[0][1] <= -BETTER:
        raise BetterOptimum(found[0][0], chi2_min + found[0][1])
    valleys = _valleys(z, found + list(others), VALLEYS * base)
    if len(valleys) > 1:
        law = valley_thresholds(problem, valleys, GRADIENTS, nuisance_quantile)
        out |= {name: max(out.get(name, 0.0), scale * q) for name, q in law.items()}
    return out, [v for v in valleys[1:2] if found and v[0] is found[0][0]]


def _free_valley(problem, start, chi2_min) -> list:
    """[(z, delta chi^2)] of the optimum a free fit from `start` (lambda's profile at 0;
    None: none) converges to within FREE_NFEV evaluations, or []."""
    if start is None:
        return []
    try:
        found, c, res = local_fit(problem, start, tol=1e-7, max_nfev=FREE_NFEV)
    except SolverError:
        return []
    # an optimum: a fit still crawling is on the estimate's valley
    return [(found, c - chi2_min)] if res.status > 0 else []


def _valleys(z, candidates, within: float) -> list:
    """(z, delta chi^2) of the estimate and of the candidates below `within`, each more than
    1e-2 from those before it in some coordinate (stages.alternates' rule)."""
    out = [(np.asarray(z, float), 0.0)]
    for v, d in candidates:
        if d < within and all(np.max(np.abs(v - w)) > 1e-2 for w, _ in out):
            out.append((v, max(float(d), 0.0)))
    return out
