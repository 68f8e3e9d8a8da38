"""The command line's lab files: Fiji Results tables as the radius files, PIVlab or OpenPIV
folders as the velocity profiles, the wound centre and the rings (inputs/fiji.py, piv.py,
centre.py, rings.py). options.py calls `add_lab_file_arguments(parser)` and, in its fit,
`read_lab_inputs(args)`: None when no lab-file option is given (the plain CSV readers run),
else every wound's (name, RadiusSeries, VelocityProfile or None) in order."""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass


@dataclass(frozen=True)
class Cut:
    """How the cut is placed on a movie's clock. The times read are counted from frame
    `origin` (n at (n - origin) x the frame interval); after it the cut is `fixed_s` (given)
    or fitted in [0, `bound_s`] (the nuisance cut_s, each wound's of several), or, both None, at the
    origin itself; `text` says which, as the summary, the JSON and the report print it."""

    origin: float
    fixed_s: float | None
    bound_s: float | None
    text: str


@dataclass(frozen=True)
class LabInputs:
    names: list
    radii: list
    profiles: list  # one per wound, or empty
    cut: Cut | None = None  # the movie's clock (frames), None for times read from a file

    @property
    def series(self) -> dict:
        return dict(zip(self.names, self.radii))


def add_lab_file_arguments(parser) -> None:
    g = parser.add_argument_group(
        "a lab's own files (Fiji, PIVlab, OpenPIV; docs/fitting.md, 'Lab files')",
        "Frames number the movie from 1: frame n is at (n - N) x FRAME_INTERVAL_S after frame "
        "N, the last before the cut; one wound's cut is then fitted between frames N and N + 1 "
        "(cut_s, docs/fitting.md). --length-unit px with --pixel-size-um converts areas in px^2 "
        "and PIV positions in px.",
    )
    g.add_argument(
        "--area-col",
        metavar="NAME",
        help="RADIUS.csv files are Fiji/ImageJ Results tables: the column of the wound's area "
        "(px^2 or um^2; radius = sqrt(area / pi)), e.g. Area",
    )
    g.add_argument(
        "--frame-col",
        metavar="NAME",
        help="the frame column of a Fiji table (default: Frame, else Slice)",
    )
    g.add_argument(
        "--frame-interval-s", type=float, metavar="S", help="time between two frames (s)"
    )
    g.add_argument(
        "--cut-after-frame",
        type=float,
        metavar="N",
        help="the number of the last frame recorded before the cut: frames 1..N are skipped; an "
        "integer: the cut is fitted between frames N and N + 1 (one wound; several wounds: taken "
        "at frame N); a fraction (3.2: 0.2 frame intervals after frame 3): the cut given",
    )
    g.add_argument(
        "--piv",
        action="append",
        metavar="FOLDER|'GLOB'",
        help="PIVlab or OpenPIV text files, one per frame pair (a folder, or a glob in quotes); "
        "with several wounds repeat it once per wound in their order",
    )
    g.add_argument(
        "--piv-format",
        choices=("auto", "pivlab", "openpiv"),
        default="auto",
        help="the program that wrote the PIV files (auto: told by their first lines)",
    )
    g.add_argument(
        "--piv-units",
        default="px,px/s",
        metavar="LENGTH,VELOCITY",
        help="units of OpenPIV files, which do not state them: LENGTH px, um, mm or m; "
        "VELOCITY LENGTH/s or LENGTH/frame (PIVlab files name theirs)",
    )
    g.add_argument(
        "--piv-window",
        default="32px",
        metavar="SIZE",
        help="the side of the PIV interrogation window of the final pass, e.g. 32px (with "
        "--pixel-size-um) or 6.4um (default: 32px, OpenPIV's tutorial and PIVlab's last pass; "
        "files in um without a pixel size: 4 grid steps, OpenPIV's window 32 with overlap 24)",
    )
    g.add_argument(
        "--piv-first-frame",
        type=int,
        default=1,
        metavar="N",
        help="the number of the first frame of the first PIV frame pair",
    )
    g.add_argument(
        "--piv-pair-step",
        type=int,
        default=1,
        metavar="K",
        help="the number of frames from one pair's first frame to the next's (1 for pairs 1-2, "
        "2-3; 2 for 1-2, 3-4)",
    )
    g.add_argument(
        "--piv-keep-interpolated",
        action="store_true",
        help="keep vectors the PIV program interpolated (dropped by default: not measured)",
    )
    g.add_argument(
        "--centre-um",
        action="append",
        metavar="X,Y",
        help="the wound centre in the PIV files' axes in um (default: estimated from the flow); "
        "one per wound or one for all",
    )
    g.add_argument(
        "--centre-px",
        action="append",
        metavar="X,Y",
        help="the wound centre in pixels (image axes, y down; needs --pixel-size-um)",
    )
    g.add_argument(
        "--ring-width-um",
        type=float,
        metavar="UM",
        help="width of the PIV rings in um (default: the PIV grid spacing)",
    )
    g.add_argument(
        "--piv-likelihood",
        choices=("rings", "vectors"),
        default="rings",
        help="rings: ring means with their scatter as the noise; vectors: every vector "
        "(slower, docs/fitting.md)",
    )


