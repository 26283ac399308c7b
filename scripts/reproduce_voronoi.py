"""Regenerate a Poisson-Voronoi data set like the paper's V-268402 and compare with its tables.

``grainclass voronoi 268402 --seed S -o F.parquet`` then ``grainclass summarize F.parquet``;
every class fraction (Table V totals) and round<=k percentage (the V row of the round table)
is printed beside the paper's with its deviation in binomial standard errors, sqrt(p (1 - p) / N)
for the paper's fraction p, and in standard errors of the difference of two such samples (the
paper's and this one). Exits 1 if any deviates by more than 4 of the latter.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from paper_tables import V_CLASSES, V_GRAINS, V_ROUND


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=20170101)
    args = parser.parse_args()
    gc = [sys.executable, "-m", "grainclass"]
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "v.parquet"
        start = time.perf_counter()
        subprocess.run(
            [*gc, "voronoi", str(V_GRAINS), "--seed", str(args.seed), "-o", str(out)], check=True
        )
        seconds = time.perf_counter() - start
        summary = json.loads(
            subprocess.run(
                [*gc, "summarize", str(out), "--format", "json"], capture_output=True, check=True
            ).stdout
        )
    head = summary["headline"]
    print(f"{V_GRAINS} seeds (seed {args.seed}): generated and classified in {seconds:.1f} s")
    print(
        f"mean faces per grain {head['mean_faces']:.3f} (paper 15.535, theory "
        f"{48 * math.pi**2 / 35 + 2:.3f}); triangles {head['triangle_faces_percent']:.2f}% "
        f"(paper 13.50)"
    )
    total = next(r for r in summary["classes"] if r["n"] == "total")
    rnd = next(r for r in summary["round"] if r["grains"] == "all")
    worst = 0.0
    print(f"  {'':10s}{'paper %':>9s}{'here %':>9s}{'dev/SE':>8s}{'dev/SEd':>9s}")
    rows = [(k, 100 * v / V_GRAINS, 100 * total[k] / total["all"]) for k, v in V_CLASSES.items()]
    rows += [(k, v, rnd[k]) for k, v in V_ROUND.items()]
    grains = total["all"]
    for name, paper, here in rows:
        p, q = paper / 100, here / 100
        se = 100 * math.sqrt(p * (1 - p) / V_GRAINS)
        # Both are samples: the difference of two binomial fractions has this standard error.
        se_difference = 100 * math.sqrt(p * (1 - p) / V_GRAINS + q * (1 - q) / grains)
        worst = max(worst, abs(here - paper) / se_difference)
        print(
            f"  {name:10s}{paper:9.2f}{here:9.2f}{(here - paper) / se:8.1f}"
            f"{(here - paper) / se_difference:9.1f}"
        )
    print(
        f"largest deviation: {worst:.1f} standard errors of the difference (SEd); dev/SE is in "
        "binomial standard errors of the paper's fraction alone"
    )
    return 0 if worst <= 4 else 1


if __name__ == "__main__":
    sys.exit(main())
