"""``grainclass draw``: Schlegel diagrams of single grains, and galleries of a data set's types."""

from __future__ import annotations

import click

from grainclass.cli import errors, exit_codes, options, startup
from grainclass.options import LONGEST_BELT, SHORTEST_DRAWN_BELT, ReadOptions
from grainclass.vocabulary import CLASSES, FACE_LABELS
from grainclass.weinberg_grains import NAMED_GRAINS

EPILOG = exit_codes.epilog(
    "success",
    "an input could not be read, a grain asked for is not in it or is not ok (degenerate, "
    "non-simple, invalid), a grain has no such face or belt, matplotlib is not installed, or "
    "an output could not be written; nothing is written then",
)
MAX_INDEX = 2**31 - 1


@click.command("draw", cls=errors.Command, epilog=EPILOG)
@click.argument("inputs", nargs=-1, metavar="[INPUT]...")
@options.figure_output()
@click.option(
    "--id", "ids", multiple=True, metavar="ID", help="The grain with this id (repeatable)."
)
@click.option(
    "--weinberg",
    multiple=True,
    metavar="CODE",
    help="The grain with this Weinberg vector, as types writes it (repeatable).",
)
@click.option(
    "--named",
    multiple=True,
    type=click.Choice(list(NAMED_GRAINS)),
    help="A grain the paper names (repeatable): see docs/figures.md.",
)
@click.option(
    "--top",
    type=click.IntRange(1, 2**63 - 1),
    metavar="K",
    help="The K most frequent types of the inputs, as types counts them.",
)
@options.faces(
    "The most frequent types with N faces (with --top, the K first; alone, all).",
    multiple=False,
    name="n_faces",
)
@click.option(
    "--class",
    "class_name",
    type=click.Choice(CLASSES),
    help="The most frequent types of this class (with --top, the K first; alone, all).",
)
@click.option(
    "--outer-face",
    type=click.IntRange(0, MAX_INDEX),
    metavar="F",
    help="The face (0-based, in the input's order) that bounds the diagram (default: a largest "
    "one, the one whose farthest face is nearest).",
)
@click.option(
    "--labels",
    type=click.Choice(FACE_LABELS),
    help="What each face shows: its number of sides, its id (0-based, or the input's own), or "
    "nothing (default: sides; ids with --trees).",
)
@click.option("--dual", is_flag=True, help="Draw the dual graph of the faces.")
@click.option(
    "--belt-length",
    "belts_drawn",
    type=click.IntRange(SHORTEST_DRAWN_BELT, LONGEST_BELT),
    metavar="L",
    help="Draw each belt of L faces (3 to 10; for 3 the non-trivial ones), a panel each.",
)
@click.option(
    "--belt",
    type=click.IntRange(1, MAX_INDEX),
    metavar="K",
    help="With --belt-length: only the K-th belt (from 1, in the order of --data's belts).",
)
@click.option(
    "--flips",
    is_flag=True,
    help="Draw each edge bold where its flip gives another type, zigzag where it gives the same, "
    "dashed where it is not admissible.",
)
@click.option(
    "--trees",
    is_flag=True,
    help="Shade the faces reverse truncations remove by depth, and draw the truncation forest.",
)
@click.option(
    "--3d",
    "solid",
    is_flag=True,
    help="Draw each grain in space beside its diagram, from its input's corner positions "
    "(Surface Evolver, Neper; grains chosen by --id).",
)
@click.option(
    "--columns",
    type=click.IntRange(1, 1000),
    metavar="C",
    help="Panels in a row (default: 4; 3 with --trees or --3d, 2 with both).",
)
@click.option(
    "--data",
    metavar="JSON",
    callback=options.nonempty_path,
    help="Also write what is drawn: per grain its corners' places, faces, edges, belts, ...",
)
@options.reading(types_default=None)
def draw_cmd(
    inputs: tuple[str, ...],
    output: str,
    ids: tuple[str, ...],
    weinberg: tuple[str, ...],
    named: tuple[str, ...],
    top: int | None,
    n_faces: int | None,
    class_name: str | None,
    outer_face: int | None,
    labels: str | None,
    dual: bool,
    belts_drawn: int | None,
    belt: int | None,
    flips: bool,
    trees: bool,
    solid: bool,
    columns: int | None,
    data: str | None,
    reading: ReadOptions,
    quiet: bool,
) -> None:
    """Draw the Schlegel diagrams of grains: one face bounds the drawing, every other is a
    convex polygon inside it.

    The grains are those of INPUT... with the ids given, those of the Weinberg vectors and
    names given, and the most frequent types of INPUT... (--top, --n, --class). INPUT is any
    input classify reads, or a per-grain Parquet table (its grains drawn from their Weinberg
    vectors). Each grain gets a panel, titled with its faces, p-vector, class and split type.
    Needs the plot extra: pip install 'grainclass[plot]'.
    """
    from grainclass.options import DrawingOptions

    request = DrawingOptions(
        ids=ids,
        weinberg=weinberg,
        named=named,
        top=top,
        n_faces=n_faces,
        class_name=class_name,
        outer_face=outer_face,
        face_label=labels,
        dual=dual,
        belt_length=belts_drawn,
        belt=belt,
        flips=flips,
        trees=trees,
        solid=solid,
        columns=columns,
    )
    if inputs:
        startup.begin(inputs, reading, [output, data])
    import json
    from contextlib import nullcontext

    from grainclass.atomic import atomic_output
    from grainclass.cli.output import write_all
    from grainclass.diagram_plots import draw_grains
    from grainclass.drawing import grain_drawings
    from grainclass.plots import figure_format, require_matplotlib
    from grainclass.schlegel import drawing_data
    from grainclass.vocabulary import plural

    require_matplotlib()
    # Both outputs are opened before the work and appear together, or neither does.
    with (
        atomic_output(output) as figure,
        atomic_output(data) if data is not None else nullcontext() as drawn,
    ):
        drawings = grain_drawings(list(inputs), request, reading, startup.watcher(quiet))
        draw_grains(drawings, figure, figure_format(output), columns)
        if drawn is not None:
            write_all(drawn, json.dumps(drawing_data(drawings)) + "\n")
    if not quiet:
        click.echo(f"grainclass: {plural(len(drawings), 'grain')} drawn, to {output}", err=True)
