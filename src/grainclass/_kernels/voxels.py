"""The topology of a 3D label image: one compiled pass over its voxels, plane by plane.

A voxel ``(z, y, x)`` is the cube ``[x, x+1] x [y, y+1] x [z, z+1]``. The 8 voxels around a
lattice point make a *block*, indexed ``c = dx + 2 dy + 4 dz`` from its voxel of least
coordinates; the block of plane ``p`` joins planes ``p`` and ``p + 1``.

:func:`_scan_planes` reads planes once and keeps, per label (labels index dense tables): its
voxels, whether it touches a side of the image that does not wrap or the background, and the
Euler characteristic of its voxels (``V - E + F - C`` of the union of closed cubes, summed over
lattice points, lattice edges, voxel faces and voxels); per pair of labels, the voxel faces they
share; and every block with three labels or more, the only places where triple lines and
quadruple points can be.

:func:`_resolve_blocks` turns each such block into triple lines and quadruple points. The block
is cut into 24 tetrahedra, whose corners are its 8 voxel centres, the centres of its 6 faces
(each the 2x2 column of voxels around a lattice edge) and its own centre; a face centre and the
block centre get one of the labels around them. Every simplex of that mesh with three labels is
a piece of a triple line, with four a quadruple point. The mesh fills space, so whatever labels
the centres get, the triple lines and quadruple points found are those of one partition of space
into grains: they agree between the three (four) grains that share them. The labels given to
the centres are where ambiguous junctions are decided, from evidence gathered over the whole
image (the voxel faces each pair of labels shares): a column of four labels in cyclic order
a, b, c, d joins a with c or b with d; a column a, b, a, c joins b with c or separates them; a
block of five labels or more holds two quadruple points joined by a short triple line, or the
flipped three around a small face, according to its centre's label.
"""

import numpy as np

from grainclass._numba import njit

# The faces of a block, each as its 4 corners in cyclic order.
BLOCK_FACES = np.array(
    [[0, 2, 6, 4], [1, 3, 7, 5], [0, 1, 5, 4], [2, 3, 7, 6], [0, 1, 3, 2], [4, 5, 7, 6]], np.int64
)
# The columns of a block counted as its own (around the lattice edges from its centre towards
# -z, -y and -x), so that each lattice edge of the image is counted once.
OWN_COLUMNS = np.array([[0, 1, 2, 3], [0, 1, 4, 5], [0, 2, 4, 6]], np.int64)

PAIR_SHIFT = np.int64(32)


@njit(inline="always")
def _pair_key(a, b):
    lo, hi = (a, b) if a < b else (b, a)
    return (np.int64(lo) << PAIR_SHIFT) | np.int64(hi)


