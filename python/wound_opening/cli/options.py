"""The command line `wound-opening`: fit, sweep, simulate. Bad input ends with one line
naming the file, the file line and the problem, and exit code 2 (no traceback); a fit that did
not converge prints why, writes its JSON ("converged": false) and exits with 1."""

from __future__ import annotations

import argparse
import os
import sys

from .commands import fit_command, simulate_command, sweep_command


class HelpFormatter(argparse.ArgumentDefaultsHelpFormatter):
    """Appends "(default: X)" to an option's help unless it has no default (None, False) or
    its help already names one."""

    def _get_help_string(self, action):
        text = action.help or ""
        if action.default in (None, False, argparse.SUPPRESS) or "default" in text.lower():
            return text
        return super()._get_help_string(action)


def frames_to_fit(group) -> None:
    """--until-max and --until-s on the fit's parser (or one of its groups)."""
    group.add_argument(
        "--until-max",
        action="store_true",
        help="fit the radius only up to its maximum before a sustained decrease (a wound that "
        "closes again after opening; the decrease decided with the noise, docs/fitting.md)",
    )
    group.add_argument(
        "--until-s",
        type=float,
        metavar="T",
        help="fit only the times up to T (s) after the cut, radius and profile",
    )


def parser() -> argparse.ArgumentParser:
    from .lab import add_lab_file_arguments

    top = argparse.ArgumentParser(
        prog="wound-opening",
        description=(
            "Fit laser-ablation experiments, sweep parameters and simulate the wound-opening model "
            "(docs/fitting.md). Units: um, s, Pa; lambda and sigma dimensionless."
        ),
    )
    sub = top.add_subparsers(dest="command", required=True)

    f = sub.add_parser(
        "fit",
        help="fit R0_um, sigma, lambda, T_s to a radius series (and a velocity profile); "
        "several wounds of one tissue: their shared material and each R0",
        formatter_class=HelpFormatter,
    )
    f.add_argument(
        "radius_csv",
        metavar="RADIUS.csv",
        nargs="+",
        help="columns time_s,radius_um (time since the "
        "cut), or as named by --time-col, --radius-col; several files: several wounds of one "
        "tissue, "
        "fitted together (shared viscous length, tension/G, zeta/G, eta/G; each wound its R0)",
    )
    f.add_argument(
        "--profile",
        metavar="PROFILE.csv",
        action="append",
        help="columns time_s,r_um,velocity_um_s (r: current distance from the wound centre); with "
        "several wounds, repeat it once per wound in their order",
    )
    f.add_argument(
        "--outer-radius-um",
        required=True,
        metavar="UM[,UM..]",
        help="outer radius of the tissue (um); "
        "with several wounds one for all or one per wound in their order (100,120,90)",
    )
    f.add_argument(
        "--wound-col",
        metavar="NAME",
        help="RADIUS.csv is one long table of several wounds, this "
        "column naming the wound of each row (times ascending within each wound)",
    )
    f.add_argument("--json", metavar="OUT.json", help="write the result as JSON")
    f.add_argument(
        "--plot", metavar="OUT.png", help="data with the fit, residuals, profile likelihoods"
    )
    f.add_argument(
        "--export",
        metavar="STEM",
        help="write STEM_radius.csv (data, model, residual, normalised "
        "residual, flagged), STEM_curve.csv (the fitted R(t) on a fine grid) and, with a profile, "
        "STEM_profile.csv and STEM_profile_curve.csv; units in the column names (docs/fitting.md)",
    )
    f.add_argument(
        "--report",
        metavar="OUT.html",
        help="a self-contained HTML report: input files and their "
        "SHA-256, noise, chi^2, estimates with intervals, flagged points, the figure, versions",
    )
    f.add_argument(
        "--radius-noise-um",
        type=float,
        help="noise of the radii in um (default: column radius_sd_um if "
        "present, else from the residuals)",
    )
    f.add_argument(
        "--velocity-noise-um-s",
        type=float,
        help="noise of the velocities in um/s (default: column "
        "velocity_sd_um_s if present, else from the residuals)",
    )
    c = f.add_argument_group(
        "the files' columns and units",
        "Both files share the units; the times are "
        "read from either file as (time - CUT_TIME) in TIME_UNIT. Separators , ; or tab, "
        "decimal commas in ;- or tab-separated files, '#' comment lines and a UTF-8 BOM "
        "are accepted.",
    )
    c.add_argument(
        "--time-col",
        default="time_s",
        metavar="NAME",
        help="time column of RADIUS.csv (default time_s)",
    )
    c.add_argument(
        "--radius-col",
        default="radius_um",
        metavar="NAME",
        help="radius column (default radius_um)",
    )
    c.add_argument(
        "--radius-sd-col",
        metavar="NAME",
        help="per-point standard deviations of the radius "
        "(default: the column radius_sd_um if present)",
    )
    c.add_argument(
        "--piv-time-col",
        default="time_s",
        metavar="NAME",
        help="time column of PROFILE.csv (default time_s)",
    )
    c.add_argument(
        "--piv-r-col",
        default="r_um",
        metavar="NAME",
        help="distance column of PROFILE.csv (default r_um)",
    )
    c.add_argument(
        "--piv-velocity-col",
        default="velocity_um_s",
        metavar="NAME",
        help="velocity column of PROFILE.csv (default velocity_um_s)",
    )
    c.add_argument(
        "--piv-velocity-sd-col",
        metavar="NAME",
        help="per-point standard deviations of the velocity "
        "(default: the column velocity_sd_um_s if present)",
    )
    c.add_argument(
        "--time-unit", choices=("ms", "s", "min"), default="s", help="unit of the times (default s)"
    )
    c.add_argument(
        "--length-unit",
        choices=("um", "px"),
        default="um",
        help="unit of radii and distances (default um; px needs --pixel-size-um); velocities are "
        "in "
        "length unit per time unit",
    )
    c.add_argument(
        "--pixel-size-um",
        type=float,
        metavar="UM",
        help="size of a pixel in um (with --length-unit px)",
    )
    c.add_argument(
        "--cut-time",
        type=float,
        default=0.0,
        metavar="TIME",
        help="time of the cut in the files' time unit, subtracted from every time (default 0)",
    )
    frames_to_fit(c)  # --until-max, --until-s
    f.add_argument(
        "--loss",
        choices=("linear", "soft_l1", "cauchy"),
        default="linear",
        help="linear: least squares; soft_l1, cauchy: robust to outliers (flagged in the output)",
    )
    k = f.add_argument_group(
        "what is known before the fit",
        "Names and units: R0_um (um), sigma (tension / G), "
        "lambda (viscous length / R0), T_s (s), G_pa (Pa; not in the model: for the "
        "absolute eta, zeta and tension). With several wounds: viscous_length_um (um), "
        "tension_over_G, zeta_over_G_s_per_um2 (s/um^2), R0_um[NAME] or R0_um[K] (wound NAME "
        "or the K-th, from 1) and G_pa. Repeat an option for several parameters.",
    )
    k.add_argument(
        "--fix",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="hold a parameter fixed, e.g. --fix R0_um=10 (the radius of the cut), --fix G_pa=1000",
    )
    k.add_argument(
        "--bound",
        action="append",
        default=[],
        metavar="NAME=MIN:MAX",
        help="bound a parameter, either side may be empty, e.g. --bound lambda=0:5, --bound T_s=1:",
    )
    k.add_argument(
        "--prior",
        action="append",
        default=[],
        metavar="NAME=MEAN:SD",
        help="a Gaussian prior (mean, standard deviation), e.g. --prior G_pa=1200:200 (AFM), "
        "--prior T_s=8:2; it enters chi^2 as ((value - MEAN) / SD)^2",
    )
    add_lab_file_arguments(f)  # Fiji tables, PIVlab and OpenPIV fields (lab.py)
    f.set_defaults(run=fit_command)

    s = sub.add_parser(
        "sweep",
        help="outputs over a lambda x sigma x R_inf grid (dimensionless by default)",
        formatter_class=HelpFormatter,
        description="Columns lambda, sigma, R_inf, time, wound_radius, "
        "edge_velocity (lengths in R0, times in T); with --R0-um and --T-s: time_s, "
        "wound_radius_um, "
        "edge_velocity_um_s.",
    )
    s.add_argument(
        "--lambda",
        dest="lam",
        required=True,
        metavar="L1,L2,..",
        help="viscous length / R0 (dimensionless, >= 0)",
    )
    s.add_argument("--sigma", required=True, metavar="S1,S2,..", help="tension / G (dimensionless)")
    s.add_argument(
        "--R-inf",
        dest="r_inf",
        required=True,
        metavar="R1,R2,..",
        help="outer radius / R0 (dimensionless, > 1)",
    )
    s.add_argument(
        "--times", required=True, metavar="T1,T2,..", help="in T, or in s with --R0-um and --T-s"
    )
    s.add_argument(
        "--R0-um",
        type=float,
        help="radius of the cut in um (with --T-s: physical units; default: none, lengths in R0)",
    )
    s.add_argument(
        "--T-s",
        type=float,
        help="time scale zeta R0^2 / 4G in s (with --R0-um; default: none, times in T)",
    )
    s.add_argument(
        "--csv",
        required=True,
        metavar="OUT.csv",
        help="the table (every number with the shortest digits that read back exactly)",
    )
    s.add_argument("--parquet", metavar="OUT.parquet", help="the table as Parquet (pyarrow)")
    s.add_argument(
        "--plot",
        metavar="OUT.png",
        help="opening fraction R(t) coloured by lambda, half-opening time",
    )
    s.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="a Dask scheduler (tcp://host:port); default: local processes",
    )
    s.add_argument("--processes", type=int, help="local processes (default: all cores)")
    s.set_defaults(run=sweep_command)

    m = sub.add_parser(
        "simulate",
        help="radius, edge velocity (and profiles) in um and s: a table, or CSV",
        formatter_class=HelpFormatter,
        description="Give the dimensionless set (--lambda, --sigma, "
        "--T-s) or the material set (--G-pa, --eta-pa-s, --zeta-pa-s-per-um2, --tension-pa): "
        "lambda = 2 sqrt(eta / zeta) / R0, sigma = tension / G, T = zeta R0^2 / (4 G). Prints a "
        "table "
        "(time_s, radius_um, edge_velocity_um_s; with --radii-um also r_um, displacement_um, "
        "velocity_um_s) or writes it to --csv.",
    )
    m.add_argument(
        "--lambda", dest="lam", type=float, help="viscous length / R0 (dimensionless set)"
    )
    m.add_argument("--sigma", type=float, help="tension / G (dimensionless set)")
    m.add_argument(
        "--T-s", type=float, help="time scale zeta R0^2 / (4 G) in s (dimensionless set)"
    )
    m.add_argument(
        "--G-pa", type=float, help="shear modulus in Pa (material set, or with --edge-stress-pa)"
    )
    m.add_argument("--eta-pa-s", type=float, help="viscosity in Pa s (material set)")
    m.add_argument(
        "--zeta-pa-s-per-um2", type=float, help="substrate friction in Pa s/um^2 (material set)"
    )
    m.add_argument(
        "--tension-pa",
        type=float,
        help="homeostatic tension (edge stress before the cut) in Pa (material set)",
    )
    m.add_argument("--R0-um", type=float, required=True, help="radius of the cut (um)")
    m.add_argument(
        "--outer-radius-um", type=float, required=True, help="outer radius of the tissue (um)"
    )
    m.add_argument(
        "--times",
        metavar="T1,T2,..",
        help="times in s since the cut (default: --points from 0 to --t-end)",
    )
    m.add_argument("--t-end", type=float, default=60.0, help="last time (s)")
    m.add_argument("--points", type=int, default=61, help="number of times from 0 to --t-end")
    m.add_argument(
        "--radii-um", metavar="R1,R2,..", help="current distances from the wound centre (um)"
    )
    m.add_argument(
        "--edge-stress-pa",
        type=float,
        help="a constant stress at the wound edge (Pa; default: none, a free edge); needs --G-pa",
    )
    m.add_argument(
        "--csv",
        metavar="OUT.csv",
        help="write the table here (every number with the shortest digits "
        "that read back exactly) instead of printing it (6 significant digits)",
    )
    m.add_argument(
        "--plot", metavar="OUT.png", help="radius and edge velocity against time (and the profiles)"
    )
    m.set_defaults(run=simulate_command)
    return top


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    from .._native import NativeLibraryMissing
    from ..inputs.columns import InputError

    try:
        code = args.run(args) or 0
    except (
        BrokenPipeError
    ):  # the reader of a printed table stopped (| head): not an error of the input
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except (InputError, ValueError, OSError, NativeLibraryMissing) as e:
        message = " ".join(str(e).split())
        print(f"wound-opening {args.command}: error: {message}", file=sys.stderr)
        return 2
    return code
