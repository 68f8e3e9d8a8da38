"""The threshold of delta chi^2 where the likelihood has more than one valley the data allow.

Wilks' chi^2_1 (and bounds.py's q(rho) next to lambda's bound) assume one valley, Gaussian
to the scale of the noise. Next to lambda = 0 the radius can have two: one on the bound
(or close to it) and one at lambda ~ 0.4, within delta chi^2 ~ 1 of each other (friction
regime, radius only). With the truth in one valley, the fit's minimum is in the other in a
fair share of draws, and delta chi^2 at the truth is then the valleys' gap plus its own
chi^2_1: at lambda = 0.05 its 95 % point is 5.5 for R0 (docs/fitting.md, "Coverage next to
lambda = 0"), where the single-valley thresholds (~3.9) held the truth in 90.5 % of draws.

The law of that ratio is computed here from the local Gaussian model of every valley k,
exact at the valley's point z_k (its optimum, or its lowest point on lambda = 0): m_k the
model there and J_k its
Jacobian (whitened: the residuals are (m - y) / sd), data drawn at a truth z* = z_j,
y = m_j + sd e with e ~ N(0, I), give near valley k the residuals

    r_k(z) = d_k - e + J_k (z - z_k),        d_k = (m_k - m_j) / sd   (exact)

and chi^2 = |r_k|^2 there. The fit's minimum is the least of the valleys' minima; held at
the truth's value of a quantity g^T z = g^T z* (a parameter, or ln zeta/G = ln 4 - 2 ln R0
+ ln T), the constrained minimum is again the least over valleys. A valley on lambda's bound
(lambda_k = 0) moves psi = lambda^2 >= 0 (its column (r(PSI_STEP) - r(0)) / PSI_STEP^2:
the model is even in lambda); each quadratic minimum with psi < 0 is taken again on psi =
0, which is its minimum on the half space (a convex quadratic). The ratio's 95 % point at
each valley's point as the truth is estimated from DRAWS draws; the valleys the data allow
as truths are those whose delta chi^2 lies below that point (the test there, inverted),
and the largest of their points is the threshold: like bounds.q(rho), the largest over the
truths the data allow. With one valley this law is chi^2_1 (or, on the
bound, bounds.py's mixture), so it is only computed where there are two or more; and the
same draws give the ratio of the truth's valley alone, whose exact point corrects the
estimate (a control variate: Q(valleys) - Q(alone) + exact), so that a valley that never
holds the minimum changes nothing, and the sampling error is only that of the other
valleys' effect.
"""

from __future__ import annotations

import numpy as np
from scipy import special

#: Draws of the Gaussian model per truth: the 95 % point of 2000 draws lies between the
#: law's 94.0 % and 96.0 % points (two binomial standard deviations; for chi^2_1, 3.54 and
#: 4.21 about 3.84); the draws are the same in every fit (seed 0), so a threshold does not
#: change from one run to the next.
DRAWS = 2000
#: Relative step of lambda for psi's column at lambda = 0.
PSI_STEP = 1e-2
#: chi^2_1's 95 % point.
CHI2_95 = float(special.chdtri(1, 0.05))
#: Draws per block (the noise of a block is a size x BLOCK matrix).
BLOCK = 500


def padded(g, n: int) -> np.ndarray:
    """A gradient over one wound's four parameters as one over n coordinates (a problem's
    nuisances after them: the quantity does not depend on them)."""
    out = np.zeros(n)
    out[: len(g)] = g
    return out


def psi_jacobian(problem, z, zero: float = 1e-8) -> tuple[np.ndarray, np.ndarray]:
    """(residuals, Jacobian) at z, where lambda = z[2] is 0 (at most `zero`) with psi =
    lambda^2's column in place of lambda's (which vanishes there): (r(PSI_STEP) - r(z)) /
    PSI_STEP^2, exact to O(PSI_STEP^2) since r is even in lambda."""
    r = problem.residuals(z)
    jac = problem.jacobian(z)
    if z[2] <= zero:
        up = np.array(z, float)
        up[2] = PSI_STEP
        jac[:, 2] = (problem.residuals(up) - r) / PSI_STEP**2
    return r, jac


def whitened(problem, z, free):
    """(residuals, Jacobian over `free`, index of psi among them or None) at a valley."""
    r, jac = psi_jacobian(problem, z)
    on_bound = 2 in free and z[2] <= 1e-8
    return r, jac[:, free], (free.index(2) if on_bound else None)


