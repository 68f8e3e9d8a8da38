/*
 * Two FMUs built from this library, loaded side by side in one process: WoundOpening and
 * PurseString, each its own shared object (its own copy of the library, its own handle
 * tables). Both copies are driven through the same sequence of calls, so that handle
 * numbering by call order alone would give the same numbers in both. Every handle of one
 * copy handed to the other is refused as unknown:
 *   1. FMI 2.0: a PurseString FMU state to fmi2SetFMUstate, fmi2SerializedFMUstateSize and
 *      fmi2FreeFMUstate of a WoundOpening instance (and the other way round), and a
 *      PurseString instance to WoundOpening's fmi2DoStep;
 *   2. FMI 3.0: the same with fmi3SetFMUState, fmi3SerializedFMUStateSize, fmi3DoStep;
 *   3. the direct C API (wo_*, exported by both binaries): a solver and a saved state of
 *      one copy to wo_solver_advance, wo_solver_restore_state and wo_state_free of the other.
 * Each copy's own handles keep working throughout.
 *
 *   two_libraries <WoundOpening.fmu dir> <PurseString.fmu dir> <WoundOpening-fmi3.fmu dir>
 *                 <PurseString-fmi3.fmu dir>     (each extracted)
 *
 * Run under valgrind by scripts/c_tests.sh: no error, no leak.
 */
#define _POSIX_C_SOURCE 200809L

#include "check.h"
#include "fmi3_standard.h"
#include "fmu_loader.h"

#include <dlfcn.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

/* ---- FMI 2.0 ---- */

static struct log_record LOG2;
static const fmi2CallbackFunctions CALLBACKS2 = {record_logger, NULL, NULL, NULL, &LOG2};

static fmi2Component fmi2_started(const struct fmu *fmu) {
    fmi2Component c = fmu->fmi2Instantiate("x", fmi2CoSimulation, fmu->guid, "file:///unused", &CALLBACKS2,
                                           fmi2False, fmi2False);
    CHECK(c != NULL, "fmi2Instantiate(%s): %s", fmu->identifier, LOG2.message);
    if (c == NULL) return NULL;
    CHECK(fmu->fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK, "%s", fmu->identifier);
    CHECK(fmu->fmi2EnterInitializationMode(c) == fmi2OK, "%s", fmu->identifier);
    CHECK(fmu->fmi2ExitInitializationMode(c) == fmi2OK, "%s", fmu->identifier);
    return c;
}

/* `c` of library `own`, `state` of library `other`: refused; `mine` is c's own state. */
static void fmi2_crossed(const struct fmu *own, fmi2Component c, fmi2FMUstate mine, fmi2Component foreign_c,
                         fmi2FMUstate foreign) {
    size_t size = 0;
    fmi2FMUstate slot = foreign;
    CHECK(own->fmi2SetFMUstate(c, foreign) == fmi2Error, "%s accepted a foreign FMU state", own->identifier);
    CHECK(own->fmi2SerializedFMUstateSize(c, foreign, &size) == fmi2Error && size == 0,
          "%s sized a foreign FMU state (%zu bytes)", own->identifier, size);
    CHECK(own->fmi2FreeFMUstate(c, &slot) == fmi2Error && slot == foreign, "%s freed a foreign FMU state",
          own->identifier);
    CHECK(strstr(LOG2.message, "unknown") != NULL || strstr(LOG2.message, "not") != NULL, "%s: reason logged: %s",
          own->identifier, LOG2.message);
    CHECK(own->fmi2DoStep(foreign_c, 0.0, 0.5, fmi2True) == fmi2Error, "%s stepped a foreign instance",
          own->identifier);
    CHECK(own->fmi2SetFMUstate(c, mine) == fmi2OK, "%s: its own state still works", own->identifier);
}

static void fmi2_case(const char *wound_dir, const char *purse_dir) {
    struct fmu wound, purse;
    if (!fmu_load(&wound, wound_dir) || !fmu_load(&purse, purse_dir)) {
        CHECK(0, "FMI 2.0 FMUs not loaded");
        fmu_unload(&wound);
        fmu_unload(&purse);
        return;
    }
    CHECK(wound.fmi2SetFMUstate != purse.fmi2SetFMUstate, "two copies of the library (not one mapped twice)");
    CHECK(fmu_value_reference(&wound, "wound_radius") == fmu_value_reference(&purse, "wound_radius"),
          "both number wound_radius alike");
    fmi2Component w = fmi2_started(&wound), p = fmi2_started(&purse);
    if (w != NULL && p != NULL) {
        fmi2FMUstate ws = NULL, ps = NULL;
        CHECK(wound.fmi2GetFMUstate(w, &ws) == fmi2OK && purse.fmi2GetFMUstate(p, &ps) == fmi2OK, "states");
        CHECK(wound.fmi2DoStep(w, 0.0, 1.0, fmi2True) == fmi2OK, "WoundOpening steps");
        CHECK(purse.fmi2DoStep(p, 0.0, 1.0, fmi2True) == fmi2OK, "PurseString steps");
        fmi2_crossed(&wound, w, ws, p, ps);
        fmi2_crossed(&purse, p, ps, w, ws);
        CHECK(wound.fmi2FreeFMUstate(w, &ws) == fmi2OK && purse.fmi2FreeFMUstate(p, &ps) == fmi2OK, "own frees");
    }
    if (w != NULL) wound.fmi2FreeInstance(w);
    if (p != NULL) purse.fmi2FreeInstance(p);
    fmu_unload(&wound);
    fmu_unload(&purse);
}

