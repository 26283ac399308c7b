"""Turn a :class:`~grainclass.summary.Summary` into text, CSV, Markdown, LaTeX, JSON or Parquet."""

from __future__ import annotations

import io
import json
import math

import pandas as pd

from grainclass.errors import OptionError
from grainclass.summary import Summary

TITLES = {
    "classes": "Grains by number of faces n and class (the paper's Tables II, V, R, E)",
    "round": "Percent of ok grains in round<=k and in the sc family (the paper's round table)",
    "split": "flag grains by number of faces n and split type k:m (m = n-4-k)",
    "geometry": "Mean isoperimetric quotient Q of ok grains, with its standard error, by n and by "
    "round_k",
}


def _title(summary: Summary, name: str) -> str:
    """A table's title; the split table's names its belts' length when they are not 4."""
    length = summary.split.attrs.get("belt_length", 4)
    if name == "split" and length != 4:
        return (
            f"flag grains by number of faces n and split type k:{length}:m of their "
            f"{length}-belts (m = n-{length}-k)"
        )
    return TITLES[name]


def headline(summary: Summary) -> str:
    """One line of headline figures: grains by status, mean faces, percent triangles, types."""
    h = summary.headline
    return (
        f"grains: {h['grains']} (ok {h['ok']}, degenerate {h['degenerate']}, "
        f"non_simple {h['non_simple']}, invalid {h['invalid']}); "
        + (
            f"mean faces per grain {h['mean_faces']:.3f}; "
            f"triangles {h['triangle_faces_percent']:.2f}% of faces; "
            if h["ok"]
            else "no ok grains to average; "
        )
        + (
            f"{h['types']} distinct types"
            if h["types"] is not None
            else "distinct types not known (--types, or tables classified with them)"
        )
        + (
            f"; {h['boundary_excluded']} boundary grains left out"
            if h.get("boundary_excluded")
            else ""
        )
    )


def _display(summary: Summary, name: str) -> pd.DataFrame:
    """The table as strings for people: percentages with two decimals, split cells as k:m."""
    table = summary.table(name)
    if name == "round":
        shown = table.copy()
        for column in shown.columns[2:]:
            shown[column] = shown[column].map(lambda x: "" if math.isnan(x) else f"{x:.2f}")
        return shown.astype(str)
    if name == "geometry":
        shown = table.copy()
        for column in ("mean_Q", "se_Q"):
            shown[column] = shown[column].map(lambda x: "" if math.isnan(x) else f"{x:.4f}")
        return shown.astype(str)
    if name == "split":
        shown = table.astype(str)
        length = table.attrs.get("belt_length", 4)
        middle = "" if length == 4 else f"{length}:"
        for column in table.columns[1:]:
            k = int(column)
            shown[column] = [
                f"{count} x {k}:{middle}{n - length - k}" if count else ""
                for n, count in zip(table["n"], table[column], strict=True)
            ]
        return shown
    return table.astype(str)


def _text(table: pd.DataFrame) -> str:
    """A table as aligned text; an empty one as "(none)", not pandas' "Empty DataFrame"."""
    return table.to_string(index=False) if len(table) else "(none)"


def _cells(table: pd.DataFrame) -> pd.DataFrame:
    """Every cell as text, a missing one (None, NaN, pandas' NA) empty."""
    return table.astype(object).where(table.notna(), "").map(str)


def _markdown(table: pd.DataFrame) -> str:
    lines = ["| " + " | ".join(table.columns) + " |", "|" + "---:|" * len(table.columns)]
    lines += ["| " + " | ".join(row) + " |" for row in _cells(table).itertuples(index=False)]
    return "\n".join(lines)


