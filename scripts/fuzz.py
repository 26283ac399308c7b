"""``make fuzz``: mutation fuzzing of every reader, in process, from the seed files in tests/data.

Each case takes a seed (adjacency text, face loops, planar_code, Voro++ output, Neper .tess,
Surface Evolver .fe, 3D label images: NumPy, TIFF, DREAM.3D, .vti, SPPARKS dump, .tesr),
mutates its bytes (flips, insertions, deletions, repeats, splices with another seed, numbers
made huge, negative or long, lines cut or repeated), reads it with the seed's format named and
classifies it with types. A finding is any exception that is not a typed grainclass error, a
lost row (classify's table shorter than the batches read, or, for adjacency text, fewer rows
than lines of grains), or a case slower than a bound. A label image is also opened with its
format's reader and read slab by slab: it must end in a whole image (every slab of the shape
and type the image declares, as many voxels as it has) or in a typed grainclass error. Each
finding's input is written to a folder (``--findings``), to be kept in
tests/data/fuzz/findings, where tests/test_fuzz_findings.py runs each through the same checks.
"""

from __future__ import annotations

import argparse
import logging
import random
import sys
import tempfile
import time
import traceback
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data"

# (seed file, format named, file suffix)
SEEDS = [
    (DATA / "fuzz" / "grains.txt", "adjacency", ".txt"),
    (DATA / "fuzz" / "cells.loops", "loops", ".loops"),
    (DATA / "fuzz" / "plantri-8.pc", "planar_code", ".pc"),
    (DATA / "fuzz" / "cells.voro", "voro", ".voro"),
    (DATA / "neper" / "cube.tess", "neper", ".tess"),
    (DATA / "neper" / "two_cells.tess", "neper", ".tess"),
    (DATA / "evolver" / "two_cubes.fe", "evolver", ".fe"),
    (DATA / "evolver" / "grain3d" / "21000-00000053.fe", "evolver", ".fe"),
    (DATA / "fuzz" / "image.npy", "npy", ".npy"),
    (DATA / "fuzz" / "images" / "labels.tif", "tiff", ".tif"),
    (DATA / "fuzz" / "images" / "labels.dream3d", "dream3d", ".dream3d"),
    (DATA / "fuzz" / "images" / "raw.vti", "vti", ".vti"),
    (DATA / "fuzz" / "images" / "zlib.vti", "vti", ".vti"),
    (DATA / "fuzz" / "images" / "ascii.vti", "vti", ".vti"),
    (DATA / "images" / "damask-voronoi.vti", "vti", ".vti"),
    (DATA / "fuzz" / "images" / "sites.dump", "spparks", ".dump"),
    (DATA / "fuzz" / "images" / "ascii.tesr", "tesr", ".tesr"),
    (DATA / "fuzz" / "images" / "binary.tesr", "tesr", ".tesr"),
]

NUMBERS = [b"0", b"-1", b"1", b"2147483648", b"9223372036854775808", b"1e308", b"nan", b"-0",
           b"99999999999999999999999999", b"3.5", b"inf"]  # fmt: skip


def mutate(data: bytes, other: bytes, rng: random.Random) -> bytes:
    """One to four random mutations of ``data`` (``other``: another seed to splice from)."""
    buf = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        kind = rng.randrange(9)
        at = rng.randrange(len(buf) + 1)
        if kind == 0 and buf:  # flip a bit
            i = rng.randrange(len(buf))
            buf[i] ^= 1 << rng.randrange(8)
        elif kind == 1:  # insert random bytes or a separator
            piece = rng.choice([b";", b" ", b"\t", b"\n", b"(", b")", b",", b"\0", b"\r", b"#"])
            buf[at:at] = piece * rng.randint(1, 3)
        elif kind == 2 and buf:  # delete a run
            del buf[at : at + rng.randint(1, 16)]
        elif kind == 3 and buf:  # repeat a run
            end = min(len(buf), at + rng.randint(1, 64))
            buf[at:at] = buf[at:end] * rng.randint(1, 8)
        elif kind == 4 and other:  # splice in part of another seed
            i = rng.randrange(len(other))
            buf[at:at] = other[i : i + rng.randint(1, 200)]
        elif kind == 5:  # a number replaced by an extreme one
            digits = [i for i, c in enumerate(buf) if 48 <= c <= 57]
            if digits:
                i = rng.choice(digits)
                buf[i : i + 1] = rng.choice(NUMBERS)
        elif kind == 6:  # cut
            del buf[at:]
        elif kind == 7 and buf:  # a line repeated many times
            lines = bytes(buf).split(b"\n")
            j = rng.randrange(len(lines))
            lines[j:j] = [lines[j]] * rng.randint(2, 50)
            buf = bytearray(b"\n".join(lines))
        elif kind == 8 and buf:  # random bytes overwritten
            for _ in range(rng.randint(1, 8)):
                buf[rng.randrange(len(buf))] = rng.randrange(256)
    return bytes(buf)


