"""Every way a command can fail on bad input or options ends the same way: one line that starts
with ``Error:`` and says what is wrong, the exit code the command's help documents, no
traceback, and no output file left behind. Each command that reads grains is driven with bad
inputs made from the files of tests/data and examples/ (cut short, compressed, re-encoded,
emptied, garbled) and with bad values of its options."""

from __future__ import annotations

import gzip
import shutil
import warnings
from pathlib import Path

import pytest
from click.testing import CliRunner

from grainclass.cli import cli

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data"
EXAMPLES = ROOT / "examples"


def _bad_inputs(folder: Path) -> dict[str, Path]:
    """Inputs that cannot be read whole, or hold bad grains, made from real files."""
    made: dict[str, Path] = {}

    def put(name: str, data: bytes) -> None:
        path = folder / name
        path.write_bytes(data)
        made[name] = path

    polytopes = (EXAMPLES / "polytopes.txt").read_bytes()
    planar = (EXAMPLES / "plantri-10.pc").read_bytes()
    put("planar-cut.pc", planar[: len(planar) // 2 + 3])
    put("polytopes.txt.gz", gzip.compress(polytopes))
    put("polytopes-utf16.txt", polytopes.decode().encode("utf-16"))
    put("empty.txt", b"")
    put("garbage.bin", bytes(range(256)) * 8)
    put("voro-cut.vol", (DATA / "voro" / "walled-300.vol").read_bytes()[:5000])
    put("neper-cut.tess", (DATA / "neper" / "two_cells.tess").read_bytes()[:700])
    put("evolver-cut.fe", (DATA / "evolver" / "two_cubes.fe").read_bytes()[:400])
    put("not-parquet.parquet", b"PAR1" + polytopes[:200])
    for name in ("bad-grains.txt",):
        made[name] = EXAMPLES / name
    made["bad_face.tess"] = DATA / "neper" / "bad_face.tess"
    made["open_surface.fe"] = DATA / "evolver" / "open_surface.fe"
    (folder / "empty-folder").mkdir()
    made["empty-folder"] = folder / "empty-folder"
    made["missing.txt"] = folder / "missing.txt"
    return made


@pytest.fixture(scope="module")
def bad_inputs(tmp_path_factory) -> dict[str, Path]:
    return _bad_inputs(tmp_path_factory.mktemp("bad"))


def _documented_codes(command: str) -> set[int]:
    """The exit codes that ``grainclass COMMAND --help`` lists."""
    help_text = CliRunner().invoke(cli, [command, "--help"]).output
    section = help_text.split("Exit codes:", 1)[1]
    return {int(line.split()[0]) for line in section.splitlines() if line[:6].strip().isdigit()}


def _run(args: list[str]):
    with warnings.catch_warnings(record=True):  # an empty input warns; main() prints it
        warnings.simplefilter("always")
        return CliRunner().invoke(cli, args)


def _assert_one_line_failure(args: list[str], result, outputs: list[Path]) -> None:
    where = " ".join(args)
    assert result.exception is None or isinstance(result.exception, SystemExit), (
        f"{where}: {result.exception!r}"
    )
    assert result.exit_code in _documented_codes(args[0]), where
    lines = result.stderr.splitlines()
    assert "Traceback" not in result.stderr, where
    errors = [line for line in lines if line.startswith("Error: ")]
    if result.exit_code == 0:
        assert errors == [], where
        return
    assert len(errors) == 1, f"{where}: {result.stderr}"
    assert len(errors[0]) > len("Error: ") + 10, where
    allowed = ("Error: ", "grainclass: ", "Usage: ", "Try ")
    assert all(line.startswith(allowed) or not line.strip() for line in lines), result.stderr
    for output in outputs:
        assert not output.exists(), f"{where}: {output} left behind"


def _command_lines(command: str, path: Path, out: Path) -> tuple[list[str], list[Path]]:
    """The command line that reads ``path``, and the files it would write."""
    if command == "classify":
        target = out / "grains.parquet"
        return [command, str(path), "-o", str(target), "-q"], [target]
    if command == "perturb":
        target = out / "flipped.txt"
        return [command, str(path), "--flips", "1", "--seed", "1", "-o", str(target)], [target]
    if command == "plot":
        target = out / "round.png"
        return [command, "round", str(path), "-o", str(target), "-q"], [target]
    target = out / f"{command}.csv"
    return [command, str(path), "-o", str(target), "-q"], [target]


COMMANDS = ["classify", "summarize", "types", "penalties", "perturb", "plot"]


# Inputs that cannot be read at all, whatever the command: the others hold bad grains, which are
# rows with their status (a figure of no ok grain cannot be drawn, though).
UNREADABLE = {
    "empty-folder",
    "missing.txt",
    "neper-cut.tess",
    "not-parquet.parquet",
    "polytopes-utf16.txt",
    "polytopes.txt.gz",
}


@pytest.mark.parametrize("command", COMMANDS)
def test_bad_inputs_end_in_one_line_and_a_documented_code(command, bad_inputs, tmp_path):
    failed = set()
    for name, path in sorted(bad_inputs.items()):
        args, outputs = _command_lines(command, path, tmp_path)
        result = _run(args)
        _assert_one_line_failure(args, result, outputs)
        if result.exit_code:
            failed.add(name)
        for output in outputs:
            output.unlink(missing_ok=True)
    assert sorted(UNREADABLE - failed) == []


BAD_OPTIONS = {
    "classify": [
        ["--chunk-size", "0"],
        ["--chunk-size", "99999999999999999999999"],
        ["--belt-length", "12"],
        ["--belt-length", "3"],
        ["--input-format", "nope"],
        ["--jobs", "0"],
        ["--triple-edges", "color"],
        ["-o", ""],
    ],
    "summarize": [
        ["--table", "round", "--belt-length", "6"],
        ["--format", "parquet"],
        ["--table", "classes", "--n", "14"],
        ["--n", "2"],
        ["--format", "xml"],
    ],
    "types": [["--top", "0"], ["--n", "-1"], ["--class", "cube"], ["--belt-length", "99"]],
    "penalties": [["--belt-length", "11"], ["--n", "3"]],
    "perturb": [
        [],
        ["--flips", "1", "--all-flips"],
        ["--all-flips", "--seed", "3"],
        ["--flips", "-1"],
        ["--flips", "1", "--seed", str(2**64)],
    ],
    "plot": [
        ["round", "-o", "f.txt"],
        ["classes", "-o", "f.png", "--n", "14"],
        ["round", "-o", "f.png", "--seed", "1"],
        ["round", "-o", "f.png", "--penalty", "sym"],
        ["evolution", "-o", "f.png", "--times", "1,2"],
        ["evolution", "-o", "f.png", "--label", "a", "--label", "b"],
        ["round", "-o", "f.png", "--label", "a", "--label", "b"],
        ["penalty", "-o", "f.png", "--min-frequency", "2"],
    ],
}


@pytest.mark.parametrize(
    ("command", "options"),
    [(command, options) for command, lists in BAD_OPTIONS.items() for options in lists],
)
def test_bad_options_end_in_one_line_and_exit_2(command, options, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    shutil.copy(EXAMPLES / "polytopes.txt", tmp_path / "grains.txt")
    if command == "plot":
        args = ["plot", options[0], "grains.txt", *options[1:]]
    else:
        args = [command, "grains.txt", *options]
    before = set(tmp_path.iterdir())
    result = _run(args)
    assert result.exit_code == 2, f"{args}: {result.stderr}"
    _assert_one_line_failure(args, result, [])
    assert set(tmp_path.iterdir()) == before, args


def test_a_library_error_with_a_remedy_is_worded_with_its_flag(tmp_path):
    """A per-grain table without belts asked for its split type by L-belts: the library says
    what is missing, the command line which flag would mend it."""
    table = tmp_path / "grains.parquet"
    made = _run(["classify", str(EXAMPLES / "polytopes.txt"), "-o", str(table), "-q"])
    assert made.exit_code == 0
    args = ["summarize", str(table), "--table", "split", "--belt-length", "7"]
    result = _run(args)
    _assert_one_line_failure(args, result, [])
    assert result.exit_code == 1
    assert "classify the input again with --belt-length 7" in result.stderr


def test_every_command_words_library_errors_alike():
    from grainclass.cli.errors import Command

    assert all(isinstance(command, Command) for command in cli.commands.values())


POINTS = {
    "particles.dump": (
        b"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
        b"ITEM: ATOMS id type x y z\n1 1 0.1 0.2 0.3\n2 1 0.6 0.7 0.8\n",
        "a LAMMPS dump of points",
    ),
    "particles.xyz": (
        b'2\nLattice="1 0 0 0 1 0 0 0 1" Properties=species:S:1:pos:R:3\n'
        b"Fe 0.1 0.2 0.3\nFe 0.6 0.7 0.8\n",
        "an XYZ file of points",
    ),
    "particles.csv": (b"id,x,y,z\n1,0.1,0.2,0.3\n2,0.6,0.7,0.8\n", "a CSV table of points"),
    "particles.txt": (b"1 0.1 0.2 0.3\n2 0.6 0.7 0.8\n", "Voro++'s input of points"),
    "particles.npy": (b"\x93NUMPY\x01\x00v\x00{'descr': '<f8'", "a NumPy array of points"),
}


@pytest.mark.parametrize("name", sorted(POINTS))
@pytest.mark.parametrize("command", ["classify", "summarize", "perturb"])
def test_a_points_file_where_grains_are_read_says_what_it_is(command, name, tmp_path):
    data, what = POINTS[name]
    path = tmp_path / name
    path.write_bytes(data)
    args, outputs = _command_lines(command, path, tmp_path)
    result = _run(args)
    _assert_one_line_failure(args, result, outputs)
    assert result.exit_code == 1
    assert f"{what}, not grains: grainclass voronoi --points FILE" in result.stderr


def test_output_that_is_an_input_is_refused_and_the_input_kept(tmp_path):
    grains = tmp_path / "grains.txt"
    shutil.copy(EXAMPLES / "polytopes.txt", grains)
    link = tmp_path / "link.txt"
    link.symlink_to(grains)
    before = grains.read_bytes()
    for args in (
        ["classify", str(grains), "-o", str(grains)],
        ["classify", str(grains), "-o", str(link)],
        ["summarize", str(link), "-o", str(grains)],
        ["perturb", str(grains), "--flips", "1", "-o", str(link)],
    ):
        result = _run(args)
        _assert_one_line_failure(args, result, [])
        assert result.exit_code == 1, args
        assert "is also an input" in result.stderr
        assert grains.read_bytes() == before
