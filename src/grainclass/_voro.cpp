// grainclass._voro: Voronoi and Laguerre cells of points, as flat arrays, from Voro++.
//
// A Tessellation holds the points in one Voro++ container per thread (Voro++'s containers keep
// scratch state while they compute a cell, so threads do not share one). cells(indices)
// computes the cells of those points on every thread at once, without the GIL, and hands back
// per cell the faces across each edge of each face (the face adjacency, counter-clockwise seen
// from outside), the point behind each face (a negative number: the wall of a non-periodic
// side), its volume, its surface area, flags and its reach along z (below).
//
// A tessellation in parts (grainclass.voronoi_parts) holds, besides the points whose cells it
// computes (the first ``owned``), a margin of other parts' points: faces towards those are
// checked across parts, not here. A cell's reach along z says how far its neighbours may be:
// a point q changes the cell of p only if, at some corner v, q is nearer than p in the power
// distance, |v - q|^2 - r_q^2 < |v - p|^2 - r_p^2 <= |v - p|^2 - r_p^2 + R^2 with R the
// largest radius (0 for Voronoi cells): q lies in the ball about v of that radius. reach_up
// and reach_down bound those balls above and below the point, so that a cell whose balls stay
// inside the points held is the cell of all points.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include "voro++.hh"

namespace py = pybind11;

namespace {

// What the cells of a run of points come to: CSR arrays, one entry per cell, per face and per
// corner of a face.
// Flags per cell.
constexpr int8_t BAD_CORNER = 1;  // a corner not on exactly three faces
constexpr int8_t OPEN = 2;        // an edge not on exactly two faces
constexpr int8_t WALL = 4;        // a face on a wall of the box

// What the cells of a run of points come to: CSR arrays, one entry per cell, per face and per
// edge of a face.
struct Cells {
    std::vector<int32_t> face_counts;   // per cell; 0 where the point has no cell
    std::vector<int32_t> loop_lengths;  // per face: its edges
    std::vector<int32_t> adjacent;      // per edge of a face: the cell's face across it
    std::vector<int64_t> neighbors;     // per face: the point behind it, or a wall (< 0)
    std::vector<double> volume;         // per cell
    std::vector<double> area;           // per cell
    std::vector<int8_t> flags;          // per cell
    std::vector<double> reach_up;       // per cell: the balls' highest z, from the point
    std::vector<double> reach_down;     // per cell: the balls' lowest z, below the point

    void append(Cells &&other) {
        auto move = [](auto &to, auto &from) { to.insert(to.end(), from.begin(), from.end()); };
        move(face_counts, other.face_counts);
        move(loop_lengths, other.loop_lengths);
        move(adjacent, other.adjacent);
        move(neighbors, other.neighbors);
        move(volume, other.volume);
        move(area, other.area);
        move(flags, other.flags);
        move(reach_up, other.reach_up);
        move(reach_down, other.reach_down);
    }
};

// A Voro++ cell whose faces, neighbours, volume and area come from one walk over its edges
// (Voro++'s face_vertices, neighbors, volume and surface_area each walk them once; the walk and
// the sums are theirs, in their order).
class FlatCell : public voro::voronoicell_neighbor {
  public:
    // Appends per face its corner count and corners to ``loops`` and the point behind it to
    // ``neighbors``; sets the volume and the surface area. False if an edge was not walked (the
    // edges do not close into faces).
    bool walk(std::vector<int> &loops, std::vector<int> &neighbors, double &volume,
              double &area) {
        loops.clear();
        neighbors.clear();
        double vol = 0.0, twice_area = 0.0;
        const double *q = pts;  // corners relative to the point, doubled, three numbers each
        for (int i = 1; i < p; ++i) {
            const double ux = q[0] - q[3 * i], uy = q[1] - q[3 * i + 1], uz = q[2] - q[3 * i + 2];
            for (int j = 0; j < nu[i]; ++j) {
                int k = ed[i][j];
                if (k < 0) continue;
                neighbors.push_back(ne[i][j]);
                const size_t start = loops.size();
                loops.push_back(0);
                loops.push_back(i);
                ed[i][j] = -1 - k;
                int l = cycle_up(ed[i][nu[i] + j], k);
                double vx = q[3 * k] - q[0], vy = q[3 * k + 1] - q[1], vz = q[3 * k + 2] - q[2];
                int m;
                do {
                    loops.push_back(k);
                    m = ed[k][l];
                    ed[k][l] = -1 - m;
                    const int n = cycle_up(ed[k][nu[k] + l], m);
                    if (m != i) {
                        const double wx = q[3 * m] - q[0], wy = q[3 * m + 1] - q[1],
                                     wz = q[3 * m + 2] - q[2];
                        vol += ux * vy * wz + uy * vz * wx + uz * vx * wy - uz * vy * wx -
                               uy * vx * wz - ux * vz * wy;
                        // The triangle (i, k, m) of the fan from corner i.
                        const double ax = q[3 * k] - q[3 * i], ay = q[3 * k + 1] - q[3 * i + 1],
                                     az = q[3 * k + 2] - q[3 * i + 2];
                        const double bx = q[3 * m] - q[3 * i], by = q[3 * m + 1] - q[3 * i + 1],
                                     bz = q[3 * m + 2] - q[3 * i + 2];
                        const double cx = ay * bz - az * by, cy = az * bx - ax * bz,
                                     cz = ax * by - ay * bx;
                        twice_area += std::sqrt(cx * cx + cy * cy + cz * cz);
                        vx = wx;
                        vy = wy;
                        vz = wz;
                    }
                    k = m;
                    l = n;
                } while (k != i);
                loops[start] = static_cast<int>(loops.size() - start - 1);
            }
        }
        volume = vol * (1 / 48.0);  // as Voro++ has it: not always vol / 48 to the last bit
        area = 0.125 * twice_area;
        bool whole = true;  // every edge walked: marked -1 - k; marked back as Voro++ does
        for (int i = 0; i < p; ++i) {
            for (int j = 0; j < nu[i]; ++j) {
                if (ed[i][j] >= 0)
                    whole = false;
                else
                    ed[i][j] = -1 - ed[i][j];
            }
        }
        return whole;
    }

