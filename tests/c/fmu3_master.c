/*
 * A minimal FMI 3.0 master in C. It loads the shared object of WoundOpening-fmi3.fmu
 * (extracted into argv[1], binaries/<platform>: dynamic_library.h), knowing only the standard
 * (fmi3_standard.h) and modelDescription.xml, and checks:
 *   1. all 75 functions of fmi3Functions.h are exported;
 *   2. co-simulation: the paper's lambda = 1 case against the exact solution (reference.h);
 *   3. Model Exchange: the states are uncoupled linear modes, c_k' = (g_k - c_k) / nu_k, so
 *      two derivative evaluations (at c = 0 and c = 1) give g_k and nu_k, the master
 *      integrates each mode exactly, and the radius read back matches the reference;
 *   4. instance A's FMU state handed to instance B is refused, and stays A's;
 *   5. every function it uses on NULL, made-up and freed instances returns fmi3Error and
 *      logs nothing (there is no instance to log for).
 * Run under valgrind by scripts/c_tests.sh: no error, no leak.
 */
#define _POSIX_C_SOURCE 200809L

#include "check.h"
#include "dynamic_library.h"
#include "fmi3_standard.h"
#include "read_file.h"
#include "reference.h"

#include <stdlib.h>

#define VR_RADIUS 4u
#define VR_VELOCITY 5u

static int logged = 0;
static int errors_logged = 0;

static void logger(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message) {
    (void)env;
    (void)category;
    logged++;
    if (status == fmi3Error) errors_logged++;
    if (status != fmi3OK && status != fmi3Warning) fprintf(stderr, "  [log %d] %s\n", (int)status, message);
}

/* The instantiationToken attribute of modelDescription.xml. */
static int token_of(const char *xml, char *out, size_t size) {
    const char *start = strstr(xml, "instantiationToken=\"");
    if (start == NULL) return 0;
    start += strlen("instantiationToken=\"");
    const char *end = strchr(start, '"');
    if (end == NULL || (size_t)(end - start) >= size) return 0;
    memcpy(out, start, (size_t)(end - start));
    out[end - start] = '\0';
    return 1;
}

/* fmi3GetDirectionalDerivative and fmi3GetAdjointDerivative (the same signature). */
typedef fmi3Status fmi3DerivativeTYPE(fmi3Instance instance, const fmi3ValueReference unknowns[], size_t nUnknowns,
                                      const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[],
                                      size_t nSeed, fmi3Float64 sensitivity[], size_t nSensitivity);
typedef fmi3DerivativeTYPE fmi3GetDirectionalDerivativeTYPE, fmi3GetAdjointDerivativeTYPE;

#define FIELD(name) name##TYPE *name;
static struct {
    FIELD(fmi3InstantiateModelExchange) FIELD(fmi3InstantiateCoSimulation) FIELD(fmi3FreeInstance)
    FIELD(fmi3EnterInitializationMode) FIELD(fmi3ExitInitializationMode) FIELD(fmi3Terminate)
    FIELD(fmi3GetFloat64) FIELD(fmi3SetFloat64) FIELD(fmi3DoStep) FIELD(fmi3UpdateDiscreteStates)
    FIELD(fmi3EnterContinuousTimeMode) FIELD(fmi3SetTime) FIELD(fmi3SetContinuousStates)
    FIELD(fmi3GetContinuousStateDerivatives) FIELD(fmi3GetNumberOfContinuousStates) FIELD(fmi3GetFMUState)
    FIELD(fmi3FreeFMUState) FIELD(fmi3SerializedFMUStateSize) FIELD(fmi3SetFMUState)
    FIELD(fmi3GetDirectionalDerivative) FIELD(fmi3GetAdjointDerivative)
} F;
#undef FIELD

static void outputs(fmi3Instance c, double *radius, double *velocity) {
    const fmi3ValueReference vr[2] = {VR_RADIUS, VR_VELOCITY};
    double out[2] = {NAN, NAN};
    CHECK(F.fmi3GetFloat64(c, vr, 2, out, 2) <= fmi3Warning, "fmi3GetFloat64");
    *radius = out[0];
    *velocity = out[1];
}

