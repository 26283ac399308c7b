"""grainclass: the combinatorial types of grains in 3D cellular microstructures.

Classifies each grain (a simple 3-polytope, given by its face adjacency) as in Lutz, Mason,
Lazar and MacPherson, *Roundness of grains in cellular microstructures*: stacked, flag or
severely constricted, with truncation trees, roundness, 4-belts, split type and penalty.

From paths in one call: :func:`read_grains` (per-grain rows as a pandas DataFrame),
:func:`summary_tables` (the paper's tables), :func:`type_counts`; batch by batch, for streams:
:func:`read_dataset`, :func:`classify`, :func:`summarize` (docs/library.md). The heavy modules
(numba, pyarrow, pandas) load on first use, so that importing the package and running
``grainclass --help`` stays fast.
"""

from importlib import import_module

__version__ = "0.1.0"

__all__ = [
    "GrainBatch",
    "GrainclassError",
    "ReadOptions",
    "__version__",
    "classify",
    "read_dataset",
    "read_grains",
    "summarize",
    "summary_tables",
    "type_counts",
]

_LAZY = {
    "GrainBatch": "grainclass.batch",
    "GrainclassError": "grainclass.errors",
    "ReadOptions": "grainclass.options",
    "classify": "grainclass.classification",
    "read_dataset": "grainclass.readers",
    "read_grains": "grainclass.datasets",
    "summarize": "grainclass.summary",
    "summary_tables": "grainclass.datasets",
    "type_counts": "grainclass.datasets",
}


def __getattr__(name: str) -> object:
    if name in _LAZY:
        return getattr(import_module(_LAZY[name]), name)
    raise AttributeError(f"module 'grainclass' has no attribute {name!r}")
