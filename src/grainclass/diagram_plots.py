"""Schlegel diagrams drawn with matplotlib (the ``plot`` extra), from the drawings of
:mod:`grainclass.schlegel`.

One panel per grain, or per belt drawn; with the truncation forest, a second plot beside each
diagram. Edges are black; a flip's result is told by the line alone (bold, zigzag, dashed), as
the paper draws it, so that a figure reads in black and white print. Faces are filled only to
show something: a belt in red, truncated faces in blues that darken with their depth.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, BinaryIO

import numpy as np

from grainclass.plots import pyplot_styled, save_figure
from grainclass.schlegel import Belt, Diagram, GrainDrawing, label_place

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

PANEL = (2.6, 2.95)  # inches: a diagram, and its title of up to three lines above it
DIAGRAM = 2.45  # inches: the side of a diagram's square
FOREST_WIDTH = 1.9  # inches beside a diagram for its truncation forest
SOLID_WIDTH = 2.6  # inches beside a diagram (and forest) for the grain in space
VIEW = (20.0, -60.0)  # elevation and azimuth, in degrees, the grain in space is seen from
LIGHT = np.array([-0.4, -0.5, 0.77])  # towards the light, from above the viewer's left
SOLID = "#d9dee6"
LEGEND = 0.35  # inches under the panels for the flips' legend
LIMIT = 1.32  # the diagram's axes reach past the unit circle, for the outer face's label
OUTER_BAND = 1.12  # the outer face, when filled, is the band out to this radius
BELT = "#f2a5a5"
BELT_LINE = "#a4161a"
DUAL = "#1f5fa8"
DEPTHS = ("#c6dbef", "#9ecae1", "#6baed6", "#4292c6", "#2171b5", "#08519c", "#08306b")
DARK_FROM = 4  # depths from this one on are dark enough for white labels
STYLE = {
    "font.size": 8,
    "savefig.dpi": 150,
    "lines.solid_capstyle": "round",
    "svg.fonttype": "none",
}
FLIP_WORDS = {
    "other": "flip gives another type",
    "same": "flip gives the same type",
    "none": "flip not admissible",
}


def draw_grains(
    drawings: Sequence[GrainDrawing], sink: BinaryIO, fmt: str, columns: int | None = None
) -> None:
    """Draw ``drawings``, a panel each (one per belt where belts are drawn), ``columns`` to a
    row (default: up to four), into ``sink`` as ``fmt`` (``png``, ``svg`` or ``pdf``).

    Raises
    ------
    MissingDependencyError
        Without matplotlib.
    """
    panels = [(d, belt, number) for d in drawings for belt, number in _belts_of(d)]
    forest = any(d.truncations is not None for d in drawings)
    solid = any(d.shape is not None for d in drawings)
    columns = min(columns or (2 if forest and solid else 3 if forest or solid else 4), len(panels))
    rows = math.ceil(len(panels) / columns)
    width = PANEL[0] + (FOREST_WIDTH if forest else 0.0) + (SOLID_WIDTH if solid else 0.0)
    legend = LEGEND if any(d.flips is not None for d in drawings) else 0.0
    size = (columns * width, rows * PANEL[1] + legend)
    with pyplot_styled(STYLE) as plt:
        # Every place is fixed in inches, never fitted to the text: a layout engine's
        # iterations would make the same figure differ in the last digits from run to run.
        fig = plt.figure(figsize=size)
        try:
            for i, (drawing, belt, number) in enumerate(panels):
                row, column = divmod(i, columns)
                left, top = column * width, row * PANEL[1]
                _panel(fig, size, (left, top), drawing, belt, number, forest, solid)
            if legend:
                _flip_legend(fig)
            save_figure(fig, sink, fmt)
        finally:
            plt.close(fig)


def _belts_of(drawing: GrainDrawing) -> list[tuple[Belt | None, int]]:
    if drawing.belt_length is None:
        return [(None, 0)]
    if not drawing.belts:
        return [(None, 0)]  # a grain without such belts: its diagram, and the title says so
    return list(zip(drawing.belts, drawing.belt_numbers, strict=True))


def _panel(
    fig: Figure,
    size: tuple[float, float],
    corner: tuple[float, float],
    drawing: GrainDrawing,
    belt: Belt | None,
    number: int,
    forest: bool,
    solid: bool,
) -> None:
    """A panel whose top left corner is ``corner`` inches from the figure's."""
    left, top = corner

    def axes(x: float, bottom: float, w: float, h: float, **kind: str) -> Axes:
        """Axes ``w`` by ``h`` inches, ``x`` from the panel's left and ``bottom`` down from its
        top."""
        return fig.add_axes(
            ((left + x) / size[0], 1 - (top + bottom) / size[1], w / size[0], h / size[1]),
            **kind,
        )

    lines = [drawing.title, drawing.caption]
    if drawing.belt_length is not None:
        lines.append(_belt_line(drawing, belt, number))
    fig.text(
        (left + PANEL[0] / 2) / size[0],
        1 - (top + 0.08) / size[1],
        "\n".join(lines),
        ha="center",
        va="top",
        fontsize=8,
    )
    margin = (PANEL[0] - DIAGRAM) / 2
    _diagram(axes(margin, PANEL[1] - 0.05, DIAGRAM, DIAGRAM), drawing, belt)
    if forest:
        _forest(axes(PANEL[0], PANEL[1] - 0.25, FOREST_WIDTH - 0.15, DIAGRAM - 0.3), drawing)
    if solid and drawing.shape is not None:
        x = PANEL[0] + (FOREST_WIDTH if forest else 0.0)
        _solid(axes(x, PANEL[1] - 0.05, DIAGRAM, DIAGRAM, projection="3d"), drawing, belt)


