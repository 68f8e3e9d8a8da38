"""Material constants in and out, and parameters fixed, bounded or with a Gaussian prior:
the conversion against the exact solution, the refusals, what a fixed value, a bound and a
prior do to the estimates and the profile intervals, and the absolute eta with a prior on
G against a brute-force profile over (theta, G)."""

from __future__ import annotations

import math

import fmu_harness
import numpy as np
import pytest
import wound_exact as we
from scipy import optimize

import wound_opening as wo
from wound_opening.fitting.derived import Reparametrised
from wound_opening.fitting.local import local_fit
from wound_opening.fitting.objective import Objective, to_z, wound_coordinates
from wound_opening.fitting.parameters import Parameter, Parameters, from_options

LAM, SIGMA, R0, T, OUTER, NOISE = 0.5, 0.5, 10.0, 10.0, 100.0, 0.05


def series(noise=NOISE, seed=3):
    t = np.linspace(0.5, 60, 30)
    r = R0 * we.edge(LAM, SIGMA, OUTER / R0, t / T)[0] + noise * np.random.default_rng(
        seed
    ).standard_normal(t.size)
    return wo.RadiusSeries(t, r, noise_um=noise)


@pytest.fixture(scope="module")
def free():
    return wo.fit(series(), outer_radius_um=OUTER)


def params(**spec):
    p = Parameters()
    for name, kw in spec.items():
        p.add(name, **kw)
    return p


# --- material in -------------------------------------------------------------------------


def test_material_constants_convert_both_ways_and_simulate_takes_them():
    rng = np.random.default_rng(7)
    for _ in range(5):
        G, eta, zeta = 10 ** rng.uniform(1, 4), 10 ** rng.uniform(0, 4), 10 ** rng.uniform(-1, 2)
        tension, r0 = G * rng.uniform(0.1, 2), rng.uniform(3, 30)
        p = wo.from_material(
            G_pa=G, eta_pa_s=eta, zeta_pa_s_per_um2=zeta, tension_pa=tension, R0_um=r0
        )
        # lambda = 2 sqrt(eta / zeta) / R0, sigma = tension / G, T = zeta R0^2 / (4 G)
        assert p["lam"] == pytest.approx(2 * math.sqrt(eta / zeta) / r0, rel=1e-14)
        assert p["sigma"] == pytest.approx(tension / G, rel=1e-14)
        assert p["T_s"] == pytest.approx(zeta * r0**2 / (4 * G), rel=1e-14)
        back = wo.to_material(lam=p["lam"], sigma=p["sigma"], T_s=p["T_s"], R0_um=r0, G_pa=G)
        for name, value in (
            ("eta_pa_s", eta),
            ("zeta_pa_s_per_um2", zeta),
            ("tension_pa", tension),
        ):
            assert back[name] == pytest.approx(value, rel=1e-13), name
    # the worked example: G 100 Pa, eta 1000 Pa s, zeta 40 Pa s/um^2, tension 100 Pa, R0 10 um
    times = np.array([0.5, 3.0, 20.0, 90.0])
    sim = wo.simulate(
        times,
        G_pa=100.0,
        eta_pa_s=1000.0,
        zeta_pa_s_per_um2=40.0,
        tension_pa=100.0,
        R0_um=10.0,
        outer_radius_um=100.0,
    )
    exact = 10.0 * we.edge(1.0, 1.0, 10.0, times / 10.0)[0]
    opening = 10.0 * (we.final_radius(1.0, 10.0) - we.initial_radius(1.0))
    assert np.max(np.abs(sim.radius_um - exact)) < 1e-9 * opening


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(lam=1.0, sigma=1.0, T_s=10.0, eta_pa_s=1000.0), "not both"),
        (dict(G_pa=100.0, eta_pa_s=1000.0, zeta_pa_s_per_um2=40.0), "need tension_pa"),
        (
            dict(G_pa=100.0, eta_pa_s=1000.0, tension_pa=100.0, zeta_pa_s_per_um2=0.0),
            "zeta_pa_s_per_um2 = 0.0 is invalid",
        ),
        (dict(lam=1.0, sigma=1.0), "missing T_s"),
    ],
)
def test_simulate_refuses_a_mixed_or_incomplete_set(kwargs, message):
    with pytest.raises(ValueError, match=message):
        wo.simulate([1.0], R0_um=10.0, outer_radius_um=100.0, **kwargs)


