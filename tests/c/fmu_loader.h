/*
 * What a minimal FMI 2.0 co-simulation master needs to load an extracted FMU: read the
 * GUID and model identifier from modelDescription.xml, load
 * binaries/<platform>/<modelIdentifier><suffix> (dynamic_library.h), resolve all 34 functions with the standard's
 * types (fmi2_standard.h), and a printf-like logger that records what it was told.
 */
#ifndef TESTS_FMU_LOADER_H
#define TESTS_FMU_LOADER_H

#include "fmi2_standard.h"
#include "dynamic_library.h"
#include "read_file.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct fmu {
    void *library;
    char *xml;
    char guid[128];
    char identifier[128];
#define FIELD(name) name##TYPE *name;
    FMI2_CS_FUNCTIONS(FIELD)
    FMI2_ME_FUNCTIONS(FIELD)
#undef FIELD
};

/* The value of attribute `name` of the first element holding it, into `out`. */
static int xml_attribute(const char *xml, const char *name, char *out, size_t size) {
    char key[64];
    snprintf(key, sizeof key, " %s=\"", name);
    const char *start = strstr(xml, key);
    if (start == NULL) return 0;
    start += strlen(key);
    const char *end = strchr(start, '"');
    if (end == NULL || (size_t)(end - start) >= size) return 0;
    memcpy(out, start, (size_t)(end - start));
    out[end - start] = '\0';
    return 1;
}

/* Load the FMU extracted in `dir`; 1 on success, else 0 with the reason on stderr. */
static int fmu_load(struct fmu *fmu, const char *dir) {
    char path[4096];
    memset(fmu, 0, sizeof *fmu);
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    fmu->xml = read_file(path);
    int ok = fmu->xml != NULL && xml_attribute(fmu->xml, "guid", fmu->guid, sizeof fmu->guid) &&
             xml_attribute(fmu->xml, "modelIdentifier", fmu->identifier, sizeof fmu->identifier);
    if (!ok) {
        fprintf(stderr, "cannot read guid and modelIdentifier from %s\n", path);
        return 0;
    }
    snprintf(path, sizeof path, "%s/binaries/" FMI2_PLATFORM "/%s" LIBRARY_SUFFIX, dir, fmu->identifier);
    fmu->library = library_open(path);
    if (fmu->library == NULL) {
        fprintf(stderr, "cannot load %s: %s\n", path, library_error());
        return 0;
    }
#define LOAD(name)                                                                                               \
    fmu->name = (name##TYPE *)library_symbol(fmu->library, #name);                                                        \
    if (fmu->name == NULL) {                                                                                     \
        fprintf(stderr, "%s does not export %s\n", path, #name);                                                 \
        ok = 0;                                                                                                  \
    }
    FMI2_CS_FUNCTIONS(LOAD)
    FMI2_ME_FUNCTIONS(LOAD)
#undef LOAD
    return ok;
}

static void fmu_unload(struct fmu *fmu) {
    if (fmu->library != NULL) library_close(fmu->library);
    free(fmu->xml);
    fmu->library = NULL;
    fmu->xml = NULL;
}

/* The valueReference of the ScalarVariable called `name` (as a master reads it), or ~0u. */
static fmi2ValueReference fmu_value_reference(const struct fmu *fmu, const char *name) {
    char key[160], value[32];
    snprintf(key, sizeof key, "name=\"%s\"", name);
    const char *at = strstr(fmu->xml, key);
    const char *element_end = at != NULL ? strchr(at, '>') : NULL;
    if (at == NULL || element_end == NULL) return ~0u;
    const char *vr = strstr(at, "valueReference=\"");
    if (vr == NULL || vr > element_end || !xml_attribute(vr - 1, "valueReference", value, sizeof value)) return ~0u;
    return (fmi2ValueReference)strtoul(value, NULL, 10);
}

/* What the logger was told last, and how often it was called. */
struct log_record {
    int count;
    fmi2Status status;
    char instance[128];
    char category[64];
    char message[2048];
    int foreign_environment; /* calls whose componentEnvironment was not this record */
};

/* The importer's logger: printf-like, so the FMU's format and arguments go through vsnprintf. */
static void record_logger(fmi2ComponentEnvironment env, fmi2String instanceName, fmi2Status status,
                          fmi2String category, fmi2String message, ...) {
    static struct log_record dummy;
    struct log_record *log = env != NULL ? (struct log_record *)env : &dummy;
    va_list args;
    va_start(args, message);
    vsnprintf(log->message, sizeof log->message, message, args);
    va_end(args);
    snprintf(log->instance, sizeof log->instance, "%s", instanceName != NULL ? instanceName : "(NULL)");
    snprintf(log->category, sizeof log->category, "%s", category != NULL ? category : "(NULL)");
    log->status = status;
    log->count++;
    log->foreign_environment += env == NULL;
    if (getenv("WO_VERBOSE") != NULL) {
        fprintf(stderr, "  [%s] %s (status %d): %s\n", log->instance, log->category, (int)status, log->message);
    }
}

#endif /* TESTS_FMU_LOADER_H */