def _belt_line(drawing: GrainDrawing, belt: Belt | None, number: int) -> str:
    length = drawing.belt_length
    if belt is None:
        return f"no {length}-belt"
    k, m = belt.sides
    return f"{length}-belt {number} of {drawing.belt_count}, {k}:{length}:{m}"


def _face_colours(drawing: GrainDrawing, belt: Belt | None) -> list[str | None]:
    """Each face's fill: its belt's, its truncation depth's, or none."""
    colours: list[str | None] = [None] * drawing.diagram.n_faces
    if drawing.truncations is not None:
        for face, depth in enumerate(drawing.truncations.depth):
            if depth:
                colours[face] = DEPTHS[min(depth, len(DEPTHS)) - 1]
    if belt is not None:
        for face in belt.faces:
            colours[face] = BELT
    return colours


def _diagram(ax: Axes, drawing: GrainDrawing, belt: Belt | None) -> None:
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path

    d = drawing.diagram
    ax.set_aspect("equal")
    ax.set_xlim(-LIMIT, LIMIT)
    ax.set_ylim(-LIMIT, LIMIT)
    ax.axis("off")
    colours = _face_colours(drawing, belt)
    filled = [f for f in range(d.n_faces) if colours[f] is not None and f != d.outer_face]
    if filled:
        ax.add_collection(
            PolyCollection(
                [d.polygon(f) for f in filled],
                facecolors=[colours[f] for f in filled],
                edgecolors="none",
            )
        )
    if colours[d.outer_face] is not None:
        # The outer face is all the plane outside its polygon: a band round the drawing.
        circle = Path.circle((0, 0), OUTER_BAND)
        hole = d.polygon(d.outer_face)[::-1]  # turning against the circle: a hole
        band = Path.make_compound_path(circle, Path(np.vstack([hole, hole[:1]]), closed=True))
        ax.add_patch(PathPatch(band, facecolor=colours[d.outer_face], edgecolor="none"))
    _edges(ax, drawing)
    if drawing.dual:
        _dual(ax, drawing)
    if belt is not None:
        _belt_cycle(ax, drawing, belt)
    ax.plot(*d.positions.T, "o", color="black", markersize=1.6, linestyle="none")
    _labels(ax, drawing, colours)


def _edges(ax: Axes, drawing: GrainDrawing) -> None:
    d = drawing.diagram
    styles = drawing.flips or ("plain",) * len(d.edges)
    lines: dict[str, list[np.ndarray]] = {}
    for (a, b, _, _), style in zip(d.edges.tolist(), styles, strict=True):
        segment = d.positions[[a, b]]
        lines.setdefault(style, []).append(_zigzag(segment) if style == "same" else segment)
    looks = {
        "plain": {"linewidth": 1.0},
        "other": {"linewidth": 2.6},
        "same": {"linewidth": 0.9},
        "none": {"linewidth": 1.0, "linestyle": (0, (3.0, 2.0))},
    }
    for style, parts in lines.items():
        _polylines(ax, parts, color="black", **looks[style])


def _polylines(ax: Axes, parts: list[np.ndarray], **style: object) -> None:
    """Lines drawn as one path, each part apart from the next (a file holds one element,
    not one per edge)."""
    gap = np.full((1, 2), np.nan)
    joined = np.vstack([row for part in parts for row in (part, gap)])
    ax.plot(*joined.T, **style)


def _zigzag(segment: np.ndarray, teeth_per_unit: float = 16.0) -> np.ndarray:
    """A zigzag along a segment: teeth of equal size, at least three, the ends kept."""
    start, end = segment
    along = end - start
    length = float(np.hypot(*along))
    teeth = max(3, round(length * teeth_per_unit))
    across = np.array([-along[1], along[0]]) / length
    amplitude = min(0.025, length / 6)
    t = np.linspace(0, 1, 2 * teeth + 1)
    offsets = np.zeros_like(t)
    offsets[1:-1:2] = amplitude
    offsets[2:-1:2] = -amplitude
    return start + np.outer(t, along) + np.outer(offsets, across)


