/*
 * Compile-time check: every FMI 2.0 function declared by include/wound_opening.h (and so
 * exported by the library: the header is generated from the Rust shims) has exactly the
 * type the FMI 2.0 standard declares. Each is assigned to a pointer of the standard's
 * function type from fmi2_standard.h; built with -Wall -Wextra -Werror
 * -Wincompatible-pointer-types, any difference in a parameter or result type fails the
 * build. The program itself only counts.
 */
#include "fmi2_standard.h" /* first: the standard's types, written out independently */
#include "wound_opening.h" /* then the generated declarations, which must agree */

#include <stdio.h>

#define CHECK(name) static name##TYPE *const check_##name = name;
FMI2_CS_FUNCTIONS(CHECK)
FMI2_ME_FUNCTIONS(CHECK)
#undef CHECK

int main(void) {
    int n = 0;
#define COUNT(name) n += check_##name != NULL;
    FMI2_CS_FUNCTIONS(COUNT)
    FMI2_ME_FUNCTIONS(COUNT)
#undef COUNT
    printf("fmi2_signatures: %d of 44 FMI 2.0 functions (co-simulation and Model Exchange) have the standard's type\n", n);
    return n == 44 ? 0 : 1;
}
