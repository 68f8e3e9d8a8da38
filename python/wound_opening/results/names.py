"""The names results are reported under: one wound's four parameters and the material that
several wounds of one tissue share (fitting/wounds.py explains the coordinates)."""

#: One wound's parameters, in the order of the optimiser's coordinates z (fitting/objective.py).
NAMES = ("R0_um", "sigma", "lambda", "T_s")
#: The shared coordinates of several wounds (y[0], y[1], y[2]) and the derived eta/G.
SHARED = ("viscous_length_um", "tension_over_G", "zeta_over_G_s_per_um2")
ETA = "eta_over_G_s"