def _dual(ax: Axes, drawing: GrainDrawing) -> None:
    """The dual graph: a vertex in each inner face, an edge through the middle of each edge;
    the outer face's vertex, out at infinity, is not drawn (as the paper leaves out the back
    face's), its edges leave the drawing."""
    d = drawing.diagram
    paths = []
    for a, b, f, g in d.edges.tolist():
        middle = d.positions[[a, b]].mean(axis=0)
        ends = [_dual_end(d, f, middle), middle, _dual_end(d, g, middle)]
        paths.append(np.array(ends))
    _polylines(ax, paths, color=DUAL, linewidth=0.8, zorder=3)
    inner = [f for f in range(d.n_faces) if f != d.outer_face]
    centres = np.array([d.centre(f) for f in inner])
    ax.plot(
        *centres.T,
        "o",
        markersize=9,
        markerfacecolor="white",
        markeredgecolor=DUAL,
        markeredgewidth=0.8,
        zorder=4,
    )


def _dual_end(d: Diagram, face: int, middle: np.ndarray) -> np.ndarray:
    if face == d.outer_face:
        return middle / np.hypot(*middle) * 1.12
    return d.centre(face)


def _belt_cycle(ax: Axes, drawing: GrainDrawing, belt: Belt) -> None:
    """The belt's dual cycle, closed: through each belt face's centre and the middle of the
    edge to the next; through the outer face along an arc outside the drawing."""
    d = drawing.diagram
    points: list[np.ndarray] = []
    faces = belt.faces
    for i, face in enumerate(faces):
        before, after = faces[i - 1], faces[(i + 1) % len(faces)]
        if face == d.outer_face:
            points += _outer_arc(_middle(d, before, face), _middle(d, face, after))
        else:
            points.append(d.centre(face))
        points.append(_middle(d, face, after))
    cycle = np.array([*points, points[0]])
    ax.plot(*cycle.T, color=BELT_LINE, linewidth=1.4, linestyle=(0, (4.0, 1.5)), zorder=3)


def _middle(d: Diagram, a: int, b: int) -> np.ndarray:
    corners = d.edges[d.edge_between(a, b), :2]
    return d.positions[corners].mean(axis=0)


def _outer_arc(start: np.ndarray, end: np.ndarray, radius: float = 1.06) -> list[np.ndarray]:
    """From ``start`` out to ``radius``, the shorter way round to ``end``'s angle, and in."""
    a0, a1 = math.atan2(start[1], start[0]), math.atan2(end[1], end[0])
    turn = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
    angles = a0 + turn * np.linspace(0, 1, 24)
    arc = radius * np.column_stack([np.cos(angles), np.sin(angles)])
    return [start, *arc, end]


def _labels(ax: Axes, drawing: GrainDrawing, colours: list[str | None]) -> None:
    d = drawing.diagram
    if drawing.labels == "none":
        return
    for face in range(d.n_faces):
        text = drawing.label(face)
        x, y = label_place(d, face)
        if face == d.outer_face:
            ax.text(x, y, f"{text} (outer)", ha="left", va="center", fontsize=7, style="italic")
            continue
        polygon = d.polygon(face)
        size = float(np.clip(18 * math.sqrt(_area(polygon)), 3.0, 8.0))
        dark = colours[face] in DEPTHS[DARK_FROM - 1 :]
        ax.text(
            x,
            y,
            text,
            ha="center",
            va="center",
            fontsize=size,
            color="white" if dark else "black",
            zorder=5,
        )


def _area(polygon: np.ndarray) -> float:
    x, y = polygon.T
    return abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))) / 2


def _forest(ax: Axes, drawing: GrainDrawing) -> None:
    """The truncation forest: each removed face a node, coloured by its depth as in the
    diagram, under its parent; roots on top, trees side by side in order of their faces."""
    ax.axis("off")
    truncations = drawing.truncations
    if truncations is None:
        return
    depth, parent = truncations.depth, truncations.parent
    removed = [f for f, k in enumerate(depth) if k]
    if not removed:
        ax.text(0.5, 0.5, "fundamental:\nno truncations", ha="center", va="center")
        return
    children: dict[int, list[int]] = {f: [] for f in removed}
    roots = []
    for face in removed:
        (children[parent[face]] if parent[face] >= 0 else roots).append(face)
    x: dict[int, float] = {}
    next_leaf = [0.0]

    def place(face: int) -> float:
        if not children[face]:
            x[face] = next_leaf[0]
            next_leaf[0] += 1
        else:
            x[face] = float(np.mean([place(child) for child in children[face]]))
        return x[face]

    for root in roots:
        place(root)
        next_leaf[0] += 0.5  # a gap between trees
    for face in removed:
        if parent[face] >= 0:
            p = parent[face]
            ax.plot([x[p], x[face]], [-depth[p], -depth[face]], color="black", linewidth=0.8)
    for face in removed:
        colour = DEPTHS[min(depth[face], len(DEPTHS)) - 1]
        ax.plot(x[face], -depth[face], "o", markersize=11, color=colour, markeredgecolor="black")
        ax.text(
            x[face],
            -depth[face],
            drawing.label(face) if drawing.labels != "none" else "",
            ha="center",
            va="center",
            fontsize=6,
            color="white" if depth[face] >= DARK_FROM else "black",
        )
    deepest = max(depth)
    ax.set_xlim(-0.7, max(next_leaf[0] - 1.0, 0.0) + 0.2)
    ax.set_ylim(-deepest - 0.6, -0.4)
    words = truncations.forest if truncations.forest is not None else "to the tetrahedron"
    ax.set_title(f"trees {words}", fontsize=7)