    // How far above (``up``) and below (``down``) the point the balls about the corners reach
    // (see the top of this file); ``extra`` is R^2 - r_p^2.
    void reach(double extra, double &up, double &down) const {
        up = down = 0.0;
        for (int i = 0; i < p; ++i) {
            const double x = 0.5 * pts[3 * i], y = 0.5 * pts[3 * i + 1],
                         z = 0.5 * pts[3 * i + 2];
            const double radius = std::sqrt(x * x + y * y + z * z + extra);
            up = std::max(up, z + radius);
            down = std::max(down, radius - z);
        }
    }
};

template <class T>
py::array_t<T> to_array(const std::vector<T> &values) {
    py::array_t<T> out(static_cast<py::ssize_t>(values.size()));
    if (!values.empty()) std::memcpy(out.mutable_data(), values.data(), values.size() * sizeof(T));
    return out;
}

class EngineBase {
  public:
    virtual ~EngineBase() = default;
    virtual std::vector<bool> placed() const = 0;
    virtual std::vector<int64_t> one_sided() const = 0;
    virtual Cells cells(const int64_t *indices, int64_t count) = 0;
};

// The box as Voro++ takes it: its sides, periodic or walled, or a tilted (triclinic) box,
// periodic on every side, with its tilts.
struct Geometry {
    std::array<double, 6> box;
    std::array<bool, 3> periodic;
    std::array<int, 3> blocks;
    std::optional<std::array<double, 3>> tilt;  // xy, xz, yz
};

template <class Container>
std::unique_ptr<Container> make_container(const Geometry &g) {
    if constexpr (std::is_base_of_v<voro::container_periodic_base, Container>) {
        const auto &t = *g.tilt;
        return std::make_unique<Container>(g.box[1] - g.box[0], t[0], g.box[3] - g.box[2], t[1],
                                           t[2], g.box[5] - g.box[4], g.blocks[0], g.blocks[1],
                                           g.blocks[2], 8);
    } else {
        return std::make_unique<Container>(g.box[0], g.box[1], g.box[2], g.box[3], g.box[4],
                                           g.box[5], g.blocks[0], g.blocks[1], g.blocks[2],
                                           g.periodic[0], g.periodic[1], g.periodic[2], 8);
    }
}

// The same computation for Voronoi (voro::container, voro::container_periodic) and Laguerre
// (voro::container_poly, voro::container_periodic_poly) cells. Loop visits the points Voro++
// placed (c_loop_all, or c_loop_all_periodic for a tilted box).
template <class Container, class Loop>
class Engine : public EngineBase {
  public:
    Engine(const double *xyz, const double *radii, int64_t n, const Geometry &geometry,
           int copies, int64_t owned, double reach_radius)
        : block_(n, -1), slot_(n, -1), owned_(owned),
          listed_(copies, std::vector<uint64_t>(n)), listed_back_(copies, std::vector<uint64_t>(n)) {
        if (radii) {
            radii_.assign(radii, radii + n);
            for (double r : radii_) reach_radius = std::max(reach_radius, r);
        }
        reach_radius_squared_ = reach_radius * reach_radius;
        for (int k = 0; k < copies; ++k) {
            containers_.emplace_back(make_container<Container>(geometry));
            Container &con = *containers_.back();
            for (int64_t i = 0; i < n; ++i) put(con, static_cast<int>(i), xyz + 3 * i, radii);
        }
        Loop loop(*containers_.front());
        if (loop.start()) {
            do {
                block_[loop.pid()] = loop.ijk;
                slot_[loop.pid()] = loop.q;
            } while (loop.inc());
        }
    }

