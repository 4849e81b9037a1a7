#include "sdflow/flow/substrate_topology.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

namespace sdflow {
namespace {

//! The boundary loops as vertex lists in the order of their boundary halfedges (against the faces:
//! clockwise seen from above for a film whose normals point out of it).
std::vector<std::vector<int>> rim_loops(const Mesh& mesh)
{
  std::vector<std::vector<int>> loops;
  for (const auto& loop : boundary_loops(mesh)) {
    std::vector<int>& vertices = loops.emplace_back();
    for (const auto h : loop)
      vertices.push_back(mesh.from_vertex_handle(h).idx());
  }
  return loops;
}

//! Where a cut of `mesh` leaves it: the surface without the faces `removed`, repaired into an
//! oriented manifold with its new rim on the plane.
struct Cut {
  Mesh mesh;
  long removed = 0, debris = 0;
};

//! Remove the faces flagged in `removed`; then, until nothing changes: at a vertex whose kept faces
//! form several fans, only the largest fan is kept (the others removed); the vertices beside removed
//! faces are lowered onto the plane (they are the new contact line); kept faces lying flat on the
//! plane with a lowered vertex are removed. Pieces of fewer than `min_faces` faces are debris.
//! Nullopt when nothing is left.
std::optional<Cut> cut_out(const Mesh& mesh, std::vector<bool> removed, double z0, int min_faces)
{
  VertexVectors x = vertex_positions(mesh);
  const FaceIndices t = face_indices(mesh);
  std::vector<bool> lowered(mesh.n_vertices(), false);
  const auto kept = [&](Mesh::FaceHandle f) { return f.is_valid() && !removed[static_cast<std::size_t>(f.idx())]; };
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto v : mesh.vertices()) {
      // The faces around v in rotational order, a boundary slot counting as a gap.
      std::vector<Mesh::FaceHandle> slots;
      for (const auto h : mesh.voh_range(v))
        slots.push_back(mesh.face_handle(h));
      const std::size_t n = slots.size();
      bool touched = false;
      for (const auto f : slots)
        touched = touched || (f.is_valid() && removed[static_cast<std::size_t>(f.idx())]);
      if (!touched)
        continue;
      // Runs of kept faces, cyclically: start after a gap.
      std::size_t start = n;
      for (std::size_t i = 0; i < n; ++i)
        if (!kept(slots[i])) {
          start = i;
          break;
        }
      std::vector<std::vector<Mesh::FaceHandle>> fans;
      bool in_run = false;
      for (std::size_t k = 1; k <= n && start < n; ++k) {
        const Mesh::FaceHandle f = slots[(start + k) % n];
        if (kept(f)) {
          if (!in_run)
            fans.emplace_back();
          fans.back().push_back(f);
          in_run = true;
        } else {
          in_run = false;
        }
      }
      if (fans.empty())
        continue;
      if (!lowered[static_cast<std::size_t>(v.idx())] && x(v.idx(), 2) != z0) {
        lowered[static_cast<std::size_t>(v.idx())] = true;
        x(v.idx(), 2) = z0;
        changed = true;
      }
      if (fans.size() > 1) {
        const auto largest = std::max_element(fans.begin(), fans.end(),
                                              [](const auto& a, const auto& b) { return a.size() < b.size(); });
        for (auto fan = fans.begin(); fan != fans.end(); ++fan)
          if (fan != largest)
            for (const auto f : *fan)
              removed[static_cast<std::size_t>(f.idx())] = true;
        changed = true;
      }
    }
    for (const auto f : mesh.faces()) {
      if (!kept(f))
        continue;
      bool flat = true, lowered_corner = false;
      for (const auto v : f.vertices()) {
        flat = flat && x(v.idx(), 2) == z0;
        lowered_corner = lowered_corner || lowered[static_cast<std::size_t>(v.idx())];
      }
      if (flat && lowered_corner) {
        removed[static_cast<std::size_t>(f.idx())] = true;
        changed = true;
      }
    }
  }
  // Pieces of the kept faces (through shared edges); the small ones are debris.
  std::vector<int> piece(mesh.n_faces(), -1);
  std::vector<long> piece_faces;
  for (const auto seed : mesh.faces()) {
    if (!kept(seed) || piece[static_cast<std::size_t>(seed.idx())] >= 0)
      continue;
    const int id = static_cast<int>(piece_faces.size());
    piece_faces.push_back(0);
    std::vector<Mesh::FaceHandle> stack{seed};
    piece[static_cast<std::size_t>(seed.idx())] = id;
    while (!stack.empty()) {
      const Mesh::FaceHandle f = stack.back();
      stack.pop_back();
      ++piece_faces.back();
      for (const auto h : mesh.fh_range(f)) {
        const Mesh::FaceHandle g = mesh.opposite_face_handle(h);
        if (kept(g) && piece[static_cast<std::size_t>(g.idx())] < 0) {
          piece[static_cast<std::size_t>(g.idx())] = id;
          stack.push_back(g);
        }
      }
    }
  }
  Cut cut;
  std::vector<int> index(mesh.n_vertices(), -1);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (const auto f : mesh.faces()) {
    const auto i = static_cast<std::size_t>(f.idx());
    if (!kept(f)) {
      ++cut.removed;
      continue;
    }
    if (piece_faces[static_cast<std::size_t>(piece[i])] < min_faces) {
      ++cut.debris;
      continue;
    }
    std::array<int, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      int& j = index[static_cast<std::size_t>(t(f.idx(), k))];
      if (j < 0) {
        j = static_cast<int>(points.size());
        points.push_back(x.row(t(f.idx(), k)).transpose());
      }
      triangle[static_cast<std::size_t>(k)] = j;
    }
    triangles.push_back(triangle);
  }
  if (triangles.empty())
    return std::nullopt;
  cut.mesh = make_mesh(point_rows(points), triangle_rows(triangles));
  return cut;
}

