"""The command line's lab files: Fiji Results tables as the radius files, PIVlab or OpenPIV
folders as the velocity profiles, the wound centre and the rings (inputs/fiji.py, piv.py,
centre.py, rings.py). options.py calls `add_lab_file_arguments(parser)` and, in its fit,
`read_lab_inputs(args)`: None when no lab-file option is given (the plain CSV readers run),
else every wound's (name, RadiusSeries, VelocityProfile or None) in order."""

from __future__ import annotations

import sys
from dataclasses import dataclass


@dataclass(frozen=True)
class LabInputs:
    names: list
    radii: list
    profiles: list  # one per wound, or empty

    @property
    def series(self) -> dict:
        return dict(zip(self.names, self.radii))


def add_lab_file_arguments(parser) -> None:
    g = parser.add_argument_group(
        "a lab's own files (Fiji, PIVlab, OpenPIV; docs/fitting.md, 'Lab files')",
        "Frames number the movie from 1: frame n is at (n - CUT_AFTER_FRAME) x FRAME_INTERVAL_S "
        "after the cut. --length-unit px with --pixel-size-um converts areas in px^2 and PIV "
        "positions in px.",
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
        type=int,
        metavar="N",
        help="the number of the last frame recorded before the cut: frames 1..N are skipped",
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
    if args.area_col:
        radii = [_fiji(args, path) for path in args.radius_csv]
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
            profiles.append(_piv(args, where, radius, outer[k % len(outer)], centres[k]))
    for s in radii + profiles:
        for f in s.files:
            for note in f.notes:
                print(f"note: {note}", file=sys.stderr)
    return LabInputs(names, radii, profiles)


def _fiji(args, path):
    from ..inputs.fiji import read_fiji

    if args.time_unit != "s" or args.cut_time:
        from ..inputs.columns import InputError

        raise InputError(
            "a Fiji table's times come from its frames: give --frame-interval-s and "
            "--cut-after-frame, not --time-unit or --cut-time"
        )
    return read_fiji(
        path,
        area_col=args.area_col,
        frame_col=args.frame_col,
        frame_interval_s=args.frame_interval_s,
        cut_after_frame=args.cut_after_frame,
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


def _piv(args, where, radius, outer, centre):
    from ..inputs.columns import InputError
    from ..inputs.piv import Frames, read_field
    from ..inputs.rings import field_profile

    if args.frame_interval_s is None or args.cut_after_frame is None:
        raise InputError("--piv needs --frame-interval-s and --cut-after-frame (the pairs' times)")
    units = tuple(s.strip() for s in args.piv_units.split(","))
    if len(units) != 2:
        raise InputError(f"--piv-units {args.piv_units!r}: expected LENGTH,VELOCITY")
    frames = Frames(
        args.frame_interval_s, args.cut_after_frame, args.piv_first_frame, args.piv_pair_step
    )
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
    )
    return profile