def _lab_mode(args) -> bool:
    return bool(args.area_col or args.piv)


def cut_of(args, several: bool) -> Cut | None:
    """The cut on the movie's clock from --cut-after-frame N (or, for a Fiji table,
    --cut-time on ImageJ's clock, frame 1 at 0 s: N = 1 + cut time / frame interval). A Fiji
    table of one wound: times from frame floor(N), the cut fitted in [0, frame interval] for
    an integer N, else fixed at the fraction of N; with several wounds each wound's
    (cut_s[NAME]). A radius file with its own times: times from the cut at frame N. None without the
    options (the readers refuse)."""
    from ..inputs.columns import InputError

    dt, fiji = args.frame_interval_s, bool(args.area_col)
    if fiji and args.cut_time:
        if args.cut_after_frame is not None:
            raise InputError(
                "give the cut as --cut-after-frame or as --cut-time (s, frame 1 at 0 s), not both"
            )
        if dt is None or not (math.isfinite(args.cut_time) and dt > 0):
            return None
        n_cut, given = 1.0 + args.cut_time / dt, f"--cut-time {args.cut_time:g} s"
    else:
        n_cut, given = args.cut_after_frame, f"--cut-after-frame {args.cut_after_frame:g}"
    if n_cut is None or dt is None:
        return None
    if not (math.isfinite(n_cut) and n_cut >= 0):
        raise InputError(
            f"{given}: the cut must be at or after frame 0 (the last frame before the cut, "
            "a fraction for a cut between frames)"
        )
    n = math.floor(n_cut)
    after = (n_cut - n) * dt
    if fiji:
        each = " for each wound (cut_s[NAME])" if several else ""
        if n_cut == n:
            return Cut(
                n,
                None,
                dt,
                f"after frame {n} ({given}): fitted between frames {n} and {n + 1}{each} (cut_s "
                f"in [0, {dt:g}] s after frame {n})",
            )
        return Cut(n, after, None, f"{given}: {after:.6g} s after frame {n} (cut_s fixed{each})")
    why = "the PIV pairs"
    if n_cut == n:
        return Cut(n_cut, None, None, f"at frame {n} ({given}; {why}, not fitted)")
    return Cut(n_cut, None, None, f"{given}: {after:.6g} s after frame {n} ({why})")


def read_lab_inputs(args):
    """LabInputs of the lab-file options, or None without them (module docstring)."""
    if not _lab_mode(args):
        return None
    from ..inputs.columns import InputError, float_list
    from ..inputs.lab_files import read_radius

    if args.piv and args.profile:
        raise InputError("give the velocities either as --profile CSV files or as --piv fields")
    if args.wound_col:
        raise InputError("--wound-col reads a long CSV table, not Fiji tables or PIV fields")
    outer = float_list(args.outer_radius_um, "--outer-radius-um")
    cut = cut_of(args, bool(args.wound_col) or len(args.radius_csv) > 1)
    origin = None if cut is None else cut.origin
    if args.area_col:
        radii = [_fiji(args, path, origin) for path in args.radius_csv]
    else:
        radii = [
            read_radius(
                path,
                time_col=args.time_col,
                radius_col=args.radius_col,
                sd_col=args.radius_sd_col,
                noise_um=args.radius_noise_um,
                time_unit=args.time_unit,
                length_unit=args.length_unit,
                pixel_size_um=args.pixel_size_um,
                cut_time=args.cut_time,
            )
            for path in args.radius_csv
        ]
    names = list(args.radius_csv)
    profiles = []
    if args.piv:
        if len(args.piv) != len(radii):
            raise InputError(
                f"--piv: {len(args.piv)} fields for {len(radii)} wounds: give one per wound, in "
                "the order of the radius files"
            )
        centres = _centres(args, len(radii))
        for k, (where, radius) in enumerate(zip(args.piv, radii)):
            profiles.append(_piv(args, where, radius, outer[k % len(outer)], centres[k], origin))
    for s in radii + profiles:
        for f in s.files:
            for note in f.notes:
                print(f"note: {note}", file=sys.stderr)
    return LabInputs(names, radii, profiles, cut)