def _least(a, J, G, c, psi):
    """min over d of |a + J d|^2 with G^T d = c (G: k x m, m >= 0 constraints) and, if `psi`
    is an index, d[psi] >= 0; a: size x draws. Returns the minima (draws,)."""
    k = J.shape[1]
    if G.shape[1]:
        d0 = G @ np.linalg.lstsq(G.T @ G, c, rcond=None)[0]
        _, s, vt = np.linalg.svd(G.T)
        N = vt[np.sum(s > 1e-12 * s.max()) :].T  # the directions the constraints leave free
    else:
        d0, N = np.zeros(k), np.eye(k)
    b = a + (J @ d0)[:, None]
    A = J @ N
    if A.shape[1]:
        w = np.linalg.lstsq(A, -b, rcond=None)[0]
        res = b + A @ w
        d = d0[:, None] + N @ w
    else:
        res, d = b, np.repeat(d0[:, None], b.shape[1], axis=1)
    out = np.einsum("ij,ij->j", res, res)
    if psi is not None:
        bad = d[psi] < 0
        if np.any(bad):
            e = np.zeros((k, 1))
            e[psi] = 1.0
            out[bad] = _least(a[:, bad], J, np.hstack([G, e]), np.append(c, 0.0), None)
    return out


def valley_thresholds(problem, valleys, gradients, one_valley, draws=DRAWS, seed=0):
    """name -> the 95 % point of delta chi^2 at the truth of each quantity g^T z (gradients:
    name -> g over z's four coordinates), the largest over the valleys (z, delta chi^2 at
    z; the first the estimate) that are truths the data allow: whose delta lies below the
    95 % point at themselves (the test at that truth, inverted). Every valley given is one
    the fit may end in. `one_valley(rho)`: the exact 95 % point of the ratio with the truth's
    valley alone, on lambda's bound (bounds.nuisance_quantile; chi^2_1's inside), the
    control variate (`_law`). Only for the linear loss. Coordinates the problem holds fixed
    are left out."""
    n = len(valleys[0][0])
    free = [i for i in range(n) if i not in problem.fixed]
    local = [(np.asarray(z, float), *whitened(problem, z, free)) for z, _ in valleys]
    rng = np.random.default_rng(seed)
    out = {name: 0.0 for name in gradients}
    for j, (_, dj) in enumerate(valleys):
        law = _law(local, j, free, gradients, one_valley, draws, rng)
        for name, q in law.items():
            if dj <= q:
                out[name] = max(out[name], q)
    return out


def _law(local, j, free, gradients, one_valley, draws, rng) -> dict:
    """name -> the 95 % point of delta chi^2 with valley j the truth.

    The same draws give the ratio of valley j alone, whose law is known exactly (chi^2_1
    inside the bounds, bounds.py's q(rho) on lambda's bound, rho from valley j's
    Jacobian): the estimate is Q(all valleys) - Q(valley j) + exact (a control variate).
    Where the other valleys never hold the minimum the two ratios are equal draw by draw and
    the estimate is exact; otherwise only the valleys' effect carries the sampling error."""
    many, alone = ratios(local, j, free, gradients, draws, rng)
    _, _, Jj, pj = local[j]
    out = {}
    for name, g in gradients.items():
        exact = _exact(Jj, pj, padded(g, local[j][0].size)[free], one_valley)
        q = np.quantile(many[name], 0.95) - np.quantile(alone[name], 0.95)
        out[name] = float(q + exact)
    return out


def ratios(local, j, free, gradients, draws, rng) -> tuple[dict, dict]:
    """Draws of delta chi^2 at the truth of each quantity, valley j the truth: (name -> with
    every valley, name -> with valley j alone). `local`: per valley (z, residuals, Jacobian
    over `free`, psi's index or None) as `whitened` gives them."""
    zj, rj, _, _ = local[j]
    many = {name: [] for name in gradients}
    alone = {name: [] for name in gradients}
    empty = np.zeros((len(free), 0))
    for start in range(0, draws, BLOCK):
        e = rng.standard_normal((rj.size, min(BLOCK, draws - start)))
        shifted = [(zk, (rk - rj)[:, None] - e, Jk, pk) for zk, rk, Jk, pk in local]
        fulls = [_least(a, J, empty, np.zeros(0), p) for _, a, J, p in shifted]
        for name, g in gradients.items():
            gf = padded(g, zj.size)[free][:, None]
            held = [
                _least(a, J, gf, np.array([gf[:, 0] @ (zj - zk)[free]]), p)
                for zk, a, J, p in shifted
            ]
            many[name].append(np.min(held, axis=0) - np.min(fulls, axis=0))
            alone[name].append(held[j] - fulls[j])
    join = np.concatenate
    return {n: join(v) for n, v in many.items()}, {n: join(v) for n, v in alone.items()}


def _exact(J, psi, g, one_valley) -> float:
    """The 95 % point of the ratio of one valley with Jacobian J: chi^2_1's where psi is None
    (inside the bounds), else one_valley(rho), rho = corr(g^T z_hat, psi_hat) (0 where
    either variance vanishes)."""
    if psi is None:
        return CHI2_95
    rho = correlation(np.linalg.pinv(J.T @ J), psi, g)
    return one_valley(0.0 if rho is None else rho)


def correlation(cov, k: int, g) -> float | None:
    """corr(g^T z_hat, z_hat[k]) under the covariance `cov`; None where either variance is
    not positive."""
    var = float(g @ cov @ g)
    if var > 0 and cov[k, k] > 0:
        return float(g @ cov[:, k]) / float(np.sqrt(var * cov[k, k]))
    return None
