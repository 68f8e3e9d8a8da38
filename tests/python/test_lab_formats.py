"""Layouts the programs really write beyond the defaults of test_lab_readers.py, each checked
against the program's own code: PIVlab's info line (+export/file_save.m: the conversion
factors, a displacements-only calibration writing m/frame under "u [m/s]"), OpenPIV files
of every openpiv.tools.save since 2011 (no heading before 0.23, "# x y u v mask" in 0.23,
"# x y u v s2n mask" late 2020, "# x y u v flags mask" since 0.24.4). Readers only, no fit."""

from __future__ import annotations

import re
from pathlib import Path

import make_lab_examples as lab
import numpy as np
import pytest
from test_lab_readers import fiji  # the Fiji reader with the fixture's settings

from wound_opening.inputs.centre import Centre, radial
from wound_opening.inputs.columns import InputError
from wound_opening.inputs.piv import Frames, read_field

R0 = 8.0
FRAMES = Frames(lab.FRAME_S, lab.CUT_AFTER, lab.PIV_FIRST, lab.PIV_STEP)
CENTRE = Centre(*(np.array(lab.CENTRE_PX) * lab.PIXEL_UM))


#: The exact radial velocities of a pair at the positions read, kept per process: the
#: OpenPIV layouts below read the same grid, and the exact values cost about 2 s a field.
_EXACT: dict = {}


def _exact_radial(k: int, dx: np.ndarray, dy: np.ndarray) -> np.ndarray:
    key = (k, dx.tobytes(), dy.tobytes())
    if key not in _EXACT:
        _EXACT[key] = lab.measured_radial(R0, lab.pair_time(k), dx, dy)
    return _EXACT[key]


def radial_error(field) -> float:
    """The largest error of the radial velocity against the exact one, relative to its max."""
    worst = 0.0
    for k in np.unique(field.pair):
        s = field.pair == k
        r, vr = radial(
            CENTRE, *(a[s] for a in (field.x_um, field.y_um, field.u_um_s, field.v_um_s))
        )
        exact = _exact_radial(int(k), field.x_um[s] - CENTRE.x_um, field.y_um[s] - CENTRE.y_um)
        worst = max(worst, float(np.max(np.abs(vr - exact)) / np.max(np.abs(exact))))
    return worst


def rewrite_pivlab(folder: Path, edit) -> None:
    """Apply `edit(lines)` to every PIVlab file's CRLF lines (info, info, headings, data)."""
    for p in folder.glob("PIVlab_*.txt"):
        lines = p.read_bytes().decode().split("\r\n")
        p.write_bytes("\r\n".join(edit(lines)).encode())


def test_a_pivlab_displacement_export_labelled_m_per_s_is_read_in_m_per_frame(tmp_path):
    """PIVlab calibrated with a time step of 0 writes displacements [m/frame] under the heading
    "u [m/s]" (file_save.m, no derivatives) and the uv factor equal to the xy one."""
    lab.write_pivlab(tmp_path, R0)

    def displacements(lines):
        xy = re.search(r"xy \(px -> m\): (\S+),", lines[1]).group(1)
        lines[1] = re.sub(r"(uv \(px/frame -> m/s\): )\S+", rf"\g<1>{xy}", lines[1])
        for i in range(3, len(lines)):
            if lines[i]:
                c = lines[i].split(",")
                c[2], c[3] = (f"{float(v) * lab.FRAME_S:.10g}" for v in c[2:4])
                lines[i] = ",".join(c)
        return lines

    rewrite_pivlab(tmp_path, displacements)
    field = read_field(str(tmp_path), FRAMES, pixel_size_um=lab.PIXEL_UM)
    assert radial_error(field) < 1e-8
    assert all("m/frame" in f.notes[0] for f in field.files)


def test_a_pivlab_time_step_other_than_the_frame_interval_is_refused(tmp_path):
    """The info line's factors give PIVlab's time step (xy / uv = 0.25 s): a frame interval
    typed in ms (250) disagrees with it and is refused, naming the step."""
    lab.write_pivlab(tmp_path, R0)
    wrong = Frames(lab.FRAME_S * 1000, lab.CUT_AFTER, lab.PIV_FIRST, lab.PIV_STEP)
    with pytest.raises(InputError, match=r"time step of 0.25 s .* --frame-interval-s is 250 s"):
        read_field(str(tmp_path), wrong, pixel_size_um=lab.PIXEL_UM)
    # without the info lines there is nothing to check against: read as the headings say
    rewrite_pivlab(tmp_path, lambda lines: lines[2:])
    assert read_field(str(tmp_path), FRAMES, pixel_size_um=lab.PIXEL_UM).files