static void co_simulation(const char *token) {
    fmi3Instance c = F.fmi3InstantiateCoSimulation("cs", token, NULL, false, false, false, false, NULL, 0, NULL,
                                                   logger, NULL);
    CHECK(c != NULL, "fmi3InstantiateCoSimulation");
    if (c == NULL) return;
    CHECK(F.fmi3EnterInitializationMode(c, false, 0, 0, false, 0) == fmi3OK, "EnterInitializationMode");
    CHECK(F.fmi3ExitInitializationMode(c) == fmi3OK, "ExitInitializationMode");
    double t = 0.0;
    for (int k = 0; k < 5; k++) {
        fmi3Boolean event = true, terminate = true, early = true;
        double last = NAN, radius, velocity;
        CHECK(F.fmi3DoStep(c, t, REFERENCE[k].t - t, true, &event, &terminate, &early, &last) == fmi3OK, "DoStep");
        CHECK(!event && !early && last == REFERENCE[k].t, "DoStep out-arguments");
        t = REFERENCE[k].t;
        outputs(c, &radius, &velocity);
        CHECK(matches_reference("FMI 3.0 co-simulation", k, radius, velocity), "t = %g", t);
    }
    CHECK(F.fmi3Terminate(c) == fmi3OK, "Terminate");
    F.fmi3FreeInstance(c);
}

#define VR_EDGE_STRESS 3u
#define VR_STATE0 13u /* modal_coordinate[1]; der(modal_coordinate[k]) at VR_STATE0 + nx + k - 1 */

/* The exact Jacobian: J (states and edge stress -> derivatives and wound radius) by
 * fmi3GetDirectionalDerivative equals finite differences of the derivatives (the system
 * is linear), its state block is diagonal with the rates -1/nu_m of `rate` (0 on the spare
 * states), and fmi3GetAdjointDerivative is its transpose: v^T (J w) = (J^T v)^T w. */
static void jacobian(fmi3Instance c, size_t nx, const double *rate) {
    size_t nu = nx + 1, nk = nx + 1;
    fmi3ValueReference *unknowns = calloc(nu, sizeof *unknowns), *knowns = calloc(nk, sizeof *knowns);
    double *v = calloc(nu, sizeof *v), *w = calloc(nk, sizeof *w), *jw = calloc(nu, sizeof *jw), *jtv = calloc(nk, sizeof *jtv);
    double *x = calloc(nx, sizeof *x), *f0 = calloc(nx, sizeof *f0), *f1 = calloc(nx, sizeof *f1);
    for (size_t m = 0; m < nx; m++) {
        unknowns[m] = VR_STATE0 + (fmi3ValueReference)(nx + m);
        knowns[m] = VR_STATE0 + (fmi3ValueReference)m;
        x[m] = 1e-3 * sin(0.7 * (double)m);
    }
    unknowns[nx] = VR_RADIUS;
    knowns[nx] = VR_EDGE_STRESS;
    for (size_t m = 0; m < nu; m++) v[m] = cos(1.3 * (double)m);
    for (size_t m = 0; m < nk; m++) w[m] = sin(0.9 * (double)m + 0.2);
    CHECK(F.fmi3SetContinuousStates(c, x, nx) == fmi3OK, "SetContinuousStates");
    CHECK(F.fmi3GetDirectionalDerivative(c, unknowns, nu, knowns, nk, w, nk, jw, nu) == fmi3OK, "GetDirectionalDerivative");
    CHECK(F.fmi3GetAdjointDerivative(c, unknowns, nu, knowns, nk, v, nu, jtv, nk) == fmi3OK, "GetAdjointDerivative");
    CHECK(F.fmi3GetDirectionalDerivative(c, unknowns, nu, knowns, nk, w, nk - 1, jw, nu) == fmi3Error, "nSeed != nKnowns");
    double vjw = 0, jtvw = 0, scale = 0;
    for (size_t m = 0; m < nu; m++) vjw += v[m] * jw[m], scale += fabs(v[m] * jw[m]);
    for (size_t m = 0; m < nk; m++) jtvw += jtv[m] * w[m];
    CHECK(fabs(vjw - jtvw) <= 1e-13 * scale, "adjoint: v^T (J w) = %.17g but (J^T v)^T w = %.17g", vjw, jtvw);
    /* Finite differences of the derivatives along w (states part, then edge stress). */
    double e = 1e-6, p = e * w[nx];
    CHECK(F.fmi3GetContinuousStateDerivatives(c, f0, nx) == fmi3OK, "derivatives at x");
    for (size_t m = 0; m < nx; m++) x[m] += e * w[m];
    fmi3ValueReference edge = VR_EDGE_STRESS;
    CHECK(F.fmi3SetContinuousStates(c, x, nx) == fmi3OK && F.fmi3SetFloat64(c, &edge, 1, &p, 1) == fmi3OK, "x + e w");
    CHECK(F.fmi3GetContinuousStateDerivatives(c, f1, nx) == fmi3OK, "derivatives at x + e w");
    int bad = 0;
    for (size_t m = 0; m < nx; m++) bad += !(fabs((f1[m] - f0[m]) / e - jw[m]) <= 1e-6 * fmax(fabs(jw[m]), 1.0));
    CHECK(bad == 0, "J w against finite differences: %d of %zu rows differ", bad, nx);
    /* The state block alone: J e_m = -rate_m e_m. */
    double one = 1.0;
    bad = 0;
    for (size_t m = 0; m < nx; m++) {
        CHECK(F.fmi3GetDirectionalDerivative(c, unknowns, nx, &knowns[m], 1, &one, 1, jw, nx) == fmi3OK, "column %zu", m);
        for (size_t i = 0; i < nx; i++) bad += i == m ? !(fabs(jw[m] + rate[m]) <= 1e-12 * rate[m]) : jw[i] != 0.0;
    }
    CHECK(bad == 0, "the state block is diag(-1/nu): %d entries differ", bad);
    double zero = 0.0;
    CHECK(F.fmi3SetFloat64(c, &edge, 1, &zero, 1) == fmi3OK, "edge stress back to 0");
    free(unknowns), free(knowns), free(v), free(w), free(jw), free(jtv), free(x), free(f0), free(f1);
}

