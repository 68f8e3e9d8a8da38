"""What each command of `wound-opening` (options.py) does with its parsed arguments: `fit` (one
wound, or several sharing a material), `sweep` and `simulate`. Each prints its results and
writes the files asked for; bad input raises (InputError, ValueError, OSError), which the
command line turns into one line and exit code 2.

Before a fit, the frames to fit (--until-max, --until-s: the opening
alone, inputs/truncate.py; the result's warnings say which lines were fitted and which
dropped) and the recording in seconds, with the unit named in the message
(fitting/recording.py); the cut time against the file's own times is checked as the file is
read (inputs/lab_files.py, check_cut)."""

from __future__ import annotations

import math
import shlex
import sys

from ..inputs.columns import InputError
from ..results.settings import raw_files


def fit_command(args) -> None:
    from ..fitting.objective import NUISANCES, wound_coordinates
    from ..fitting.parameters import from_options
    from ..fitting.single import fit
    from ..inputs.columns import InputError, float_list
    from ..inputs.lab_files import read_profile, read_radius
    from .lab import read_lab_inputs

    units = dict(
        time_unit=args.time_unit,
        length_unit=args.length_unit,
        pixel_size_um=args.pixel_size_um,
        cut_time=args.cut_time,
    )
    outer = float_list(args.outer_radius_um, "--outer-radius-um")
    profiles = [
        read_profile(
            p,
            time_col=args.piv_time_col,
            r_col=args.piv_r_col,
            velocity_col=args.piv_velocity_col,
            sd_col=args.piv_velocity_sd_col,
            noise_um_s=args.velocity_noise_um_s,
            **units,
        )
        for p in args.profile or []
    ]
    lab = read_lab_inputs(args)  # Fiji tables and PIV fields (lab.py); None without them
    profiles = lab.profiles if lab else profiles
    if args.wound_col or len(args.radius_csv) > 1:
        return _fit_wounds(args, units, outer, profiles, lab)
    if len(outer) > 1 or len(profiles) > 1:
        raise InputError(
            f"one radius file (one wound) takes one outer radius and at most one --profile, got "
            f"{len(outer)} and {len(profiles)}"
        )
    radius = (lab.radii[0] if lab else None) or read_radius(
        args.radius_csv[0],
        time_col=args.time_col,
        radius_col=args.radius_col,
        sd_col=args.radius_sd_col,
        noise_um=args.radius_noise_um,
        **units,
    )
    radius, profile = prepare(args, radius, profiles[0] if profiles else None)
    names = wound_coordinates(outer[0], NUISANCES)  # a nuisance named joins the fit
    fix, bound = cut_options(args, lab)
    params = from_options(names, fix, bound, outline_prior(args))
    result = fit(radius, profile, outer_radius_um=outer[0], loss=args.loss, params=params)
    result.settings = settings_of(args, series=(radius, profile), lab=lab)
    print(result.summary())
    _print_cut(result.settings)

    def report(path):
        from ..results.report import write_report

        write_report(path, result, radius, profile, command=_command_line())

    def figure(path):
        from ..results.plots import fit_figure

        fit_figure(result, radius, profile, path)

    return _outputs(args, result, report, figure)


def cut_options(args, lab) -> tuple[list, list]:
    """--fix and --bound with the cut of a movie's clock (lab.Cut) added as the nuisance
    cut_s: fixed where given, bounded by the frame interval where only "after frame N" is
    known; the user's own --fix/--bound/--prior cut_s=... wins."""
    fix, bound = list(args.fix), list(args.bound)
    cut = lab.cut if lab else None
    if cut is None or _names_cut(args):
        return fix, bound
    if cut.fixed_s is not None:
        fix.append(f"cut_s={cut.fixed_s!r}")
    elif cut.bound_s is not None:
        bound.append(f"cut_s=0:{cut.bound_s!r}")
    return fix, bound


