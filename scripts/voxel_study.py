"""Label images of periodic Voronoi tessellations, their exact grains, and the naive voxel rule.

The ground truth of issue 40's resolution study. Seeds in the periodic unit cube (uniform
random, or centroidal after Lloyd iterations) are tessellated exactly, by grainclass (types) and
by the ``voro++`` program (each cell's shortest edge), and voxelized: R^3 voxels, each labelled
by the seed nearest to its centre (periodic distance), label = seed id (1-based, 0 stays free).
The naive rule reads a grain's faces and their adjacencies off the image; ``compare`` measures
any per-grain Parquet of an image (the naive rule's, or ``grainclass classify IMAGE.npy``'s)
against the truth.

    python scripts/voxel_study.py seeds cvt 200 --seed 1 -o cvt200.seeds.txt
    python scripts/voxel_study.py voxelize cvt200.seeds.txt 146 -o cvt200_146.npy
    python scripts/voxel_study.py truth cvt200.seeds.txt 146 --image cvt200_146.npy -o T.parquet
    python scripts/voxel_study.py naive cvt200_146.npy -o cvt200_146.naive.parquet
    python scripts/voxel_study.py compare cvt200_146.naive.parquet T.parquet
    python scripts/voxel_study.py image cvt 200 146 --out DIR     (the four steps above)
    python scripts/voxel_study.py study --out DIR                 (every image of the study)
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numba
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

THRESHOLDS = (1, 2, 3)  # shortest true edge, in voxels, of the grains counted apart
LLOYD_STEPS = 20
SEED = 40  # the random seed of every seed set of the study
TOPOLOGY_HELP = "also grainclass classify IMAGE.npy (NAME.grainclass.parquet), measured beside"


# ---------------------------------------------------------------------------------- seeds


def read_seeds(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """Ids (int64) and positions (float64, shape (N, 3), x y z) of a Voro++ points file."""
    table = np.loadtxt(path, ndmin=2)
    return table[:, 0].astype(np.int64), np.ascontiguousarray(table[:, 1:4])


def write_seeds(path: str | Path, xyz: np.ndarray) -> None:
    """Points ``1 .. N`` as Voro++ reads them (``id x y z``), every digit of each float kept."""
    with open(path, "w") as out:
        for k, (x, y, z) in enumerate(xyz.tolist(), start=1):
            out.write(f"{k} {x!r} {y!r} {z!r}\n")


def run_voro(xyz: np.ndarray, custom: str) -> list[str]:
    """The ``voro++`` program's custom output ``custom`` (which starts with ``%i``) for the
    periodic unit cube, one line a seed, in the seeds' order (``-o``), checked by its ids."""
    with tempfile.TemporaryDirectory() as tmp:
        points = Path(tmp) / "points"
        write_seeds(points, xyz)
        subprocess.run(
            ["voro++", "-p", "-o", "-c", custom, "0", "1", "0", "1", "0", "1", str(points)],
            check=True,
        )
        lines = Path(f"{points}.vol").read_text().splitlines()
    if [int(line.split(maxsplit=1)[0]) for line in lines] != list(range(1, len(xyz) + 1)):
        raise RuntimeError(f"voro++ gave the cells of {len(xyz)} seeds out of order, or not all")
    return lines


def make_seeds(kind: str, n: int, seed: int = SEED, lloyd: int = LLOYD_STEPS) -> np.ndarray:
    """``n`` uniform random seeds (``poisson``), or those moved ``lloyd`` times to the centroids
    of their periodic Voronoi cells (``cvt``, Lloyd's algorithm), in [0, 1)^3."""
    xyz = np.random.default_rng(seed).random((n, 3))
    if kind == "poisson":
        return xyz
    for _ in range(lloyd):
        lines = run_voro(xyz, "%i %C")
        centroids = np.array([[float(v) for v in line.split()[1:4]] for line in lines])
        xyz = centroids % 1.0
        xyz[xyz >= 1.0] = 0.0  # -1e-17 % 1.0 is 1.0
    return xyz


# ---------------------------------------------------------------------------------- voxels