def _fiji(args, path, origin):
    from ..inputs.fiji import read_fiji

    if args.time_unit != "s":
        from ..inputs.columns import InputError

        raise InputError(
            "a Fiji table's times come from its frames: give --frame-interval-s and "
            "--cut-after-frame (or --cut-time in s, frame 1 at 0 s), not --time-unit"
        )
    return read_fiji(
        path,
        area_col=args.area_col,
        frame_col=args.frame_col,
        frame_interval_s=args.frame_interval_s,
        cut_after_frame=args.cut_after_frame if origin is None else origin,
        length_unit=args.length_unit,
        pixel_size_um=args.pixel_size_um,
        noise_um=args.radius_noise_um,
    )


def _centres(args, n: int) -> list:
    from ..inputs.centre import Centre, parse_point
    from ..inputs.columns import InputError

    if args.centre_um and args.centre_px:
        raise InputError("give the wound centre in um or in px, not both")
    given = args.centre_um or args.centre_px or []
    option = "--centre-um" if args.centre_um else "--centre-px"
    if given and len(given) not in (1, n):
        raise InputError(f"{option}: {len(given)} centres for {n} wounds: one for all or one each")
    if not given:
        return [None] * n
    scale = 1.0
    if args.centre_px:
        if args.pixel_size_um is None:
            raise InputError("--centre-px needs --pixel-size-um")
        scale = args.pixel_size_um
    points = [parse_point(g, option) for g in given]
    return [Centre(scale * p[0], scale * p[1]) for p in (points * n)[:n]]


def _piv(args, where, radius, outer, centre, origin):
    from ..inputs.columns import InputError
    from ..inputs.piv import Frames, read_field
    from ..inputs.rings import field_profile

    if args.frame_interval_s is None or origin is None:
        raise InputError("--piv needs --frame-interval-s and --cut-after-frame (the pairs' times)")
    units = tuple(s.strip() for s in args.piv_units.split(","))
    if len(units) != 2:
        raise InputError(f"--piv-units {args.piv_units!r}: expected LENGTH,VELOCITY")
    frames = Frames(args.frame_interval_s, origin, args.piv_first_frame, args.piv_pair_step)
    field = read_field(
        where,
        frames,
        pixel_size_um=args.pixel_size_um,
        program=args.piv_format,
        units=units,
        keep_interpolated=args.piv_keep_interpolated,
    )
    profile, _ = field_profile(
        field,
        radius,
        outer,
        centre=centre,
        ring_width_um=args.ring_width_um,
        likelihood=args.piv_likelihood,
        noise_um_s=args.velocity_noise_um_s,
        units=units if field_is_openpiv(field) else None,
        frame_interval_s=args.frame_interval_s,
        pixel_size_um=args.pixel_size_um,
        window_um=window_of(args.piv_window, args.pixel_size_um, field),
    )
    return profile


def window_of(text: str, pixel_size_um, field) -> float:
    """The interrogation window's side [um] from --piv-window (32px, 6.4um)."""
    from ..inputs.columns import InputError

    value, unit = text.strip()[:-2], text.strip()[-2:]
    try:
        size = float(value)
    except ValueError:
        size = float("nan")
    if unit not in ("px", "um") or not (math.isfinite(size) and size > 0):
        raise InputError(f"--piv-window {text!r}: expected a size such as 32px or 6.4um")
    if unit == "um":
        return size
    if pixel_size_um is not None:
        return size * pixel_size_um
    return 4.0 * field.spacing_um  # um files of OpenPIV's tutorial (window 32, overlap 24)


def field_is_openpiv(field) -> bool:
    """Whether the field's files are OpenPIV's (their units as --piv-units says)."""
    return any("OpenPIV" in f.kind for f in field.files)