# --- the specification's refusals ----------------------------------------------------------


@pytest.mark.parametrize(
    "spec, message",
    [
        (dict(R_inf=dict(value=10, vary=False)), "'R_inf' is unknown"),
        (
            {
                n: dict(value=v, vary=False)
                for n, v in (("R0_um", 10), ("sigma", 0.5), ("lambda", 0.5), ("T_s", 10))
            },
            "every fit parameter is fixed",
        ),
        (dict(T_s=dict(min=5, max=5)), "min = 5 is not below max = 5"),
        (dict(T_s=dict(value=math.inf, vary=False)), "must be finite"),
        (dict(sigma=dict(prior=(0.5, 0.0))), "sd = 0"),
        (dict(sigma=dict(prior=(math.nan, 0.1))), "must be finite"),
        (dict(R0_um=dict(value=150, vary=False)), "outside the accepted range"),
        (dict(lambda_=dict(value=60, vary=False)), "outside the accepted range"),
        (dict(T_s=dict(value=-1, vary=False)), "outside the accepted range"),
        (dict(lambda_=dict(min=51, max=60)), "leave nothing of the accepted range"),
        (dict(G_pa=dict(min=100, max=2000)), "bounds are not supported"),
        (dict(G_pa=dict()), "give a fixed value"),
        (dict(G_pa=dict(value=-5, vary=False)), "must be > 0"),
        (
            dict(sigma=dict(value=0.5, vary=False, prior=(0.5, 0.1))),
            "a fixed parameter takes no bounds and no prior",
        ),
    ],
)
def test_a_bad_specification_is_refused_with_the_reason(spec, message):
    p = Parameters()
    for name, kw in spec.items():
        p.add(name.rstrip("_"), **kw)
    with pytest.raises(ValueError, match=message):
        wo.fit(series(), outer_radius_um=OUTER, params=p, intervals=False)


def test_an_lmfit_style_object_with_an_expression_is_refused_and_one_without_is_read():
    class LmfitParameter:  # the attributes of lmfit.Parameter
        def __init__(self, name, value=None, vary=True, min=-math.inf, max=math.inf, expr=None):
            self.name, self.value, self.vary, self.min, self.max, self.expr = (
                name,
                value,
                vary,
                min,
                max,
                expr,
            )

    with pytest.raises(ValueError, match="expressions"):
        wo.fit(
            series(), outer_radius_um=OUTER, params={"T_s": LmfitParameter("T_s", expr="2 * R0_um")}
        )
    result = wo.fit(
        series(),
        outer_radius_um=OUTER,
        intervals=False,
        params={"R0_um": LmfitParameter("R0_um", value=10.0, vary=False)},
    )
    assert result.theta[0] == 10.0 and result.dof == 30 - 3


@pytest.mark.parametrize(
    "fix, bound, prior, message",
    [
        (["R0_um"], [], [], "expected NAME=VALUE"),
        (["R0_um=ten"], [], [], "'ten' is not a number"),
        ([], ["lambda=0-5"], [], "expected NAME=MIN:MAX"),
        ([], [], ["G=1200:200"], "'G' is unknown"),
    ],
)
def test_command_line_constraints_are_parsed_or_refused(fix, bound, prior, message):
    with pytest.raises(ValueError, match=message):
        from_options(wound_coordinates(OUTER), fix, bound, prior)


def test_command_line_constraints_build_the_parameters():
    p = from_options(
        wound_coordinates(OUTER),
        ["R0_um=10"],
        ["lambda=0:5", "T_s=1:"],
        ["G_pa=1200:200", "T_s=8:2"],
    )
    assert p["R0_um"] == Parameter("R0_um", 10.0, False)
    assert (p["lambda"].min, p["lambda"].max) == (0.0, 5.0)
    assert (p["T_s"].min, p["T_s"].max, p["T_s"].prior) == (1.0, math.inf, (8.0, 2.0))
    assert p["G_pa"].prior == (1200.0, 200.0)