def _latex(table: pd.DataFrame) -> str:
    def escape(text: str) -> str:
        return text.replace("<=", "$\\leq$").replace(">=", "$\\geq$").replace("_", "\\_")

    lines = [
        "\\begin{tabular}{" + "r" * len(table.columns) + "}",
        " & ".join(escape(c) for c in table.columns) + " \\\\",
        "\\hline",
    ]
    rows = _cells(table).itertuples(index=False)
    lines += [" & ".join(escape(c) for c in row) + " \\\\" for row in rows]
    lines.append("\\end{tabular}")
    return "\n".join(lines)


def _records(table: pd.DataFrame) -> list[dict]:
    """JSON-ready rows, floats kept to 15 digits (pandas rounds to 10 by default). A table
    with a "total" row holds n as text: every other n is a number again."""
    rows = json.loads(table.to_json(orient="records", double_precision=15))
    for row in rows:
        if isinstance(row.get("n"), str) and row["n"].isdigit():
            row["n"] = int(row["n"])
    return rows


def render_frame(table: pd.DataFrame, fmt: str, title: str) -> str | bytes:
    """One table on its own (``grainclass types``) in one of
    :data:`grainclass.vocabulary.OUTPUT_FORMATS`."""
    if fmt == "parquet":
        buffer = io.BytesIO()
        table.to_parquet(buffer, index=False)
        return buffer.getvalue()
    if fmt == "json":
        return json.dumps(_records(table), indent=2) + "\n"
    if fmt == "csv":
        return table.to_csv(index=False)
    if fmt == "markdown":
        return f"**{title}**\n\n{_markdown(table)}\n"
    if fmt == "latex":
        return f"% {title}\n{_latex(table)}\n"
    return f"{title}\n{_text_with_codes_last(table)}\n"


def _text_with_codes_last(table: pd.DataFrame) -> str:
    """Aligned text with the Weinberg codes (as long as 6n - 11 numbers) last and left-aligned,
    where right-aligned first they pushed every other column off the screen; fractions to six
    digits, not seventeen."""
    shown = _cells(
        table.assign(**{c: table[c].map("{:.6g}".format) for c in table.select_dtypes("float")})
    )
    if "weinberg" not in shown.columns or not len(shown):
        return _text(shown)
    rest = _text(shown.drop(columns="weinberg")).splitlines()
    codes = ["weinberg", *shown["weinberg"]]
    return "\n".join(f"{line}  {code}" for line, code in zip(rest, codes, strict=True))


def render(summary: Summary, tables: tuple[str, ...], fmt: str) -> str | bytes:
    """Render the headline and the named tables in one of
    :data:`grainclass.vocabulary.OUTPUT_FORMATS`.

    Parquet holds one table, so ``fmt="parquet"`` needs exactly one name in ``tables``.
    """
    if fmt == "parquet":
        if len(tables) != 1:
            raise OptionError("format", "parquet output holds one table")
        buffer = io.BytesIO()
        summary.table(tables[0]).to_parquet(buffer, index=False)
        return buffer.getvalue()
    if fmt == "json":
        # JSON has no NaN: an average of no grains is null, as in the tables' records.
        payload: dict[str, object] = {
            "headline": {
                key: None if isinstance(value, float) and not math.isfinite(value) else value
                for key, value in summary.headline.items()
            }
        }
        for name in tables:
            payload[name] = _records(summary.table(name))
        return json.dumps(payload, indent=2, allow_nan=False) + "\n"
    parts = {"csv": [], "latex": [f"% {headline(summary)}"]}.get(fmt, [headline(summary)])
    for name in tables:
        if fmt == "csv":
            body = summary.table(name).to_csv(index=False).rstrip("\n")
            parts.append(body if len(tables) == 1 else f"# {name}\n{body}")
        elif fmt == "markdown":
            parts.append(f"**{_title(summary, name)}**\n\n{_markdown(_display(summary, name))}")
        elif fmt == "latex":
            parts.append(f"% {_title(summary, name)}\n{_latex(_display(summary, name))}")
        else:
            parts.append(f"{_title(summary, name)}\n{_text(_display(summary, name))}")
    return "\n\n".join(parts) + "\n"
