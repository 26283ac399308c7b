"""The paper's figures drawn with matplotlib (the ``plot`` extra) from :mod:`grainclass.figures`'
tidy tables.

Data sets differ by marker and line style as well as colour, so that a figure reads in black and
white print; axes carry the paper's words. The Agg backend draws without a display, and the same
table gives the same SVG bytes (no date, a fixed hash salt).
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, BinaryIO

import numpy as np
import pandas as pd

from grainclass import vocabulary
from grainclass.errors import MissingDependencyError, OptionError
from grainclass.figures import ROUND_PEAK

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

FORMATS = ("png", "svg", "pdf")
MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "<", ">")
LINES = ("-", "--", ":", "-.")
Q_LABEL = "mean isoperimetric quotient $Q = 36\\pi V^2/S^3$"
N_LABEL = "number of faces $n$"


def figure_format(path: str) -> str:
    """``png``, ``svg`` or ``pdf``, from the figure's file name.

    Raises
    ------
    OptionError
        For any other extension.
    """
    extension = os.path.splitext(path)[1].lower().lstrip(".")
    if extension not in FORMATS:
        raise OptionError("output", f"{path!r}: a figure is a .png, .svg or .pdf file")
    return extension


def require_matplotlib() -> None:
    """Raise :class:`MissingDependencyError` unless matplotlib can be imported."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise MissingDependencyError(
            "plotting needs matplotlib, which is not installed: pip install 'grainclass[plot]'"
        ) from None


def _pyplot():
    require_matplotlib()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


@contextmanager
def pyplot_styled(style: dict) -> Iterator[object]:
    """matplotlib's pyplot on the Agg backend, with ``style`` as its rcParams for the block,
    and the SVG hash salt that makes the same figure the same bytes.

    Raises
    ------
    MissingDependencyError
        Without matplotlib.
    """
    plt = _pyplot()
    with plt.rc_context({"svg.hashsalt": "grainclass", "figure.dpi": 100, **style}):
        yield plt


def save_figure(fig: Figure, sink: BinaryIO, fmt: str) -> None:
    """Write ``fig`` into ``sink`` as ``fmt`` (:func:`figure_format`), with no date or
    version in it, so that the same figure is the same bytes."""
    metadata = {
        "png": {"Software": None},
        "svg": {"Date": None},
        "pdf": {"CreationDate": None},
    }
    fig.savefig(sink, format=fmt, metadata=metadata[fmt])


def _style() -> contextlib.AbstractContextManager[object]:
    return pyplot_styled(
        {
            "savefig.dpi": 150,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "legend.frameon": False,
            "font.size": 9,
        }
    )


def _style_of(i: int) -> dict:
    """Marker, line style and colour of the i-th line: they differ together."""
    return {
        "marker": MARKERS[i % len(MARKERS)],
        "linestyle": LINES[i % len(LINES)],
        "color": f"C{i % 10}",
        "markersize": 4,
        "linewidth": 1,
    }


def _lines(ax: Axes, data: pd.DataFrame, key: str = "dataset") -> None:
    for i, (name, part) in enumerate(data.groupby(key, sort=False)):
        ax.plot(part["x"], part["y"], label=name, **_style_of(i))


def _labelled_lines(ax: Axes, data: pd.DataFrame) -> None:
    """A line per (data set, series), labelled with whichever of the two varies."""
    keys = [k for k in ("dataset", "series") if data[k].nunique() > 1] or ["dataset"]
    for i, (name, part) in enumerate(data.groupby(keys, sort=False)):
        label = " ".join(name) if isinstance(name, tuple) else name
        ax.plot(part["x"], part["y"], label=label, **_style_of(i))


def _round(fig: Figure, data: pd.DataFrame) -> None:
    ax = fig.subplots()
    _labelled_lines(ax, data)
    ax.set_xlabel("$k$")
    ax.set_ylabel("round$_{\\leq k}$ grains (% of grains)")
    ax.set_xticks(list(range(7)))
    ax.legend()


def _classes(fig: Figure, data: pd.DataFrame) -> None:
    panels = ("all", *vocabulary.CLASSES)
    axes = fig.subplots(2, 5, sharex=True).ravel()
    for ax, series in zip(axes, panels, strict=True):
        _lines(ax, data[data["series"] == series])
        ax.set_title("distribution of $n$" if series == "all" else series)
    for ax in axes[5:]:
        ax.set_xlabel(N_LABEL)
    for ax in axes[::5]:
        ax.set_ylabel("frequency")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside upper center", ncol=max(1, len(labels)))


def _quotient(fig: Figure, data: pd.DataFrame, by_round: bool) -> None:
    ax = fig.subplots()
    if by_round:
        values = sorted(set(data["x"]), key=lambda v: (v == "sc", v if v != "sc" else 0))
        position = {value: i for i, value in enumerate(values)}
        ax.set_xticks(range(len(values)), [str(v) for v in values])
        ax.set_xlabel("round$_k$ grains, $k$ (sc: severely constricted)")
    else:
        position = None
        ax.set_xlabel(N_LABEL)
    for i, (name, part) in enumerate(data.groupby("dataset", sort=False)):
        style = _style_of(i)
        x = np.array([position[v] for v in part["x"]] if position else part["x"], float)
        y, err = part["y"].to_numpy(float), part["yerr"].to_numpy(float)
        ax.errorbar(x, y, yerr=np.nan_to_num(err), label=name, capsize=2, **style)
        single = np.isnan(err)  # a class of a single grain: an open marker
        if single.any():
            ax.plot(
                x[single],
                y[single],
                linestyle="none",
                marker=style["marker"],
                markersize=style["markersize"] + 2,
                markerfacecolor="white",
                markeredgecolor=style["color"],
            )
    ax.set_ylabel(Q_LABEL)
    ax.legend()