def openpiv_as(folder: Path, out: Path, columns, heading, fmt="%.4e") -> Path:
    """The OpenPIV fixture re-saved as an older openpiv.tools.save wrote it."""
    out.mkdir()
    for p in sorted(folder.glob("exp_*.txt")):
        a = np.loadtxt(p)[:, columns]
        np.savetxt(out / p.name, a, fmt=fmt, delimiter="\t", header=heading or "")
    return out


@pytest.fixture(scope="module")
def openpiv_new(tmp_path_factory) -> Path:
    """The OpenPIV fixture as openpiv.tools.save writes it today, written once."""
    folder = tmp_path_factory.mktemp("openpiv") / "new"
    lab.write_openpiv(folder, R0)
    return folder


@pytest.mark.parametrize(
    "columns, heading, program",
    [
        ([0, 1, 2, 3, 5], None, "openpiv"),  # before 0.23: no heading, x y u v mask, %8.4f
        ([0, 1, 2, 3, 5], "x\ty\tu\tv\tmask", "auto"),  # 0.23 to 0.24.3
        ([0, 1, 2, 3, 4, 5], "x\ty\tu\tv\ts2n\tmask", "auto"),  # late 2020
    ],
)
def test_older_openpiv_files_are_read(tmp_path, openpiv_new, columns, heading, program):
    old = openpiv_as(openpiv_new, tmp_path / "old", columns, heading, fmt="%8.4f")
    if heading is None:
        with pytest.raises(InputError, match="--piv-format .*openpiv for OpenPIV files without"):
            read_field(str(old), FRAMES, pixel_size_um=lab.PIXEL_UM)
    field = read_field(str(old), FRAMES, pixel_size_um=lab.PIXEL_UM, program=program)
    new = read_field(str(openpiv_new), FRAMES, pixel_size_um=lab.PIXEL_UM)
    assert field.x_um.size == new.x_um.size  # the masked vectors dropped, the first row kept
    assert radial_error(field) < 2e-3  # %8.4f in px/s


def fiji_rows(path: Path) -> list[str]:
    lab.write_fiji(path, R0)
    return path.read_text().splitlines()


def test_a_fiji_hyperstack_table_is_timed_by_frame_not_by_its_z_slice(tmp_path):
    """ImageJ's Analyzer writes Slice (z) and Frame (t) for a hyperstack with z slices and
    frames: the default frame column is Frame; Slice (1 in every row) used to be taken."""
    rows = fiji_rows(tmp_path / "plain.csv")
    hyper = [rows[0] + ",Frame"] + [
        ",".join(r.split(",")[:-1] + ["1", r.split(",")[-1]]) for r in rows[1:]
    ]
    (tmp_path / "hyper.csv").write_text("\n".join(hyper) + "\n")
    plain, got = fiji(tmp_path / "plain.csv"), fiji(tmp_path / "hyper.csv")
    np.testing.assert_array_equal(got.times_s, plain.times_s)
    np.testing.assert_array_equal(got.radius_um, plain.radius_um)


def test_fiji_rows_out_of_order_are_sorted_and_a_frame_measured_twice_is_refused(tmp_path):
    rows = fiji_rows(tmp_path / "plain.csv")
    body = rows[1:]
    shuffled = [rows[0]] + body[::-1]  # measured from the last frame back
    (tmp_path / "reversed.csv").write_text("\r\n".join(shuffled) + "\r\n")
    plain = fiji(tmp_path / "plain.csv")
    got = fiji(tmp_path / "reversed.csv")
    np.testing.assert_array_equal(got.times_s, plain.times_s)
    np.testing.assert_array_equal(got.radius_um, plain.radius_um)
    assert "sorted by Slice" in got.files[0].notes[0]
    two_rois = [rows[0]] + [r for row in body for r in (row, row)]  # two ROIs per slice
    (tmp_path / "two.csv").write_text("\n".join(two_rois) + "\n")
    with pytest.raises(InputError, match="line 3: Slice 1 measured again .*several ROIs"):
        fiji(tmp_path / "two.csv")


@pytest.mark.parametrize(
    "pixel_size, message",
    [
        (
            200.0,
            r"radius of 1.01\de\+04 um, over 1000 um: is the pixel size in nm\? "
            r"\(--pixel-size-um 0.2\)",
        ),
        (2e-4, "under 1.5 um: is the pixel size in mm"),
    ],
)
def test_a_pixel_size_in_nm_or_mm_is_refused(tmp_path, pixel_size, message):
    fiji_rows(tmp_path / "r.csv")
    with pytest.raises(InputError, match=message):
        fiji(tmp_path / "r.csv", pixel_size_um=pixel_size)