/* Exact integration of the uncoupled modes by the master, from two derivative
 * evaluations: the states are the departure from the response to the edge stress held
 * (0 while it is), so the master's exact solution keeps them at 0 and the FMU's outputs
 * follow the reference results through fmi3SetTime. */
static void model_exchange(const char *token) {
    fmi3Instance c = F.fmi3InstantiateModelExchange("me", token, NULL, false, false, NULL, logger);
    CHECK(c != NULL, "fmi3InstantiateModelExchange");
    if (c == NULL) return;
    size_t nx = 0;
    CHECK(F.fmi3GetNumberOfContinuousStates(c, &nx) == fmi3OK && nx == 217, "217 states, not %zu", nx);
    CHECK(F.fmi3EnterInitializationMode(c, false, 0, 0, false, 0) == fmi3OK, "EnterInitializationMode");
    CHECK(F.fmi3ExitInitializationMode(c) == fmi3OK, "ExitInitializationMode");
    fmi3Boolean a, b, d, e, g;
    double next;
    CHECK(F.fmi3UpdateDiscreteStates(c, &a, &b, &d, &e, &g, &next) == fmi3OK && !a && !b && !g, "UpdateDiscreteStates");
    CHECK(F.fmi3EnterContinuousTimeMode(c) == fmi3OK, "EnterContinuousTimeMode");
    double *x = calloc(nx, sizeof *x), *d0 = calloc(nx, sizeof *d0), *d1 = calloc(nx, sizeof *d1), *rate = calloc(nx, sizeof *rate);
    CHECK(F.fmi3GetContinuousStateDerivatives(c, d0, nx) == fmi3OK, "derivatives at c = 0");
    for (size_t k = 0; k < nx; k++) x[k] = 1.0;
    CHECK(F.fmi3SetContinuousStates(c, x, nx) == fmi3OK, "SetContinuousStates");
    CHECK(F.fmi3GetContinuousStateDerivatives(c, d1, nx) == fmi3OK, "derivatives at c = 1");
    for (size_t m = 0; m < nx; m++) rate[m] = d0[m] - d1[m]; /* 1 / nu_m; 0 for the spare states */
    jacobian(c, nx, rate);
    for (int k = 0; k < 5; k++) {
        double t = REFERENCE[k].t, radius, velocity;
        for (size_t m = 0; m < nx; m++) x[m] = rate[m] > 0 ? d0[m] / rate[m] * -expm1(-t * rate[m]) : 0.0;
        CHECK(F.fmi3SetTime(c, t) == fmi3OK && F.fmi3SetContinuousStates(c, x, nx) == fmi3OK, "set t = %g", t);
        outputs(c, &radius, &velocity);
        CHECK(matches_reference("FMI 3.0 Model Exchange", k, radius, velocity), "t = %g", t);
    }
    free(x);
    free(d0);
    free(d1);
    free(rate);
    CHECK(F.fmi3Terminate(c) == fmi3OK, "Terminate");
    F.fmi3FreeInstance(c);
}