def _penalty(fig: Figure, data: pd.DataFrame) -> None:
    ax = fig.subplots()
    n = data["series"].str.removeprefix("n=").astype(int) if len(data) else pd.Series([], int)
    scatter = None
    for i, (name, part) in enumerate(data.groupby("dataset", sort=False)):
        scatter = ax.scatter(
            part["x"],
            part["y"],
            c=n[part.index],
            cmap="viridis",
            vmin=n.min(),
            vmax=n.max(),
            marker=MARKERS[i % len(MARKERS)],
            s=14,
            label=name,
            edgecolors="black",
            linewidths=0.3,
        )
    if scatter is not None:
        from matplotlib.ticker import MaxNLocator

        fig.colorbar(scatter, ax=ax, label=N_LABEL, ticks=MaxNLocator(integer=True))
    ax.set_yscale("log")
    candidate = data.attrs.get("penalty", "P4")  # grainclass.penalties.CANDIDATES
    if candidate == "P4":
        ax.set_xlabel("penalty $P = n\\sum_k x_k\\, k(n-k-4)$")
    else:
        ax.set_xlabel(f"penalty {candidate} (L = 6)")
    ax.set_ylabel("frequency of the flag type")
    legend = ax.legend()
    for handle in legend.legend_handles:  # markers tell the data sets apart, colours n
        handle.set_array(None)
        handle.set_facecolor("lightgray")


def _ranks(fig: Figure, data: pd.DataFrame) -> None:
    ax = fig.subplots()
    for i, (name, part) in enumerate(data.groupby("dataset", sort=False)):
        style = _style_of(i)
        style["markevery"] = 0.1  # evenly spaced on the log axes
        ax.plot(part["x"], part["y"], label=name, **style)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("rank of the type (most frequent first)")
    ax.set_ylabel("frequency of the type")
    ax.legend()


def _evolution(fig: Figure, data: pd.DataFrame) -> None:
    ax = fig.subplots()
    peak = data[data["series"] == ROUND_PEAK]
    _lines(ax, data[data["series"] != ROUND_PEAK], key="series")
    for x in peak["x"]:
        ax.axvline(x, color="black", linestyle="--", linewidth=0.8)
        ax.annotate(
            "Round",
            (x, 1),
            xycoords=("data", "axes fraction"),
            xytext=(3, -12),
            textcoords="offset points",
        )
    ax.set_xlabel("time step")
    ax.set_ylabel("% of grains (triangles: % of faces)")
    ax.legend()


def _edge_errors(fig: Figure, data: pd.DataFrame) -> None:
    """Figs. round_k_cuts and combined_cut_types: a line per data set and number of edge
    errors over k, and its sc family as a marker apart, labelled with the EEPG only for the
    data set drawn with several; on a log scale, where the roughly exponential decay in k is a
    straight line (a 0% point is left out)."""
    ax = fig.subplots()
    values = list(dict.fromkeys(data["x"]))  # 0..k, then sc
    position = {value: i for i, value in enumerate(values)}
    several = data.groupby("dataset", sort=False)["series"].nunique() > 1
    for i, ((name, series), part) in enumerate(data.groupby(["dataset", "series"], sort=False)):
        x = np.array([position[v] for v in part["x"]], float)
        y = part["y"].to_numpy(float)
        y = np.where(y > 0, y, np.nan)
        sc = (part["x"] == "sc").to_numpy()
        style = _style_of(i)
        label = f"{name}, {series}" if several[name] else name
        ax.plot(x[~sc], y[~sc], label=label, **style)
        ax.plot(x[sc], y[sc], **(style | {"linestyle": "none"}))
    ax.set_xticks(range(len(values)), [str(v) for v in values])
    ax.set_yscale("log")
    ax.set_xlabel("round$_k$ grains, $k$ (sc: severely constricted)")
    ax.set_ylabel("% of grains")
    ax.legend()


_DRAW = {
    "round": _round,
    "classes": _classes,
    "faces-q": lambda fig, data: _quotient(fig, data, by_round=False),
    "round-q": lambda fig, data: _quotient(fig, data, by_round=True),
    "penalty": _penalty,
    "ranks": _ranks,
    "evolution": _evolution,
    "edge-errors": _edge_errors,
}
_SIZES = {"classes": (12.0, 5.0)}


def draw(kind: str, data: pd.DataFrame, sink: BinaryIO, fmt: str) -> None:
    """Draw the figure ``kind`` (one of :data:`grainclass.vocabulary.PLOT_KINDS`) from its tidy
    table into ``sink``, as ``fmt`` (``png``, ``svg`` or ``pdf``: :func:`figure_format`).

    Raises
    ------
    MissingDependencyError
        Without matplotlib.
    """
    with _style() as plt:
        fig = plt.figure(figsize=_SIZES.get(kind, (6.0, 4.0)), layout="constrained")
        try:
            _DRAW[kind](fig, data)
            save_figure(fig, sink, fmt)
        finally:
            plt.close(fig)