@pytest.mark.parametrize("interval, fix", [(250.0, "0.25"), (2.5e-4, "0.25")])
def test_a_fiji_frame_interval_in_another_unit_names_the_option(tmp_path, capsys, interval, fix):
    """Refused before any fit, naming --frame-interval-s (not --time-unit, which a Fiji table
    refuses) and the interval in s that makes the recording a usual one."""
    from wound_opening.cli import main

    fiji_rows(tmp_path / "r.csv")
    code = main(
        [
            "fit",
            str(tmp_path / "r.csv"),
            "--area-col",
            "Area",
            "--cut-after-frame",
            "3",
            "--frame-interval-s",
            str(interval),
            "--length-unit",
            "px",
            "--pixel-size-um",
            "0.2",
            "--outer-radius-um",
            "100",
        ]
    )
    err = capsys.readouterr().err
    assert code == 2 and f"--frame-interval-s {fix}: frames 250 ms apart" in err
    assert "--time-unit" not in err


def test_the_rows_of_analyze_summarize_are_skipped_and_counted(tmp_path):
    """Analyze > Summarize appends rows labelled Mean, SD, Min, Max holding each column's
    statistics (ImageJ's ResultsTable; their Slice is not a frame: 83, 47.198, 1, 163)."""
    rows = fiji_rows(tmp_path / "plain.csv")
    n = len(rows) - 1
    stats = [("Mean", "83", "1111.111"), ("SD", "47.198", "22.2"), ("Min", "1", "0")]
    stats.append(("Max", "163", "9999.9"))
    summary = [f"{n + 1 + k},{label},{a},{a},{sl}" for k, (label, sl, a) in enumerate(stats)]
    (tmp_path / "summarized.csv").write_text("\n".join(rows + summary) + "\n")
    got = fiji(tmp_path / "summarized.csv")
    plain = fiji(tmp_path / "plain.csv")
    np.testing.assert_array_equal(got.radius_um, plain.radius_um)
    assert got.files[0].counts["summary rows"] == 4
    assert "4 summary rows" in got.files[0].notes[0]


@pytest.mark.parametrize("option", ["--centre-px", "--centre-um"])
def test_a_given_centre_outside_the_field_is_refused(option):
    """The README's noisy PIVlab folder with the true centre in px: used as given with
    --centre-px; typed into --centre-um (pixels read as um, 200 um off, outside the field):
    refused, naming the axes, where it used to be projected on as given."""
    from test_lab_readers import readme_lab_command

    from wound_opening.cli import parser
    from wound_opening.cli.lab import read_lab_inputs

    argv = readme_lab_command().split()[1:] + [option, "{:g},{:g}".format(*lab.CENTRE_PX)]
    if option == "--centre-px":
        assert not read_lab_inputs(parser().parse_args(argv)).profiles[0].warnings
        return
    with pytest.raises(InputError, match=r"outside the PIV field.*other\s+axes"):
        read_lab_inputs(parser().parse_args(argv))


def test_a_given_centre_the_flow_disagrees_with_is_used_with_a_warning():
    """A centre 7 um off the true one (axes shifted, or a wrong pixel size), inside the
    field: used as given, the fit warned with the distance, never refused."""
    from test_lab_readers import readme_lab_command

    from wound_opening.cli import parser
    from wound_opening.cli.lab import read_lab_inputs

    x, y = lab.CENTRE_PX
    off = 7.0 / lab.PIXEL_UM
    argv = readme_lab_command().split()[1:] + ["--centre-px", f"{x + off:g},{y:g}"]
    profile = read_lab_inputs(parser().parse_args(argv)).profiles[0]
    (warning,) = profile.warnings
    # The distance is to the flow's estimate, itself off the truth within its uncertainty.
    found = re.search(
        r"is ([\d.]+) um from the centre the velocities point away from, "
        r"\([\d.]+ \+- ([\d.]+), [\d.]+ \+- ([\d.]+)\)",
        warning,
    )
    assert found, warning
    distance, sd = float(found[1]), max(float(found[2]), float(found[3]))
    assert abs(distance - 7.0) < 3 * sd, warning
    assert "used as given" in warning