def tissue_options(args, lab, every) -> tuple[list, list, list]:
    """--fix, --bound and --prior of a fit of several wounds with the nuisances of the lab's
    files (tissue.TissueNuisances `every`: the wounds that can have each) added as for one
    wound: each wound's cut_s[NAME] (cut_options), one outline offset for the wounds' area
    tables (one segmentation) and each field's piv_gain[NAME] (outline_prior). The user's
    own option of a name wins."""
    fix, bound = list(args.fix), list(args.bound)
    cut = lab.cut if lab else None
    for name in every.cut if cut is not None else ():
        if _names_cut(args, f"cut_s[{name}]"):
            continue
        if cut.fixed_s is not None:
            fix.append(f"cut_s[{name}]={cut.fixed_s!r}")
        elif cut.bound_s is not None:
            bound.append(f"cut_s[{name}]=0:{cut.bound_s!r}")
    prior = [p for p in outline_prior(args) if not p.startswith("piv_gain=")]
    if getattr(args, "piv", None):
        prior += [
            f"piv_gain[{name}]=1:{PIV_GAIN_SD!r}"
            for name in every.gain
            if not _names_cut(args, f"piv_gain[{name}]")
        ]
    return fix, bound, prior


def _names_cut(args, name: str = "cut_s") -> bool:
    options = [*args.fix, *args.bound, *args.prior]
    return any(o.split("=")[0].strip() == name for o in options)


#: The PIV field's gain's prior standard deviation (objective.PIV_GAIN): a PIV program's
#: velocities are good to some 10 % (OpenPIV's tutorial read 4-11 % high, or 9 % low, on
#: movies rendered from the exact solution).
PIV_GAIN_SD = 0.1


def outline_prior(args) -> list:
    """--prior with the outline's offset of an area table (a threshold's outline: Fiji,
    ImageJ) added, 0 +- one pixel (fiji.PIXEL_UM without --pixel-size-um): a threshold puts
    the edge a fraction of a pixel to a pixel off, and from the radius alone that offset moves
    R0 unseen; and, with PIV files (--piv), the field's gain, 1 +- PIV_GAIN_SD. The user's
    own --fix/--bound/--prior of either name wins."""
    prior = list(args.prior)
    if getattr(args, "piv", None) and not _names_cut(args, "piv_gain"):
        prior.append(f"piv_gain=1:{PIV_GAIN_SD!r}")
    if not getattr(args, "area_col", None) or _names_cut(args, "outline_offset_um"):
        return prior
    from ..inputs.fiji import PIXEL_UM

    sd = args.pixel_size_um if args.pixel_size_um else PIXEL_UM
    return prior + [f"outline_offset_um=0:{sd!r}"]


def _print_cut(settings: dict) -> None:
    if settings.get("cut"):
        print(f"cut: {settings['cut']}")


def _outputs(args, result, report, figure) -> int:
    """The fit's files: --json, --report (`report(path)`), --plot (`figure(path)`; a failed
    fit's report and figure show the model where it stopped and why) and, if it converged,
    --export; the exit code (1: not converged). The report and the figure import matplotlib
    only when asked for."""
    if args.json:
        with open(args.json, "w") as f:
            f.write(result.to_json() + "\n")
    if args.report:
        report(args.report)
        print(f"report -> {args.report}")
    if args.plot:
        figure(args.plot)
    if not result.converged:
        print(
            "the fit did not converge"
            + (": the figure shows the model where it stopped" if args.plot else "")
            + ("; no export" if args.export else ""),
            file=sys.stderr,
        )
        return 1
    if args.export:
        print("exported: " + ", ".join(map(str, result.export(args.export))))
    return 0


def _command_line() -> str:
    return "wound-opening " + " ".join(shlex.quote(a) for a in sys.argv[1:])


