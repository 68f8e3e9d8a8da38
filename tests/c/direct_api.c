/*
 * The direct C API (wo_*), linked against libwound_opening.so:
 *   1. the paper's lambda = 1 case against the exact solution (reference.h), on a grid
 *      chosen by tolerance and on the default grid;
 *   2. profiles u(r), u_t(r) at the grid nodes, consistent with the edge values;
 *   3. save / restore of a state, bit for bit;
 *   4. bad input: every refused call gives its status and a message naming what was
 *      wrong, changes nothing, and the solver still reproduces the reference afterwards;
 *   5. wo_series (a whole R(t) in one call) against the reference, and wo_profile_series
 *      at current radii r = X + u(X, t) against the handle's profile at X; bad input;
 *      wo_series_sensitivities: the same R(t), and dR/dlambda, dR/dR_inf against central
 *      differences of wo_series (step 1e-4; their own checks are in the Rust and Python tests);
 *      wo_profile_rates: the velocity of wo_profile_series, its derivatives in R_inf and in
 *      the current radius against central differences of wo_profile_series;
 *      wo_pair_displacement against the step API's displacements at the pair's two times,
 *      wo_point_rates against wo_profile_rates at each point's time;
 *   6. huge counts (2^57, SIZE_MAX): WO_INVALID_ARGUMENT with the reason, the process alive.
 * Run under valgrind by scripts/c_tests.sh: no error, no leak.
 */
#include "wound_opening.h"

#include "check.h"
#include "reference.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A refused call: `status` is `want` and wo_last_error() contains `needle`. */
#define REFUSED(call, want, needle)                                                                              \
    do {                                                                                                         \
        wo_status got_ = (call);                                                                                 \
        const char *msg_ = wo_last_error();                                                                      \
        CHECK(got_ == (want) && strstr(msg_, (needle)) != NULL, "%s returned %s with \"%s\"; expected %s with \"%s\"", \
              #call, wo_status_name((int)got_), msg_, #want, (needle));                                          \
    } while (0)

#define OK(call)                                                                                                 \
    do {                                                                                                         \
        wo_status got_ = (call);                                                                                 \
        CHECK(got_ == WO_OK, "%s returned %s: %s", #call, wo_status_name((int)got_), wo_last_error());           \
    } while (0)

/* Advance `s` through the reference times and compare; returns the number of mismatches. */
static void reproduce(const char *who, wo_solver *s) {
    for (int k = 0; k < 5; k++) {
        double radius = NAN, velocity = NAN;
        OK(wo_solver_advance(s, REFERENCE[k].t, 0.0));
        OK(wo_solver_wound_radius(s, &radius));
        OK(wo_solver_edge_velocity(s, &velocity));
        CHECK(matches_reference(who, k, radius, velocity), "%s at t = %g", who, REFERENCE[k].t);
    }
}

static void lambda_one_case(void) {
    wo_solver *s = NULL;
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-10, &s));
    reproduce("tolerance 1e-10", s);
    OK(wo_solver_free(s));

    OK(wo_solver_new_grid(1.0, 1.0, 10.0, 8, 10, 0.05, &s));
    reproduce("default grid", s);
    OK(wo_solver_free(s));
}