def test_openpiv_lengths_in_um_read_as_px_are_refused(tmp_path):
    """OpenPIV files scaled to um (openpiv.scaling.uniform) read with the default px,px/s: the
    field shrinks 5 times and lies mostly inside the wound; it used to be fitted."""
    from test_lab_readers import readme_lab_command

    from wound_opening.cli import parser
    from wound_opening.cli.lab import read_lab_inputs

    lab.write_openpiv(tmp_path / "px", R0)
    um = openpiv_as(tmp_path / "px", tmp_path / "um", [0, 1, 2, 3, 4, 5], "x\ty\tu\tv\tflags\tmask")
    for p in um.glob("*.txt"):
        a = np.loadtxt(p)
        a[:, :4] *= lab.PIXEL_UM
        np.savetxt(p, a, fmt="%.4e", delimiter="\t", header="x\ty\tu\tv\tflags\tmask")
    argv = readme_lab_command().split()[1:]
    argv[argv.index("examples/lab/piv_8um")] = str(um)
    with pytest.raises(InputError, match=r"of 3\d\d\d PIV vectors lie inside the wound.*units"):
        read_lab_inputs(parser().parse_args(argv))
    assert read_lab_inputs(parser().parse_args(argv + ["--piv-units", "um,um/s"])).profiles


@pytest.mark.parametrize(
    "first, step, message",
    [
        (1, 1, "start at images 4 and 24 .*20 frames per pair.*give --piv-pair-step 20"),
        (1, 20, "images 4-5 by its file names .*give --piv-first-frame 4 .* or 5 \\(from 0"),
        (5, 20, None),  # images numbered from 0: image 4 is frame 5
        (4, 20, None),
    ],
)
def test_pivlab_file_names_check_the_pair_options(tmp_path, first, step, message):
    """The info line names each pair's images (wound8um_0004.tif & wound8um_0005.tif, ...):
    pairs timed with the default --piv-first-frame 1 --piv-pair-step 1 used to be read at
    the wrong times with no word."""
    lab.write_pivlab(tmp_path, R0)
    frames = Frames(lab.FRAME_S, lab.CUT_AFTER, first, step)
    if message is None:
        assert read_field(str(tmp_path), frames, pixel_size_um=lab.PIXEL_UM).files
        return
    with pytest.raises(InputError, match=message):
        read_field(str(tmp_path), frames, pixel_size_um=lab.PIXEL_UM)


def test_pivlab_pairs_two_frames_apart_are_refused(tmp_path):
    """Pairs of images two frames apart (PIVlab's sequencing 1-3, 2-4): the velocity per
    pair is over two frame intervals, refused rather than read as over one."""
    lab.write_pivlab(tmp_path, R0)

    def two_apart(s):
        second = lambda m: f"_{int(m.group(1)) + 1:04d}.tif,"  # noqa: E731
        return [s[0], re.sub(r"_(\d+)\.tif,", second, s[1])] + s[2:]

    rewrite_pivlab(tmp_path, two_apart)
    with pytest.raises(InputError, match="images 4 and 6 .*2 frames apart.*consecutive"):
        read_field(str(tmp_path), FRAMES, pixel_size_um=lab.PIXEL_UM)


def test_a_radius_csv_in_px_with_a_pixel_size_in_nm_is_refused(tmp_path):
    """The plain reader: it used to end in a misleading "outer radius not larger than the
    largest wound radius" (1.6 cm)."""
    from wound_opening.inputs.lab_files import read_radius

    path = tmp_path / "r.csv"
    t = np.arange(1, 30) * lab.FRAME_S
    rows = [f"{a:g},{r / lab.PIXEL_UM:.3f}" for a, r in zip(t, lab.radius(R0, t))]
    path.write_text("time_s,radius_px\n" + "\n".join(rows) + "\n")
    kw = dict(radius_col="radius_px", length_unit="px")
    assert read_radius(str(path), pixel_size_um=lab.PIXEL_UM, **kw).radius_um.size == t.size
    with pytest.raises(InputError, match=r"radius_px median .* nm\? \(--pixel-size-um 0.2\)"):
        read_radius(str(path), pixel_size_um=200.0, **kw)


def test_a_fiji_table_resaved_with_semicolons_and_decimal_commas_is_read(tmp_path):
    """A spreadsheet in a decimal-comma locale re-saves ImageJ's CSV with ";" and "1234,5"."""
    rows = fiji_rows(tmp_path / "plain.csv")
    (tmp_path / "excel.csv").write_text(
        "\r\n".join(r.replace(",", ";").replace(".", ",").replace("Perim,", "Perim.") for r in rows)
    )
    got, plain = fiji(tmp_path / "excel.csv"), fiji(tmp_path / "plain.csv")
    np.testing.assert_array_equal(got.radius_um, plain.radius_um)