def data_lines(data: bytes) -> int | None:
    """Lines of grains in adjacency text (not blank, not a comment: ``#`` after any blanks, as
    the reader has it), or None if the text is
    not plain enough to count (a byte that is not printable ASCII, tab or newline)."""
    if any((c < 32 and c not in (9, 10)) or c > 126 for c in data):
        return None
    lines = data.split(b"\n")
    return sum(1 for line in lines if line.strip() and not line.lstrip().startswith(b"#"))


def run_image_case(path: Path, fmt: str) -> tuple[str | None, float]:
    """``(finding, seconds)``: what is wrong with opening the label image ``path`` and reading
    it in slabs of 2 slices, or None."""
    import numpy as np

    from grainclass.errors import GrainclassError
    from grainclass.readers.images import IMAGE_OPENERS

    opener = IMAGE_OPENERS[fmt]
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            image = opener(str(path))
            _, ny, nx = image.shape
            voxels = 0
            for slab in image.slabs(2):
                if not (
                    isinstance(slab, np.ndarray)
                    and slab.ndim == 3
                    and 1 <= slab.shape[0] <= 2
                    and slab.shape[1:] == (ny, nx)
                    and slab.dtype == image.dtype
                ):
                    shape = getattr(slab, "shape", None)
                    return f"a slab of shape {shape} in a {image.shape} image", 0.0
                voxels += slab.size
    except GrainclassError:
        return None, time.perf_counter() - start
    except Exception:  # a finding: anything else that escapes
        return traceback.format_exc(limit=6), time.perf_counter() - start
    if voxels != image.voxels:
        return f"lost voxels: {voxels} read of {image.voxels}", time.perf_counter() - start
    return None, time.perf_counter() - start


def run_case(path: Path, fmt: str, data: bytes) -> tuple[str | None, float]:
    """``(finding, seconds)``: what is wrong with reading and classifying ``path``, or None. A
    label image is first read slab by slab (:func:`run_image_case`)."""
    from grainclass import classify, read_dataset
    from grainclass.errors import GrainclassError
    from grainclass.readers.images import IMAGE_OPENERS

    opened = 0.0
    if fmt in IMAGE_OPENERS:
        finding, opened = run_image_case(path, fmt)
        if finding:
            return finding, opened
    start = time.perf_counter() - opened
    rows = read = 0
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for batch in read_dataset(str(path), input_format=fmt):
                table = classify(batch)
                read += len(batch)
                rows += table.num_rows
                if None in table.column("status").to_pylist():
                    return "a row without a status", time.perf_counter() - start
    except GrainclassError:
        return None, time.perf_counter() - start
    except Exception:  # a finding: anything else that escapes
        return traceback.format_exc(limit=6), time.perf_counter() - start
    seconds = time.perf_counter() - start
    if rows != read:
        return f"lost rows: {read} grains read, {rows} rows", seconds
    if fmt == "adjacency":
        lines = data_lines(data)
        if lines is not None and rows != lines:
            return f"lost rows: {lines} lines of grains, {rows} rows", seconds
    return None, seconds


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--bound", type=float, default=2.0, help="seconds a case may take")
    parser.add_argument("--findings", type=Path, default=ROOT / "build" / "fuzz-findings")
    parser.add_argument(
        "--formats", help="only the seeds of these formats, comma-separated (default: all)"
    )
    args = parser.parse_args()
    from grainclass import parallel

    # tifffile logs what it finds wrong in a damaged file; the reader's error says enough.
    logging.getLogger("tifffile").setLevel(logging.CRITICAL)

    parallel.set_jobs(1)  # one case at a time, in this thread: tracebacks point at the kernel
    rng = random.Random(args.seed)
    formats = None if args.formats is None else set(args.formats.split(","))
    seeds = [
        (path.read_bytes(), fmt, suffix)
        for path, fmt, suffix in SEEDS
        if formats is None or fmt in formats
    ]
    findings = 0
    slowest = 0.0
    started = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        for case in range(args.cases):
            data, fmt, suffix = rng.choice(seeds)
            other = rng.choice(seeds)[0]
            mutated = mutate(data, other, rng)
            path = Path(tmp) / f"case{suffix}"
            path.write_bytes(mutated)
            finding, seconds = run_case(path, fmt, mutated)
            if finding is None and seconds > args.bound:
                # Once more: the first case to need a kernel waits for numba to compile it.
                finding, seconds = run_case(path, fmt, mutated)
                if finding is None and seconds > args.bound:
                    finding = f"slow: {seconds:.2f} s, more than {args.bound} s"
            slowest = max(slowest, seconds)
            if finding is not None:
                findings += 1
                args.findings.mkdir(parents=True, exist_ok=True)
                kept = args.findings / f"case-{args.seed}-{case}-{fmt}{suffix}"
                kept.write_bytes(mutated)
                print(f"case {case} ({fmt}): {kept}\n{finding}", flush=True)
            if (case + 1) % 10_000 == 0:
                elapsed = time.perf_counter() - started
                print(f"{case + 1} cases, {findings} findings, {elapsed:.0f} s", file=sys.stderr)
    elapsed = time.perf_counter() - started
    print(
        f"{args.cases} cases from {len(seeds)} seeds, {findings} findings; "
        f"slowest case {slowest:.2f} s; {elapsed:.0f} s in all"
    )
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