@njit
def _scan_planes(planes, first, last, z0, nz, px, py, pz, background, counts, euler, boundary):
    """Planes ``first .. last - 1`` of ``planes`` (shape (m, ny, nx); plane p + 1 follows
    plane p, and the last one is read only as the follower of the one before it, unless it is
    the image's last and z does not wrap). ``z0`` is the image's z of ``planes[0]``.

    Adds to ``counts``, ``euler`` (int64) and ``boundary`` (uint8), indexed by label; returns
    the keys ``lo << 32 | hi`` of the voxel faces between two labels (one entry per face, not
    background) and the blocks of three labels or more (rows of 8 labels, int64).
    O(voxels)."""
    m, ny, nx = planes.shape
    contacts = np.empty(3 * (last - first) * ny * nx + 1, np.int64)
    blocks = np.empty(((last - first) * ny * nx + 1, 8), np.int64)
    n_contacts = 0
    n_blocks = 0
    labels = np.empty(8, np.int64)
    seen = np.empty(8, np.int64)
    for p in range(first, last):
        z = z0 + p
        has_next = p + 1 < m
        side_z = pz == 0 and (z == 0 or z == nz - 1)
        for y in range(ny):
            yn = y + 1
            if yn == ny:
                yn = 0 if py else -1
            for x in range(nx):
                xn = x + 1
                if xn == nx:
                    xn = 0 if px else -1
                a = planes[p, y, x]
                counts[a] += 1
                if background[a]:
                    # A grain beyond one of its voxel faces touches the background.
                    if xn >= 0:
                        boundary[planes[p, y, xn]] = 1
                    if yn >= 0:
                        boundary[planes[p, yn, x]] = 1
                    if has_next:
                        boundary[planes[p + 1, y, x]] = 1
                    continue
                euler[a] += 5
                if side_z or (px == 0 and (x == 0 or x == nx - 1)):
                    boundary[a] = 1
                if py == 0 and (y == 0 or y == ny - 1):
                    boundary[a] = 1
                # Voxel faces towards +x, +y, +z.
                for k in range(3):
                    if k == 0:
                        if xn < 0:
                            continue
                        b = planes[p, y, xn]
                    elif k == 1:
                        if yn < 0:
                            continue
                        b = planes[p, yn, x]
                    else:
                        if not has_next:
                            continue
                        b = planes[p + 1, y, x]
                    if b == a:
                        euler[a] -= 1
                    elif background[b]:
                        boundary[a] = 1
                    else:
                        contacts[n_contacts] = _pair_key(a, b)
                        n_contacts += 1
            # The blocks of this row: lattice points and the edges counted as theirs.
            if yn < 0 or not has_next:
                continue
            for x in range(nx):
                xn = x + 1
                if xn == nx:
                    if not px:
                        continue
                    xn = 0
                labels[0] = planes[p, y, x]
                labels[1] = planes[p, y, xn]
                labels[2] = planes[p, yn, x]
                labels[3] = planes[p, yn, xn]
                labels[4] = planes[p + 1, y, x]
                labels[5] = planes[p + 1, y, xn]
                labels[6] = planes[p + 1, yn, x]
                labels[7] = planes[p + 1, yn, xn]
                a = labels[0]
                same = True
                for c in range(1, 8):
                    if labels[c] != a:
                        same = False
                        break
                if same:
                    if not background[a]:
                        euler[a] -= 2  # one lattice point, three lattice edges
                    continue
                n_seen = 0
                has_background = False
                for c in range(8):
                    label = labels[c]
                    new = True
                    for s in range(n_seen):
                        if seen[s] == label:
                            new = False
                            break
                    if new:
                        seen[n_seen] = label
                        n_seen += 1
                        if background[label]:
                            has_background = True
                        else:
                            euler[label] += 1
                for col in range(3):
                    for i in range(4):
                        label = labels[OWN_COLUMNS[col, i]]
                        if background[label]:
                            continue
                        new = True
                        for j in range(i):
                            if labels[OWN_COLUMNS[col, j]] == label:
                                new = False
                                break
                        if new:
                            euler[label] -= 1
                if n_seen >= 3 and not has_background:
                    for c in range(8):
                        blocks[n_blocks, c] = labels[c]
                    n_blocks += 1
    return contacts[:n_contacts].copy(), blocks[:n_blocks].copy()


@njit(inline="always")
def _weight(pair_keys, pair_counts, a, b):
    """The voxel faces labels a and b share (0 if none); ``pair_keys`` sorted."""
    key = _pair_key(a, b)
    i = np.searchsorted(pair_keys, key)
    if i < len(pair_keys) and pair_keys[i] == key:
        return pair_counts[i]
    return 0


@njit(inline="always")
def _column_centre(l0, l1, l2, l3, pair_keys, pair_counts):
    """The label of the centre of a column of labels l0, l1, l2, l3 in cyclic order: which
    diagonal neighbours it joins. Symmetric under turning and mirroring the column, so that the
    two blocks sharing it agree."""
    if l0 == l2 and l1 == l3:
        return min(l0, l1)
    if l0 == l2 or l1 == l3:
        a, b, c = (l0, l1, l3) if l0 == l2 else (l1, l0, l2)
        if b == c:
            return min(a, b)
        # a meets itself across the lattice edge: b and c join there if they share voxel faces
        # elsewhere (the triple line a, b, c passes), else a does.
        if _weight(pair_keys, pair_counts, b, c) > 0:
            return min(b, c)
        return a
    if l0 != l1 and l1 != l2 and l2 != l3 and l3 != l0:
        # Four labels: a quadruple point seen edge-on, or a small face between one diagonal
        # pair: the pair sharing more voxel faces elsewhere is joined.
        w02 = _weight(pair_keys, pair_counts, l0, l2)
        w13 = _weight(pair_keys, pair_counts, l1, l3)
        if w02 > w13 or (w02 == w13 and min(l0, l2) < min(l1, l3)):
            return min(l0, l2)
        return min(l1, l3)
    # Three labels or fewer, one of them on two neighbouring voxels: any centre gives the same
    # junction; take the label on two voxels (the smaller, of two such).
    best = l0
    found = False
    for a, b in ((l0, l1), (l1, l2), (l2, l3), (l3, l0)):
        if a == b and (not found or a < best):
            best = a
            found = True
    return best