/* Instance A's FMU state handed to instance B: refused with a logged reason, and A's
 * state stays A's (FMU states belong to the instance that made them). */
static void foreign_state(const char *token) {
    fmi3Instance a = F.fmi3InstantiateCoSimulation("a", token, NULL, false, false, false, false, NULL, 0, NULL, logger, NULL);
    fmi3Instance b = F.fmi3InstantiateCoSimulation("b", token, NULL, false, false, false, false, NULL, 0, NULL, logger, NULL);
    CHECK(a != NULL && b != NULL, "two instances");
    if (a == NULL || b == NULL) return;
    fmi3FMUState theirs = NULL, slot = NULL;
    size_t size = 0;
    CHECK(F.fmi3GetFMUState(a, &theirs) == fmi3OK && theirs != NULL, "A's state");
    int before = errors_logged;
    CHECK(F.fmi3SetFMUState(b, theirs) == fmi3Error, "B refuses A's state");
    slot = theirs;
    CHECK(F.fmi3GetFMUState(b, &slot) == fmi3Error && slot == theirs, "B does not save into A's state");
    CHECK(F.fmi3SerializedFMUStateSize(b, theirs, &size) == fmi3Error && size == 0, "B does not size A's state");
    CHECK(F.fmi3FreeFMUState(b, &slot) == fmi3Error && slot == theirs, "B does not free A's state");
    CHECK(errors_logged == before + 4, "each refusal logged");
    CHECK(F.fmi3SetFMUState(a, theirs) == fmi3OK && F.fmi3FreeFMUState(a, &theirs) == fmi3OK && theirs == NULL,
          "A's state is still A's");
    F.fmi3FreeInstance(a);
    F.fmi3FreeInstance(b);
}