@numba.njit(cache=True, nogil=True)
def _nearest_seeds(xyz, cell_start, cell_seeds, grid, resolution, z0, z1, out):
    """Label voxels z0 <= z < z1 of ``out`` (uint32, [z, y, x]) with the 1-based index of the
    seed nearest (periodic) to each voxel's centre; ties go to the lower index. Seeds are found
    ring by ring of the ``grid``^3 cell list until no farther ring can hold a nearer one."""
    side = 1.0 / grid
    for z in range(z0, z1):
        pz = (z + 0.5) / resolution
        cz = min(int(pz * grid), grid - 1)
        for y in range(resolution):
            py = (y + 0.5) / resolution
            cy = min(int(py * grid), grid - 1)
            for x in range(resolution):
                px = (x + 0.5) / resolution
                cx = min(int(px * grid), grid - 1)
                best, best_d2 = -1, np.inf
                ring = 0
                while True:
                    for dz in range(-ring, ring + 1):
                        for dy in range(-ring, ring + 1):
                            for dx in range(-ring, ring + 1):
                                if max(abs(dx), abs(dy), abs(dz)) != ring:
                                    continue
                                cell = ((cz + dz) % grid * grid + (cy + dy) % grid) * grid + (
                                    cx + dx
                                ) % grid
                                for k in range(cell_start[cell], cell_start[cell + 1]):
                                    s = cell_seeds[k]
                                    ex = xyz[s, 0] - px
                                    ey = xyz[s, 1] - py
                                    ez = xyz[s, 2] - pz
                                    ex -= np.floor(ex + 0.5)
                                    ey -= np.floor(ey + 0.5)
                                    ez -= np.floor(ez + 0.5)
                                    d2 = ex * ex + ey * ey + ez * ez
                                    if d2 < best_d2 or (d2 == best_d2 and s < best):
                                        best, best_d2 = s, d2
                    # A seed in ring r + 1 or beyond is at least r cell sides away.
                    if best >= 0 and best_d2 <= (ring * side) ** 2:
                        break
                    if 2 * ring + 1 >= grid:
                        break
                    ring += 1
                out[z, y, x] = best + 1