def _fit_wounds(args, units, outer, profiles, lab=None) -> int:
    """Several wounds of one tissue: one radius file each, or one long table with --wound-col."""
    from ..fitting.wounds import Wound, fit_wounds
    from ..inputs.columns import InputError
    from ..inputs.lab_files import read_radius, read_wounds

    columns = dict(
        time_col=args.time_col,
        radius_col=args.radius_col,
        sd_col=args.radius_sd_col,
        noise_um=args.radius_noise_um,
        **units,
    )
    if lab:
        series = lab.series
    elif args.wound_col:
        if len(args.radius_csv) > 1:
            raise InputError(
                f"--wound-col reads one long table with every wound: {len(args.radius_csv)} files "
                f"given"
            )
        series = read_wounds(args.radius_csv[0], wound_col=args.wound_col, **columns)
    else:
        series = {path: read_radius(path, **columns) for path in args.radius_csv}
    names = list(series)
    if len(outer) not in (1, len(names)):
        raise InputError(
            f"--outer-radius-um: {len(outer)} values for {len(names)} wounds "
            f"({', '.join(names)}): give "
            "one for all or one per wound, in this order"
        )
    if profiles and len(profiles) != len(names):
        raise InputError(
            f"--profile: {len(profiles)} files for {len(names)} wounds ({', '.join(names)}): give "
            f"one "
            "per wound, in this order, or none"
        )
    series, profiles = prepare_wounds(args, series, profiles)
    from ..fitting.parameters import from_options
    from ..fitting.tissue import TissueNuisances
    from ..fitting.wounds import tissue_coordinates

    wounds = [
        Wound(s, outer[k % len(outer)], profiles[k] if profiles else None, name)
        for k, (name, s) in enumerate(series.items())
    ]
    every = TissueNuisances.every(names, [w.profile is not None for w in wounds])
    coordinates = tissue_coordinates(names, [w.outer_radius_um for w in wounds], every)
    params = from_options(coordinates, *tissue_options(args, lab, every))
    result = fit_wounds(wounds, loss=args.loss, params=params)
    result.settings = settings_of(args, names, [*series.values(), *(profiles or [])], lab)
    print(result.summary())
    _print_cut(result.settings)

    def report(path):
        from ..results.tissue_report import write_report

        write_report(path, result, wounds, command=_command_line())

    def figure(path):
        from ..results.tissue_plots import tissue_figure

        tissue_figure(result, path)

    return _outputs(args, result, report, figure)


def sweep_command(args) -> None:
    from ..inputs.columns import float_list
    from ..sweeping import sweep

    grid = {
        "lambda": float_list(args.lam, "--lambda"),
        "sigma": float_list(args.sigma, "--sigma"),
        "R_inf": float_list(args.r_inf, "--R-inf"),
    }
    df = sweep(
        grid,
        times=float_list(args.times, "--times"),
        R0_um=args.R0_um,
        T_s=args.T_s,
        scheduler=args.scheduler,
        processes=args.processes,
    )
    df.to_csv(args.csv, index=False)  # shortest digits that read back to the same doubles
    if args.parquet:
        df.to_parquet(args.parquet)
    if args.plot:
        from ..results.sim_plots import sweep_figure

        sweep_figure(df, args.plot)
    print(f"{len(df)} rows -> {args.csv}")


def simulate_command(args) -> None:
    import numpy as np

    from ..inputs.columns import float_list
    from ..model import simulate

    times = (
        float_list(args.times, "--times") if args.times else np.linspace(0, args.t_end, args.points)
    )
    radii = float_list(args.radii_um, "--radii-um") if args.radii_um else None
    sim = simulate(
        times,
        lam=args.lam,
        sigma=args.sigma,
        R0_um=args.R0_um,
        T_s=args.T_s,
        outer_radius_um=args.outer_radius_um,
        edge_stress_pa=args.edge_stress_pa,
        G_pa=args.G_pa,
        eta_pa_s=args.eta_pa_s,
        zeta_pa_s_per_um2=args.zeta_pa_s_per_um2,
        tension_pa=args.tension_pa,
        radii_um=radii,
    )
    frame = sim.to_frame()
    if args.csv:
        frame.to_csv(args.csv, index=False)  # shortest digits that read back to the same doubles
    else:
        print(frame.to_string(index=False, float_format=lambda x: f"{x:.6g}"))
    if args.plot:
        from ..results.sim_plots import simulate_figure

        simulate_figure(sim, args.plot)
    if args.csv:
        print(f"{len(times)} times -> {args.csv}")


