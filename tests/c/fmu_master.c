/*
 * A minimal FMI 2.0 co-simulation master in C. It loads the shared object of
 * WoundOpening.fmu (extracted into argv[1]) with dlopen, knowing only the standard
 * (fmi2_standard.h) and modelDescription.xml, and checks:
 *   1. the paper's lambda = 1 case against the exact solution (reference.h);
 *   2. bad input: NULL everywhere, NaN / inf, lambda < 0, R_inf <= 1, a wrong GUID, calls in
 *      the wrong state, a wrong communication point, non-positive steps, FMU states freed
 *      twice, truncated / corrupted / foreign serialized states. Each call must return
 *      fmi2Error and log, through the variadic logger, a message naming what was wrong
 *      (fmu_bad_input.h), after which the instance still reproduces the reference;
 *   3. FMU states and reset give back the same numbers bit for bit.
 * Run under valgrind by scripts/c_tests.sh: no error, no leak.
 */
#define _POSIX_C_SOURCE 200809L

#include "fmu_common.h"

#include "reference.h"

/* Step from the instance's time `*t` through REFERENCE[from..4], checking each point. */
static void reproduce(const char *who, fmi2Component c, double *t, int from) {
    for (int k = from; k < 5; k++) {
        double radius, velocity;
        OK(F.fmi2DoStep(c, *t, REFERENCE[k].t - *t, fmi2True));
        *t = REFERENCE[k].t;
        outputs(c, &radius, &velocity);
        CHECK(matches_reference(who, k, radius, velocity), "%s at t = %g", who, REFERENCE[k].t);
    }
}

/* The bad-input checks: part of this translation unit (they share F, LOG and the checks). */
#include "fmu_bad_input.h"

static void lambda_one_case(void) {
    double t = 0.0, r1, v1, again, v;
    fmi2Component c = initialized("lambda1", 1.0);
    if (c == NULL) return;
    fmi2FMUstate at_start = NULL;
    OK(F.fmi2GetFMUstate(c, &at_start));
    reproduce("FMU", c, &t, 0);
    outputs(c, &r1, &v1);

    /* Back to t = 0 through the saved FMU state: the same numbers, bit for bit. */
    OK(F.fmi2SetFMUstate(c, at_start));
    t = 0.0;
    reproduce("FMU after fmi2SetFMUstate", c, &t, 0);
    outputs(c, &again, &v);
    CHECK(again == r1 && v == v1, "R(100) = %.17g after restore, %.17g before", again, r1);
    OK(F.fmi2FreeFMUstate(c, &at_start));
    CHECK(at_start == NULL, "fmi2FreeFMUstate sets the state to NULL");

    /* fmi2Reset, then the same experiment again. */
    OK(F.fmi2Terminate(c));
    OK(F.fmi2Reset(c));
    OK(F.fmi2SetupExperiment(c, fmi2True, 1e-9, 0.0, fmi2True, 100.0));
    OK(F.fmi2EnterInitializationMode(c));
    OK(F.fmi2ExitInitializationMode(c));
    t = 0.0;
    reproduce("FMU after fmi2Reset", c, &t, 0);
    outputs(c, &again, &v);
    CHECK(again == r1, "R(100) = %.17g after reset, %.17g before", again, r1);
    fmi2Boolean terminated = fmi2False;
    OK(F.fmi2GetBooleanStatus(c, fmi2Terminated, &terminated));
    CHECK(terminated == fmi2True, "stop time 100 reached: fmi2Terminated should be true");
    F.fmi2FreeInstance(c);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s <directory of the extracted WoundOpening.fmu>\n", argv[0]);
        return 2;
    }
    if (!load_fmu(argv[1])) return 1;
    CHECK(strcmp(F.fmi2GetVersion(), "2.0") == 0, "fmi2GetVersion = %s", F.fmi2GetVersion());
    CHECK(strcmp(F.fmi2GetTypesPlatform(), "default") == 0, "fmi2GetTypesPlatform = %s", F.fmi2GetTypesPlatform());

    lambda_one_case();
    bad_instantiation();
    every_call_is_an_error(NULL, NULL, "NULL component");
    bad_calls();
    CHECK(LOG.foreign_environment == 0, "%d logger calls had another componentEnvironment", LOG.foreign_environment);

    fmu_unload(&F);
    return check_report("fmu_master");
}
