"""Unusual inputs and usages that once ended in a traceback, a wrong exit code, silence or lost
data: each now ends in one line and its documented exit code, with nothing half-written."""

from __future__ import annotations

from pathlib import Path

import pyarrow as pa
import pyarrow.parquet as pq
import pytest
from click.testing import CliRunner

from grainclass.cli import cli

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
TETRAHEDRON = "tet\t1 2 3;0 3 2;0 1 3;0 2 1\n"


def _run(*args: object):
    return CliRunner().invoke(cli, [str(a) for a in args])


def _one_error_line(result) -> str:
    errors = [line for line in result.stderr.splitlines() if line.startswith("Error: ")]
    assert len(errors) == 1, result.stderr
    assert "Traceback" not in result.stderr
    return errors[0]


@pytest.mark.parametrize(
    "args",
    [["penalty", "tet.txt"], ["penalty", str(EXAMPLES / "polytopes.txt"), "--min-frequency", "1"]],
)
def test_a_figure_with_nothing_to_draw_exits_1_and_writes_nothing(tmp_path, args):
    (tmp_path / "tet.txt").write_text(TETRAHEDRON)
    figure = tmp_path / "p.png"
    args = [a if a != "tet.txt" else str(tmp_path / a) for a in args]
    result = _run("plot", *args, "-o", figure)
    assert result.exit_code == 1
    assert "no flag type with a frequency of at least" in _one_error_line(result)
    assert not figure.exists()


def test_a_figure_whose_data_cannot_be_written_is_not_written_either(tmp_path):
    figure = tmp_path / "round.png"
    result = _run(
        "plot",
        "round",
        EXAMPLES / "polytopes.txt",
        "-o",
        figure,
        "--data",
        tmp_path / "no" / "d.csv",
    )
    assert result.exit_code == 1
    _one_error_line(result)
    assert not figure.exists()


@pytest.fixture(scope="module")
def grains(tmp_path_factory) -> pa.Table:
    path = tmp_path_factory.mktemp("table") / "grains.parquet"
    assert _run("classify", EXAMPLES / "polytopes.txt", "-o", path, "-q").exit_code == 0
    return pq.read_table(path)


BROKEN = [
    ("n_faces", None, "an ok grain without n_faces"),
    ("class", None, "an ok grain without class"),
    ("n_faces", -3, "an ok grain of -3 faces (n_faces)"),
    ("status", None, "column status has a null"),
]
COMMANDS = [["summarize"], ["types"], ["plot", "classes"]]


@pytest.mark.parametrize(
    ("column", "values", "said", "command"),
    [(*broken, command) for broken in BROKEN for command in COMMANDS]
    + [("p_vector", None, "an ok grain without p_vector", ["types"])],  # only types reads it
)
def test_a_table_with_nulls_where_values_must_be_is_named(
    grains, tmp_path, column, values, said, command
):
    field = grains.schema.field(column)
    broken = grains.set_column(
        grains.schema.get_field_index(column),
        field,
        pa.nulls(len(grains), field.type)
        if values is None
        else pa.array([values] * len(grains), field.type),
    )
    path = tmp_path / "broken.parquet"
    pq.write_table(broken, path)
    extra = ["-o", tmp_path / "f.png"] if command[0] == "plot" else []
    result = _run(*command, path, *extra)
    assert result.exit_code == 1
    assert said in _one_error_line(result)


def _dump(bounds: str, tilted: bool = False) -> str:
    header = "ITEM: BOX BOUNDS xy xz yz pp pp pp" if tilted else "ITEM: BOX BOUNDS pp pp pp"
    return (
        f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\n{header}\n{bounds}\n"
        "ITEM: ATOMS id x y z\n1 0.1 0.2 0.3\n2 0.6 0.7 0.8\n"
    )


BAD_BOXES = {
    "x bounds 0 0": (_dump("0 0\n0 1\n0 1"), "each side must be from"),
    "x bounds 1 0": (_dump("1 0\n0 1\n0 1"), "each side must be from"),
    "x bounds 0 nan": (_dump("0 nan\n0 1\n0 1"), "must be finite numbers"),
    "x bounds 0 1e309": (_dump("0 1e309\n0 1\n0 1"), "must be finite numbers"),
    "a tilt larger than the box": (_dump("0 1 5\n0 1 0\n0 1 0", True), "a tilt larger"),
    "a NaN tilt": (_dump("0 1 nan\n0 1 0\n0 1 0", True), "must be finite numbers"),
    "a flat Lattice": (
        '2\nLattice="1 0 0 0 1 0 0 0 0"\nH 0.1 0.1 0.1\nH 0.5 0.5 0.5\n',
        "each side must be from",
    ),
    "a negative Lattice": (
        '2\nLattice="-1 0 0 0 1 0 0 0 1"\nH 0.1 0.1 0.1\nH 0.5 0.5 0.5\n',
        "each side must be from",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_BOXES))