@njit
def _block_simplices(block, pair_keys, pair_counts, tri, quad):
    """The 24 tetrahedra of one block (8 labels): writes the label sets of their simplices with
    three labels into ``tri`` (rows, sorted) and with four into ``quad``; returns how many of
    each. Duplicates are kept: they are evidence."""
    centres = np.empty(6, np.int64)
    for f in range(6):
        c = BLOCK_FACES[f]
        centres[f] = _column_centre(
            block[c[0]], block[c[1]], block[c[2]], block[c[3]], pair_keys, pair_counts
        )
    # The block's centre: the label that shares voxel faces with the most others of the block,
    # then the one on most of its voxels, then the smallest.
    best, best_touch, best_voxels = -1, -1, -1
    for c in range(8):
        label = block[c]
        repeat = False
        for d in range(c):
            if block[d] == label:
                repeat = True
                break
        if repeat:
            continue
        touch, voxels = 0, 0
        for d in range(8):
            other = block[d]
            if other == label:
                voxels += 1
                continue
            first = True
            for e in range(d):
                if block[e] == other:
                    first = False
                    break
            if first and _weight(pair_keys, pair_counts, label, other) > 0:
                touch += 1
        if (
            touch > best_touch
            or (touch == best_touch and voxels > best_voxels)
            or (touch == best_touch and voxels == best_voxels and label < best)
        ):
            best, best_touch, best_voxels = label, touch, voxels
    centre = best
    n_tri, n_quad = 0, 0
    t = np.empty(4, np.int64)
    for f in range(6):
        c = BLOCK_FACES[f]
        for k in range(4):
            t[0] = centre
            t[1] = centres[f]
            t[2] = block[c[k]]
            t[3] = block[c[(k + 1) % 4]]
            distinct = 1
            for i in range(1, 4):
                new = True
                for j in range(i):
                    if t[j] == t[i]:
                        new = False
                        break
                if new:
                    distinct += 1
            if distinct == 4:
                s = np.sort(t)
                for i in range(4):
                    quad[n_quad, i] = s[i]
                n_quad += 1
            if distinct >= 3:
                # Its triangles (centre, face centre, corner k), (centre, k, k + 1) and
                # (face centre, k, k + 1): each triangle of the mesh once per tetrahedron.
                for u, v, w in ((t[0], t[1], t[2]), (t[0], t[2], t[3]), (t[1], t[2], t[3])):
                    if u != v and v != w and u != w:
                        lo = min(u, v, w)
                        hi = max(u, v, w)
                        tri[n_tri, 0] = lo
                        tri[n_tri, 1] = u + v + w - lo - hi
                        tri[n_tri, 2] = hi
                        n_tri += 1
    return n_tri, n_quad


@njit(inline="always")
def _column_triple(block, col, out, row):
    """Writes the labels of a block's own column ``col`` to ``out[row]`` (sorted) when it
    holds exactly three; returns whether it did."""
    n = 0
    for i in range(4):
        label = block[OWN_COLUMNS[col, i]]
        new = True
        for j in range(n):
            if out[row, j] == label:
                new = False
                break
        if new:
            if n == 3:
                return False
            out[row, n] = label
            n += 1
    if n != 3:
        return False
    a, b, c = out[row, 0], out[row, 1], out[row, 2]
    lo, hi = min(a, b, c), max(a, b, c)
    out[row, 0], out[row, 1], out[row, 2] = lo, a + b + c - lo - hi, hi
    return True


@njit(inline="always")
def _add_row(rows, weights, n, start, row, width):
    """Adds one to the weight of ``row`` among ``rows[start:n]``, or appends it; returns n."""
    for r in range(start, n):
        same = True
        for c in range(width):
            if rows[r, c] != row[c]:
                same = False
                break
        if same:
            weights[r] += 1
            return n
    for c in range(width):
        rows[n, c] = row[c]
    weights[n] = 1
    return n + 1