def test_a_fiji_table_without_stack_position_names_the_setting(tmp_path):
    rows = fiji_rows(tmp_path / "plain.csv")
    (tmp_path / "r.csv").write_text("\n".join(r.rsplit(",", 1)[0] for r in rows) + "\n")
    with pytest.raises(InputError, match="no column 'Slice'.*Set Measurements > Stack position"):
        fiji(tmp_path / "r.csv")


def test_a_folder_with_two_exports_of_the_same_pairs_is_refused(tmp_path):
    """PIVlab's FRAME: k repeated (an export saved twice under two names): the vectors used to
    be counted twice, each pair's noise halved."""
    lab.write_pivlab(tmp_path, R0)
    (tmp_path / "PIVlab_0002 (copy).txt").write_bytes((tmp_path / "PIVlab_0002.txt").read_bytes())
    with pytest.raises(InputError, match=r"frame pair 2 again \(first in .*PIVlab_0002.*glob"):
        read_field(str(tmp_path), FRAMES, pixel_size_um=lab.PIXEL_UM)
    field = read_field(str(tmp_path / "PIVlab_000?.txt"), FRAMES, pixel_size_um=lab.PIXEL_UM)
    assert len(field.files) == lab.PIV_PAIRS


def test_an_older_pivlab_export_without_vector_types_is_read(tmp_path):
    """PIVlab before March 2021 (PIVlab_GUI.m): first line 'PIVlab by W.Th. & E.J.S., ASCII
    chart output - DATE', headings 'x [m],y [m],u [m/s],v [m/s]', masked vectors NaN."""
    lab.write_pivlab(tmp_path / "new", R0)
    (tmp_path / "old").mkdir()
    for p in (tmp_path / "new").glob("*.txt"):
        lines = p.read_bytes().decode().split("\r\n")
        lines[0] = "PIVlab by W.Th. & E.J.S., ASCII chart output - 02-Dec-2020"
        lines[2:] = [",".join(s.split(",")[:4]) for s in lines[2:]]
        (tmp_path / "old" / p.name).write_bytes("\r\n".join(lines).encode())
    old = read_field(str(tmp_path / "old"), FRAMES, pixel_size_um=lab.PIXEL_UM)
    new = read_field(str(tmp_path / "new"), FRAMES, pixel_size_um=lab.PIXEL_UM)
    np.testing.assert_array_equal(old.u_um_s, new.u_um_s)
    assert "no 'Vector type' column" in old.files[0].notes[0]


def test_a_cut_given_as_a_time_in_ms_names_the_frame_number(tmp_path):
    fiji_rows(tmp_path / "r.csv")
    with pytest.raises(InputError, match="last frame is 163: --cut-after-frame is the number"):
        fiji(tmp_path / "r.csv", cut_after_frame=750)  # 0.75 s typed in ms


@pytest.mark.parametrize("units, refused", [("px,px/s", False), ("px,px/frame", True)])
def test_piv_velocities_in_another_unit_than_the_edge_speed_are_refused(tmp_path, units, refused):
    """OpenPIV px/s read as px/frame at 4 frames/s: velocities 4 times too large, which the
    fit used to turn into sigma 1.23 [1.21, 1.26] "identified" (truth 0.5), exit 0."""
    from test_lab_readers import readme_lab_command

    from wound_opening.cli import parser
    from wound_opening.cli.lab import read_lab_inputs

    lab.write_fiji(tmp_path / "r.csv", R0)
    lab.write_openpiv(tmp_path / "piv", R0)
    argv = readme_lab_command().split()[1:] + ["--piv-units", units]
    argv[argv.index("examples/lab/Results_8um.csv")] = str(tmp_path / "r.csv")
    argv[argv.index("examples/lab/piv_8um")] = str(tmp_path / "piv")
    if refused:
        with pytest.raises(
            InputError, match=r"edge speed dR/dt of the radius file = 3\.\d+ .*units"
        ):
            read_lab_inputs(parser().parse_args(argv))
        return
    notes = [
        n for f in read_lab_inputs(parser().parse_args(argv)).profiles[0].files for n in f.notes
    ]
    said = r"dR/dt of the radius file = 0\.8\d+ \+- 0\.00\d+ \(5 frame pairs"
    assert any(re.search(said, n) for n in notes), notes