//! Whether every vertex of `mesh` has one fan of faces (at most one boundary halfedge leaving it).
bool manifold_vertices(const Mesh& mesh)
{
  for (const auto v : mesh.vertices()) {
    int boundary = 0;
    for (const auto h : mesh.voh_range(v))
      boundary += mesh.is_boundary(h) ? 1 : 0;
    if (boundary > 1 || mesh.valence(v) == 0)
      return false;
  }
  return true;
}

Eigen::Vector2d xy(const VertexVectors& x, int v) { return {x(v, 0), x(v, 1)}; }

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

//! The closest point of segment [a, b] to p.
Eigen::Vector2d closest_on_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b)
{
  const Eigen::Vector2d d = b - a;
  const double length2 = d.squaredNorm();
  const double s = length2 > 0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return a + s * d;
}

//! The closest points of two segments in the plane (p on [a, b], q on [c, d]); equal when they cross.
std::pair<Eigen::Vector2d, Eigen::Vector2d> closest_points(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                                           const Eigen::Vector2d& c, const Eigen::Vector2d& d)
{
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a), d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    const Eigen::Vector2d crossing = a + (b - a) * (d3 / (d3 - d4));
    return {crossing, crossing};
  }
  std::array<std::pair<Eigen::Vector2d, Eigen::Vector2d>, 4> candidates{
      std::pair{a, closest_on_segment(a, c, d)}, std::pair{b, closest_on_segment(b, c, d)},
      std::pair{closest_on_segment(c, a, b), c}, std::pair{closest_on_segment(d, a, b), d}};
  return *std::min_element(candidates.begin(), candidates.end(), [](const auto& l, const auto& r) {
    return (l.first - l.second).squaredNorm() < (r.first - r.second).squaredNorm();
  });
}

//! A rim edge: loop `loop`, from its vertex `at` to the next.
struct RimEdge {
  int loop = 0, at = 0;
};

//! Two rim edges closer than δ in the plane and far apart along the contact line.
struct Meeting {
  RimEdge first, second;
  Eigen::Vector2d p, q; //!< their closest points
  double gap = 0;
};