# --- fixed, bounded, prior -------------------------------------------------------------------


def test_a_fixed_r0_gives_the_other_estimates_of_the_fit_whose_r0_it_is(free):
    """The same optimum with R0 held at the free fit's value: the other three agree to far
    below their standard errors; R0 leaves the degrees of freedom, the Jacobian and the profiles."""
    r0_hat = free.theta[0]
    held = wo.fit(
        series(), outer_radius_um=OUTER, params=params(R0_um=dict(value=r0_hat, vary=False))
    )
    assert held.converged and held.theta[0] == r0_hat and held.dof == free.dof + 1
    for i, name in enumerate(("sigma", "lambda", "T_s"), start=1):
        assert abs(held.theta[i] - free.theta[i]) < 1e-3 * free.reports[name].stderr, name
        # the other parameters' intervals are narrower: R0 no longer varies along their profiles
        lo, hi = held.reports[name].ci95
        flo, fhi = free.reports[name].ci95
        assert flo <= lo < held.theta[i] < hi <= fhi, name
    assert held.reports["R0_um"].ci95 == (r0_hat, r0_hat) and held.reports["R0_um"].stderr == 0
    assert held.to_dict()["parameters"]["R0_um"]["fixed"] is True


@pytest.mark.parametrize("name, i", [("lambda", 2), ("T_s", 3)])
def test_a_fixed_lambda_or_t_is_honoured_by_the_global_stage_and_the_fit(name, i):
    value = (LAM, T)[i - 2] * 1.3  # off the truth: the fit must not drift back
    result = wo.fit(
        series(), outer_radius_um=OUTER, params=params(**{name: dict(value=value, vary=False)})
    )
    assert result.converged, result.reasons
    assert result.theta[i] == value and result.reports[name].ci95 == (value, value)
    other = "T_s" if name == "lambda" else "lambda"
    assert result.reports[other].identifiable


def test_a_fixed_time_scale_the_data_cannot_have_is_refused_with_the_reason():
    """T held at 1e4 s, a thousand times the truth, with 60 s of data: the model cannot open
    in the minute recorded, no grid point gives a wound inside the tissue, and the fit says
    why (it used to say only "could not be evaluated from any start:")."""
    with pytest.raises(
        ValueError, match="no point of the global grid .* with the fixed values and bounds given"
    ):
        wo.fit(series(), outer_radius_um=OUTER, params=params(T_s=dict(value=1e4, vary=False)))


def test_a_tight_prior_gives_an_interval_of_the_prior_plus_minus_1_96_sd(free):
    """Prior R0 = 10 +- sd with sd a tenth of the data's standard error: the interval is
    the precision-weighted combination, within ~0.5 % of the prior's +- 1.96 sd."""
    se = free.reports["R0_um"].stderr
    mean, sd = 10.0, se / 10
    result = wo.fit(series(), outer_radius_um=OUTER, params=params(R0_um=dict(prior=(mean, sd))))
    lo, hi = result.reports["R0_um"].ci95
    root = math.sqrt(result.threshold)
    assert root == pytest.approx(1.959964, rel=1e-6)  # the noise is given: chi^2(1)
    precision = 1 / sd**2 + 1 / se**2
    centre = (mean / sd**2 + free.theta[0] / se**2) / precision
    half = root / math.sqrt(precision)
    assert abs(lo - (centre - half)) < 0.05 * sd and abs(hi - (centre + half)) < 0.05 * sd, (
        lo,
        hi,
        centre,
        half,
    )
    assert abs(lo - (mean - root * sd)) < 0.2 * sd and abs(hi - (mean + root * sd)) < 0.2 * sd
    assert result.dof == free.dof + 1  # the prior counts as a datum
    assert result.to_dict()["parameters"]["R0_um"]["prior"] == [mean, sd]