@njit
def _resolve_blocks(blocks, first, last, pair_keys, pair_counts, index):
    """Triple lines and quadruple points of blocks ``first .. last - 1`` (rows of 8 labels, each
    with three labels or more): ``(tri, tri_weight, quad, quad_weight, col, col_weight)``, rows
    of 3, 4 and 3 grain indices (``index[label]``) sorted within a row, distinct within a block,
    weighted by the simplices of the block's mesh with those three (four) labels, and by the
    block's own lattice edges whose column holds exactly those three. O(blocks)."""
    n = last - first
    tri_out = np.empty((56 * n, 3), np.int64)
    tri_weight = np.empty(56 * n, np.int64)
    quad_out = np.empty((24 * n, 4), np.int64)
    quad_weight = np.empty(24 * n, np.int64)
    col_out = np.empty((3 * n, 3), np.int64)
    col_weight = np.empty(3 * n, np.int64)
    tri = np.empty((72, 3), np.int64)
    quad = np.empty((24, 4), np.int64)
    col = np.empty((3, 3), np.int64)
    row = np.empty(4, np.int64)
    n_tri, n_quad, n_col = 0, 0, 0
    for b in range(first, last):
        nt, nq = _block_simplices(blocks[b], pair_keys, pair_counts, tri, quad)
        start = n_tri
        for i in range(nt):
            for j in range(3):
                row[j] = index[tri[i, j]]
            n_tri = _add_row(tri_out, tri_weight, n_tri, start, row, 3)
        start = n_quad
        for i in range(nq):
            for j in range(4):
                row[j] = index[quad[i, j]]
            n_quad = _add_row(quad_out, quad_weight, n_quad, start, row, 4)
        start = n_col
        for k in range(3):
            if _column_triple(blocks[b], k, col, 0):
                for j in range(3):
                    row[j] = index[col[0, j]]
                n_col = _add_row(col_out, col_weight, n_col, start, row, 3)
    return (
        tri_out[:n_tri].copy(),
        tri_weight[:n_tri].copy(),
        quad_out[:n_quad].copy(),
        quad_weight[:n_quad].copy(),
        col_out[:n_col].copy(),
        col_weight[:n_col].copy(),
    )


@njit
def _face_cycles(group_start, face_k, quad_lo, quad_hi, quad_kl, order, ordered):
    """Each face's neighbours in cyclic order where the quadruple points allow.

    Face groups: ``face_k[group_start[g]:group_start[g + 1]]`` are the neighbours (sorted) of
    face g of its grain; ``quad_kl[quad_lo[g]:quad_hi[g]]`` the pairs (k, l) of the
    quadruple points {grain, face, k, l}. Writes the neighbours walked round into ``order``
    and 1 into ``ordered[g]`` when the pairs make one cycle through all of them; else copies
    them sorted and writes 0. O(neighbours log neighbours)."""
    n_groups = len(group_start) - 1
    for g in range(n_groups):
        s, e = group_start[g], group_start[g + 1]
        m = e - s
        nbrs = face_k[s:e]
        for i in range(m):
            order[s + i] = nbrs[i]
        ordered[g] = 0
        if m < 3:
            continue
        partner = np.full((m, 2), -1, np.int64)
        good = True
        for q in range(quad_lo[g], quad_hi[g]):
            u = np.searchsorted(nbrs, quad_kl[q, 0])
            v = np.searchsorted(nbrs, quad_kl[q, 1])
            if u >= m or v >= m or nbrs[u] != quad_kl[q, 0] or nbrs[v] != quad_kl[q, 1]:
                good = False
                break
            for a, b in ((u, v), (v, u)):
                if partner[a, 0] < 0:
                    partner[a, 0] = b
                elif partner[a, 1] < 0 and partner[a, 0] != b:
                    partner[a, 1] = b
                elif partner[a, 0] != b and partner[a, 1] != b:
                    good = False
        if not good:
            continue
        prev, cur, steps = -1, 0, 0
        walk = np.empty(m, np.int64)
        while steps < m:
            if partner[cur, 1] < 0:
                break
            walk[steps] = nbrs[cur]
            steps += 1
            nxt = partner[cur, 0] if partner[cur, 0] != prev else partner[cur, 1]
            prev, cur = cur, nxt
            if cur == 0:
                break
        if steps == m and cur == 0:
            for i in range(m):
                order[s + i] = walk[i]
            ordered[g] = 1
