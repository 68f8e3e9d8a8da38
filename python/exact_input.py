"""Exact wound radius under a time-varying edge stress p(t) = P (1 - exp(-t / tau)), from
the Laplace-domain solution of `wound_exact` (the model is linear in p).

`wound_exact.edge_transform(s, lam, 0, r_inf, 1)` is V(1, s) for a unit step of p, whose
transform is 1/s; this input's is P / (s (1 + tau s)), so

    V(1, s) = V_sigma(1, s) + P edge_transform(s, lam, 0, r_inf, 1) / (1 + tau s)
    R(t)    = 1 + sigma/6 + v(1, t)

inverted on the same contour as `wound_exact.edge`. The input is smooth and starts at 0
with slope P / tau: a Model Exchange integrator meets it as it meets a coupled closure
model whose edge stress builds up from the cut.
"""

from __future__ import annotations

import numpy as np
import wound_exact


def edge_stress(t, amplitude: float, tau: float):
    """p(t) = P (1 - exp(-t / tau))."""
    return -amplitude * np.expm1(-np.asarray(t, dtype=float) / tau)


def edge(lam: float, sigma: float, r_inf: float, t, amplitude: float, tau: float) -> np.ndarray:
    """Exact R(t) at t > 0 under `edge_stress(t, amplitude, tau)`."""

    def f(s):
        return wound_exact.edge_transform(
            s, lam, sigma, r_inf, 0.0
        ) + amplitude * wound_exact.edge_transform(s, lam, 0.0, r_inf, 1.0) / (1 + tau * s)

    return 1 + sigma / 6 + wound_exact._invert(f, t)
