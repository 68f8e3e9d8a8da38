/*
 * A misbehaving FMI 2.0 master: what the standard calls undefined, done on purpose. It
 * loads WoundOpening.fmu (extracted into argv[1]) like fmu_master.c and
 *   1. passes instance A's FMU state to instance B: fmi2SetFMUstate, fmi2GetFMUstate into
 *      it, fmi2FreeFMUstate, fmi2SerializedFMUstateSize, fmi2SerializeFMUstate and
 *      fmi2DeSerializeFMUstate into it are each refused with fmi2Error and a logged reason,
 *      and B's own state and time are untouched (A's state stays A's);
 *   2. frees A, then calls every FMI function on it, and frees it twice more;
 *   3. calls every FMI function on NULL and on forged components (a made-up number, the
 *      address of its own memory).
 * Every such call returns fmi2Error; without a live instance nothing is logged or written.
 * Run under valgrind by scripts/c_tests.sh: no crash, no memory error, no leak.
 */
#define _POSIX_C_SOURCE 200809L

#include "fmu_common.h"

/* The reason every refusal of a foreign state gives. */
static const char *const NOT_OURS = "move it with fmi2SerializeFMUstate and fmi2DeSerializeFMUstate";

static double last_time(fmi2Component c) {
    fmi2Real t = NAN;
    OK(F.fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t));
    return t;
}

/* Instance A's state `theirs` handed to instance B, which is at t = 2 with its own state
 * `ours` saved at t = 1: every call is refused and changes nothing. */
static void foreign_state(fmi2Component b, fmi2FMUstate theirs, fmi2FMUstate ours) {
    double r0, v0, r1, v1;
    outputs(b, &r0, &v0);
    fmi2FMUstate slot = theirs;
    size_t size = 0;
    unsigned char bytes[4096];
    REFUSED(F.fmi2SetFMUstate(b, theirs), NOT_OURS);
    REFUSED(F.fmi2GetFMUstate(b, &slot), NOT_OURS);
    CHECK(slot == theirs, "a refused fmi2GetFMUstate leaves the handle as it was");
    REFUSED(F.fmi2FreeFMUstate(b, &slot), NOT_OURS);
    CHECK(slot == theirs, "a refused fmi2FreeFMUstate leaves the handle as it was");
    REFUSED(F.fmi2SerializedFMUstateSize(b, theirs, &size), NOT_OURS);
    CHECK(size == 0, "nothing written by a refused fmi2SerializedFMUstateSize");
    REFUSED(F.fmi2SerializeFMUstate(b, theirs, (fmi2Byte *)bytes, sizeof bytes), NOT_OURS);
    /* B's own bytes, deserialized into A's handle. */
    OK(F.fmi2SerializedFMUstateSize(b, ours, &size));
    CHECK(size <= sizeof bytes, "state of %zu bytes", size);
    OK(F.fmi2SerializeFMUstate(b, ours, (fmi2Byte *)bytes, sizeof bytes));
    REFUSED(F.fmi2DeSerializeFMUstate(b, (const fmi2Byte *)bytes, size, &slot), NOT_OURS);
    CHECK(slot == theirs, "a refused fmi2DeSerializeFMUstate leaves the handle as it was");

    /* B is where it was, and its own state is still its own. */
    outputs(b, &r1, &v1);
    CHECK(r1 == r0 && v1 == v0, "B's outputs changed: R %.17g -> %.17g", r0, r1);
    CHECK(last_time(b) == 2.0, "B's time after the refused calls: %g, expected 2", last_time(b));
    OK(F.fmi2SetFMUstate(b, ours));
    CHECK(last_time(b) == 1.0, "B's own state restores t = 1, not %g", last_time(b));
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s <directory of the extracted WoundOpening.fmu>\n", argv[0]);
        return 2;
    }
    if (!load_fmu(argv[1])) return 1;

    fmi2Component a = initialized("A", 1.0), b = initialized("B", 1.0);
    if (a == NULL || b == NULL) return check_report("fmu_misuse");
    fmi2FMUstate theirs = NULL, ours = NULL;
    OK(F.fmi2GetFMUstate(a, &theirs));
    OK(F.fmi2DoStep(b, 0.0, 1.0, fmi2True));
    OK(F.fmi2GetFMUstate(b, &ours));
    OK(F.fmi2DoStep(b, 1.0, 1.0, fmi2True));
    CHECK(theirs != ours, "state handles are unique in the process");
    foreign_state(b, theirs, ours);
    OK(F.fmi2SetFMUstate(a, theirs)); /* A's state is still A's */

    /* A freed: every call is an error, a second and third free are ignored, and A's
     * state is not B's either. */
    F.fmi2FreeInstance(a);
    every_call_is_an_error(a, theirs, "freed instance");
    F.fmi2FreeInstance(a);
    REFUSED(F.fmi2SetFMUstate(b, theirs), NOT_OURS);

    /* NULL and forged components. */
    uint64_t own[64] = {0};
    every_call_is_an_error(NULL, ours, "NULL component");
    every_call_is_an_error((fmi2Component)(uintptr_t)0xdeadbeef, ours, "made-up component");
    every_call_is_an_error((fmi2Component)own, ours, "component pointing at the caller's memory");
    int untouched = 1;
    for (int i = 0; i < 64; i++) untouched &= own[i] == 0;
    CHECK(untouched, "nothing written through a forged component");

    /* B goes on. */
    OK(F.fmi2DoStep(b, 1.0, 1.0, fmi2True));
    OK(F.fmi2FreeFMUstate(b, &ours));
    F.fmi2FreeInstance(b);
    CHECK(LOG.foreign_environment == 0, "%d logger calls had another componentEnvironment", LOG.foreign_environment);
    fmu_unload(&F);
    return check_report("fmu_misuse");
}
