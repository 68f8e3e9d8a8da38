/*
 * Bad input through the FMI 2.0 functions. Part of fmu_master.c (one translation unit:
 * it uses F, LOG, CALLBACKS, the checks and helpers of fmu_common.h).
 */

/* CRC-32 (IEEE 802.3, reflected, as zlib), to forge states that pass the checksum. */
static uint32_t crc32_ieee(const unsigned char *p, size_t n) {
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

static void put_u32(unsigned char *p, uint32_t v) {
    for (int i = 0; i < 4; i++) p[i] = (unsigned char)(v >> (8 * i));
}

/* Re-seal a modified serialized state: CRC-32 of everything before the last 4 bytes. */
static void reseal(unsigned char *bytes, size_t size) {
    put_u32(bytes + size - 4, crc32_ieee(bytes, size - 4));
}

#define INSTANTIATE_REFUSED(call, needle)                                                                        \
    do {                                                                                                         \
        int before_ = LOG.count;                                                                                 \
        fmi2Component got_ = (call);                                                                             \
        CHECK(got_ == NULL && LOG.count > before_ && LOG.status == fmi2Error && strstr(LOG.message, (needle)),   \
              "%s gave %p, logged \"%s\"; expected NULL with \"%s\"", #call, got_, LOG.message, (needle));       \
        if (got_ != NULL) F.fmi2FreeInstance(got_);                                                              \
    } while (0)

static void bad_instantiation(void) {
    const char *wrong = "{00000000-0000-0000-0000-000000000000}";
    char expected[256];
    /* The shared object serves two models; the message names both GUIDs, this FMU's first. */
    snprintf(expected, sizeof expected, "Expected GUID %s (WoundOpening) or ", F.guid);
    INSTANTIATE_REFUSED(F.fmi2Instantiate("x", fmi2CoSimulation, wrong, "", &CALLBACKS, fmi2False, fmi2False), expected);
    snprintf(expected, sizeof expected, "(PurseString) but was %s", wrong);
    INSTANTIATE_REFUSED(F.fmi2Instantiate("x", fmi2CoSimulation, wrong, "", &CALLBACKS, fmi2False, fmi2False), expected);
    INSTANTIATE_REFUSED(F.fmi2Instantiate("x", fmi2CoSimulation, NULL, "", &CALLBACKS, fmi2False, fmi2False), "but was NULL");
    INSTANTIATE_REFUSED(F.fmi2Instantiate(NULL, fmi2CoSimulation, F.guid, "", &CALLBACKS, fmi2False, fmi2False), "instanceName is NULL");
    INSTANTIATE_REFUSED(F.fmi2Instantiate("x", (fmi2Type)7, F.guid, "", &CALLBACKS, fmi2False, fmi2False),
                        "fmuType = 7: this FMU supports Model Exchange (0) and co-simulation (1)");
    /* Without callbacks, or without a logger, there is no one to tell: NULL, and no crash. */
    CHECK(F.fmi2Instantiate("x", fmi2CoSimulation, F.guid, "", NULL, fmi2False, fmi2False) == NULL, "NULL functions");
    const fmi2CallbackFunctions silent = {NULL, NULL, NULL, NULL, NULL};
    CHECK(F.fmi2Instantiate("x", fmi2CoSimulation, wrong, "", &silent, fmi2False, fmi2False) == NULL, "wrong GUID, no logger");
    /* A name with conversion specifiers is text, not a format. */
    fmi2Component c = F.fmi2Instantiate("%s%n%p", fmi2CoSimulation, F.guid, "", &CALLBACKS, fmi2False, fmi2False);
    CHECK(c != NULL, "instance named %%s%%n%%p");
    REFUSED(F.fmi2DoStep(c, 0.0, 1.0, fmi2False), "fmi2DoStep is not allowed in state Instantiated");
    CHECK(strcmp(LOG.instance, "%s%n%p") == 0, "logged instance name \"%s\"", LOG.instance);
    F.fmi2FreeInstance(c);
}

static fmi2Status set1(fmi2Component c, fmi2ValueReference vr, double value) {
    return F.fmi2SetReal(c, &vr, 1, &value);
}

/* Before initialization: invalid values and calls in the wrong state. */
static void before_initialization(fmi2Component c) {
    fmi2ValueReference vr = VR_LAMBDA;
    fmi2Real one = 1.0, out = 0.0;
    fmi2Integer i = 0;
    fmi2Boolean b = 0;
    fmi2String s = "x";
    REFUSED(F.fmi2DoStep(c, 0.0, 0.1, fmi2True), "fmi2DoStep is not allowed in state Instantiated");
    REFUSED(set1(c, VR_LAMBDA, NAN), "lambda = NaN is outside the accepted range: 0 or [1e-150, 1e6]");
    REFUSED(set1(c, VR_LAMBDA, -1.0), "lambda = -1 is outside the accepted range: 0 or [1e-150, 1e6]");
    REFUSED(set1(c, VR_LAMBDA, INFINITY), "lambda = inf is outside");
    REFUSED(set1(c, VR_SIGMA, INFINITY), "sigma = inf is outside the accepted range (-6, 1e6]");
    REFUSED(set1(c, VR_SIGMA, NAN), "sigma = NaN is outside");
    REFUSED(set1(c, VR_R_INF, 1.0), "R_inf = 1 is outside the accepted range [1.001, 1e6]");
    REFUSED(set1(c, VR_R_INF, 0.5), "R_inf = 0.5 is outside");
    REFUSED(set1(c, VR_R_INF, -INFINITY), "R_inf = -inf is outside");
    REFUSED(set1(c, VR_EDGE_STRESS, NAN), "edge_stress = NaN Pa is outside the accepted range");
    REFUSED(set1(c, VR_RADIUS, 2.0), "wound_radius (value reference 4) is an output and cannot be set");
    REFUSED(set1(c, 99999, 1.0), "no Real variable has value reference 99999");
    REFUSED(set1(c, 99, 1.0), "modal_coordinate[87] (value reference 99) is a continuous state or derivative");
    REFUSED(F.fmi2SetReal(c, NULL, 1, &one), "vr is NULL but 1 elements were announced");
    REFUSED(F.fmi2SetReal(c, &vr, 1, NULL), "value is NULL but 1 elements were announced");
    REFUSED(F.fmi2GetReal(c, &vr, 1, &out), "fmi2Get* is not allowed in state Instantiated");
    REFUSED(F.fmi2SetInteger(c, &vr, 1, &i), "lambda (value reference 0) is Real, not Integer");
    REFUSED(F.fmi2SetBoolean(c, &vr, 1, &b), "no Boolean variable has value reference 0");
    REFUSED(F.fmi2SetString(c, &vr, 1, &s), "no String variable has value reference 0");
    REFUSED(F.fmi2SetupExperiment(c, fmi2True, NAN, 0, fmi2False, 0), "tolerance = NaN is invalid");
    REFUSED(F.fmi2SetupExperiment(c, fmi2True, -1e-6, 0, fmi2False, 0), "tolerance = -0.000001 is invalid");
    REFUSED(F.fmi2SetupExperiment(c, fmi2False, 0, INFINITY, fmi2False, 0), "startTime = inf is invalid");
    REFUSED(F.fmi2SetupExperiment(c, fmi2False, 0, 1.0, fmi2True, 0.5),
            "stopTime = 0.5 is invalid: it must be finite and >= startTime = 1");
    const fmi2String categories[2] = {"logCalls", "%s%n%p"};
    REFUSED(F.fmi2SetDebugLogging(c, fmi2True, 2, categories), "unknown log category \"%s%n%p\"");
    REFUSED(F.fmi2SetDebugLogging(c, fmi2True, 1, NULL), "categories is NULL but 1 elements were announced");
    REFUSED(F.fmi2ExitInitializationMode(c), "fmi2ExitInitializationMode is not allowed in state Instantiated");
    /* A refused fmi2SetReal sets none of its values: sigma stays 1 (checked after initialization). */
    const fmi2ValueReference both[2] = {VR_SIGMA, VR_LAMBDA};
    const fmi2Real values[2] = {2.0, -1.0};
    REFUSED(F.fmi2SetReal(c, both, 2, values), "lambda = -1 is outside");
}

/* d(wound_radius, edge_velocity)/d edge_stress: 0 and the slope of the (affine) velocity,
 * compared with a difference quotient of two fmi2GetReal calls; the input is restored. */
static void directional_derivative(fmi2Component c) {
    const fmi2ValueReference outs[2] = {VR_RADIUS, VR_VELOCITY};
    fmi2Real seed = 2.0, dv[2] = {-1, -1}, p0 = 0, v0 = 0, v1 = 0, p1 = 0;
    OK(F.fmi2GetDirectionalDerivative(c, outs, 2, &VR_EDGE_STRESS, 1, &seed, dv));
    OK(F.fmi2GetReal(c, &VR_EDGE_STRESS, 1, &p0));
    OK(F.fmi2GetReal(c, &VR_VELOCITY, 1, &v0));
    p1 = p0 + 0.5;
    OK(F.fmi2SetReal(c, &VR_EDGE_STRESS, 1, &p1));
    OK(F.fmi2GetReal(c, &VR_VELOCITY, 1, &v1));
    OK(F.fmi2SetReal(c, &VR_EDGE_STRESS, 1, &p0));
    double fd = 2.0 * (v1 - v0) / 0.5; /* times the seed */
    CHECK(dv[0] == 0.0, "d wound_radius/d edge_stress = %g, expected 0", dv[0]);
    CHECK(dv[1] < 0.0 && fabs(dv[1] - fd) <= 1e-9 * fabs(fd), "d edge_velocity/d edge_stress x 2 = %.17g, difference quotient %.17g",
          dv[1], fd);
}

/* Initialized: fixed parameters, communication points, steps, unsupported functions. */
static void after_initialization(fmi2Component c) {
    fmi2ValueReference vr = VR_RADIUS;
    fmi2Real sigma = 0, r = 0;
    fmi2Integer i = 0, order = 1;
    fmi2Status st = fmi2OK;
    fmi2String s = NULL;
    REFUSED(F.fmi2EnterInitializationMode(c), "fmi2EnterInitializationMode is not allowed in state StepComplete");
    OK(F.fmi2GetReal(c, &VR_SIGMA, 1, &sigma));
    CHECK(sigma == 1.0, "sigma = %g after a refused fmi2SetReal, expected its start value 1", sigma);
    REFUSED(set1(c, VR_LAMBDA, 2.0), "lambda is a fixed parameter: it can only be set before fmi2ExitInitializationMode");
    REFUSED(set1(c, VR_R_INF, 20.0), "R_inf is a fixed parameter");
    REFUSED(F.fmi2SetupExperiment(c, fmi2False, 0, 0, fmi2False, 0), "fmi2SetupExperiment is not allowed in state StepComplete");
    REFUSED(F.fmi2DoStep(c, 0.5, 0.01, fmi2True), "Expected currentCommunicationPoint = 0 but was 0.5");
    REFUSED(F.fmi2DoStep(c, NAN, 0.01, fmi2True), "Expected currentCommunicationPoint = 0 but was NaN");
    REFUSED(F.fmi2DoStep(c, 0.0, 0.0, fmi2True), "communicationStepSize = 0 is invalid: it must be finite and > 0");
    REFUSED(F.fmi2DoStep(c, 0.0, -0.1, fmi2True), "communicationStepSize = -0.1 is invalid");
    REFUSED(F.fmi2DoStep(c, 0.0, NAN, fmi2True), "communicationStepSize = NaN is invalid");
    REFUSED(F.fmi2DoStep(c, 0.0, INFINITY, fmi2True), "communicationStepSize = inf is invalid");
    DISCARDED(F.fmi2GetStatus(c, fmi2DoStepStatus, &st), "fmi2GetStatus: fmi2DoStepStatus is not provided by this FMU");
    REFUSED(F.fmi2GetStatus(c, (fmi2StatusKind)7, &st), "status kind 7 is not an fmi2StatusKind");
    REFUSED(F.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, NULL), "value is NULL");
    DISCARDED(F.fmi2GetStringStatus(c, fmi2PendingStatus, &s), "fmi2GetStringStatus: fmi2PendingStatus is not provided");
    DISCARDED(F.fmi2GetIntegerStatus(c, fmi2DoStepStatus, &i), "fmi2GetIntegerStatus: fmi2DoStepStatus is not provided");
    DISCARDED(F.fmi2GetRealStatus(c, fmi2Terminated, &r), "fmi2GetRealStatus: fmi2Terminated is not provided");
    REFUSED(F.fmi2GetDirectionalDerivative(c, &vr, 1, &VR_LAMBDA, 1, &r, &r),
            "lambda (value reference 0) is a parameter but a vKnown_ref entry must be a Real input");
    REFUSED(F.fmi2GetDirectionalDerivative(c, &VR_EDGE_STRESS, 1, &VR_EDGE_STRESS, 1, &r, &r),
            "edge_stress (value reference 3) is an input but a vUnknown_ref entry must be a Real output");
    REFUSED(F.fmi2GetDirectionalDerivative(c, &vr, 1, &VR_EDGE_STRESS, 1, NULL, &r), "dvKnown is NULL but 1 elements");
    directional_derivative(c);
    fmi2Integer second = 2;
    REFUSED(F.fmi2SetRealInputDerivatives(c, &VR_EDGE_STRESS, 1, &second, &r), "order = 2 for edge_stress is invalid");
    REFUSED(F.fmi2SetRealInputDerivatives(c, &vr, 1, &order, &r), "wound_radius (value reference 4) is not an input");
    REFUSED(F.fmi2GetRealOutputDerivatives(c, &vr, 1, &order, &r), "is not supported");
    REFUSED(F.fmi2CancelStep(c), "fmi2CancelStep is not supported by this FMU");
    REFUSED(F.fmi2GetInteger(c, &vr, 1, &i), "wound_radius (value reference 4) is Real, not Integer");
    REFUSED(F.fmi2GetString(c, &vr, 1, &s), "no String variable has value reference 4");
    REFUSED(F.fmi2GetReal(c, &vr, 1, NULL), "value is NULL but 1 elements were announced");
}

/* FMU states: NULL, forged, double free; serialized states truncated, corrupted, foreign. */
static void fmu_states(fmi2Component c) {
    fmi2FMUstate st = NULL, copy = NULL, back = NULL, forged = (fmi2FMUstate)(uintptr_t)0x999;
    size_t size = 0;
    REFUSED(F.fmi2GetFMUstate(c, NULL), "FMUstate is NULL");
    REFUSED(F.fmi2GetFMUstate(c, &forged), "is unknown to this instance");
    OK(F.fmi2GetFMUstate(c, &st));
    copy = st;
    REFUSED(F.fmi2SetFMUstate(c, NULL), "FMUstate is NULL");
    REFUSED(F.fmi2FreeFMUstate(c, NULL), "FMUstate is NULL");
    OK(F.fmi2FreeFMUstate(c, &st));
    REFUSED(F.fmi2FreeFMUstate(c, &copy), "is unknown to this instance (never allocated by it, or already freed)");
    REFUSED(F.fmi2SetFMUstate(c, copy), "is unknown to this instance (never allocated by it, or already freed)");
    REFUSED(F.fmi2SerializedFMUstateSize(c, copy, &size), "is unknown");

    OK(F.fmi2GetFMUstate(c, &st));
    REFUSED(F.fmi2SerializedFMUstateSize(c, st, NULL), "size is NULL");
    OK(F.fmi2SerializedFMUstateSize(c, st, &size));
    unsigned char *bytes = malloc(size), *bad = malloc(size + 8);
    char expected[128];
    snprintf(expected, sizeof expected, "buffer of %zu bytes is too small: the state needs %zu", size - 1, size);
    REFUSED(F.fmi2SerializeFMUstate(c, st, (fmi2Byte *)bytes, size - 1), expected);
    REFUSED(F.fmi2SerializeFMUstate(c, st, NULL, size), "serializedState is NULL");
    OK(F.fmi2SerializeFMUstate(c, st, (fmi2Byte *)bytes, size));
    const fmi2Byte *b = (const fmi2Byte *)bytes;

    REFUSED(F.fmi2DeSerializeFMUstate(c, b, size, NULL), "FMUstate is NULL");
    REFUSED(F.fmi2DeSerializeFMUstate(c, NULL, size, &back), "serializedState is NULL");
    REFUSED(F.fmi2DeSerializeFMUstate(c, b, 0, &back), "is 0 bytes, shorter than its header");
    REFUSED(F.fmi2DeSerializeFMUstate(c, b, 19, &back), "is 19 bytes, shorter than its header");
    REFUSED(F.fmi2DeSerializeFMUstate(c, b, size / 2, &back), "but its header announces");
    REFUSED(F.fmi2DeSerializeFMUstate(c, b, size - 1, &back), "but its header announces");
    memcpy(bad, bytes, size);
    memset(bad + size, 0, 8);
    REFUSED(F.fmi2DeSerializeFMUstate(c, (fmi2Byte *)bad, size + 8, &back), "but its header announces");
    bad[size / 2] ^= 0x10; /* one bit flipped in the payload */
    REFUSED(F.fmi2DeSerializeFMUstate(c, (fmi2Byte *)bad, size, &back), "is corrupted: checksum");
    memcpy(bad, bytes, size);
    bad[0] = 'X';
    REFUSED(F.fmi2DeSerializeFMUstate(c, (fmi2Byte *)bad, size, &back), "does not start with \"WOUNDFMU\"");
    memcpy(bad, bytes, size);
    put_u32(bad + 8, 1); /* another (the previous) format version, with a valid checksum */
    reseal(bad, size);
    REFUSED(F.fmi2DeSerializeFMUstate(c, (fmi2Byte *)bad, size, &back), "has format version 1; this FMU reads version 3");
    CHECK(back == NULL, "a refused fmi2DeSerializeFMUstate leaves the state NULL");

    /* A state of another parameter set (lambda = 2). */
    fmi2Component other = initialized("lambda2", 2.0);
    fmi2FMUstate theirs = NULL;
    size_t their_size = 0;
    OK(F.fmi2GetFMUstate(other, &theirs));
    OK(F.fmi2SerializedFMUstateSize(other, theirs, &their_size));
    CHECK(their_size == size, "same layout: %zu and %zu bytes", their_size, size);
    OK(F.fmi2SerializeFMUstate(other, theirs, (fmi2Byte *)bad, their_size));
    REFUSED(F.fmi2DeSerializeFMUstate(c, (fmi2Byte *)bad, their_size, &back),
            "serialized FMU state has lambda = 2 but this instance has lambda = 1");
    OK(F.fmi2FreeFMUstate(other, &theirs));
    F.fmi2FreeInstance(other);

    /* The genuine bytes round-trip. */
    double r0, v0, r1, v1;
    outputs(c, &r0, &v0);
    OK(F.fmi2DeSerializeFMUstate(c, b, size, &back));
    OK(F.fmi2SetFMUstate(c, back));
    outputs(c, &r1, &v1);
    CHECK(r1 == r0 && v1 == v0, "deserialized state gives R = %.17g, expected %.17g", r1, r0);
    OK(F.fmi2FreeFMUstate(c, &back));
    OK(F.fmi2FreeFMUstate(c, &st));
    free(bytes);
    free(bad);
}

static void bad_calls(void) {
    double t = 0.0;
    fmi2Component c = instantiate("bad");
    CHECK(c != NULL, "fmi2Instantiate(bad): %s", LOG.message);
    if (c == NULL) return;
    before_initialization(c);
    OK(F.fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0));
    OK(F.fmi2EnterInitializationMode(c));
    OK(F.fmi2ExitInitializationMode(c));
    after_initialization(c);
    reproduce("FMU after refused calls", c, &t, 0);
    fmu_states(c);
    /* logCalls: every call is logged with its arguments, status fmi2OK. */
    const fmi2String calls[1] = {"logCalls"};
    OK(F.fmi2SetDebugLogging(c, fmi2True, 1, calls));
    fmi2Real last = NAN;
    OK(F.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &last));
    CHECK(last == t, "fmi2LastSuccessfulTime = %g, expected %g", last, t);
    CHECK(strcmp(LOG.category, "logCalls") == 0 && LOG.status == fmi2OK && strstr(LOG.message, "fmi2GetRealStatus(2)"),
          "logCalls logged [%s] \"%s\"", LOG.category, LOG.message);
    F.fmi2FreeInstance(c);
}