static void profiles(void) {
    wo_solver *s = NULL;
    size_t n = 0;
    double radius = NAN, velocity = NAN, time = NAN;
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-9, &s));
    OK(wo_solver_advance(s, 1.0, 0.0));
    OK(wo_solver_node_count(s, &n));
    CHECK(n >= 2, "node count %zu", n);
    double *r = malloc(n * sizeof *r), *u = malloc(n * sizeof *u), *v = malloc(n * sizeof *v);
    OK(wo_solver_nodes(s, r, n));
    CHECK(r[0] == 1.0 && r[n - 1] == 10.0, "nodes span [%g, %g], expected [1, 10]", r[0], r[n - 1]);
    for (size_t i = 1; i < n; i++) CHECK(r[i] > r[i - 1], "nodes ascend at %zu", i);
    OK(wo_solver_displacement(s, r, u, n));
    OK(wo_solver_velocity(s, r, v, n));
    OK(wo_solver_wound_radius(s, &radius));
    OK(wo_solver_edge_velocity(s, &velocity));
    OK(wo_solver_time(s, &time));
    CHECK(time == 1.0, "time %.17g, expected 1", time);
    /* u(1) is the wound radius minus 1, u_t(1) the edge velocity (1e-12: rounding of the modal sum). */
    CHECK(fabs(1.0 + u[0] - radius) < 1e-12, "1 + u(1) = %.17g but R = %.17g", 1.0 + u[0], radius);
    CHECK(fabs(v[0] - velocity) < 1e-12 * fmax(1.0, fabs(velocity)), "u_t(1) = %.17g, dR/dt = %.17g", v[0], velocity);
    /* The departure from the uniform tension u = r / 6 of the cut is an opening: positive
       everywhere and largest at the wound edge, decaying into the tissue. */
    for (size_t i = 1; i < n; i++) {
        double here = u[i] - r[i] / 6.0, before = u[i - 1] - r[i - 1] / 6.0;
        CHECK(here > 0.0 && here < before, "u - r/6 = %g at r = %g after %g at r = %g", here, r[i], before, r[i - 1]);
    }
    /* In place: the output array may be the radii array. */
    double first = u[0];
    OK(wo_solver_displacement(s, r, r, n));
    CHECK(r[0] == first, "in-place u(1) = %.17g, expected %.17g", r[0], first);
    free(r), free(u), free(v);
    OK(wo_solver_free(s));
}

static void save_and_restore(void) {
    wo_solver *s = NULL, *twin = NULL;
    wo_state *at1 = NULL;
    double r1 = NAN, r10 = NAN, again = NAN, time = NAN;
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-9, &s));
    OK(wo_solver_advance(s, 1.0, 0.25));
    OK(wo_solver_wound_radius(s, &r1));
    OK(wo_solver_save_state(s, &at1));
    OK(wo_solver_advance(s, 10.0, 0.0));
    OK(wo_solver_wound_radius(s, &r10));
    OK(wo_solver_restore_state(s, at1));
    OK(wo_solver_time(s, &time));
    OK(wo_solver_wound_radius(s, &again));
    CHECK(time == 1.0 && again == r1, "restored t = %g, R = %.17g; expected 1, %.17g", time, again, r1);
    OK(wo_solver_advance(s, 10.0, 0.0));
    OK(wo_solver_wound_radius(s, &again));
    CHECK(again == r10, "after restore R(10) = %.17g, first time %.17g", again, r10);
    /* Into another solver of the same problem; the state outlives the solver it came from. */
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-9, &twin));
    OK(wo_solver_free(s));
    OK(wo_solver_restore_state(twin, at1));
    OK(wo_solver_wound_radius(twin, &again));
    CHECK(again == r1, "twin R = %.17g, expected %.17g", again, r1);
    OK(wo_state_free(at1));
    OK(wo_solver_free(twin));
}