def test_a_box_read_from_a_points_file_is_checked_as_box_is(tmp_path, case):
    """Such boxes ended in a LinAlgError, a TypeError about complex numbers, or Voro++ ending
    the process with exit 2."""
    text, said = BAD_BOXES[case]
    points = tmp_path / ("points.xyz" if "Lattice" in case else "points.dump")
    points.write_text(text)
    out = tmp_path / "cells.txt"
    result = _run("voronoi", "--points", points, "-o", out)
    assert result.exit_code == 1
    line = _one_error_line(result)
    assert str(points) in line
    assert said in line
    assert not out.exists()


def test_a_points_id_past_64_bits_is_named_without_a_numpy_warning(tmp_path):
    points = tmp_path / "points.txt"
    points.write_text("18446744073709551616 0.1 0.2 0.3\n2 0.6 0.7 0.8\n")
    result = _run("voronoi", "--points", points, "-o", tmp_path / "cells.txt")
    assert result.exit_code == 1
    assert "points.txt:1: cannot read this point: id 1.84467e+19" in _one_error_line(result)
    assert "RuntimeWarning" not in result.stderr


@pytest.mark.parametrize(
    ("options", "said"),
    [
        (["--radius-column", "nope"], "--radius-column: Voro++'s input names no columns"),
        (["--periodic", ""], "expected axes among x, y, z (or none), got ''"),
    ],
)
def test_voronoi_options_that_would_be_ignored_are_refused(tmp_path, options, said):
    points = tmp_path / "points.txt"
    points.write_text("1 0.1 0.2 0.3\n2 0.6 0.7 0.8\n")
    result = _run("voronoi", "--points", points, *options, "-o", tmp_path / "cells.txt")
    assert result.exit_code == 2
    assert said in _one_error_line(result)


@pytest.mark.parametrize(
    ("options", "code", "said"),
    [
        (["--scheduler", "bogus"], 2, "--scheduler: 'bogus' is no scheduler address"),
        (["--plantri", "/bin/false"], 1, "/bin/false -u 4 failed (exit 1)"),
        (["--plantri", "/no/such/plantri"], 1, "/no/such/plantri: cannot be run"),
        (["--workers", "100000"], 2, "--workers"),
    ],
)
def test_a_census_that_cannot_start_says_so_in_one_line(tmp_path, options, code, said):
    """Each ended in a traceback (a bogus scheduler), some 90 lines of Dask workers' tracebacks
    even with -q (a plantri that fails), or workers dying as they started."""
    import subprocess
    import sys

    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "grainclass",
            "census",
            "8",
            "-o",
            str(tmp_path / "c"),
            "-q",
            *options,
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == code, run.stderr
    errors = [line for line in run.stderr.splitlines() if line.startswith("Error: ")]
    assert len(errors) == 1, run.stderr
    assert said in errors[0]
    assert "Traceback" not in run.stderr


@pytest.mark.parametrize(("signum", "code"), [("SIGINT", 130), ("SIGTERM", 143), ("SIGHUP", 129)])
def test_a_stop_while_the_command_line_loads_exits_with_its_code(signum, code):
    """Ctrl-C in the first tens of milliseconds, while click and the commands' modules were
    imported, ended in a KeyboardInterrupt traceback and death by the signal."""
    import subprocess
    import sys

    script = (
        "import os, signal, time\n"
        "from grainclass.__main__ import catch_stops_while_loading\n"
        "catch_stops_while_loading()\n"
        f"os.kill(os.getpid(), signal.{signum})\n"
        "time.sleep(30)\n"
    )
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert run.returncode == code
    assert "Traceback" not in run.stderr
    assert run.stderr.startswith("grainclass: ")


def test_the_command_line_is_loaded_after_the_stops_are_caught():
    """The console script's first import of grainclass holds nothing heavy: typing alone took
    8 of its 11 ms, a window in which Ctrl-C met Python's own handler."""
    import subprocess
    import sys

    script = "import sys\nfrom grainclass.__main__ import main\nprint(sorted(sys.modules))"
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    loaded = run.stdout
    assert "'click'" not in loaded
    assert "'typing'" not in loaded


@pytest.mark.parametrize("times", ["1,inf", "nan,2", "1,-inf"])
def test_time_steps_that_are_not_finite_are_refused_without_a_numpy_warning(tmp_path, times):
    figure = tmp_path / "e.png"
    steps = [EXAMPLES / "polytopes.txt", EXAMPLES / "plantri-10.pc"]
    result = _run("plot", "evolution", *steps, "-o", figure, "--times", times)
    assert result.exit_code == 2
    assert "a time step is a finite number" in _one_error_line(result)
    assert "Warning" not in result.stderr
    assert not figure.exists()
