"""The grains that more than one benchmark times: a sample of plantri's triangulations, and the
k-gonal prism."""

from __future__ import annotations

import subprocess
from pathlib import Path

# Triangulations of the sphere with n vertices (plantri's counts, OEIS A000109).
TRIANGULATIONS = {14: 339_722, 15: 2_406_841, 16: 17_490_241, 17: 129_664_753}


def sample_parts(n: int) -> int:
    """How many parts ``sample`` cuts the enumeration with n vertices into."""
    return max(1, TRIANGULATIONS.get(n, 0) // 1_000_000)


def sample(plantri: str, n: int, path: Path) -> None:
    """About a million triangulations with n vertices into ``path``: plantri's part 0 of as many
    (``0/mod``) as the enumeration has millions. Its first million would not do: at n = 16 they
    are all stacked, a grain the kernels classify without looking for empty triangles, 4-belts
    or truncation trees (the whole enumeration is 10% stacked, 72% flag and 18% sc; part 0/17,
    10%, 69% and 18%)."""
    subprocess.run(
        [plantri, str(n), f"0/{sample_parts(n)}", str(path)], check=True, capture_output=True
    )


def prism_line(k: int) -> str:
    """The k-gonal prism as a line of adjacency text: k quadrilaterals and two k-gons."""
    faces = [[k, (i - 1) % k, k + 1, (i + 1) % k] for i in range(k)]
    faces += [list(range(k)), list(reversed(range(k)))]
    return f"prism{k}\t" + ";".join(" ".join(map(str, f)) for f in faces) + "\n"