static void bad_creation(void) {
    wo_solver *s = (wo_solver *)&s; /* not NULL: a refused creation must set it to NULL */
    REFUSED(wo_solver_new(NAN, 1, 10, 1e-9, &s), WO_INVALID_ARGUMENT, "lambda = NaN is outside the accepted range: 0 or [1e-150, 1e6]");
    CHECK(s == NULL, "solver not set to NULL on failure");
    REFUSED(wo_solver_new(-1, 1, 10, 1e-9, &s), WO_INVALID_ARGUMENT, "lambda = -1 is outside the accepted range: 0 or [1e-150, 1e6]");
    REFUSED(wo_solver_new(INFINITY, 1, 10, 1e-9, &s), WO_INVALID_ARGUMENT, "lambda = inf is outside");
    REFUSED(wo_solver_new(1, INFINITY, 10, 1e-9, &s), WO_INVALID_ARGUMENT, "sigma = inf is outside the accepted range (-6, 1e6]");
    REFUSED(wo_solver_new(1, NAN, 10, 1e-9, &s), WO_INVALID_ARGUMENT, "sigma = NaN is outside");
    REFUSED(wo_solver_new(1, 1, 1.0, 1e-9, &s), WO_INVALID_ARGUMENT, "R_inf = 1 is outside the accepted range [1.001, 1e6]");
    REFUSED(wo_solver_new(1, 1, 0.5, 1e-9, &s), WO_INVALID_ARGUMENT, "R_inf = 0.5 is outside");
    REFUSED(wo_solver_new(1, 1, -INFINITY, 1e-9, &s), WO_INVALID_ARGUMENT, "R_inf = -inf is outside");
    REFUSED(wo_solver_new(1, 1, 10, 0.0, &s), WO_INVALID_ARGUMENT, "tolerance = 0 is invalid");
    REFUSED(wo_solver_new(1, 1, 10, -1e-6, &s), WO_INVALID_ARGUMENT, "tolerance = -0.000001 is invalid");
    REFUSED(wo_solver_new(1, 1, 10, NAN, &s), WO_INVALID_ARGUMENT, "tolerance = NaN is invalid");
    REFUSED(wo_solver_new(1, 1, 10, 1e-9, NULL), WO_NULL_POINTER, "wo_solver_new: solver is NULL");
    REFUSED(wo_solver_new_grid(1, 1, 10, 8, 10, 0.05, NULL), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_new_grid(1, 1, 10, 0, 10, 0.05, &s), WO_INVALID_ARGUMENT, "degree = 0 is invalid");
    REFUSED(wo_solver_new_grid(1, 1, 10, 33, 1, 0.05, &s), WO_INVALID_ARGUMENT, "degree = 33 is invalid: expected 1 <= degree <= 32");
    REFUSED(wo_solver_new_grid(1, 1, 10, 8, 0, 0.05, &s), WO_INVALID_ARGUMENT, "elements = 0 is invalid");
    REFUSED(wo_solver_new_grid(1, 1, 10, 8, 501, 0.05, &s), WO_INVALID_ARGUMENT, "elements = 501 is invalid with degree = 8");
    /* A product that overflows size_t must not wrap around to a small grid. */
    REFUSED(wo_solver_new_grid(1, 1, 10, 16, SIZE_MAX / 8, 0.05, &s), WO_INVALID_ARGUMENT, "is invalid with degree = 16");
    REFUSED(wo_solver_new_grid(1, 1, 10, 8, 10, 0.0, &s), WO_INVALID_ARGUMENT, "edge_scale = 0 is invalid");
    REFUSED(wo_solver_new_grid(1, 1, 10, 8, 10, NAN, &s), WO_INVALID_ARGUMENT, "edge_scale = NaN is invalid");
    REFUSED(wo_solver_new_grid(1, 1, 10, 8, 10, 1e-320, &s), WO_INVALID_ARGUMENT, "edge_scale = 0.00000");
    REFUSED(wo_solver_new_grid(-2, 1, 10, 8, 10, 0.05, &s), WO_INVALID_ARGUMENT, "lambda = -2 is outside");
    CHECK(s == NULL, "solver not set to NULL on failure");
}