    // Which points Voro++ placed (a point outside a non-periodic side is not placed).
    std::vector<bool> placed() const override {
        std::vector<bool> out(block_.size());
        for (size_t i = 0; i < block_.size(); ++i) out[i] = block_[i] >= 0;
        return out;
    }

    // The owned points whose cells list a face that the cell behind it does not list back (of
    // the cells computed so far: meaningful once every owned point's cell is).
    std::vector<int64_t> one_sided() const override {
        std::vector<int64_t> out;
        for (size_t i = 0; i < static_cast<size_t>(owned_); ++i) {
            uint64_t a = 0, b = 0;
            for (size_t t = 0; t < listed_.size(); ++t) {
                a += listed_[t][i];
                b += listed_back_[t][i];
            }
            if (a != b) out.push_back(static_cast<int64_t>(i));
        }
        return out;
    }

    Cells cells(const int64_t *indices, int64_t count) override {
        const int threads = static_cast<int>(containers_.size());
        std::vector<Cells> parts(threads);
        std::vector<std::thread> workers;
        for (int t = 0; t < threads; ++t) {
            const int64_t first = count * t / threads, last = count * (t + 1) / threads;
            workers.emplace_back([this, t, indices, first, last, &parts] {
                parts[t] = compute(*containers_[t], indices + first, last - first, t);
            });
        }
        for (auto &worker : workers) worker.join();
        Cells all = std::move(parts[0]);
        for (int t = 1; t < threads; ++t) all.append(std::move(parts[t]));
        return all;
    }

  private:
    std::vector<std::unique_ptr<Container>> containers_;
    std::vector<int> block_, slot_;
    int64_t owned_;  // points from owned_ on are a margin: their cells are not computed
    std::vector<double> radii_;  // Laguerre cells: the points' radii
    double reach_radius_squared_ = 0.0;  // R^2 (see the top of this file)
    // Per thread and point: the sum of mix(q) over the faces the point's cell lists (q behind
    // the face), and over the faces other cells list with the point behind them.
    std::vector<std::vector<uint64_t>> listed_, listed_back_;

    static void put(Container &con, int i, const double *p, const double *radii) {
        if constexpr (std::is_base_of_v<voro::radius_poly, Container>)
            con.put(i, p[0], p[1], p[2], radii[i]);
        else
            con.put(i, p[0], p[1], p[2]);
    }

