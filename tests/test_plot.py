"""`grainclass plot`: the paper's figures, their numbers checked against summarize, types and
pandas, drawn in every format."""

from __future__ import annotations

import io
import shutil
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from conftest import EXAMPLES, ROOT
from grainclass.cli import cli
from grainclass.vocabulary import CLASSES, PLOT_KINDS

pytest.importorskip("matplotlib")

EVOLVER = ROOT / "tests" / "data" / "evolver"


def _run(*args: str, input: str | None = None):
    return CliRunner().invoke(cli, [str(a) for a in args], input=input)


def _ok(*args: str) -> str:
    result = _run(*args)
    assert result.exit_code == 0, result.output
    return result.stdout


def _csv(text: str) -> pd.DataFrame:
    return pd.read_csv(io.StringIO(text))


@pytest.fixture(scope="module")
def grains(tmp_path_factory):
    """Two data sets with volumes: Poisson-Voronoi tessellations of 1500 and 2500 seeds."""
    folder = tmp_path_factory.mktemp("plot")
    paths = []
    for n, seed in ((1500, 3), (2500, 4)):
        path = folder / f"pv{n}.txt"
        _ok("voronoi", n, "--seed", seed, "-o", path, "-q")
        paths.append(path)
    return paths


def _plot(tmp_path, kind, *inputs, extra=(), fmt="svg"):
    figure, data = tmp_path / f"{kind}.{fmt}", tmp_path / f"{kind}.csv"
    _ok("plot", kind, *inputs, "-o", figure, "--data", data, "-q", *extra)
    return figure, pd.read_csv(data)


def test_round_equals_the_round_table(tmp_path, grains):
    _, data = _plot(tmp_path, "round", *grains, extra=["--n", "14", "--n", "15"])
    for path in grains:
        table = _csv(
            _ok("summarize", path, "--table", "round", "--n", "14", "--n", "15", "--format", "csv")
        )
        for label in ("n=14", "n=15"):
            drawn = data[(data.dataset == path.name) & (data.series == label)]
            row = table[table.grains == label].iloc[0]
            expected = [row["round0"], *(row[f"round<={k}"] for k in range(1, 7))]
            assert drawn.x.tolist() == list(range(7))
            assert drawn.y.tolist() == pytest.approx(expected, rel=1e-12)
    assert set(data.series) == {"n=14", "n=15"}


def test_classes_are_the_class_table_over_its_total(tmp_path, grains):
    _, data = _plot(tmp_path, "classes", grains[0], extra=["--label", "V"])
    table = _csv(_ok("summarize", grains[0], "--table", "classes", "--format", "csv"))
    total = table.loc[table.n == "total", "all"].iloc[0]
    by_n = table[table.n != "total"]
    for series in ("all", *CLASSES):
        expected = {int(n): c / total for n, c in zip(by_n.n, by_n[series], strict=True) if c}
        drawn = data[data.series == series]
        assert dict(zip(drawn.x, drawn.y, strict=True)) == pytest.approx(expected, rel=1e-12)
    assert set(data.dataset) == {"V"}
    assert data[data.series == "all"].y.sum() == pytest.approx(1.0)


@pytest.mark.parametrize(("kind", "by"), [("faces-q", "n_faces"), ("round-q", "round")])
def test_mean_quotient_and_its_standard_error_are_pandas_own(tmp_path, grains, kind, by):
    parquet = tmp_path / "pv.parquet"
    _ok("classify", grains[1], "-o", parquet, "-q", "--no-types")
    rows = pd.read_parquet(parquet)
    rows = rows[rows.status == "ok"]
    rows["round"] = rows.round_k.astype("Int64").astype(str).where(rows.family != "sc", "sc")
    expected = rows.groupby(by).isoperimetric.agg(["mean", "sem", "count"])
    _, data = _plot(tmp_path, kind, parquet)
    assert len(data) == len(expected)
    for x, y, yerr in zip(data.x, data.y, data.yerr, strict=True):
        key = int(x) if by == "n_faces" else str(x)
        mean, sem, count = expected.loc[key]
        assert y == pytest.approx(mean, rel=1e-12)
        if count == 1:
            assert np.isnan(yerr)  # one grain: no error bar, an open marker
        else:
            assert yerr == pytest.approx(sem, rel=1e-9)
    if by == "round":
        assert data.x.tolist()[-1] == "sc"