static void bad_calls(void) {
    wo_solver *s = NULL, *other = NULL, *coarse = NULL;
    wo_state *st = NULL, *foreign = NULL, *wrong_grid = NULL;
    double x = 0.0, r[3] = {1.0, 2.0, 3.0}, out[3];
    size_t n = 0;
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-10, &s));

    /* NULL solver, everywhere one is taken. */
    REFUSED(wo_solver_advance(NULL, 1, 0), WO_NULL_POINTER, "wo_solver_advance: solver is NULL");
    REFUSED(wo_solver_time(NULL, &x), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_wound_radius(NULL, &x), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_edge_velocity(NULL, &x), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_node_count(NULL, &n), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_nodes(NULL, out, 3), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_displacement(NULL, r, out, 3), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_velocity(NULL, r, out, 3), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_save_state(NULL, &st), WO_NULL_POINTER, "solver is NULL");
    REFUSED(wo_solver_restore_state(NULL, st), WO_NULL_POINTER, "solver is NULL");
    /* NULL outputs and arrays. */
    REFUSED(wo_solver_time(s, NULL), WO_NULL_POINTER, "time is NULL");
    REFUSED(wo_solver_wound_radius(s, NULL), WO_NULL_POINTER, "radius is NULL");
    REFUSED(wo_solver_edge_velocity(s, NULL), WO_NULL_POINTER, "velocity is NULL");
    REFUSED(wo_solver_node_count(s, NULL), WO_NULL_POINTER, "count is NULL");
    REFUSED(wo_solver_nodes(s, NULL, 5), WO_NULL_POINTER, "radii (with count = 5) is NULL");
    REFUSED(wo_solver_displacement(s, NULL, out, 3), WO_NULL_POINTER, "radii (with count = 3) is NULL");
    REFUSED(wo_solver_displacement(s, r, NULL, 3), WO_NULL_POINTER, "u (with count = 3) is NULL");
    REFUSED(wo_solver_velocity(s, r, NULL, 3), WO_NULL_POINTER, "v (with count = 3) is NULL");
    REFUSED(wo_solver_save_state(s, NULL), WO_NULL_POINTER, "state is NULL");
    REFUSED(wo_solver_restore_state(s, NULL), WO_NULL_POINTER, "state is NULL");
    OK(wo_solver_displacement(s, NULL, NULL, 0)); /* nothing asked, nothing read */

    /* Values out of range. */
    OK(wo_solver_advance(s, REFERENCE[0].t, 0.0));
    REFUSED(wo_solver_advance(s, NAN, 0), WO_INVALID_ARGUMENT, "t_end = NaN is invalid: expected a finite time >= the solver's time 0.01");
    REFUSED(wo_solver_advance(s, INFINITY, 0), WO_INVALID_ARGUMENT, "t_end = inf is invalid");
    REFUSED(wo_solver_advance(s, 0.005, 0), WO_INVALID_ARGUMENT, "t_end = 0.005 is invalid: expected a finite time >= the solver's time 0.01");
    REFUSED(wo_solver_advance(s, 1.0, NAN), WO_INVALID_ARGUMENT, "edge stress NaN (in units of G) is outside the accepted range [-1e6, 1e6]");
    REFUSED(wo_solver_advance(s, 1.0, -INFINITY), WO_INVALID_ARGUMENT, "edge stress -inf (in units of G) is outside");
    OK(wo_solver_node_count(s, &n));
    REFUSED(wo_solver_nodes(s, out, 3), WO_INVALID_ARGUMENT, "count = 3 is invalid: the solver has");
    r[1] = 0.5;
    REFUSED(wo_solver_displacement(s, r, out, 3), WO_INVALID_ARGUMENT, "radii[1] = 0.5 is outside the tissue: expected 1 <= r <= R_inf = 10");
    r[1] = 10.5;
    REFUSED(wo_solver_velocity(s, r, out, 3), WO_INVALID_ARGUMENT, "radii[1] = 10.5 is outside the tissue");
    r[1] = NAN;
    REFUSED(wo_solver_velocity(s, r, out, 3), WO_INVALID_ARGUMENT, "radii[1] = NaN is outside the tissue");
    r[1] = 2.0;

    /* Handles: forged, freed, of the wrong kind, states of another problem. */
    OK(wo_solver_save_state(s, &st));
    REFUSED(wo_solver_advance((wo_solver *)(uintptr_t)0x7fff0001u, 1, 0), WO_UNKNOWN_HANDLE, "is unknown (never created by this library, or already freed)");
    REFUSED(wo_solver_advance((wo_solver *)st, 1, 0), WO_UNKNOWN_HANDLE, "solver 0x");
    REFUSED(wo_solver_restore_state(s, (wo_state *)s), WO_UNKNOWN_HANDLE, "state 0x");
    OK(wo_solver_new(2.0, 1.0, 10.0, 1e-10, &other));
    OK(wo_solver_save_state(other, &foreign));
    REFUSED(wo_solver_restore_state(s, foreign), WO_INCOMPATIBLE_STATE, "was saved with lambda = 2 but this solver has lambda = 1");
    OK(wo_solver_new_grid(1.0, 1.0, 10.0, 2, 4, 0.5, &coarse));
    OK(wo_solver_save_state(coarse, &wrong_grid));
    REFUSED(wo_solver_restore_state(s, wrong_grid), WO_INCOMPATIBLE_STATE, "was saved on grid");
    OK(wo_solver_free(other));
    REFUSED(wo_solver_free(other), WO_UNKNOWN_HANDLE, "wo_solver_free: solver 0x");
    REFUSED(wo_solver_wound_radius(other, &x), WO_UNKNOWN_HANDLE, "already freed");
    OK(wo_state_free(foreign));
    REFUSED(wo_state_free(foreign), WO_UNKNOWN_HANDLE, "wo_state_free: state 0x");
    REFUSED(wo_solver_restore_state(s, foreign), WO_UNKNOWN_HANDLE, "already freed");
    OK(wo_solver_free(NULL)); /* as free(NULL) */
    OK(wo_state_free(NULL));
    OK(wo_state_free(wrong_grid));
    OK(wo_solver_free(coarse));

    CHECK(strcmp(wo_status_name(WO_INCOMPATIBLE_STATE), "WO_INCOMPATIBLE_STATE") == 0, "status name");
    CHECK(strcmp(wo_status_name(99), "unknown status") == 0 && strcmp(wo_status_name(-1), "unknown status") == 0, "unknown status name");
    OK(wo_solver_time(s, &x));
    CHECK(strcmp(wo_last_error(), "") == 0, "a success clears the message, got \"%s\"", wo_last_error());

    /* Nothing refused above changed the solver: it goes on to the reference values. */
    double t0 = NAN;
    OK(wo_solver_time(s, &t0));
    CHECK(t0 == REFERENCE[0].t, "time %g after refused calls, expected %g", t0, REFERENCE[0].t);
    reproduce("after refused calls", s);
    OK(wo_solver_restore_state(s, st));
    reproduce("restored after refused calls", s);
    OK(wo_state_free(st));
    OK(wo_solver_free(s));
}