//! The closest pair of rim edges of different loops, or of one loop with more than 3δ of contact line
//! and at least one edge between them, closer than δ in the plane (a grid of cells of δ or the
//! mean rim edge, whichever is larger, finds the candidates).
std::optional<Meeting> closest_meeting(const VertexVectors& x, const std::vector<std::vector<int>>& loops, double delta)
{
  std::vector<RimEdge> edges;
  std::vector<std::vector<double>> arc(loops.size()); // cumulative length along each loop
  double total = 0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::vector<int>& loop = loops[l];
    arc[l].assign(loop.size() + 1, 0.0);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const double length = (xy(x, loop[(i + 1) % loop.size()]) - xy(x, loop[i])).norm();
      arc[l][i + 1] = arc[l][i] + length;
      total += length;
      edges.push_back({static_cast<int>(l), static_cast<int>(i)});
    }
  }
  if (edges.size() < 2)
    return std::nullopt;
  const double cell = std::max(delta, total / static_cast<double>(edges.size()));
  const auto end_points = [&](const RimEdge& e) {
    const std::vector<int>& loop = loops[static_cast<std::size_t>(e.loop)];
    return std::pair{xy(x, loop[static_cast<std::size_t>(e.at)]),
                     xy(x, loop[(static_cast<std::size_t>(e.at) + 1) % loop.size()])};
  };
  std::map<std::pair<long, long>, std::vector<int>> grid;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const auto [a, b] = end_points(edges[k]);
    const Eigen::Vector2d lo = a.cwiseMin(b).array() - delta, hi = a.cwiseMax(b).array() + delta;
    for (auto i = static_cast<long>(std::floor(lo.x() / cell)); i <= static_cast<long>(std::floor(hi.x() / cell)); ++i)
      for (auto j = static_cast<long>(std::floor(lo.y() / cell)); j <= static_cast<long>(std::floor(hi.y() / cell)); ++j)
        grid[{i, j}].push_back(static_cast<int>(k));
  }
  const auto far_along = [&](const RimEdge& e, const RimEdge& f) {
    if (e.loop != f.loop)
      return true;
    const auto l = static_cast<std::size_t>(e.loop);
    const long n = static_cast<long>(loops[l].size());
    const long apart = std::abs(static_cast<long>(e.at) - f.at);
    if (std::min(apart, n - apart) < 2)
      return false;
    const double length = arc[l].back();
    const double s = arc[l][static_cast<std::size_t>(std::min(e.at, f.at)) + 1],
                 u = arc[l][static_cast<std::size_t>(std::max(e.at, f.at))];
    const double between = u - s; // from the end of the first edge to the start of the second
    const double around = length - (arc[l][static_cast<std::size_t>(std::max(e.at, f.at)) + 1] -
                                     arc[l][static_cast<std::size_t>(std::min(e.at, f.at))]);
    return std::min(between, around) > 3 * delta;
  };
  std::optional<Meeting> best;
  for (const auto& [key, members] : grid)
    for (std::size_t i = 0; i < members.size(); ++i)
      for (std::size_t j = i + 1; j < members.size(); ++j) {
        const RimEdge& e = edges[static_cast<std::size_t>(std::min(members[i], members[j]))];
        const RimEdge& f = edges[static_cast<std::size_t>(std::max(members[i], members[j]))];
        if (!far_along(e, f))
          continue;
        const auto [a, b] = end_points(e);
        const auto [c, d] = end_points(f);
        const auto [p, q] = closest_points(a, b, c, d);
        const double gap = (p - q).norm();
        if (gap < delta && (!best || gap < best->gap))
          best = Meeting{e, f, p, q, gap};
      }
  return best;
}

//! The outward normal in the plane of rim edge `e` (e_z × its direction, out of the film).
Eigen::Vector2d outward(const VertexVectors& x, const std::vector<std::vector<int>>& loops, const RimEdge& e)
{
  const std::vector<int>& loop = loops[static_cast<std::size_t>(e.loop)];
  const Eigen::Vector2d d = xy(x, loop[(static_cast<std::size_t>(e.at) + 1) % loop.size()]) -
                            xy(x, loop[static_cast<std::size_t>(e.at)]);
  return Eigen::Vector2d(-d.y(), d.x()).normalized();
}

//! The stretch of `loop` around its edge `at` whose vertices lie within `reach` of `centre` in the
//! plane, in the loop's order (at least the edge's two ends; at most a third of the loop).
std::vector<int> arc_near(const VertexVectors& x, const std::vector<int>& loop, int at, const Eigen::Vector2d& centre,
                          double reach)
{
  const long n = static_cast<long>(loop.size());
  const auto vertex = [&](long i) { return loop[static_cast<std::size_t>(((i % n) + n) % n)]; };
  const long limit = std::max(2L, n / 3);
  long first = at, last = at + 1;
  while (last - first + 1 < limit && (xy(x, vertex(first - 1)) - centre).norm() < reach)
    --first;
  while (last - first + 1 < limit && (xy(x, vertex(last + 1)) - centre).norm() < reach)
    ++last;
  std::vector<int> arc;
  for (long i = first; i <= last; ++i)
    arc.push_back(vertex(i));
  return arc;
}