    Cells compute(Container &con, const int64_t *indices, int64_t count, int thread) {
        Cells out;
        out.face_counts.reserve(count);
        out.volume.reserve(count);
        out.area.reserve(count);
        out.flags.reserve(count);
        out.reach_up.reserve(count);
        out.reach_down.reserve(count);
        FlatCell cell;
        std::vector<int> neighbors, loops;
        double volume, area;
        std::vector<int32_t> face_of_edge;  // directed edge u -> v of a loop: its face
        std::vector<int32_t> faces_at;      // per corner: the faces around it
        uint64_t *listed = listed_[thread].data(), *listed_back = listed_back_[thread].data();
        for (int64_t k = 0; k < count; ++k) {
            const int64_t i = indices[k];
            if (block_[i] < 0 ||
                !con.compute_cell(static_cast<voro::voronoicell_neighbor &>(cell), block_[i],
                                  slot_[i])) {
                out.face_counts.push_back(0);
                out.volume.push_back(0.0);
                out.area.push_back(0.0);
                out.flags.push_back(0);
                out.reach_up.push_back(0.0);
                out.reach_down.push_back(0.0);
                continue;
            }
            // loops: per face its corner count, then its corners
            int8_t flag = cell.walk(loops, neighbors, volume, area) ? 0 : OPEN;
            const int corners = cell.p;
            face_of_edge.assign(static_cast<size_t>(corners) * corners, -1);
            faces_at.assign(corners, 0);
            int32_t f = 0;
            for (size_t j = 0; j < loops.size(); j += loops[j] + 1, ++f) {
                const int length = loops[j];
                for (int e = 0; e < length; ++e) {
                    const int u = loops[j + 1 + e], v = loops[j + 1 + (e + 1) % length];
                    face_of_edge[static_cast<size_t>(u) * corners + v] = f;
                    ++faces_at[u];
                }
            }
            // Voro++'s loops turn clockwise seen from outside (cycle_up is the next edge
            // counter-clockwise at a corner, seen from outside): walked backwards, they give
            // each face's neighbours counter-clockwise, as the Weinberg walks read them.
            f = 0;
            for (size_t j = 0; j < loops.size(); j += loops[j] + 1, ++f) {
                const int length = loops[j];
                out.loop_lengths.push_back(length);
                for (int e = length - 1; e >= 0; --e) {
                    const int u = loops[j + 1 + e], v = loops[j + 1 + (e + 1) % length];
                    const int32_t other = face_of_edge[static_cast<size_t>(v) * corners + u];
                    if (other < 0 || other == f) flag |= OPEN;
                    out.adjacent.push_back(other);
                }
            }
            for (int u = 0; u < corners; ++u)
                if (faces_at[u] != 3) flag |= BAD_CORNER;
            const uint64_t self = mix(static_cast<uint64_t>(i));
            for (int n : neighbors) {
                if (n < 0) {
                    flag |= WALL;
                } else if (n < owned_) {  // a margin point's face is checked across parts
                    listed[i] += mix(static_cast<uint64_t>(n));
                    listed_back[n] += self;
                }
            }
            out.face_counts.push_back(static_cast<int32_t>(neighbors.size()));
            out.neighbors.insert(out.neighbors.end(), neighbors.begin(), neighbors.end());
            out.volume.push_back(volume);
            out.area.push_back(area);
            out.flags.push_back(flag);
            double up, down;
            const double own = radii_.empty() ? 0.0 : radii_[i];
            cell.reach(reach_radius_squared_ - own * own, up, down);
            out.reach_up.push_back(up);
            out.reach_down.push_back(down);
        }
        return out;
    }

    // A 64-bit mix of a point index (splitmix64's finalizer): sums of mixed ids over a cell's
    // faces agree both ways round when every face is listed by both of its cells.
    static uint64_t mix(uint64_t x) {
        x += 0x9e3779b97f4a7c15ULL;
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
        return x ^ (x >> 31);
    }
};

class Tessellation {
  public:
    using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

    Tessellation(Array points, std::optional<Array> radii, std::array<double, 6> box,
                 std::array<bool, 3> periodic, std::array<int, 3> blocks, int threads,
                 std::optional<std::array<double, 3>> tilt, std::optional<int64_t> owned,
                 double reach_radius) {
        if (points.ndim() != 2 || points.shape(1) != 3)
            throw std::invalid_argument("points must be an array of shape (n, 3)");
        const int64_t n = points.shape(0);
        if (n >= INT32_MAX) throw std::invalid_argument("too many points for Voro++'s int ids");
        if (radii && (radii->ndim() != 1 || radii->shape(0) != n))
            throw std::invalid_argument("radii must be an array of shape (n,)");
        if (threads < 1) throw std::invalid_argument("threads must be at least 1");
        const int64_t mine = owned.value_or(n);
        if (mine < 0 || mine > n) throw std::invalid_argument("owned must be from 0 to n");
        if (!(reach_radius >= 0)) throw std::invalid_argument("reach_radius must be >= 0");
        for (int a = 0; a < 3; ++a) {
            if (!(box[2 * a] < box[2 * a + 1]))
                throw std::invalid_argument("each side of the box must have low < high");
            if (blocks[a] < 1) throw std::invalid_argument("blocks must be at least 1");
        }
        if (tilt && (box[0] != 0 || box[2] != 0 || box[4] != 0 || !periodic[0] ||
                     !periodic[1] || !periodic[2]))
            throw std::invalid_argument("a tilted box starts at 0 and is periodic on every side");
        n_ = n;
        const double *xyz = points.data();
        const double *r = radii ? radii->data() : nullptr;
        const Geometry geometry{box, periodic, blocks, tilt};
        py::gil_scoped_release release;
        if (tilt && r)
            engine_ = std::make_unique<
                Engine<voro::container_periodic_poly, voro::c_loop_all_periodic>>(
                xyz, r, n, geometry, threads, mine, reach_radius);
        else if (tilt)
            engine_ =
                std::make_unique<Engine<voro::container_periodic, voro::c_loop_all_periodic>>(
                    xyz, r, n, geometry, threads, mine, reach_radius);
        else if (r)
            engine_ = std::make_unique<Engine<voro::container_poly, voro::c_loop_all>>(
                xyz, r, n, geometry, threads, mine, reach_radius);
        else
            engine_ = std::make_unique<Engine<voro::container, voro::c_loop_all>>(
                xyz, r, n, geometry, threads, mine, reach_radius);
    }

