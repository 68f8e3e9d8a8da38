/*
 * What the C masters (fmu_master.c, fmu_misuse.c) share: the loaded FMU and its log, the
 * value references, the status checks, and instance helpers. Each program is one
 * translation unit that includes this header once.
 */
#ifndef TESTS_FMU_COMMON_H
#define TESTS_FMU_COMMON_H

#include "fmu_loader.h"

#include "check.h"

#include <math.h>
#include <stdint.h>

static struct fmu F;
static struct log_record LOG;
static fmi2ValueReference VR_LAMBDA, VR_SIGMA, VR_R_INF, VR_EDGE_STRESS, VR_RADIUS, VR_VELOCITY;

#define OK(call)                                                                                                 \
    do {                                                                                                         \
        fmi2Status got_ = (call);                                                                                \
        CHECK(got_ == fmi2OK, "%s returned %d; last log: %s", #call, (int)got_, LOG.message);                    \
    } while (0)

/* `call` returns `want` and logs, under category `cat` with status `want`, a message
 * containing `needle`. */
#define LOGGED(call, want, cat, needle)                                                                     \
    do {                                                                                                         \
        int before_ = LOG.count;                                                                                 \
        fmi2Status got_ = (call);                                                                                \
        CHECK(got_ == (want) && LOG.count > before_ && LOG.status == (want) &&                                   \
                  strcmp(LOG.category, (cat)) == 0 && strstr(LOG.message, (needle)) != NULL,                \
              "%s returned %d, logged [%s, %d] \"%s\"; expected %d with [%s] \"%s\"", #call, (int)got_,          \
              LOG.category, (int)LOG.status, LOG.message, (int)(want), (cat), (needle));                    \
    } while (0)

/* A refused call: fmi2Error, and a logged error (logStatusError) containing `needle`. */
#define REFUSED(call, needle) LOGGED(call, fmi2Error, "logStatusError", needle)

/* A discarded call: fmi2Discard, and a message under logStatusDiscard containing `needle`. */
#define DISCARDED(call, needle) LOGGED(call, fmi2Discard, "logStatusDiscard", needle)

static const fmi2CallbackFunctions CALLBACKS = {record_logger, NULL, NULL, NULL, &LOG};

/* Load the FMU extracted in `dir` and read the value references; 0 on failure. */
static int load_fmu(const char *dir) {
    if (!fmu_load(&F, dir)) {
        fmu_unload(&F);
        return 0;
    }
    VR_LAMBDA = fmu_value_reference(&F, "lambda");
    VR_SIGMA = fmu_value_reference(&F, "sigma");
    VR_R_INF = fmu_value_reference(&F, "R_inf");
    VR_EDGE_STRESS = fmu_value_reference(&F, "edge_stress");
    VR_RADIUS = fmu_value_reference(&F, "wound_radius");
    VR_VELOCITY = fmu_value_reference(&F, "edge_velocity");
    CHECK(VR_VELOCITY != ~0u && VR_RADIUS != ~0u && VR_EDGE_STRESS != ~0u, "value references in modelDescription.xml");
    return 1;
}

static fmi2Component instantiate(const char *name) {
    return F.fmi2Instantiate(name, fmi2CoSimulation, F.guid, "file:///unused", &CALLBACKS, fmi2False, fmi2False);
}

/* Instantiate with lambda, sigma = 1, R_inf = 10 and initialize at t = 0. */
static fmi2Component initialized(const char *name, double lambda) {
    fmi2Component c = instantiate(name);
    CHECK(c != NULL, "fmi2Instantiate(%s) failed: %s", name, LOG.message);
    if (c == NULL) return NULL;
    const fmi2ValueReference vr[3] = {VR_LAMBDA, VR_SIGMA, VR_R_INF};
    const fmi2Real value[3] = {lambda, 1.0, 10.0};
    OK(F.fmi2SetReal(c, vr, 3, value));
    OK(F.fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(F.fmi2EnterInitializationMode(c));
    OK(F.fmi2ExitInitializationMode(c));
    return c;
}

static void outputs(fmi2Component c, double *radius, double *velocity) {
    const fmi2ValueReference vr[2] = {VR_RADIUS, VR_VELOCITY};
    fmi2Real value[2] = {NAN, NAN};
    OK(F.fmi2GetReal(c, vr, 2, value));
    *radius = value[0];
    *velocity = value[1];
}

/* Every function that takes an instance, on `c`, which is not a live instance (NULL,
 * freed, forged): each returns fmi2Error, and nothing is logged (there is no logger to
 * tell) or written. `state` is passed where an FMU state is expected. */
static void every_call_is_an_error(fmi2Component c, fmi2FMUstate state, const char *who) {
    fmi2ValueReference vr = 0;
    fmi2Real r = 0;
    fmi2Integer i = 0;
    fmi2Boolean b = 0;
    fmi2String s = NULL;
    fmi2Status st = fmi2OK;
    fmi2FMUstate slot = state;
    size_t size = 0;
    fmi2Byte byte = 0;
    const fmi2Status e = fmi2Error;
    const fmi2String cats[1] = {"logCalls"};
    int before = LOG.count;
    CHECK(F.fmi2SetDebugLogging(c, fmi2True, 1, cats) == e, "%s: SetDebugLogging", who);
    CHECK(F.fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0) == e, "%s: SetupExperiment", who);
    CHECK(F.fmi2EnterInitializationMode(c) == e && F.fmi2ExitInitializationMode(c) == e, "%s: init", who);
    CHECK(F.fmi2Terminate(c) == e && F.fmi2Reset(c) == e, "%s: Terminate, Reset", who);
    CHECK(F.fmi2GetReal(c, &vr, 1, &r) == e && F.fmi2SetReal(c, &vr, 1, &r) == e, "%s: Get/SetReal", who);
    CHECK(F.fmi2GetInteger(c, &vr, 1, &i) == e && F.fmi2SetInteger(c, &vr, 1, &i) == e, "%s: Get/SetInteger", who);
    CHECK(F.fmi2GetBoolean(c, &vr, 1, &b) == e && F.fmi2SetBoolean(c, &vr, 1, &b) == e, "%s: Get/SetBoolean", who);
    CHECK(F.fmi2GetString(c, &vr, 1, &s) == e && F.fmi2SetString(c, &vr, 1, &s) == e, "%s: Get/SetString", who);
    CHECK(F.fmi2GetFMUstate(c, &slot) == e && F.fmi2SetFMUstate(c, state) == e, "%s: Get/SetFMUstate", who);
    CHECK(F.fmi2FreeFMUstate(c, &slot) == e && slot == state, "%s: FreeFMUstate", who);
    CHECK(F.fmi2SerializedFMUstateSize(c, state, &size) == e && size == 0, "%s: SerializedFMUstateSize", who);
    CHECK(F.fmi2SerializeFMUstate(c, state, &byte, 1) == e, "%s: SerializeFMUstate", who);
    CHECK(F.fmi2DeSerializeFMUstate(c, &byte, 1, &slot) == e && slot == state, "%s: DeSerializeFMUstate", who);
    CHECK(F.fmi2GetDirectionalDerivative(c, &vr, 1, &vr, 1, &r, &r) == e, "%s: GetDirectionalDerivative", who);
    CHECK(F.fmi2SetRealInputDerivatives(c, &vr, 1, &i, &r) == e, "%s: SetRealInputDerivatives", who);
    CHECK(F.fmi2GetRealOutputDerivatives(c, &vr, 1, &i, &r) == e, "%s: GetRealOutputDerivatives", who);
    CHECK(F.fmi2DoStep(c, 0, 1, fmi2False) == e && F.fmi2CancelStep(c) == e, "%s: DoStep, CancelStep", who);
    CHECK(F.fmi2GetStatus(c, fmi2DoStepStatus, &st) == e, "%s: GetStatus", who);
    CHECK(F.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &r) == e, "%s: GetRealStatus", who);
    CHECK(F.fmi2GetIntegerStatus(c, fmi2DoStepStatus, &i) == e, "%s: GetIntegerStatus", who);
    CHECK(F.fmi2GetBooleanStatus(c, fmi2Terminated, &b) == e, "%s: GetBooleanStatus", who);
    CHECK(F.fmi2GetStringStatus(c, fmi2DoStepStatus, &s) == e, "%s: GetStringStatus", who);
    fmi2EventInfo info;
    fmi2Boolean enter = 0, stop = 0;
    CHECK(F.fmi2EnterEventMode(c) == e && F.fmi2NewDiscreteStates(c, &info) == e, "%s: EnterEventMode, NewDiscreteStates", who);
    CHECK(F.fmi2EnterContinuousTimeMode(c) == e && F.fmi2CompletedIntegratorStep(c, fmi2True, &enter, &stop) == e,
          "%s: EnterContinuousTimeMode, CompletedIntegratorStep", who);
    CHECK(F.fmi2SetTime(c, 0) == e && F.fmi2SetContinuousStates(c, &r, 1) == e, "%s: SetTime, SetContinuousStates", who);
    CHECK(F.fmi2GetDerivatives(c, &r, 1) == e && F.fmi2GetEventIndicators(c, &r, 1) == e, "%s: GetDerivatives, GetEventIndicators", who);
    CHECK(F.fmi2GetContinuousStates(c, &r, 1) == e && F.fmi2GetNominalsOfContinuousStates(c, &r, 1) == e,
          "%s: GetContinuousStates, GetNominalsOfContinuousStates", who);
    CHECK(r == 0 && i == 0 && b == 0 && s == NULL && st == fmi2OK, "%s: nothing written", who);
    F.fmi2FreeInstance(c);
    CHECK(LOG.count == before, "%s: nothing can be logged without an instance", who);
}

#endif /* TESTS_FMU_COMMON_H */