/* ---- FMI 3.0 ---- */

#define FMI3_USED(X)                                                                                             \
    X(fmi3InstantiateCoSimulation)                                                                               \
    X(fmi3FreeInstance)                                                                                          \
    X(fmi3EnterInitializationMode)                                                                               \
    X(fmi3ExitInitializationMode)                                                                                \
    X(fmi3DoStep)                                                                                                \
    X(fmi3GetFMUState)                                                                                           \
    X(fmi3SetFMUState)                                                                                           \
    X(fmi3FreeFMUState)                                                                                          \
    X(fmi3SerializedFMUStateSize)

struct fmu3 {
    void *library;
    char *xml;
    char token[128];
    char identifier[128];
#define FIELD(name) name##TYPE *name;
    FMI3_USED(FIELD)
#undef FIELD
};

static int fmi3_errors = 0;

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category, fmi3String message) {
    (void)env;
    (void)category;
    (void)message;
    if (status == fmi3Error) fmi3_errors++;
}

static int fmu3_load(struct fmu3 *fmu, const char *dir) {
    char path[4096];
    memset(fmu, 0, sizeof *fmu);
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    fmu->xml = read_file(path);
    if (fmu->xml == NULL || !xml_attribute(fmu->xml, "instantiationToken", fmu->token, sizeof fmu->token) ||
        !xml_attribute(fmu->xml, "modelIdentifier", fmu->identifier, sizeof fmu->identifier)) {
        fprintf(stderr, "cannot read %s\n", path);
        return 0;
    }
    snprintf(path, sizeof path, "%s/binaries/x86_64-linux/%s.so", dir, fmu->identifier);
    fmu->library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (fmu->library == NULL) {
        fprintf(stderr, "dlopen(%s): %s\n", path, dlerror());
        return 0;
    }
    int ok = 1;
#define LOAD(name)                                                                                               \
    fmu->name = (name##TYPE *)dlsym(fmu->library, #name);                                                        \
    ok &= fmu->name != NULL;
    FMI3_USED(LOAD)
#undef LOAD
    return ok;
}

static void fmu3_unload(struct fmu3 *fmu) {
    if (fmu->library != NULL) dlclose(fmu->library);
    free(fmu->xml);
}

static fmi3Instance fmi3_started(const struct fmu3 *fmu) {
    fmi3Instance c = fmu->fmi3InstantiateCoSimulation("x", fmu->token, NULL, false, false, false, false, NULL, 0,
                                                      NULL, logger3, NULL);
    CHECK(c != NULL, "fmi3InstantiateCoSimulation(%s)", fmu->identifier);
    if (c == NULL) return NULL;
    CHECK(fmu->fmi3EnterInitializationMode(c, false, 0, 0, false, 0) == fmi3OK, "%s", fmu->identifier);
    CHECK(fmu->fmi3ExitInitializationMode(c) == fmi3OK, "%s", fmu->identifier);
    return c;
}

static void fmi3_crossed(const struct fmu3 *own, fmi3Instance c, fmi3FMUState mine, fmi3Instance foreign_c,
                         fmi3FMUState foreign) {
    size_t size = 0;
    fmi3FMUState slot = foreign;
    fmi3Boolean event, terminate, early;
    double last;
    int before = fmi3_errors;
    CHECK(own->fmi3SetFMUState(c, foreign) == fmi3Error, "%s accepted a foreign FMU state", own->identifier);
    CHECK(own->fmi3SerializedFMUStateSize(c, foreign, &size) == fmi3Error && size == 0,
          "%s sized a foreign FMU state", own->identifier);
    CHECK(own->fmi3FreeFMUState(c, &slot) == fmi3Error && slot == foreign, "%s freed a foreign FMU state",
          own->identifier);
    CHECK(fmi3_errors == before + 3, "%s: each refusal logged", own->identifier);
    CHECK(own->fmi3DoStep(foreign_c, 0.0, 0.5, true, &event, &terminate, &early, &last) == fmi3Error,
          "%s stepped a foreign instance", own->identifier);
    CHECK(own->fmi3SetFMUState(c, mine) == fmi3OK, "%s: its own state still works", own->identifier);
}

static void fmi3_case(const char *wound_dir, const char *purse_dir) {
    struct fmu3 wound, purse;
    if (!fmu3_load(&wound, wound_dir) || !fmu3_load(&purse, purse_dir)) {
        CHECK(0, "FMI 3.0 FMUs not loaded");
        fmu3_unload(&wound);
        fmu3_unload(&purse);
        return;
    }
    fmi3Instance w = fmi3_started(&wound), p = fmi3_started(&purse);
    if (w != NULL && p != NULL) {
        fmi3FMUState ws = NULL, ps = NULL;
        CHECK(wound.fmi3GetFMUState(w, &ws) == fmi3OK && purse.fmi3GetFMUState(p, &ps) == fmi3OK, "states");
        fmi3_crossed(&wound, w, ws, p, ps);
        fmi3_crossed(&purse, p, ps, w, ws);
        CHECK(wound.fmi3FreeFMUState(w, &ws) == fmi3OK && purse.fmi3FreeFMUState(p, &ps) == fmi3OK, "own frees");
    }
    if (w != NULL) wound.fmi3FreeInstance(w);
    if (p != NULL) purse.fmi3FreeInstance(p);
    fmu3_unload(&wound);
    fmu3_unload(&purse);
}

/* ---- the direct C API, from both binaries ---- */

typedef int wo_solver_new_fn(double, double, double, double, void **);
typedef int wo_solver_advance_fn(void *, double, double);
typedef int wo_handle_fn(void *);
typedef int wo_solver_save_state_fn(const void *, void **);
typedef int wo_solver_restore_state_fn(void *, const void *);
enum { WO_OK = 0, WO_UNKNOWN_HANDLE = 3 };

struct capi {
    wo_solver_new_fn *solver_new;
    wo_solver_advance_fn *advance;
    wo_handle_fn *solver_free, *state_free;
    wo_solver_save_state_fn *save;
    wo_solver_restore_state_fn *restore;
};

static int capi_load(struct capi *api, void *library) {
    /* dlsym returns void *; the standard way to turn it into a function pointer is a copy. */
    void *p;
#define SYM(field, name)                                                                                         \
    p = dlsym(library, name);                                                                                    \
    if (p == NULL) return 0;                                                                                     \
    memcpy(&api->field, &p, sizeof p);
    SYM(solver_new, "wo_solver_new")
    SYM(advance, "wo_solver_advance")
    SYM(solver_free, "wo_solver_free")
    SYM(state_free, "wo_state_free")
    SYM(save, "wo_solver_save_state")
    SYM(restore, "wo_solver_restore_state")
#undef SYM
    return 1;
}

static void capi_case(const char *wound_dir, const char *purse_dir) {
    struct fmu wound, purse;
    struct capi a, b;
    if (!fmu_load(&wound, wound_dir) || !fmu_load(&purse, purse_dir) || !capi_load(&a, wound.library) ||
        !capi_load(&b, purse.library)) {
        CHECK(0, "the wo_* functions of both binaries");
        fmu_unload(&wound);
        fmu_unload(&purse);
        return;
    }
    void *sa = NULL, *sb = NULL, *xa = NULL, *xb = NULL;
    CHECK(a.solver_new(1.0, 1.0, 10.0, 1e-6, &sa) == WO_OK && b.solver_new(1.0, 1.0, 10.0, 1e-6, &sb) == WO_OK,
          "a solver in each copy");
    CHECK(a.save(sa, &xa) == WO_OK && b.save(sb, &xb) == WO_OK, "a saved state in each copy");
    CHECK(a.advance(sb, 1.0, 1.0) == WO_UNKNOWN_HANDLE, "copy A advanced copy B's solver");
    CHECK(b.advance(sa, 1.0, 1.0) == WO_UNKNOWN_HANDLE, "copy B advanced copy A's solver");
    CHECK(a.restore(sa, xb) == WO_UNKNOWN_HANDLE, "copy A restored copy B's state");
    CHECK(a.state_free(xb) == WO_UNKNOWN_HANDLE, "copy A freed copy B's state");
    CHECK(b.solver_free(sa) == WO_UNKNOWN_HANDLE, "copy B freed copy A's solver");
    CHECK(a.advance(sa, 1.0, 1.0) == WO_OK && a.restore(sa, xa) == WO_OK, "copy A's own handles work");
    CHECK(a.state_free(xa) == WO_OK && b.state_free(xb) == WO_OK, "own states freed");
    CHECK(a.solver_free(sa) == WO_OK && b.solver_free(sb) == WO_OK, "own solvers freed");
    fmu_unload(&wound);
    fmu_unload(&purse);
}

int main(int argc, char **argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: %s <WoundOpening.fmu> <PurseString.fmu> <WoundOpening-fmi3.fmu> <PurseString-fmi3.fmu>"
                        " (directories, extracted)\n", argv[0]);
        return 2;
    }
    fmi2_case(argv[1], argv[2]);
    fmi3_case(argv[3], argv[4]);
    capi_case(argv[1], argv[2]);
    return check_report("two_libraries");
}