/* Every function used above on something that is no live instance: fmi3Error, no log. */
static void no_instance(fmi3Instance c, const char *who) {
    int before = logged;
    double r = 0.0;
    size_t n = 0;
    fmi3ValueReference vr = VR_RADIUS;
    fmi3Boolean flag = false;
    fmi3FMUState state = NULL;
    CHECK(F.fmi3EnterInitializationMode(c, false, 0, 0, false, 0) == fmi3Error, "%s: EnterInitializationMode", who);
    CHECK(F.fmi3ExitInitializationMode(c) == fmi3Error && F.fmi3Terminate(c) == fmi3Error, "%s: Exit, Terminate", who);
    CHECK(F.fmi3GetFloat64(c, &vr, 1, &r, 1) == fmi3Error && F.fmi3SetFloat64(c, &vr, 1, &r, 1) == fmi3Error, "%s: Float64", who);
    CHECK(F.fmi3DoStep(c, 0, 1, false, &flag, &flag, &flag, &r) == fmi3Error, "%s: DoStep", who);
    CHECK(F.fmi3UpdateDiscreteStates(c, &flag, &flag, &flag, &flag, &flag, &r) == fmi3Error, "%s: UpdateDiscreteStates", who);
    CHECK(F.fmi3EnterContinuousTimeMode(c) == fmi3Error && F.fmi3SetTime(c, 0) == fmi3Error, "%s: CT mode, SetTime", who);
    CHECK(F.fmi3SetContinuousStates(c, &r, 1) == fmi3Error, "%s: SetContinuousStates", who);
    CHECK(F.fmi3GetContinuousStateDerivatives(c, &r, 1) == fmi3Error, "%s: GetContinuousStateDerivatives", who);
    CHECK(F.fmi3GetNumberOfContinuousStates(c, &n) == fmi3Error && n == 0, "%s: GetNumberOfContinuousStates", who);
    CHECK(F.fmi3GetFMUState(c, &state) == fmi3Error && state == NULL, "%s: GetFMUState", who);
    CHECK(F.fmi3SerializedFMUStateSize(c, (fmi3FMUState)1, &n) == fmi3Error && n == 0, "%s: SerializedFMUStateSize", who);
    CHECK(F.fmi3FreeFMUState(c, &state) == fmi3Error, "%s: FreeFMUState", who);
    F.fmi3FreeInstance(c);
    CHECK(logged == before, "%s: nothing logged without a live instance", who);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s <directory of the extracted WoundOpening-fmi3.fmu>\n", argv[0]);
        return 2;
    }
    char path[4096], token[128];
    snprintf(path, sizeof path, "%s/modelDescription.xml", argv[1]);
    char *xml = read_file(path);
    CHECK(xml != NULL && token_of(xml, token, sizeof token), "instantiationToken in %s", path);
    free(xml);
    snprintf(path, sizeof path, "%s/binaries/" FMI3_PLATFORM "/WoundOpening" LIBRARY_SUFFIX, argv[1]);
    void *lib = library_open(path);
    CHECK(lib != NULL, "cannot load %s: %s", path, lib == NULL ? library_error() : "");
    if (lib == NULL) return check_report("fmu3_master");
    int exported = 0;
#define COUNT(name) exported += library_symbol(lib, #name) != NULL;
    FMI3_ALL_FUNCTIONS(COUNT)
#undef COUNT
    CHECK(exported == 75, "%d of the 75 FMI 3.0 functions exported", exported);
#define LOAD(name) *(void **)(&F.name) = library_symbol(lib, #name);
    LOAD(fmi3InstantiateModelExchange) LOAD(fmi3InstantiateCoSimulation) LOAD(fmi3FreeInstance)
    LOAD(fmi3EnterInitializationMode) LOAD(fmi3ExitInitializationMode) LOAD(fmi3Terminate) LOAD(fmi3GetFloat64)
    LOAD(fmi3SetFloat64) LOAD(fmi3DoStep) LOAD(fmi3UpdateDiscreteStates) LOAD(fmi3EnterContinuousTimeMode)
    LOAD(fmi3SetTime) LOAD(fmi3SetContinuousStates) LOAD(fmi3GetContinuousStateDerivatives)
    LOAD(fmi3GetNumberOfContinuousStates) LOAD(fmi3GetFMUState) LOAD(fmi3FreeFMUState)
    LOAD(fmi3SerializedFMUStateSize) LOAD(fmi3SetFMUState) LOAD(fmi3GetDirectionalDerivative)
    LOAD(fmi3GetAdjointDerivative)
#undef LOAD
    co_simulation(token);
    model_exchange(token);
    foreign_state(token);
    int refused_before = errors_logged;
    CHECK(F.fmi3InstantiateCoSimulation("x", "{wrong}", NULL, false, false, false, false, NULL, 0, NULL, logger, NULL) == NULL
              && errors_logged == refused_before + 1, "a wrong instantiationToken: NULL, with the reason logged");
    CHECK(F.fmi3InstantiateCoSimulation("x", token, NULL, false, false, true, false, NULL, 0, NULL, logger, NULL) == NULL,
          "eventModeUsed without hasEventMode: NULL");
    fmi3Instance freed = F.fmi3InstantiateModelExchange("f", token, NULL, false, false, NULL, logger);
    F.fmi3FreeInstance(freed);
    long own = 0;
    no_instance(NULL, "NULL");
    no_instance((fmi3Instance)(uintptr_t)0xdeadbeef, "made-up");
    no_instance(freed, "freed");
    no_instance((fmi3Instance)&own, "the caller's memory");
    CHECK(own == 0, "nothing written through a forged instance");
    library_close(lib);
    return check_report("fmu3_master");
}
