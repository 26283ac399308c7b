"""Surface Evolver datafiles read over their bytes, many files in one call, in two kernels that
``readers/evolver.py`` calls in turn: :func:`.tokenize._tokenize` splits the files into numbered
entries (vertices, edges, facets, bodies), and :func:`.assemble._assemble` turns each body into
a grain.

No Python object is made per vertex, edge or facet; what the kernels cannot settle they return
as codes (``codes.py``), which the reader turns into messages. The rules are those of the
reader's docstring; the kernels' docstrings say how they are carried out.

The pieces pass named tuples of arrays, each defined where it is made:

- ``lexing.py``: bytes to the tokens of one logical line (``LineTokens``); ``numbers.py``:
  tokens to ids and floats; ``entries.py``: a numbered line into the rows of ``Entries``;
  ``tokenize.py``: whole files, keywords and periods, into ``Tokens`` (``Entries``,
  ``SlowNumbers``, ``Files``).
- ``slots.py``: ids to slots (``IdMap``); ``tables.py``: one file's entries as ``FileTables``
  (vertices, edges, facets and their sides, bodies).
- ``patches.py``: a body's ``Patches`` and ``Darts``, checked to close up; ``periodic.py``: the
  patches unwrapped across the periodic box into ``Corners``; ``faces.py``: the faces and their
  neighbours in cyclic order; ``body.py``: those steps in order, for one body, into ``BodyOut``.
- ``assemble.py``: every file's bodies into ``Grains`` and ``Surfaces``.

A step called from one place is compiled into its caller (``@njit(inline="always")``): as a
function of its own, numba would optimise it again inside every kernel that links it, compile
it once more for each literal constant it is first called with, and, called per line or per
facet, be handed every array of its named tuples anew, each as several scalars. The loops over
lines and over facets' sides (``tokenize._tokenize_file``, ``tables._fill_sides``,
``tables._edge_ends``, ``slots._slots``) hand their steps (``njit_leaf``, compiled into the
loop) the arrays one by one, as views made in the loop's own kernel (``_numba.borrowed``): a
view's reference counting compiles away only in the kernel that makes it, and a named tuple
handed to a step would have each of its arrays counted up and down on every line or side. Such a
kernel stores through those views only: numba's dead-code pass, which runs after an inlined
``borrowed()``, drops a store through an array it cannot trace to an argument (one from an
unpacked named tuple, or a view kept in a named tuple).

A body's surface is built from *patches*, one per entry of its list of facets: in a periodic
file a body may list a facet twice, once each way, where the cell meets its own image across
it. Each patch sits at a lattice translation of its facet's own frame (the facet unwrapped
along its edges' wrap marks); the translations follow from the patches' common edges, which
pair the patches' edge uses off, and the cell's corners are (vertex, translation) pairs.
"""
