/* Minimal test bookkeeping for the C programs: count failures, report, exit status. */
#ifndef TESTS_CHECK_H
#define TESTS_CHECK_H

#include <stdio.h>
#include <string.h>

static int check_failures = 0;
static int check_count = 0;

#define CHECK(cond, ...)                                                                                         \
    do {                                                                                                         \
        check_count++;                                                                                           \
        if (!(cond)) {                                                                                           \
            check_failures++;                                                                                    \
            fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                                      \
            fprintf(stderr, __VA_ARGS__);                                                                        \
            fputc('\n', stderr);                                                                                 \
        }                                                                                                        \
    } while (0)

/* The plain closing line that test runners read: "N passed, N failed". */
static int check_report(const char *program) {
    printf("%s: %d passed, %d failed\n", program, check_count - check_failures, check_failures);
    return check_failures == 0 ? 0 : 1;
}

#endif /* TESTS_CHECK_H */
