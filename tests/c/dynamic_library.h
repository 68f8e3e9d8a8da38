/*
 * The few calls a master needs to load a shared library, on POSIX (dlopen, dlsym) and on
 * Windows (LoadLibrary, GetProcAddress), and the archive's platform folders and library
 * suffix of the platform the program is compiled for (FMI 2.0: binaries/win64, linux64,
 * darwin64, aarch64-linux; FMI 3.0: binaries/<arch>-<os>).
 */
#ifndef TESTS_DYNAMIC_LIBRARY_H
#define TESTS_DYNAMIC_LIBRARY_H

#ifdef _WIN32
#include <stdio.h>
#include <windows.h>
static void *library_open(const char *path) { return (void *)LoadLibraryA(path); }
/* Through void (*)(void), which matches every function type (no -Wcast-function-type). */
static void *library_symbol(void *library, const char *name) {
    return (void *)(void (*)(void))GetProcAddress((HMODULE)library, name);
}
static void library_close(void *library) { FreeLibrary((HMODULE)library); }
static const char *library_error(void) {
    static char text[64];
    snprintf(text, sizeof text, "Windows error %lu", (unsigned long)GetLastError());
    return text;
}
#else
#include <dlfcn.h>
static void *library_open(const char *path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void *library_symbol(void *library, const char *name) { return dlsym(library, name); }
static void library_close(void *library) { dlclose(library); }
static const char *library_error(void) { return dlerror(); }
#endif

#if defined(_WIN64)
#define FMI2_PLATFORM "win64"
#define FMI3_PLATFORM "x86_64-windows"
#define LIBRARY_SUFFIX ".dll"
#elif defined(__linux__) && defined(__x86_64__)
#define FMI2_PLATFORM "linux64"
#define FMI3_PLATFORM "x86_64-linux"
#define LIBRARY_SUFFIX ".so"
#elif defined(__linux__) && defined(__aarch64__)
#define FMI2_PLATFORM "aarch64-linux" /* FMI 2.0 names no aarch64 folder: the FMI 3.0 tuple */
#define FMI3_PLATFORM "aarch64-linux"
#define LIBRARY_SUFFIX ".so"
#elif defined(__APPLE__)
#define FMI2_PLATFORM "darwin64"
#if defined(__aarch64__)
#define FMI3_PLATFORM "aarch64-darwin"
#else
#define FMI3_PLATFORM "x86_64-darwin"
#endif
#define LIBRARY_SUFFIX ".dylib"
#else
#error "no FMI platform folder for this platform"
#endif

#endif /* TESTS_DYNAMIC_LIBRARY_H */
