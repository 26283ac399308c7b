"""Classify every triangulation with n = 13 and 14 vertices and print the results beside the paper.

Runs the real pipeline, ``plantri n | grainclass classify - -o F`` then ``grainclass summarize F``,
and compares with the paper's Table II, its split-type table and the all* rows of its round
table (numbers transcribed from the paper). Exits 1 if anything differs.
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from grainclass.errors import GrainclassError
from grainclass.plantri import find_plantri
from paper_tables import CLASS_COLUMNS, ROUND_ALL, ROUND_COLUMNS, SPLIT, TABLE_II


def _run(plantri: str, n: int, directory: Path) -> tuple[dict, float]:
    out = directory / f"all{n}.parquet"
    start = time.perf_counter()
    with subprocess.Popen(
        [plantri, str(n)], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL
    ) as plantri:
        subprocess.run(
            [sys.executable, "-m", "grainclass", "classify", "-", "-o", str(out), "-q"],
            stdin=plantri.stdout,
            check=True,
        )
    seconds = time.perf_counter() - start
    summary = subprocess.run(
        [
            sys.executable,
            "-m",
            "grainclass",
            "summarize",
            str(out),
            "--n",
            str(n),
            "--format",
            "json",
        ],
        capture_output=True,
        check=True,
    )
    return json.loads(summary.stdout), seconds


def _line(label: str, values) -> str:
    return f"  {label:<10}" + "".join(f"{v:>9}" for v in values)


def main() -> int:
    try:
        plantri = find_plantri()
    except GrainclassError as error:
        print(f"Error: {error}", file=sys.stderr)
        return 1
    same = True
    with tempfile.TemporaryDirectory() as tmp:
        for n in (13, 14):
            summary, seconds = _run(plantri, n, Path(tmp))
            print(
                f"n = {n}: {summary['headline']['grains']} triangulations, "
                f"plantri | classify in {seconds:.1f} s"
            )
            row = next(r for r in summary["classes"] if r["n"] == n)
            got = tuple(row[c] for c in CLASS_COLUMNS)
            print(_line("Table II", CLASS_COLUMNS))
            print(_line("paper", TABLE_II[n]))
            print(_line("grainclass", got))
            split = next(r for r in summary["split"] if r["n"] == n)
            got_split = {int(k): v for k, v in split.items() if k != "n" and v}
            ks = sorted(SPLIT[n])
            print(_line("split k:m", [f"{k}:{n - 4 - k}" for k in ks]))
            print(_line("paper", [SPLIT[n][k] for k in ks]))
            print(_line("grainclass", [got_split.get(k, 0) for k in ks]))
            rnd = next(r for r in summary["round"] if r["grains"] == f"n={n}")
            got_round = tuple(round(rnd[c], 2) for c in ROUND_COLUMNS)
            print(_line(f"all*_n={n}", ROUND_COLUMNS))
            print(_line("paper", [f"{v:.2f}" for v in ROUND_ALL[n]]))
            print(_line("grainclass", [f"{v:.2f}" for v in got_round]))
            match = got == TABLE_II[n] and got_split == SPLIT[n] and got_round == ROUND_ALL[n]
            print(f"  {'identical to the paper' if match else 'DIFFERS FROM THE PAPER'}\n")
            same &= match
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