def settings_of(args, wounds=None, series=(), lab=None) -> dict:
    """The settings a fit's report prints (results/settings.py says the keys) that the
    command line's `args` (options.parser's fit) give; `wounds`: the names
    of the wounds in order (several radius files or a long table), None for one wound;
    `series`: the series read (their raw files go under "raw_files")."""
    radius_cols = {"time": args.time_col, "radius": args.radius_col}
    if args.radius_sd_col:
        radius_cols["sd"] = args.radius_sd_col
    if getattr(args, "wound_col", None):
        radius_cols["wound"] = args.wound_col
    piv_cols = {"time": args.piv_time_col, "r": args.piv_r_col, "velocity": args.piv_velocity_col}
    if args.piv_velocity_sd_col:
        piv_cols["sd"] = args.piv_velocity_sd_col
    files = []
    names = list(wounds) if wounds else [None] * len(args.radius_csv)
    if getattr(args, "wound_col", None):
        files.append(
            {"wound": None, "data": "radius", "path": args.radius_csv[0]} | {"columns": radius_cols}
        )
    else:
        for name, path in zip(names, args.radius_csv):
            files.append({"wound": name, "data": "radius", "path": path, "columns": radius_cols})
    for k, path in enumerate(args.profile or []):
        name = names[k] if k < len(names) else None
        files.append({"wound": name, "data": "velocity profile", "path": path, "columns": piv_cols})
    out = {
        "cut_time": args.cut_time,
        "time_unit": args.time_unit,
        "length_unit": args.length_unit,
        "pixel_size_um": args.pixel_size_um,
        "outer_radius_um": args.outer_radius_um,
        "files": files,
    }
    if lab is not None and lab.cut is not None:
        out["cut"] = lab.cut.text
        if wounds is None and _names_cut(args) and lab.cut.fixed_s is None:
            n = math.floor(lab.cut.origin)
            out["cut"] = f"after frame {n}: cut_s as the options give it (s after frame {n})"
        if args.area_col:  # a Fiji table: the frames give the times
            out.pop("cut_time")
    for key in ("frame_interval_s", "centre_um", "centre_px"):
        value = getattr(args, key, None)
        if value is not None:
            out[key] = value
    raw = raw_files(series)
    if raw:
        out["raw_files"] = raw
    return out


def prepare(args, radius, profile=None):
    """(radius, profile) of the frames to fit (--until-max, --until-s), the recording checked
    in the unit given (InputError: a unit mistake, a radius that shrinks again)."""
    from ..fitting.recording import check_recording
    from ..inputs.truncate import until_max, until_s

    if args.until_max and args.until_s is not None:
        raise InputError("--until-max and --until-s choose the frames both: give one")
    try:
        if args.until_s is not None:
            radius, profile = until_s(radius, profile, args.until_s)
        elif args.until_max:
            radius, profile = until_max(radius, profile)
        if getattr(args, "area_col", None):
            check_frame_interval(radius, args.frame_interval_s)
        check_recording(radius, profile, time_unit=args.time_unit)
    except ValueError as e:
        raise InputError(f"{radius.source or 'radius'}: {e}") from None
    return radius, profile


def prepare_wounds(args, series: dict, profiles: list):
    """`prepare` for each wound of a several-wound fit: ({name: radius}, [profile])."""
    out, kept = {}, []
    for k, (name, radius) in enumerate(series.items()):
        try:
            out[name], p = prepare(args, radius, profiles[k] if k < len(profiles) else None)
        except InputError as e:
            raise InputError(f"wound {name}: {e}") from None
        kept.append(p)
    return out, kept[: len(profiles)]


#: A frame interval typed in another unit than s: (factor to seconds, what was typed).
INTERVAL_MISTAKES = (
    (1e-3, "the interval in ms typed as s"),
    (1e3, "the interval divided by 1000 once too often"),
    (60.0, "the interval in min typed as s"),
)


def check_frame_interval(radius, frame_interval_s: float) -> None:
    """Refuse (ValueError) a Fiji table whose times, made from its frames and
    --frame-interval-s, are no recording of a passive opening (fitting/recording.py's bounds),
    naming the option and the interval in s that makes it a usual one (not --time-unit: a
    Fiji table has no time column)."""
    from ..fitting.recording import FRAME_S, LAST_S, QUIET_FRAME_S, QUIET_LAST_S, sampling
    from ..fitting.recording import duration as _s

    dt, _, last = sampling(radius.times_s)
    if (dt is None or FRAME_S[0] <= dt <= FRAME_S[1]) and LAST_S[0] <= last <= LAST_S[1]:
        return
    fixes = [
        f"{what}? (--frame-interval-s {frame_interval_s * f:.6g}: frames {_s(dt * f)} apart)"
        for f, what in INTERVAL_MISTAKES
        if dt is not None
        and QUIET_FRAME_S[0] <= dt * f <= QUIET_FRAME_S[1]
        and QUIET_LAST_S[0] <= last * f <= QUIET_LAST_S[1]
    ]
    raise ValueError(
        f"--frame-interval-s {frame_interval_s:g} makes the frames {_s(dt)} apart and the last "
        f"{_s(last)} after the cut: a passive opening after a laser cut is recorded over "
        f"seconds to minutes (accepted: frame interval {_s(FRAME_S[0])} to {_s(FRAME_S[1])}, "
        f"last time {_s(LAST_S[0])} to {_s(LAST_S[1])}); give the time between two frames in s"
        + (": " + " or ".join(fixes) if fixes else "")
    )