def _solid(ax: Axes, drawing: GrainDrawing, belt: Belt | None) -> None:
    """The grain in space, from its input's corner positions, lit from above left: its faces
    filled as in the diagram, where the input says which face each polygon is, and labelled
    where they face the viewer; Surface Evolver's facets, whose faces it does not say, grey."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    shape = drawing.shape
    if shape is None:
        return
    points = shape.positions - (shape.positions.max(axis=0) + shape.positions.min(axis=0)) / 2
    polygons = [points[polygon] for polygon in shape.polygons]
    normals = np.array([_normal(polygon) for polygon in polygons])
    light = 0.55 + 0.45 * np.clip(normals @ (LIGHT / np.linalg.norm(LIGHT)), -1.0, 1.0)
    colours = _face_colours(drawing, belt)
    faces = shape.face
    base = [
        colours[faces[i]] if faces is not None and colours[faces[i]] is not None else SOLID
        for i in range(len(polygons))
    ]
    from matplotlib.colors import to_rgb

    fill = [tuple(min(1.0, c * k) for c in to_rgb(b)) for b, k in zip(base, light, strict=True)]
    ax.add_collection3d(
        Poly3DCollection(
            polygons,
            facecolors=fill,
            edgecolors="black" if faces is not None else fill,
            linewidths=0.6 if faces is not None else 0.2,
        )
    )
    reach = float(np.abs(points).max())
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_zlim(-reach, reach)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=VIEW[0], azim=VIEW[1])
    ax.set_axis_off()
    if faces is None or drawing.labels == "none":
        return
    elevation, azimuth = np.radians(VIEW)
    towards_viewer = np.array(
        [
            np.cos(elevation) * np.cos(azimuth),
            np.cos(elevation) * np.sin(azimuth),
            np.sin(elevation),
        ]
    )
    for i, polygon in enumerate(polygons):
        if normals[i] @ towards_viewer > 0.2:
            x, y, z = polygon.mean(axis=0) + 0.02 * reach * normals[i]
            ax.text(x, y, z, drawing.label(int(faces[i])), ha="center", va="center", fontsize=6)


def _normal(polygon: np.ndarray) -> np.ndarray:
    """The unit normal of a polygon turning counter-clockwise seen from its front (Newell's)."""
    following = np.roll(polygon, -1, axis=0)
    normal = np.array(
        [
            np.sum((polygon[:, 1] - following[:, 1]) * (polygon[:, 2] + following[:, 2])),
            np.sum((polygon[:, 2] - following[:, 2]) * (polygon[:, 0] + following[:, 0])),
            np.sum((polygon[:, 0] - following[:, 0]) * (polygon[:, 1] + following[:, 1])),
        ]
    )
    length = np.linalg.norm(normal)
    return normal / length if length > 0 else normal


def _flip_legend(fig: Figure) -> None:
    from matplotlib.legend_handler import HandlerBase
    from matplotlib.lines import Line2D

    class Zigzag(HandlerBase):
        def create_artists(self, legend, handle, xdescent, ydescent, width, height, size, trans):
            xs = np.linspace(-xdescent, width - xdescent, 9)
            ys = height / 2 - ydescent + height / 3 * np.array([0, 1, -1, 1, -1, 1, -1, 1, 0])
            line = Line2D(xs, ys, color="black", linewidth=0.9)
            line.set_transform(trans)
            return [line]

    same = Line2D([], [], color="black")
    handles = [
        Line2D([], [], color="black", linewidth=2.6),
        same,
        Line2D([], [], color="black", linewidth=1.0, linestyle=(0, (3.0, 2.0))),
    ]
    fig.legend(
        handles,
        [FLIP_WORDS[k] for k in ("other", "same", "none")],
        loc="lower center",
        ncols=3,
        frameon=False,
        handler_map={same: Zigzag()},
    )
