/*
 * A strict FMI 2.0 co-simulation master in C, as fmusim, OMSimulator and PyFMI are: it
 * stops at the first call that answers anything but fmi2OK. With lambda = 0.3, sigma = 2,
 * R_inf = 20 (an edge strain of 1 at t = 3 s: the run leaves the model's validity):
 *   1. by default it stops at the step ending at t = 3 s (fmi2Warning), whose logged text
 *      names the parameter validity_warning and the value to set;
 *   2. with validity_warning = 0 it runs to its end, the crossing logged with status OK,
 *      and its radii agree with the exact solution (below) to 1e-9 of the opening;
 *   3. a tolerance of 0 with toleranceDefined (OMSimulator's SSP import without one) is
 *      taken as none given: initialization answers fmi2OK.
 * Run under valgrind by scripts/c_tests.sh: no error, no leak.
 *
 * Exact radii from python/wound_exact.py (the Laplace-domain solution, checked against
 * mpmath at 30 digits to 1e-13 by tests/python/test_reference.py), printed by
 *
 *   python -c "import sys; sys.path.insert(0, 'python'); import numpy as np, wound_exact as w;
 *              print(w.edge(0.3, 2.0, 20.0, np.array([1.0, 3.0, 10.0]))[0])"
 *
 * and the final state in closed form, R_final = 1 + (2 sigma / 3) R_inf^2 / (R_inf^2 - 1).
 */
#define _POSIX_C_SOURCE 200809L

#include "fmu_common.h"

static const double TIMES[3] = {1.0, 3.0, 10.0};
static const double EXACT[3] = {1.8047102208448647, 2.0241383467963203, 2.2144303783526684};
#define SIGMA 2.0
#define R_INF 20.0
#define R_FINAL (1.0 + 2.0 * SIGMA / 3.0 * R_INF * R_INF / (R_INF * R_INF - 1.0))
#define OPENING (R_FINAL - (1.0 + SIGMA / 6.0))

/* The case set up (tolerance as given), validity_warning set unless negative, initialized:
 * NULL if any call was not fmi2OK. */
static fmi2Component strict_case(const char *name, fmi2Boolean tolerance_defined, double tolerance, int validity_warning) {
    fmi2Component c = instantiate(name);
    CHECK(c != NULL, "fmi2Instantiate(%s): %s", name, LOG.message);
    if (c == NULL) return NULL;
    const fmi2ValueReference vr[3] = {VR_LAMBDA, VR_SIGMA, VR_R_INF};
    const fmi2Real value[3] = {0.3, SIGMA, R_INF};
    const fmi2ValueReference vw = fmu_value_reference(&F, "validity_warning");
    const fmi2Integer w = validity_warning;
    int ok = F.fmi2SetupExperiment(c, tolerance_defined, tolerance, 0.0, fmi2False, 0.0) == fmi2OK &&
             F.fmi2SetReal(c, vr, 3, value) == fmi2OK &&
             (validity_warning < 0 || F.fmi2SetInteger(c, &vw, 1, &w) == fmi2OK) &&
             F.fmi2EnterInitializationMode(c) == fmi2OK && F.fmi2ExitInitializationMode(c) == fmi2OK;
    CHECK(ok, "%s: initialization not fmi2OK: %s", name, LOG.message);
    if (!ok) {
        F.fmi2FreeInstance(c);
        return NULL;
    }
    return c;
}

/* Steps of 1 s to t = 10, then one to 1e7 s, stopping at the first status but fmi2OK:
 * the time reached; radii[k] at TIMES[k] and radii[3] at 1e7 s (NAN where not reached). */
static double run_strictly(fmi2Component c, double radii[4]) {
    double t = 0.0, v;
    int k = 0;
    for (int i = 0; i < 4; i++) radii[i] = NAN;
    while (t < 1e7) {
        double h = t < 10.0 ? 1.0 : 1e7 - t;
        if (F.fmi2DoStep(c, t, h, fmi2True) != fmi2OK) return t;
        t += h;
        if (k < 3 && t == TIMES[k]) outputs(c, &radii[k++], &v);
    }
    outputs(c, &radii[3], &v);
    return t;
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s <directory of the extracted WoundOpening.fmu>\n", argv[0]);
        return 2;
    }
    if (!load_fmu(argv[1])) return 1;
    (void)initialized; /* fmu_common.h's helpers this master does not need */
    (void)every_call_is_an_error;
    CHECK(fmu_value_reference(&F, "validity_warning") != ~0u, "validity_warning in modelDescription.xml");
    double radii[4];

    fmi2Component c = strict_case("default", fmi2False, 0.0, -1);
    if (c != NULL) {
        double stopped = run_strictly(c, radii);
        CHECK(stopped == 2.0, "stopped at t = %g: expected the step from 2 s to 3 s", stopped);
        CHECK(LOG.status == fmi2Warning && strcmp(LOG.category, "logStatusWarning") == 0 &&
                  strstr(LOG.message, "at t = 3 s the run leaves the model's validity") != NULL &&
                  strstr(LOG.message, "validity_warning is set to 0") != NULL,
              "the warning names the parameter and the value: [%d %s] %s", (int)LOG.status, LOG.category, LOG.message);
        F.fmi2FreeInstance(c);
    }

    /* validity_warning = 0; tolerance 0 defined (none given: the parameter's 1e-10). */
    for (int tolerance_zero = 0; tolerance_zero < 2; tolerance_zero++) {
        int before = LOG.count;
        c = strict_case(tolerance_zero ? "tolerance 0" : "validity_warning 0", (fmi2Boolean)tolerance_zero, 0.0, 0);
        if (c == NULL) continue;
        if (tolerance_zero) {
            CHECK(LOG.count > before && LOG.status == fmi2OK && strstr(LOG.message, "tolerance = 0 with toleranceDefined") != NULL,
                  "tolerance 0 is logged as none given: %s", LOG.message);
        }
        double reached = run_strictly(c, radii);
        CHECK(reached == 1e7, "ran to t = %g of 1e7: %s", reached, LOG.message);
        for (int k = 0; k < 3; k++) {
            double err = fabs(radii[k] - EXACT[k]) / OPENING;
            CHECK(err < 1e-9, "R(%g) = %.17g, exact %.17g: error %.2e of the opening", TIMES[k], radii[k], EXACT[k], err);
        }
        double err = fabs(radii[3] - R_FINAL) / OPENING;
        CHECK(err < 1e-9, "R(1e7) = %.17g, final %.17g: error %.2e of the opening", radii[3], R_FINAL, err);
        OK(F.fmi2Terminate(c));
        F.fmi2FreeInstance(c);
    }
    fmu_unload(&F);
    return check_report("strict_master");
}