def test_penalty_and_ranks_are_the_type_table(tmp_path, grains):
    types = _csv(_ok("types", grains[0], "--format", "csv"))
    _, ranks = _plot(tmp_path, "ranks", grains[0])
    assert ranks.x.tolist() == list(range(1, len(types) + 1))
    assert ranks.y.tolist() == pytest.approx(types.fraction.tolist(), rel=1e-12)
    floor = 1e-3
    _, penalty = _plot(tmp_path, "penalty", grains[0], extra=["--min-frequency", floor])
    flag = types[(types["class"] == "flag") & (types.fraction >= floor)]
    assert sorted(zip(penalty.x, penalty.series, strict=True)) == sorted(
        zip(flag.penalty, "n=" + flag.n_faces.astype(str), strict=True)
    )
    assert penalty.y.min() >= floor
    assert len(penalty) > 0


def test_evolution_follows_the_tables_of_each_step(tmp_path):
    steps = []
    for name, source in (("step100.pc", "plantri-10.pc"), ("step50.txt", "polytopes.txt")):
        shutil.copy(EXAMPLES / source, tmp_path / name)
        steps.append(tmp_path / name)
    series = ["flag", "cube", "dodecahedron", "0:m", "tetrahedron", "triangles", "sc>=2"]
    _, data = _plot(tmp_path, "evolution", *steps, extra=[f"--series={s}" for s in series])
    assert sorted(set(data.x)) == [50, 100]
    for step, path in ((50, steps[1]), (100, steps[0])):
        classes = _csv(_ok("summarize", path, "--table", "classes", "--format", "csv"))
        split = _csv(_ok("summarize", path, "--table", "split", "--format", "csv"))
        total = classes.loc[classes.n == "total", "all"].iloc[0]
        drawn = data[data.x == step].set_index("series").y

        def percent(count, total=total):
            return 100.0 * count / total

        assert drawn["flag"] == pytest.approx(
            percent(classes.loc[classes.n == "total", "flag"].iloc[0])
        )
        assert drawn["sc>=2"] == pytest.approx(
            percent(classes.loc[classes.n == "total", "sc>=2"].iloc[0])
        )
        assert drawn["cube"] == pytest.approx(percent(classes.loc[classes.n == "6", "flag"].sum()))
        assert drawn["tetrahedron"] == pytest.approx(
            percent(classes.loc[classes.n == "4", "all"].sum())
        )
        zero = split["0"] if "0" in split else pd.Series([0])
        assert drawn["0:m"] == pytest.approx(percent(zero.sum()))
        assert drawn["dodecahedron"] == pytest.approx(
            percent(split.loc[split.n == 12, "0"].sum() if "0" in split else 0)
        )
        headline = _ok("summarize", path, "--table", "classes").splitlines()[0]
        assert f"triangles {drawn['triangles']:.2f}% of faces" in headline
    # polytopes.txt holds one cube and two dodecahedra (the regular one and the Weaire-Phelan
    # cell) among 13 grains (tests/hand_derived.py).
    at_50 = data[data.x == 50].set_index("series").y
    assert at_50["cube"] == pytest.approx(100 / 13)
    assert at_50["dodecahedron"] == pytest.approx(200 / 13)
    peak = data[data.series == "Round (flag peak)"]
    flag = data[data.series == "flag"]
    assert peak.y.tolist() == [flag.y.max()]
    assert peak.x.tolist() == [flag.x[flag.y.idxmax()]]


def test_evolution_steps_from_times(tmp_path):
    _, data = _plot(
        tmp_path,
        "evolution",
        EXAMPLES / "polytopes.txt",
        EXAMPLES / "plantri-10.pc",
        extra=["--times", "0.5,0.25"],
    )
    assert sorted(set(data.x)) == [0.25, 0.5]
    _, single = _plot(tmp_path, "evolution", EXAMPLES / "polytopes.txt", extra=["--times", "7"])
    assert single.series.tolist() == ["flag"]  # one step: no peak is marked


