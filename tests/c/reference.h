/*
 * The paper's lambda = 1 case (sigma = 1, R_inf = 10, free edge) from the EXACT solution,
 * not from this library: printed by
 *
 *   python -c "import sys; sys.path.insert(0, 'python'); import numpy as np, wound_exact as w;
 *              print(w.edge(1.0, 1.0, 10.0, np.array([0.01, 0.1, 1, 10, 100])))"
 *
 * (python/wound_exact.py: the Laplace-domain solution of docs/model.md ("Exact results"), inverted
 * on Weideman's Talbot contour, itself checked against mpmath at 30 digits to 1e-13 by
 * tests/python/test_reference.py).
 *
 * Tolerances: 1e-9 of the opening amplitude R_final - R1 = (2/3)(100/99) - 1/6 for the
 * wound radius, and 1e-9 of max(|v|, amplitude / 100) for the edge velocity (the
 * README's error measure). The library's measured errors are about 1e-12.
 */
#ifndef TESTS_REFERENCE_H
#define TESTS_REFERENCE_H

#include <math.h>
#include <stdio.h>

struct reference {
    double t, radius, velocity;
};

static const struct reference REFERENCE[5] = {
    {0.01, 1.1687443502514037, 0.20711539214739375},
    {0.1, 1.1868688862321859, 0.19577994855827147},
    {1.0, 1.3230844084841049, 0.11558187443997481},
    {10.0, 1.5970947064445615, 0.007227097722726783},
    {100.0, 1.6719957182851066, 5.6431344168226628e-05},
};

#define REFERENCE_AMPLITUDE (2.0 / 3.0 * 100.0 / 99.0 - 1.0 / 6.0)
#define REFERENCE_TOLERANCE 1e-9

/* Compare (radius, velocity) at REFERENCE[k]; print the errors; return 1 if within tolerance. */
static int matches_reference(const char *who, int k, double radius, double velocity) {
    const struct reference *ref = &REFERENCE[k];
    double scale_v = fmax(fabs(ref->velocity), REFERENCE_AMPLITUDE / 100.0);
    double err_r = fabs(radius - ref->radius) / REFERENCE_AMPLITUDE;
    double err_v = fabs(velocity - ref->velocity) / scale_v;
    int ok = err_r <= REFERENCE_TOLERANCE && err_v <= REFERENCE_TOLERANCE;
    printf("%s: t = %-5g R = %.15f (error %.2e)  dR/dt = %.15f (error %.2e)%s\n", who, ref->t, radius, err_r,
           velocity, err_v, ok ? "" : "  <-- beyond 1e-9");
    return ok;
}

#endif /* TESTS_REFERENCE_H */
