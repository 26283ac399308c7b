"""The census beyond the paper: every triangulation with n = 4..17 vertices, on local Dask.

Runs ``grainclass census`` (which checks every n against plantri's own counts and exits 1 on a
mismatch), then compares n <= 14 with the paper's Table II and split-type table (numbers
transcribed from the paper) and prints the extended tables as Markdown, as docs/census.md
shows them.
The census directory keeps its checkpoints: an interrupted run continues where it stopped.

    python scripts/reproduce_census.py [--n 4..17] [--parts 4] [--output build/census]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd

from grainclass.render import render_frame
from paper_tables import CLASS_COLUMNS, SPLIT, TABLE_II


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", default="4..17", help="numbers of vertices (default 4..17)")
    parser.add_argument("--parts", default="4", help="plantri res/mod parts per n (default 4)")
    parser.add_argument("--output", default="build/census", help="census directory")
    args = parser.parse_args()

    start = time.perf_counter()
    command = [sys.executable, "-m", "grainclass", "census", args.n, "--parts", args.parts]
    done = subprocess.run([*command, "-o", args.output], check=False)
    seconds = time.perf_counter() - start
    if done.returncode:
        return done.returncode

    out = Path(args.output)
    classes = pd.read_csv(out / "classes.csv", dtype={"n": str})
    split = pd.read_csv(out / "split.csv")
    same = True
    for n, expected in TABLE_II.items():
        row = classes[classes["n"] == str(n)]
        if len(row) and tuple(int(row.iloc[0][c]) for c in CLASS_COLUMNS) != expected:
            print(f"n = {n}: Table II differs from the paper")
            same = False
    for n, expected in SPLIT.items():
        row = split[split["n"] == n]
        if len(row):
            got = {int(k): int(v) for k, v in row.iloc[0].items() if k != "n" and v}
            if got != expected:
                print(f"n = {n}: the split types differ from the paper")
                same = False
    provenance = json.loads((out / "provenance.json").read_text())
    print(f"\ncensus of n = {args.n} in {seconds:.0f} s (plantri {provenance['plantri']})")
    print("the paper's rows (n <= 14): " + ("all equal" if same else "DIFFER"))
    print()
    print(render_frame(classes[classes["n"] != "total"], "markdown", "Table II, extended"))
    labels = split.copy()
    for column in split.columns[1:]:
        k = int(column)
        labels[column] = [
            f"{count} x {k}:{n - 4 - k}" if count else ""
            for n, count in zip(split["n"], split[column], strict=True)
        ]
    print(render_frame(labels, "markdown", "flag triangulations by split type k:m, extended"))
    rounds = pd.read_csv(out / "round.csv")
    rounds = rounds[rounds["grains"].str.startswith("n=")]
    rounds.insert(0, "n", rounds.pop("grains").str[2:])
    for column in rounds.columns[2:]:
        rounds[column] = rounds[column].map(lambda x: f"{x:.2f}")
    title = "percent in round<=k and in sc, all triangulations with n vertices, extended"
    print(render_frame(rounds[rounds["n"].astype(int) >= 10], "markdown", title))
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