def voxelize(xyz: np.ndarray, resolution: int, jobs: int = 1) -> np.ndarray:
    """The label image (uint32, [z, y, x], ``resolution``^3) of the seeds ``xyz`` in the periodic
    unit cube: each voxel holds the 1-based index of the seed nearest its centre."""
    n = len(xyz)
    grid = max(1, round(n ** (1 / 3)))
    cells = np.minimum((xyz * grid).astype(np.int64), grid - 1)
    cell_of = (cells[:, 2] * grid + cells[:, 1]) * grid + cells[:, 0]
    cell_seeds = np.argsort(cell_of, kind="stable").astype(np.int64)
    cell_start = np.searchsorted(cell_of[cell_seeds], np.arange(grid**3 + 1)).astype(np.int64)
    out = np.zeros((resolution,) * 3, dtype=np.uint32)
    step = max(1, resolution // (8 * jobs))
    ranges = [(z, min(z + step, resolution)) for z in range(0, resolution, step)]
    args = (np.ascontiguousarray(xyz), cell_start, cell_seeds, grid, resolution)
    with ThreadPoolExecutor(jobs) as pool:
        list(pool.map(lambda r: _nearest_seeds(*args, r[0], r[1], out), ranges))
    return out


# ---------------------------------------------------------------------------------- truth


def shortest_edges(xyz: np.ndarray) -> tuple[np.ndarray, np.ndarray, list[list[int]]]:
    """Per seed, its cell's number of faces, the length of its shortest edge (box units), from
    the ``voro++`` program's vertices (%p) and faces' vertex loops (%t), and the 1-based ids of
    the seeds across its faces (%n), sorted."""
    faces, shortest, neighbors = [], [], []
    for line in run_voro(xyz, "%i %s %w %p %t %n"):
        tokens = line.split()
        n_faces, n_vertices = int(tokens[1]), int(tokens[2])
        vertices = np.array(
            [[float(v) for v in t[1:-1].split(",")] for t in tokens[3 : 3 + n_vertices]]
        )
        pairs = set()
        for loop in tokens[3 + n_vertices : 3 + n_vertices + n_faces]:
            ring = [int(v) for v in loop[1:-1].split(",")]
            pairs.update(
                (min(a, b), max(a, b)) for a, b in zip(ring, ring[1:] + ring[:1], strict=True)
            )
        ends = np.array(sorted(pairs))
        lengths = np.linalg.norm(vertices[ends[:, 0]] - vertices[ends[:, 1]], axis=1)
        faces.append(n_faces)
        shortest.append(lengths.min())
        neighbors.append(sorted(int(t) for t in tokens[3 + n_vertices + n_faces :]))
    return np.array(faces), np.array(shortest), neighbors


def truth_table(seeds: str | Path, resolution: int, image: np.ndarray | None = None) -> pa.Table:
    """The exact grains of the seeds' periodic Voronoi tessellation, one row per seed in label
    order: grainclass's type of each cell, and its shortest edge in box units and in voxels of
    an image of ``resolution``^3; with the ``image``, each label's voxel count, and the checks
    that label k is the cell of seed k."""
    ids, xyz = read_seeds(seeds)
    if not np.array_equal(ids, np.arange(1, len(ids) + 1)):
        raise ValueError(f"{seeds}: seed ids must be 1 .. N in order")
    with tempfile.TemporaryDirectory() as tmp:
        cells_path = Path(tmp) / "cells.parquet"
        subprocess.run(
            [sys.executable, "-m", "grainclass", "voronoi", "--points", str(seeds),
             "--points-format", "voro", "--box", "1", "--periodic", "xyz", "-q",
             "-o", str(cells_path)],
            check=True,
        )  # fmt: skip
        cells = pq.read_table(
            cells_path, columns=["grain_id", "status", "n_faces", "weinberg", "volume"]
        ).to_pandas()
    cells["label"] = cells["grain_id"].astype(np.int64)
    cells = cells.set_index("label").reindex(ids)
    if cells["grain_id"].isna().any():
        raise RuntimeError(f"{seeds}: grainclass gave no cell to some seeds")
    faces, shortest, neighbors = shortest_edges(xyz)
    if not np.array_equal(faces, cells["n_faces"].to_numpy()):
        raise RuntimeError(f"{seeds}: voro++ and grainclass count different faces")
    columns = {
        "grain_id": pa.array(cells["grain_id"].to_numpy(dtype=str)),
        "label": pa.array(ids.astype(np.uint32)),
        "n_faces": pa.array(faces.astype(np.int32)),
        "weinberg": pa.array(cells["weinberg"].to_numpy(dtype=str)),
        "status": pa.array(cells["status"].to_numpy(dtype=str)),
        "volume": pa.array(cells["volume"].to_numpy(dtype=np.float64)),
        "shortest_edge": pa.array(shortest),
        "shortest_edge_voxels": pa.array(shortest * resolution),
        "neighbors": pa.array(neighbors, pa.list_(pa.uint32())),
    }
    if image is not None:
        columns["voxels"] = pa.array(check_labels(image, xyz, cells["volume"].to_numpy()))
    metadata = {"resolution": str(resolution), "seeds": str(seeds)}
    return pa.table(columns).replace_schema_metadata(metadata)


def check_labels(image: np.ndarray, xyz: np.ndarray, volume: np.ndarray) -> np.ndarray:
    """Each label's voxel count, after checking that label k is seed k's cell: the voxel holding
    seed k is labelled k wherever the seed is more than a voxel inside its cell (where its
    voxel's centre is nearer to it than to any other seed), and voxel volumes follow the cells'."""
    resolution = image.shape[0]
    counts = np.bincount(image.ravel(), minlength=len(xyz) + 1)[1:]
    if counts.sum() != image.size or (image == 0).any():
        raise RuntimeError("voxels without a label")
    at_seed = image[tuple(np.minimum((xyz[:, ::-1] * resolution).astype(int), resolution - 1).T)]
    own = at_seed == np.arange(1, len(xyz) + 1)
    if own.mean() < 0.99:
        raise RuntimeError(f"only {own.mean():.1%} of the seeds lie in voxels of their label")
    error = np.abs(counts / image.size - volume).sum() / 2
    if error > 0.05:
        raise RuntimeError(f"voxel volumes are {error:.1%} off the cells' volumes")
    return counts.astype(np.int64)


# ---------------------------------------------------------------------------------- naive rule


def _distinct_triples(a, b, c, d) -> np.ndarray:
    """Sorted (i, j, k) of the 2x2 columns whose four labels hold exactly three values."""
    boundary = (a != b) | (a != c) | (a != d)
    s = np.sort(np.stack([a[boundary], b[boundary], c[boundary], d[boundary]]), axis=0)
    distinct = 1 + (s[1] != s[0]) + (s[2] != s[1]) + (s[3] != s[2])
    three = distinct == 3
    s = s[:, three]
    middle = np.where(s[0] == s[1], s[2], s[1])
    return np.stack([s[0], middle, s[3]], axis=1).astype(np.int64)


def naive_contacts(image: np.ndarray, depth: int = 16) -> tuple[np.ndarray, np.ndarray]:
    """The naive rule's pairs (i < j: labels touching across a voxel face) and triples
    (i < j < k: labels making up exactly a 2x2 column of voxels around a lattice edge) of a
    periodic label image, read in slabs of ``depth`` layers along z."""
    nz = image.shape[0]
    pairs, triples = [], []
    for z0 in range(0, nz, depth):
        block = image[np.arange(z0, min(z0 + depth, nz) + 1) % nz]
        here, above = block[:-1], block[1:]
        for other in (np.roll(here, -1, axis=2), np.roll(here, -1, axis=1), above):
            touch = here != other
            low = np.minimum(here[touch], other[touch]).astype(np.int64)
            high = np.maximum(here[touch], other[touch]).astype(np.int64)
            pairs.append(np.unique(np.stack([low, high], axis=1), axis=0))
        # The columns around the lattice edges along x, y and z from each voxel's far corner.
        y1, x1 = np.roll(here, -1, axis=1), np.roll(here, -1, axis=2)
        columns = (
            (here, y1, above, np.roll(above, -1, axis=1)),
            (here, x1, above, np.roll(above, -1, axis=2)),
            (here, y1, x1, np.roll(y1, -1, axis=2)),
        )
        for column in columns:
            triples.append(np.unique(_distinct_triples(*column), axis=0))
    return np.unique(np.concatenate(pairs), axis=0), np.unique(np.concatenate(triples), axis=0)


def naive_adjacency(image: np.ndarray) -> list[str]:
    """Adjacency text (grainclass's ``id<TAB>faces``, lists unordered) of every label of the
    image by the naive rule: the faces of grain i are the labels touching it across a voxel face;
    faces j and k of grain i share an edge wherever a 2x2 column of voxels holds exactly
    {i, j, k}, kept only where both j and k are faces of i."""
    pairs, triples = naive_contacts(image)
    faces: dict[int, set[int]] = {}
    for i, j in pairs.tolist():
        faces.setdefault(i, set()).add(j)
        faces.setdefault(j, set()).add(i)
    edges: dict[int, set[tuple[int, int]]] = {}
    for i, j, k in triples.tolist():
        edges.setdefault(i, set()).add((j, k))
        edges.setdefault(j, set()).add((i, k))
        edges.setdefault(k, set()).add((i, j))
    lines = []
    for grain in sorted(faces):
        order = sorted(faces[grain])
        index = {face: n for n, face in enumerate(order)}
        around: list[list[int]] = [[] for _ in order]
        for j, k in sorted(edges.get(grain, ())):
            if j in index and k in index:
                around[index[j]].append(index[k])
                around[index[k]].append(index[j])
        lists = ";".join(" ".join(map(str, sorted(a))) for a in around)
        lines.append(f"{grain}\t{lists}")
    return lines


def naive_table(image_path: str | Path, output: str | Path) -> None:
    """The naive rule's grains of a label image, classified by grainclass into the per-grain
    Parquet ``output`` (the columns of ``grainclass classify``; grain_id = label)."""
    from grainclass.datasets import write_grains

    image = np.load(image_path, mmap_mode="r")
    lines = naive_adjacency(np.asarray(image))
    with tempfile.TemporaryDirectory() as tmp:
        text = Path(tmp) / f"{Path(image_path).stem}.naive.txt"
        text.write_text("\n".join(lines) + "\n")
        write_grains(str(text), str(output), metadata={"image": str(image_path)})


# ---------------------------------------------------------------------------------- compare


def compare(result: str | Path, truth: str | Path) -> dict:
    """Shares of the truth's grains that the per-grain table ``result`` gets right: the exact type
    (status ok and the truth's Weinberg vector), the number of faces, and the exact type among
    grains whose shortest true edge is at least 1, 2, 3 voxels. A grain missing from the
    result counts as wrong."""
    want = pq.read_table(truth, columns=["grain_id", "n_faces", "weinberg", "shortest_edge_voxels"])
    got = pq.read_table(result, columns=["grain_id", "status", "n_faces", "weinberg"])
    got_df = got.to_pandas().drop_duplicates("grain_id").set_index("grain_id")
    want_df = want.to_pandas().set_index("grain_id")
    if len(got_df) and not got_df.index.isin(want_df.index).any():
        raise SystemExit(f"{result}: no grain_id is a label of {truth} (first: {got_df.index[0]})")
    got_df = got_df.reindex(want_df.index)
    exact = (got_df["status"] == "ok") & (got_df["weinberg"] == want_df["weinberg"])
    right_n = got_df["n_faces"] == want_df["n_faces"]
    shares = {
        "grains": len(want_df),
        "found": int(got_df["status"].notna().sum()),
        "ok": int((got_df["status"] == "ok").sum()),
        "exact_type": float(exact.mean()),
        "right_n": float(right_n.mean()),
    }
    for t in THRESHOLDS:
        chosen = want_df["shortest_edge_voxels"] >= t
        shares[f"edge_ge_{t}_grains"] = int(chosen.sum())
        shares[f"edge_ge_{t}_exact_type"] = float(exact[chosen].mean()) if chosen.any() else None
    return shares


def print_shares(shares: dict, name: str = "") -> None:
    print(
        f"{name}{shares['grains']} grains, {shares['found']} in the result, {shares['ok']} ok: "
        f"exact type {shares['exact_type']:.1%}, right n {shares['right_n']:.1%}"
    )
    for t in THRESHOLDS:
        share = shares[f"edge_ge_{t}_exact_type"]
        text = "-" if share is None else f"{share:.1%}"
        print(f"  shortest true edge >= {t} voxels: {shares[f'edge_ge_{t}_grains']} grains, "
              f"exact type {text}")  # fmt: skip


# ---------------------------------------------------------------------------------- the study


def make_image(kind: str, n: int, resolution: int, out: Path, jobs: int = 1, topology=False):
    """Seeds, image, truth and the naive rule's table and shares of one image in ``out``:
    ``{kind}{n}.seeds.txt``, ``{kind}{n}_{R}.npy``, ``.truth.parquet``, ``.naive.parquet``,
    ``.naive.json``. Files already there are kept (delete them to make them again). With
    ``topology``, ``grainclass classify`` of the image too (``.grainclass.parquet``); where that
    file is there, its shares go to ``.grainclass.json``. Returns {rule: shares}."""
    out.mkdir(parents=True, exist_ok=True)
    seeds = out / f"{kind}{n}.seeds.txt"
    name = f"{kind}{n}_{resolution}"
    image_path, truth_path = out / f"{name}.npy", out / f"{name}.truth.parquet"
    naive_path, topology_path = out / f"{name}.naive.parquet", out / f"{name}.grainclass.parquet"
    times = {}
    start = time.perf_counter()
    if not seeds.exists():
        write_seeds(seeds, make_seeds(kind, n))
        times["seeds"] = time.perf_counter() - start
    if not image_path.exists():
        start = time.perf_counter()
        image = voxelize(read_seeds(seeds)[1], resolution, jobs)
        times["voxelize"] = time.perf_counter() - start
        _save_whole(image_path, lambda path: np.save(path, image))
        del image
    if not truth_path.exists():
        start = time.perf_counter()
        image = np.load(image_path)
        table = truth_table(seeds, resolution, image)
        del image
        _save_whole(truth_path, lambda path: pq.write_table(table, path))
        times["truth"] = time.perf_counter() - start
    if not naive_path.exists():
        start = time.perf_counter()
        _save_whole(naive_path, lambda path: naive_table(image_path, path))
        times["naive"] = time.perf_counter() - start
    if topology and not topology_path.exists():
        start = time.perf_counter()
        command = [sys.executable, "-m", "grainclass", "classify", "-q", "--periodic", "xyz"]
        _save_whole(
            topology_path,
            lambda path: subprocess.run([*command, str(image_path), "-o", str(path)], check=True),
        )
        times["grainclass"] = time.perf_counter() - start
    results = {}
    for rule, table in (("naive", naive_path), ("grainclass", topology_path)):
        if not table.exists():
            continue
        shares_path = out / f"{name}.{rule}.json"
        shares = compare(table, truth_path)
        shares.update(
            image=image_path.name, kind=kind, seeds=n, resolution=resolution,
            voxels_across=round(resolution / n ** (1 / 3), 2),  # side / mean seed spacing
        )  # fmt: skip
        if times:
            shares["seconds"] = {k: round(v, 1) for k, v in times.items()}
        elif shares_path.exists():
            shares["seconds"] = json.loads(shares_path.read_text()).get("seconds", {})
        shares_path.write_text(json.dumps(shares, indent=1) + "\n")
        results[rule] = shares
    return results


def _save_whole(path: Path, save) -> None:
    """``save(temporary)`` then a rename: a file of the study is whole or absent."""
    partial = path.with_name(f".{path.stem}.partial{path.suffix}")
    save(partial)
    os.replace(partial, path)


STUDY = (
    ("cvt", 200, (25,)),  # small and fast: 146^3
    ("cvt", 2000, (8, 12, 16, 24, 25.4, 32)),  # 25.4: the 320^3
    ("poisson", 2000, (8, 12, 16, 24, 25.4, 32)),
)


def study_images(kinds=None, largest: float = 32) -> list[tuple[str, int, int]]:
    images = []
    for kind, n, acrosses in STUDY:
        if kinds and f"{kind}{n}" not in kinds:
            continue
        # R = round(v * N^(1/3)) for v voxels across a grain.
        images += [(kind, n, round(a * n ** (1 / 3))) for a in acrosses if a <= largest]
    # The 320^3 images first, after the small one: they are wanted first.
    return sorted(images, key=lambda i: (i[2] != 146, i[2] != 320, i[1], i[2], i[0]))


def table_rows(results: list[dict]) -> list[str]:
    """The study as Markdown: per seed set, each measure's share (%) by the naive rule and by
    grainclass (blank where its table is not there), and the grains each edge bound keeps."""
    rows = []
    measures = [("exact type", "exact_type"), ("right n", "right_n")]
    measures += [(f"edge >= {t}", f"edge_ge_{t}_exact_type") for t in THRESHOLDS]
    results = sorted(results, key=lambda r: (r["naive"]["seeds"], r["naive"]["resolution"]))
    for kind, title in (("cvt", "CVT"), ("poisson", "Poisson")):
        chosen = [r for r in results if r["naive"]["kind"] == kind]
        if not chosen:
            continue
        head = "| seeds | voxels across | image |"
        head += "".join(f" {label}: naive rule | {label}: grainclass |" for label, _ in measures)
        head += " grains (edge >= 1, 2, 3) |"
        rows += [f"**{title}**", "", head, "|---" * (4 + 2 * len(measures)) + "|"]
        for r in chosen:
            naive, topology = r["naive"], r.get("grainclass", {})
            row = f"| {title} {naive['seeds']} | {naive['voxels_across']:.1f} "
            row += f"| {naive['resolution']}^3 |"
            for _, key in measures:
                for share in (naive[key], topology.get(key)):
                    row += " |" if share is None else f" {100 * share:.1f} |"
            counts = ", ".join(str(naive[f"edge_ge_{t}_grains"]) for t in THRESHOLDS)
            rows.append(row + f" {naive['grains']} ({counts}) |")
        rows.append("")
    return rows


def plot_study(results: list[dict], path: str) -> None:
    """Exact-type shares of the 2,000-seed images against voxels across a grain: all grains
    (circles), and those whose shortest edge is >= 2 voxels where there are 20 or more
    (triangles); naive rule solid, grainclass dashed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6.4, 4.2))
    for (kind, color), (rule, line) in itertools.product(
        (("cvt", "C0"), ("poisson", "C3")), (("naive", "-"), ("grainclass", "--"))
    ):
        chosen = [r[rule] for r in results if rule in r and r[rule]["kind"] == kind]
        chosen = sorted((s for s in chosen if s["seeds"] == 2000), key=lambda s: s["resolution"])
        for key, marker, what in (("", "o", "all grains"), ("edge_ge_2_", "^", "edge >= 2")):
            shares = [
                100 * s[f"{key}exact_type"] if s.get(f"{key}grains", 20) >= 20 else np.nan
                for s in chosen
            ]
            name = f"{'CVT' if kind == 'cvt' else 'Poisson'}, {rule} rule, {what}"
            label = name.replace("grainclass rule", "grainclass")
            if chosen:
                across = [s["voxels_across"] for s in chosen]
                axes.plot(across, shares, line + marker, color=color, label=label)
    axes.set(xlabel="voxels across a grain", ylabel="exact types (%)", ylim=(0, 100))
    axes.legend(fontsize=7, loc="lower right")
    figure.savefig(path, dpi=120, bbox_inches="tight")


# ---------------------------------------------------------------------------------- commands


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("seeds", help="poisson or cvt seeds in the periodic unit cube")
    p.add_argument("kind", choices=("poisson", "cvt"))
    p.add_argument("n", type=int)
    p.add_argument("--seed", type=int, default=SEED)
    p.add_argument("--lloyd", type=int, default=LLOYD_STEPS)
    p.add_argument("-o", "--output", required=True)
    p = sub.add_parser("voxelize", help="the label image of a seeds file, .npy [z, y, x]")
    p.add_argument("seeds")
    p.add_argument("resolution", type=int)
    p.add_argument("-j", "--jobs", type=int, default=1)
    p.add_argument("-o", "--output", required=True)
    p = sub.add_parser("truth", help="the exact grains of a seeds file, as Parquet")
    p.add_argument("seeds")
    p.add_argument("resolution", type=int)
    p.add_argument("--image", help="the seeds' image: adds voxel counts, checks the labels")
    p.add_argument("-o", "--output", required=True)
    p = sub.add_parser("naive", help="the naive rule's grains of an image, as grainclass Parquet")
    p.add_argument("image")
    p.add_argument("-o", "--output", required=True)
    p = sub.add_parser("compare", help="shares of a per-grain Parquet against the truth")
    p.add_argument("result")
    p.add_argument("truth")
    p.add_argument("--json", action="store_true", help="the shares as JSON")
    p = sub.add_parser("image", help="seeds, image, truth and naive rule of one image")
    p.add_argument("kind", choices=("poisson", "cvt"))
    p.add_argument("n", type=int)
    p.add_argument("resolution", type=int)
    p.add_argument("--out", type=Path, required=True)
    p.add_argument("-j", "--jobs", type=int, default=1)
    p.add_argument("--grainclass", action="store_true", help=TOPOLOGY_HELP)
    p = sub.add_parser("study", help="every image of the resolution study, and its table")
    p.add_argument("--out", type=Path, required=True)
    p.add_argument("--only", nargs="*", help="seed sets to make (cvt200, cvt2000, poisson2000)")
    p.add_argument("--largest", type=float, default=32, help="most voxels across a grain")
    p.add_argument("-j", "--jobs", type=int, default=1)
    p.add_argument("--grainclass", action="store_true", help=TOPOLOGY_HELP)
    p.add_argument("--plot", help="draw the shares into this figure (.png, .svg)")
    args = parser.parse_args(argv)

    if args.command == "seeds":
        write_seeds(args.output, make_seeds(args.kind, args.n, args.seed, args.lloyd))
    elif args.command == "voxelize":
        np.save(args.output, voxelize(read_seeds(args.seeds)[1], args.resolution, args.jobs))
    elif args.command == "truth":
        image = None if args.image is None else np.load(args.image)
        pq.write_table(truth_table(args.seeds, args.resolution, image), args.output)
    elif args.command == "naive":
        naive_table(args.image, args.output)
    elif args.command == "compare":
        shares = compare(args.result, args.truth)
        if args.json:
            print(json.dumps(shares, indent=1))
        else:
            print_shares(shares)
    elif args.command == "image":
        results = make_image(
            args.kind, args.n, args.resolution, args.out, args.jobs, args.grainclass
        )
        for rule, shares in results.items():
            print_shares(shares, f"{rule}: ")
    else:
        results = []
        for kind, n, resolution in study_images(args.only, args.largest):
            shares = make_image(kind, n, resolution, args.out, args.jobs, args.grainclass)
            for rule, rule_shares in shares.items():
                print_shares(rule_shares, f"{rule_shares['image']}, {rule}: ")
            sys.stdout.flush()
            results.append(shares)
        print("\n".join(table_rows(results)))
        if args.plot:
            plot_study(results, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
