"""grainclass: the combinatorial types of grains in 3D cellular microstructures.

Classifies each grain (a simple 3-polytope, given by its face adjacency) as in Lutz, Mason,
Lazar and MacPherson, *Roundness of grains in cellular microstructures*: stacked, flag or
severely constricted, with truncation trees, roundness, 4-belts, split type and penalty.

The heavy modules (numba, pyarrow, pandas) load on first use, so that importing the package
and running ``grainclass --help`` stays fast.
"""

from importlib import import_module
from typing import Any

__version__ = "0.1.0"

# Grains per batch: per compiled call, per thread and per Parquet row group.
DEFAULT_CHUNK_SIZE = 50_000

__all__ = ["GrainBatch", "__version__", "classify", "read_dataset", "summarize"]

_LAZY = {
    "GrainBatch": "grainclass.batch",
    "classify": "grainclass.classification",
    "read_dataset": "grainclass.readers",
    "summarize": "grainclass.summary",
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'grainclass' has no attribute {name!r}")