def test_a_bound_that_excludes_the_estimate_holds_it_and_ends_the_interval(free):
    lam_hat = free.theta[2]
    top = 0.6 * lam_hat
    result = wo.fit(
        series(), outer_radius_um=OUTER, params=params(**{"lambda": dict(min=0.0, max=top)})
    )
    assert result.converged, result.reasons
    assert result.theta[2] == pytest.approx(top, abs=1e-9)
    rep = result.reports["lambda"]
    assert rep.ci95[1] == pytest.approx(top, abs=1e-12) and rep.profile.bounded == (False, True)
    assert not rep.identifiable and "bound you set" in result.advice("lambda")
    # a bound around the estimate changes nothing
    loose = wo.fit(
        series(),
        outer_radius_um=OUTER,
        intervals=False,
        params=params(**{"lambda": dict(min=0.0, max=5.0)}),
    )
    assert loose.theta == pytest.approx(free.theta, rel=1e-6)


def test_an_interval_reaching_a_bound_ends_at_the_bound(free):
    """T bounded just inside its free interval on one side: that end is the bound."""
    lo_free, _ = free.reports["T_s"].ci95
    floor = 0.5 * (lo_free + free.theta[3])
    result = wo.fit(series(), outer_radius_um=OUTER, params=params(T_s=dict(min=floor)))
    rep = result.reports["T_s"]
    assert rep.estimate == pytest.approx(free.theta[3], rel=1e-6)
    assert rep.ci95[0] == pytest.approx(floor, rel=1e-12) and rep.profile.bounded == (True, False)
    assert rep.ci95[1] == pytest.approx(free.reports["T_s"].ci95[1], rel=1e-3)


# --- material out --------------------------------------------------------------------------


def test_material_ratios_are_reported_with_their_profile_intervals(free):
    m = free.material
    assert set(m) == {
        "eta_over_G_s",
        "zeta_over_G_s_per_um2",
        "tension_over_G",
        "viscous_length_um",
    }
    R0_hat, sigma, lam, T_hat = free.theta
    for name, value in (
        ("eta_over_G_s", lam**2 * T_hat),
        ("zeta_over_G_s_per_um2", 4 * T_hat / R0_hat**2),
        ("tension_over_G", sigma),
        ("viscous_length_um", lam * R0_hat),
    ):
        lo, hi = m[name]["ci95"]
        assert m[name]["estimate"] == pytest.approx(value, rel=1e-12) and lo < value < hi, name
    truth = {
        "eta_over_G_s": LAM**2 * T,
        "zeta_over_G_s_per_um2": 4 * T / R0**2,
        "tension_over_G": SIGMA,
        "viscous_length_um": LAM * R0,
    }
    for name, value in truth.items():
        assert m[name]["ci95"][0] < value < m[name]["ci95"][1], name
    assert (
        "eta_over_G_s = " in free.summary()
        and free.to_dict()["material"]["tension_over_G"]["unit"] == "1"
    )


def test_with_g_fixed_the_absolute_values_are_g_times_the_ratios():
    G = 800.0
    result = wo.fit(series(), outer_radius_um=OUTER, params=params(G_pa=dict(value=G, vary=False)))
    m = result.material
    for absolute, ratio in (
        ("eta_pa_s", "eta_over_G_s"),
        ("zeta_pa_s_per_um2", "zeta_over_G_s_per_um2"),
        ("tension_pa", "tension_over_G"),
    ):
        assert m[absolute]["estimate"] == pytest.approx(G * m[ratio]["estimate"], rel=1e-14)
        assert m[absolute]["ci95"] == pytest.approx([G * e for e in m[ratio]["ci95"]], rel=1e-14)
    assert "G_pa = 800 Pa (fixed)" in result.summary()