static void series(void) {
    double times[5], radius[5], velocity[5];
    for (int k = 0; k < 5; k++) times[k] = REFERENCE[k].t;
    OK(wo_series((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, times, 5, radius, velocity));
    for (int k = 0; k < 5; k++) CHECK(matches_reference("wo_series", k, radius[k], velocity[k]), "wo_series at %g", times[k]);

    /* Material points X at t = 1, their current radii, then wo_profile_series there. */
    double x[3] = {1.0, 2.0, 10.0}, ux[3], vx[3], r[3], u[3], v[3];
    wo_solver *s = NULL;
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-10, &s));
    OK(wo_solver_advance(s, 1.0, 0.0));
    OK(wo_solver_displacement(s, x, ux, 3));
    OK(wo_solver_velocity(s, x, vx, 3));
    OK(wo_solver_free(s));
    for (int j = 0; j < 3; j++) r[j] = x[j] + ux[j];
    double one = 1.0;
    OK(wo_profile_series((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, &one, 1, r, 3, u, v));
    for (int j = 0; j < 3; j++) {
        CHECK(fabs(u[j] - ux[j]) < 1e-13 && fabs(v[j] - vx[j]) < 1e-12, "current radius %g: u %g vs %g, v %g vs %g", r[j], u[j],
              ux[j], v[j], vx[j]);
    }

    /* The derivatives against central differences of wo_series (same grid: 10 +- 1e-3 keeps
     * the element count the tolerance picks at 10). */
    double again[5], d_lambda[5], d_r_inf[5], up[5], down[5];
    OK(wo_series_sensitivities((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, times, 5, again, NULL, d_lambda, d_r_inf));
    for (int k = 0; k < 5; k++) CHECK(again[k] == radius[k], "wo_series_sensitivities radius at %g", times[k]);
    OK(wo_series((wo_problem){1.0001, 1.0, 10.0, 1e-10, 0.0}, times, 5, up, NULL));
    OK(wo_series((wo_problem){0.9999, 1.0, 10.0, 1e-10, 0.0}, times, 5, down, NULL));
    for (int k = 0; k < 5; k++) {
        double fd = (up[k] - down[k]) / 2e-4;
        CHECK(fabs(d_lambda[k] - fd) < 1e-7, "dR/dlambda at %g: %g vs %g", times[k], d_lambda[k], fd);
    }
    OK(wo_series((wo_problem){1.0, 1.0, 10.001, 1e-10, 0.0}, times, 5, up, NULL));
    OK(wo_series((wo_problem){1.0, 1.0, 9.999, 1e-10, 0.0}, times, 5, down, NULL));
    for (int k = 0; k < 5; k++) {
        double fd = (up[k] - down[k]) / 2e-3;
        CHECK(fabs(d_r_inf[k] - fd) < 1e-7, "dR/dR_inf at %g: %g vs %g", times[k], d_r_inf[k], fd);
    }

    /* wo_profile_rates at the middle current radius: its velocity, and d/dR_inf and d/dr
     * against central differences of wo_profile_series (R_inf 10 +- 1e-3 as above; r +- 1e-5). */
    double rates[6], edge[12], vu, vd, rm = r[1];
    OK(wo_profile_rates((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, &one, 1, &rm, 1, rates, edge));
    CHECK(fabs(rates[0] - v[1]) < 1e-12, "wo_profile_rates velocity %g vs %g", rates[0], v[1]);
    OK(wo_profile_series((wo_problem){1.0, 1.0, 10.001, 1e-10, 0.0}, &one, 1, &rm, 1, NULL, &vu));
    OK(wo_profile_series((wo_problem){1.0, 1.0, 9.999, 1e-10, 0.0}, &one, 1, &rm, 1, NULL, &vd));
    CHECK(fabs(rates[4] - (vu - vd) / 2e-3) < 1e-7, "du_t/dR_inf %g vs %g", rates[4], (vu - vd) / 2e-3);
    double rs[2] = {rm - 1e-5, rm + 1e-5}, vs[2];
    OK(wo_profile_series((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, &one, 1, rs, 2, NULL, vs));
    CHECK(fabs(rates[5] - (vs[1] - vs[0]) / 2e-5) < 1e-7, "du_t/dr %g vs %g", rates[5], (vs[1] - vs[0]) / 2e-5);
    CHECK(edge[5] == 0.0, "the edge's own velocity does not depend on r");
    REFUSED(wo_profile_rates((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, &one, 1, &rm, 1, NULL, edge), WO_NULL_POINTER,
            "rates (with count = 6) is NULL");

    /* wo_pair_displacement: the material points X at t = 1 (current radii r) followed to
     * t = 1.5, against the step API's u(X, 1.5) - u(X, 1); wo_point_rates: each point at its
     * own time as wo_profile_rates at that time alone. */
    double ux2[3], t_a[3] = {1.0, 1.0, 1.0}, t_b[3] = {1.5, 1.5, 1.5}, d[3];
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-10, &s));
    OK(wo_solver_advance(s, 1.5, 0.0));
    OK(wo_solver_displacement(s, x, ux2, 3));
    OK(wo_solver_free(s));
    OK(wo_pair_displacement((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, t_a, t_b, r, 3, d));
    for (int j = 0; j < 3; j++)
        CHECK(fabs(d[j] - (ux2[j] - ux[j])) < 1e-12, "pair displacement at %g: %g vs %g", r[j], d[j], ux2[j] - ux[j]);
    double two_times[2] = {1.5, 1.0}, two_r[2] = {3.0, rm}, pr[12], alone[6];
    OK(wo_point_rates((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, two_times, two_r, 2, pr));
    for (int q = 0; q < 6; q++) CHECK(pr[6 + q] == rates[q], "wo_point_rates at t = 1, q = %d: %g vs %g", q, pr[6 + q], rates[q]);
    OK(wo_profile_rates((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, &two_times[0], 1, &two_r[0], 1, alone, NULL));
    for (int q = 0; q < 6; q++) CHECK(fabs(pr[q] - alone[q]) <= 1e-13 * fabs(alone[q]) + 1e-15, "wo_point_rates at t = 1.5, q = %d", q);
    REFUSED(wo_pair_displacement((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, t_b, t_a, r, 3, d), WO_INVALID_ARGUMENT,
            "t_b[0] = 1 is invalid: expected a finite time >= t_a[0] = 1.5");
    REFUSED(wo_point_rates((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, two_times, two_r, 2, NULL), WO_NULL_POINTER, "rates");

    double bad_times[2] = {1.0, 0.5}, inside = 1.01;
    REFUSED(wo_series((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, bad_times, 2, radius, NULL), WO_INVALID_ARGUMENT,
            "times[1] = 0.5 is before times[0] = 1");
    REFUSED(wo_series((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, NULL, 2, radius, NULL), WO_NULL_POINTER, "times (with count = 2) is NULL");
    double zero = 0.0;
    REFUSED(wo_series((wo_problem){0.0, 1.0, 10.0, 1e-10, 0.0}, &zero, 1, radius, velocity), WO_UNDEFINED, "is infinite");
    REFUSED(wo_profile_series((wo_problem){1.0, 1.0, 10.0, 1e-10, 0.0}, &one, 1, &inside, 1, u, NULL), WO_INVALID_ARGUMENT,
            "radii[0] = 1.01 is inside the wound at times[0] = 1");
    CHECK(strcmp(wo_status_name(WO_UNDEFINED), "WO_UNDEFINED") == 0, "status name of WO_UNDEFINED");

    /* Leaving the validity (sigma = 2 by t = 10): WO_OUTSIDE_VALIDITY, as the step API, with
     * every output written and the first time named. */
    double late[2] = {1.0, 10.0}, r_late[2] = {NAN, NAN};
    REFUSED(wo_series((wo_problem){1.0, 2.0, 10.0, 1e-10, 0.0}, late, 2, r_late, NULL), WO_OUTSIDE_VALIDITY,
            "times[1] = 10: the run leaves the model's validity there");
    CHECK(isfinite(r_late[0]) && isfinite(r_late[1]) && r_late[1] > r_late[0], "outputs written with the warning: %g %g", r_late[0],
          r_late[1]);
}

/* Counts checked before anything is copied: a count whose bytes exceed the address space,
 * or that no allocation can hold, is WO_INVALID_ARGUMENT with the reason (no source path in
 * it), and the process lives on; the arrays passed are small and never read past. */
static void huge_counts(void) {
    const wo_problem problem = {1.0, 1.0, 10.0, 1e-10, 0.0};
    double times[2] = {0.5, 1.0}, radius[2], r[2] = {2.0, 3.0}, out[2];
    const size_t big = (size_t)1 << 57; /* 2^60 bytes: within isize, beyond any memory */
    REFUSED(wo_series(problem, times, SIZE_MAX, radius, NULL), WO_INVALID_ARGUMENT,
            "times: count = 18446744073709551615 is invalid: 18446744073709551615 elements of 8 bytes exceed the largest array the address space can hold");
    REFUSED(wo_series(problem, times, big, radius, NULL), WO_INVALID_ARGUMENT, "times: count = 144115188075855872 is invalid: 144115188075855872 values (1.153e18 bytes) cannot be allocated");
    REFUSED(wo_series_sensitivities(problem, times, big, radius, NULL, NULL, NULL), WO_INVALID_ARGUMENT, "cannot be allocated");
    REFUSED(wo_profile_series(problem, times, 1, r, big, out, NULL), WO_INVALID_ARGUMENT, "radii: count = 144115188075855872 is invalid");
    REFUSED(wo_profile_series(problem, times, 1, r, SIZE_MAX / 2, out, NULL), WO_INVALID_ARGUMENT, "exceed the largest array");
    REFUSED(wo_profile_rates(problem, times, 1, r, big, out, NULL), WO_INVALID_ARGUMENT, "cannot be allocated");
    REFUSED(wo_pair_displacement(problem, times, times, r, big, out), WO_INVALID_ARGUMENT, "t_a: count = 144115188075855872 is invalid");
    REFUSED(wo_pair_displacement(problem, times, times, r, SIZE_MAX, out), WO_INVALID_ARGUMENT, "exceed the largest array");
    REFUSED(wo_point_rates(problem, times, r, SIZE_MAX / 4, out), WO_INVALID_ARGUMENT, "overflows");
    REFUSED(wo_point_rates(problem, times, r, big / 8, out), WO_INVALID_ARGUMENT, "cannot be allocated");
    wo_solver *s = NULL;
    OK(wo_solver_new(1.0, 1.0, 10.0, 1e-10, &s));
    REFUSED(wo_solver_displacement(s, r, out, SIZE_MAX), WO_INVALID_ARGUMENT, "exceed the largest array the address space can hold");
    REFUSED(wo_solver_displacement(s, r, out, big), WO_INVALID_ARGUMENT, "cannot be allocated");
    REFUSED(wo_solver_velocity(s, r, out, big), WO_INVALID_ARGUMENT, "cannot be allocated");
    REFUSED(wo_solver_nodes(s, out, SIZE_MAX), WO_INVALID_ARGUMENT, "radii: count = 18446744073709551615 is invalid");
    CHECK(strstr(wo_last_error(), ".rs") == NULL, "no source path in the message: %s", wo_last_error());
    /* Still alive, and the solver untouched. */
    OK(wo_solver_advance(s, 1.0, 0.0));
    OK(wo_solver_free(s));
    OK(wo_series(problem, times, 2, radius, NULL));
}

int main(void) {
    lambda_one_case();
    profiles();
    save_and_restore();
    bad_creation();
    bad_calls();
    series();
    huge_counts();
    return check_report("direct_api");
}