    py::array_t<int64_t> one_sided() const { return to_array(engine_->one_sided()); }

    py::array_t<bool> placed() const {
        std::vector<bool> flags = engine_->placed();
        py::array_t<bool> out(static_cast<py::ssize_t>(flags.size()));
        bool *data = out.mutable_data();
        for (size_t i = 0; i < flags.size(); ++i) data[i] = flags[i];
        return out;
    }

    py::dict cells(py::array_t<int64_t, py::array::c_style | py::array::forcecast> indices) {
        if (indices.ndim() != 1) throw std::invalid_argument("indices must be one-dimensional");
        const int64_t *idx = indices.data();
        for (py::ssize_t k = 0; k < indices.shape(0); ++k)
            if (idx[k] < 0 || idx[k] >= n_) throw std::out_of_range("a point index is out of range");
        Cells out;
        {
            py::gil_scoped_release release;
            out = engine_->cells(idx, indices.shape(0));
        }
        py::dict result;
        result["face_counts"] = to_array(out.face_counts);
        result["loop_lengths"] = to_array(out.loop_lengths);
        result["adjacent"] = to_array(out.adjacent);
        result["neighbors"] = to_array(out.neighbors);
        result["volume"] = to_array(out.volume);
        result["area"] = to_array(out.area);
        result["flags"] = to_array(out.flags);
        result["reach_up"] = to_array(out.reach_up);
        result["reach_down"] = to_array(out.reach_down);
        return result;
    }

  private:
    int64_t n_ = 0;
    std::unique_ptr<EngineBase> engine_;
};

}  // namespace

PYBIND11_MODULE(_voro, m) {
    m.doc() = "Voronoi and Laguerre cells of points, as flat arrays, from Voro++.";
    py::class_<Tessellation>(m, "Tessellation")
        .def(py::init<Tessellation::Array, std::optional<Tessellation::Array>,
                      std::array<double, 6>, std::array<bool, 3>, std::array<int, 3>, int,
                      std::optional<std::array<double, 3>>, std::optional<int64_t>, double>(),
             py::arg("points"), py::arg("radii"), py::arg("box"), py::arg("periodic"),
             py::arg("blocks"), py::arg("threads"), py::arg("tilt") = py::none(),
             py::arg("owned") = py::none(), py::arg("reach_radius") = 0.0,
             "Points (n, 3) in a box (xlo, xhi, ylo, yhi, zlo, zhi), periodic per axis, cut "
             "into blocks per axis for Voro++'s search; radii (n,) or None; one container per "
             "thread. With tilt (xy, xz, yz), the box is the triclinic one with edges "
             "(xhi, 0, 0), (xy, yhi, 0), (xz, yz, zhi) from 0, periodic on every side. Points "
             "from owned on are a margin of other parts' points: their faces are not checked "
             "here. reach_radius: the largest radius of all points, those not held included.")
        .def("placed", &Tessellation::placed,
             "Per point: True where Voro++ placed it in the box.")
        .def("one_sided", &Tessellation::one_sided,
             "The owned points whose cells list a face that the cell behind it does not list "
             "back (once every owned point's cell is computed).")
        .def("cells", &Tessellation::cells, py::arg("indices"),
             "The cells of the points at these indices, on every thread, as a dict of arrays: "
             "face_counts, volume, area, flags (1: a corner not of three faces, 2: an edge not "
             "on two faces, 4: a face on a wall), reach_up and reach_down (how far above and "
             "below the point another point may change the cell) per cell (0 faces: no cell), "
             "loop_lengths and neighbors (the point behind, negative for a wall) per face, adjacent (the face "
             "across each edge, counter-clockwise seen from outside) per edge of a face.");
}