def _brute_delta_eta(result, e, mu, sd):
    """min over G and theta with tau(theta) G = e of chi^2 - chi^2_min + ((G - mu) / sd)^2,
    by constrained fits of the data at fixed tau = e / G (no interpolation), scanned over
    ln tau (G = e / tau) across tau's interval and refined around the best."""
    obj = Objective(series(), None, OUTER)
    obj.sd = np.full(obj.size, NOISE)
    rep = Reparametrised(obj, "tau_s")
    w = rep.to_w(to_z(result.theta))
    chi2_min = float(np.sum(obj.residuals(to_z(result.theta)) ** 2))

    def at(ln_tau):
        nonlocal w
        w, chi2, _ = local_fit(rep, w, fixed=3, value=ln_tau)
        return chi2 - chi2_min + ((e / math.exp(ln_tau) - mu) / sd) ** 2

    lo, hi = result.material["eta_over_G_s"]["ci95"]
    grid = np.linspace(math.log(lo) - 0.1, math.log(hi) + 0.1, 41)
    values = [at(x) for x in grid]
    k = int(np.argmin(values))
    best = optimize.minimize_scalar(
        at,
        bounds=(grid[max(k - 1, 0)], grid[min(k + 1, 40)]),
        method="bounded",
        options={"xatol": 1e-8},
    )
    return min(best.fun, values[k])


@pytest.mark.parametrize("sd", [200.0, 600.0])
def test_absolute_eta_with_a_prior_on_g_matches_a_brute_force_profile(sd):
    """The factorised profile delta_eta(e) = min_G [delta_tau(e / G) + ((G - mu) / sd)^2]
    from the walked tau profile: at its interval ends a brute-force profile over (theta, G)
    (constrained fits at fixed tau = e / G, minimised over G) rises by the threshold (3.84)
    to within 0.5 %. G = 1200 +- 200 Pa, and +- 600 Pa (G down to 24 Pa within the prior's 95 %)."""
    mu = 1200.0
    result = wo.fit(series(), outer_radius_um=OUTER, params=params(G_pa=dict(prior=(mu, sd))))
    eta = result.material["eta_pa_s"]
    lo, hi = eta["ci95"]
    assert eta["estimate"] == pytest.approx(
        mu * result.material["eta_over_G_s"]["estimate"], rel=1e-14
    )
    # wider than the ratio's interval times mu: G's uncertainty adds
    tau_lo, tau_hi = result.material["eta_over_G_s"]["ci95"]
    assert lo < mu * tau_lo and hi > mu * tau_hi
    for end in (lo, hi):
        delta = _brute_delta_eta(result, end, mu, sd)
        fmu_harness.record(
            "eta interval end with a prior on G: |brute-force delta chi^2 / threshold - 1|",
            abs(delta / result.threshold - 1),
        )
        assert abs(delta - result.threshold) < 5e-3 * result.threshold, (end, delta)


def test_a_derived_ratio_ends_at_the_bound_of_the_parameter_it_replaces():
    """lambda fixed, T bounded below inside its interval: tau = lambda^2 T ends at
    lambda^2 x the bound (the bound is a box in ln tau then), and eta's interval with G
    fixed at G times that."""
    G = 1000.0
    first = wo.fit(
        series(), outer_radius_um=OUTER, params=params(**{"lambda": dict(value=LAM, vary=False)})
    )
    lo_T = first.reports["T_s"].ci95[0]
    floor = 0.5 * (lo_T + first.theta[3])
    result = wo.fit(
        series(),
        outer_radius_um=OUTER,
        params=params(
            **{
                "lambda": dict(value=LAM, vary=False),
                "T_s": dict(min=floor),
                "G_pa": dict(value=G, vary=False),
            }
        ),
    )
    tau = result.derived_profiles["tau_s"]
    assert tau.lower == pytest.approx(LAM**2 * floor, rel=1e-12) and tau.bounded == (True, False)
    assert tau.upper == pytest.approx(LAM**2 * result.reports["T_s"].ci95[1], rel=1e-3)
    m = result.material
    assert not m["eta_over_G_s"]["identifiable"]
    assert m["eta_pa_s"]["ci95"][0] == pytest.approx(G * LAM**2 * floor, rel=1e-12)