//! The strip joining rim stretch `a` to rim stretch `b` (each in its loop's order; they face each
//! other, so they run opposite ways): walking a forwards and b backwards, each triangle advances on
//! the stretch whose next diagonal is shorter. Every triangle takes a rim edge the way its boundary
//! halfedge runs, so the strip continues both surfaces with their orientation.
std::vector<std::array<int, 3>> zip_stretches(const VertexVectors& x, const std::vector<int>& a, std::vector<int> b)
{
  std::reverse(b.begin(), b.end());
  std::vector<std::array<int, 3>> strip;
  std::size_t i = 0, j = 0;
  const auto distance = [&](int u, int v) { return (x.row(u) - x.row(v)).norm(); };
  while (i + 1 < a.size() || j + 1 < b.size()) {
    const bool along_a = j + 1 >= b.size() ||
                         (i + 1 < a.size() && distance(a[i + 1], b[j]) <= distance(a[i], b[j + 1]));
    if (along_a) {
      strip.push_back({a[i], a[i + 1], b[j]});
      ++i;
    } else {
      strip.push_back({a[i], b[j + 1], b[j]});
      ++j;
    }
  }
  return strip;
}

} // namespace

SubstrateTopologyResult change_substrate_topology(const Mesh& mesh, const SubstrateTopologyOptions& o)
{
  if (!(o.threshold > 0) || !std::isfinite(o.threshold))
    throw InvalidParameter(fmt::format("substrate topology: δ must be > 0, got {}", o.threshold));
  if (!(o.edge_length > 0) || !std::isfinite(o.edge_length))
    throw InvalidParameter(fmt::format("substrate topology: ℓ must be > 0, got {}", o.edge_length));
  SubstrateTopologyResult result;
  const VertexVectors x = vertex_positions(mesh);
  const std::vector<std::vector<int>> loops = rim_loops(mesh);
  if (loops.empty())
    return result;
  const auto n = static_cast<std::size_t>(mesh.n_vertices());
  const auto finish = [&](std::optional<Cut> cut, SubstrateChange change) {
    if (!cut || !manifold_vertices(cut->mesh))
      return;
    result.change = change;
    result.faces_removed = cut->removed;
    result.debris_faces = cut->debris;
    result.mesh = std::move(cut->mesh);
  };

  // Touchdown: vertices lower than δ and farther than ℓ in the plane from every contact line, and
  // the low part around them.
  std::vector<bool> low(n, false);
  std::vector<Mesh::VertexHandle> queue;
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto v : mesh.vertices()) {
    const double height = x(v.idx(), 2) - o.z;
    if (mesh.is_boundary(v) || !(height < o.threshold))
      continue;
    const Eigen::Vector2d p = xy(x, v.idx());
    bool far = true;
    for (const std::vector<int>& loop : loops)
      for (std::size_t i = 0; i < loop.size() && far; ++i)
        far = (closest_on_segment(p, xy(x, loop[i]), xy(x, loop[(i + 1) % loop.size()])) - p).norm() > o.edge_length;
    if (far) {
      low[static_cast<std::size_t>(v.idx())] = true;
      queue.push_back(v);
      lowest = std::min(lowest, height);
    }
  }
  if (!queue.empty()) {
    while (!queue.empty()) {
      const Mesh::VertexHandle v = queue.back();
      queue.pop_back();
      for (const auto w : mesh.vv_range(v)) {
        const auto k = static_cast<std::size_t>(w.idx());
        if (!low[k] && !mesh.is_boundary(w) && x(w.idx(), 2) - o.z < o.threshold) {
          low[k] = true;
          queue.push_back(w);
        }
      }
    }
    std::vector<bool> removed(mesh.n_faces(), false);
    long low_vertices = 0;
    for (const auto v : mesh.vertices())
      if (low[static_cast<std::size_t>(v.idx())]) {
        ++low_vertices;
        for (const auto f : mesh.vf_range(v))
          removed[static_cast<std::size_t>(f.idx())] = true;
      }
    finish(cut_out(mesh, std::move(removed), o.z, o.min_component_faces), SubstrateChange::touchdown);
    if (result.change != SubstrateChange::none) {
      result.size = lowest;
      result.detail = fmt::format("the film came {:.3g} above the substrate, within δ = {:.3g}, farther than ℓ = {:.3g} "
                                  "from its contact lines; the film lower than δ there cut out ({} vertices, {} faces, {} "
                                  "of debris) and its rim put on the plane",
                                  lowest, o.threshold, o.edge_length, low_vertices, result.faces_removed,
                                  result.debris_faces);
      return result;
    }
  }

  // Contact lines meeting.
  const std::optional<Meeting> meeting = closest_meeting(x, loops, o.threshold);
  if (!meeting)
    return result;
  const Eigen::Vector2d centre = 0.5 * (meeting->p + meeting->q);
  Eigen::Vector2d across = meeting->q - meeting->p;
  if (across.norm() < 1e-12 * o.edge_length) {
    const auto mid = [&](const RimEdge& e) {
      const std::vector<int>& loop = loops[static_cast<std::size_t>(e.loop)];
      return 0.5 * (xy(x, loop[static_cast<std::size_t>(e.at)]) +
                    xy(x, loop[(static_cast<std::size_t>(e.at) + 1) % loop.size()]));
    };
    across = mid(meeting->second) - mid(meeting->first);
  }
  // Material lies against each edge's outward normal: across it when q is behind p's edge and p behind q's.
  result.across_material =
      across.dot(outward(x, loops, meeting->first)) - across.dot(outward(x, loops, meeting->second)) < 0;
  result.size = meeting->gap;
  if (result.across_material) {
    const double reach = 0.5 * o.edge_length;
    std::vector<bool> removed(mesh.n_faces(), false);
    for (const auto f : mesh.faces()) {
      std::array<Eigen::Vector2d, 3> c;
      int k = 0;
      for (const auto v : f.vertices())
        c[static_cast<std::size_t>(k++)] = xy(x, v.idx());
      const double s0 = cross2(c[1] - c[0], centre - c[0]), s1 = cross2(c[2] - c[1], centre - c[1]),
                   s2 = cross2(c[0] - c[2], centre - c[2]);
      const bool inside = (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
      double distance = inside ? 0.0 : std::numeric_limits<double>::infinity();
      for (int e = 0; e < 3; ++e)
        distance = std::min(distance, (closest_on_segment(centre, c[static_cast<std::size_t>(e)],
                                                          c[static_cast<std::size_t>((e + 1) % 3)]) -
                                       centre).norm());
      removed[static_cast<std::size_t>(f.idx())] = distance <= reach;
    }
    finish(cut_out(mesh, std::move(removed), o.z, o.min_component_faces), SubstrateChange::contact);
    if (result.change != SubstrateChange::none)
      result.detail = fmt::format("two contact lines came {:.3g} apart, within δ = {:.3g}, across the film's footprint; "
                                  "the film within {:.3g} of the gap cut out ({} faces, {} of debris) and its rim put "
                                  "on the plane",
                                  meeting->gap, o.threshold, reach, result.faces_removed, result.debris_faces);
    return result;
  }
  const std::vector<int> a = arc_near(x, loops[static_cast<std::size_t>(meeting->first.loop)], meeting->first.at,
                                      centre, o.edge_length);
  const std::vector<int> b = arc_near(x, loops[static_cast<std::size_t>(meeting->second.loop)], meeting->second.at,
                                      centre, o.edge_length);
  for (const int v : a)
    if (std::find(b.begin(), b.end(), v) != b.end())
      return SubstrateTopologyResult{};
  const std::vector<std::array<int, 3>> strip = zip_stretches(x, a, b);
  FaceIndices triangles = face_indices(mesh);
  const Eigen::Index old_faces = triangles.rows();
  triangles.conservativeResize(old_faces + static_cast<Eigen::Index>(strip.size()), 3);
  for (std::size_t k = 0; k < strip.size(); ++k)
    for (int c = 0; c < 3; ++c)
      triangles(old_faces + static_cast<Eigen::Index>(k), c) = strip[k][static_cast<std::size_t>(c)];
  Mesh zipped;
  try {
    zipped = make_mesh(x, triangles);
  } catch (const InvalidMesh&) {
    return SubstrateTopologyResult{};
  }
  if (!manifold_vertices(zipped))
    return SubstrateTopologyResult{};
  result.change = SubstrateChange::contact;
  result.faces_added = static_cast<long>(strip.size());
  result.mesh = std::move(zipped);
  result.detail = fmt::format("two contact lines came {:.3g} apart, within δ = {:.3g}, across the bare substrate; "
                              "their {} and {} vertices within {:.3g} of the gap zipped by {} triangles in the plane",
                              meeting->gap, o.threshold, a.size(), b.size(), o.edge_length, strip.size());
  return result;
}

} // namespace sdflow