@pytest.mark.parametrize("fmt", ["png", "svg", "pdf"])
@pytest.mark.parametrize("kind", PLOT_KINDS)
def test_every_kind_renders_in_every_format(tmp_path, grains, kind, fmt):
    inputs = grains if kind != "evolution" else []
    extra = []
    if kind == "evolution":
        for step, path in enumerate(grains):
            shutil.copy(path, tmp_path / f"t{step}.txt")
            inputs.append(tmp_path / f"t{step}.txt")
        extra = ["--series", "flag", "--series", "triangles"]
    figure, _ = _plot(tmp_path, kind, *inputs, extra=extra, fmt=fmt)
    head = figure.read_bytes()[:8]
    assert head.startswith({"png": b"\x89PNG", "svg": b"<?xml", "pdf": b"%PDF"}[fmt])
    if fmt == "png":
        import matplotlib.image

        pixels = matplotlib.image.imread(figure)
        colours = np.unique(pixels.reshape(-1, pixels.shape[-1]), axis=0)
        assert len(colours) > 20  # not blank: lines, markers, text in several colours
        assert (pixels[..., :3] < 0.5).mean() > 0.005  # dark ink on the page


def test_svg_is_byte_identical_across_runs(tmp_path, grains):
    first, _ = _plot(
        tmp_path / "a" if (tmp_path / "a").mkdir() is None else None, "faces-q", *grains
    )
    second, _ = _plot(
        tmp_path / "b" if (tmp_path / "b").mkdir() is None else None, "faces-q", *grains
    )
    assert first.read_bytes() == second.read_bytes()


NOT_OK = "trihedron\t1 2;2 0;0 1\nsquare_pyramid\t1 2 3 4;2 0 4;3 0 1;4 0 2;1 0 3\n"


@pytest.mark.parametrize(
    ("kind", "name", "message"),
    [
        ("round", "bad.txt", "no ok grains to draw"),
        ("ranks", "bad.txt", "no ok grains to draw"),
        ("faces-q", "polytopes.txt", "no ok grain has a volume and an area"),
        ("evolution", "polytopes.txt", "cannot read a time step from its name"),
    ],
)
def test_an_input_that_cannot_give_the_figure_exits_1_without_a_figure(
    tmp_path, kind, name, message
):
    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "bad.txt").write_text(NOT_OK)
    shutil.copy(EXAMPLES / "polytopes.txt", tmp_path / "in")
    out = tmp_path / "out"
    out.mkdir()
    figure, data = out / "f.png", out / "f.csv"
    result = _run("plot", kind, tmp_path / "in" / name, "-o", figure, "--data", data)
    assert result.exit_code == 1
    assert message in result.stderr
    assert name in result.stderr
    assert list(out.iterdir()) == []


@pytest.mark.parametrize(
    "args",
    [
        ["plot", "round", "x.txt", "-o", "f.jpg"],
        ["plot", "round", "x.txt", "y.txt", "-o", "f.png", "--label", "one"],
        ["plot", "evolution", "x.txt", "-o", "f.png", "--times", "1,2"],
        ["plot", "faces-q", "x.txt", "-o", "f.png", "--n", "14"],
        ["plot", "nope", "x.txt", "-o", "f.png"],
    ],
)
def test_plot_usage_errors_exit_2(args):
    assert _run(*args).exit_code == 2


def test_without_matplotlib_plot_names_the_extra_and_exits_1(tmp_path):
    code = (
        "import sys\n"
        "sys.modules['matplotlib'] = None\n"
        "sys.argv = ['grainclass', *sys.argv[1:]]\n"
        "from grainclass.cli import main\n"
        "main()\n"
    )
    figure = tmp_path / "f.png"
    run = subprocess.run(
        [
            sys.executable,
            "-c",
            code,
            "plot",
            "round",
            str(EXAMPLES / "polytopes.txt"),
            "-o",
            str(figure),
        ],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 1
    assert "pip install 'grainclass[plot]'" in run.stderr
    assert not figure.exists()


def test_other_commands_never_import_matplotlib(tmp_path):
    code = (
        "import sys\n"
        "from grainclass.cli import cli\n"
        f"try:\n    cli(['classify', {str(EXAMPLES / 'polytopes.txt')!r}, '-o', "
        f"{str(tmp_path / 'g.parquet')!r}, '-q'])\n"
        "except SystemExit as exc:\n    assert not exc.code, exc.code\n"
        "try:\n    cli(['plot', '--help'])\nexcept SystemExit:\n    pass\n"
        "print('matplotlib' in sys.modules)\n"
    )
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert run.stdout.splitlines()[-1] == "False"
