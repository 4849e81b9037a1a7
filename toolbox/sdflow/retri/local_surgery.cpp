#include "sdflow/retri/local_surgery.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/soup.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"
#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/reconstruct/holes.h"
#include "sdflow/reconstruct/point_normals.h"
#include "sdflow/reconstruct/reconstruct_apart.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/retri/components.h"
#include "sdflow/retri/remove_intersections.h"
#include "sdflow/retri/surgery_patch.h"
#include "sdflow/retri/zip_loops.h"
#include "sdflow/spatial/nearest_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <utility>

namespace sdflow {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

//! An attempt that cannot finish; the message says why.
class AttemptFailed : public Error {
public:
  using Error::Error;
};

//! Rings of kept vertices beyond the cut whose points and normals the rebuild borrows.
constexpr int kContextRings = 2;
//! A rebuilt rim loop belongs to a cut loop when its vertices lie within this many of the cut
//! loop's mean edge lengths of it on average, and no vertex farther than kRimMaxDistance.
constexpr double kRimMeanDistance = 3;
constexpr double kRimMaxDistance = 5;

//! The area-weighted normal of the triangles around v (not normalised; zero in a degenerate star).
Eigen::Vector3d area_normal(const Mesh& mesh, Mesh::VertexHandle v)
{
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (const auto f : mesh.vf_range(v)) {
    const auto x = triangle_corners(mesh, f).point;
    n += (x[1] - x[0]).cross(x[2] - x[0]);
  }
  return n;
}

//! The vertices of a boundary loop, each the start of one of its halfedges, in order.
std::vector<int> loop_vertices(const Mesh& mesh, const std::vector<Mesh::HalfedgeHandle>& loop)
{
  std::vector<int> vertices;
  vertices.reserve(loop.size());
  for (const auto h : loop)
    vertices.push_back(mesh.from_vertex_handle(h).idx());
  return vertices;
}

//! Faces of a mesh taken out as a mesh of their own, its vertices numbered anew in the order met.
struct FaceSubset {
  Mesh mesh;
  std::vector<int> global; //!< the input index of each vertex
  std::vector<int> local;  //!< by input vertex: its index in `mesh`, or -1
};

//! The faces of `mesh` for which `take(face)` holds, as a FaceSubset.
template <class Take>
FaceSubset taken_out(const Mesh& mesh, Take&& take)
{
  FaceSubset subset;
  subset.local.assign(mesh.n_vertices(), -1);
  std::vector<std::array<int, 3>> triangles;
  for (const auto f : mesh.faces()) {
    if (!take(f))
      continue;
    std::array<int, 3> t{};
    int k = 0;
    for (const auto v : mesh.fv_range(f)) {
      int& index = subset.local[static_cast<std::size_t>(v.idx())];
      if (index < 0) {
        index = static_cast<int>(subset.global.size());
        subset.global.push_back(v.idx());
      }
      t[static_cast<std::size_t>(k++)] = index;
    }
    triangles.push_back(t);
  }
  VertexVectors x(static_cast<Eigen::Index>(subset.global.size()), 3);
  for (std::size_t i = 0; i < subset.global.size(); ++i)
    x.row(static_cast<Eigen::Index>(i)) = to_eigen(mesh.point(mesh.vertex_handle(subset.global[i]))).transpose();
  subset.mesh = make_mesh(x, triangle_rows(triangles));
  return subset;
}

//! The patch faces as their own mesh (its boundary is the cut), with the input index of each of
//! its vertices, and the kept vertices within kContextRings of the cut.
struct Cut {
  Mesh patch;
  std::vector<int> global;
  std::vector<int> context;
};

Cut cut_out(const Mesh& mesh, const SurgeryPatch& selection)
{
  Cut cut;
  FaceSubset taken =
      taken_out(mesh, [&](Mesh::FaceHandle f) { return selection.in_patch[static_cast<std::size_t>(f.idx())] != 0; });
  cut.patch = std::move(taken.mesh);
  cut.global = std::move(taken.global);
  const std::vector<int>& local = taken.local;

  // Rings of kept vertices around the cut, walking only through vertices with a kept face.
  const auto has_kept_face = [&](Mesh::VertexHandle v) {
    for (const auto f : mesh.vf_range(v))
      if (!selection.in_patch[static_cast<std::size_t>(f.idx())])
        return true;
    return false;
  };
  std::vector<char> seen(mesh.n_vertices(), 0);
  std::vector<int> ring;
  for (const auto v : cut.patch.vertices())
    if (cut.patch.is_boundary(v)) {
      const int g = cut.global[static_cast<std::size_t>(v.idx())];
      seen[static_cast<std::size_t>(g)] = 1;
      ring.push_back(g);
    }
  for (int r = 0; r < kContextRings; ++r) {
    std::vector<int> next;
    for (const int g : ring)
      for (const auto w : mesh.vv_range(mesh.vertex_handle(g)))
        if (!seen[static_cast<std::size_t>(w.idx())] && local[static_cast<std::size_t>(w.idx())] < 0 &&
            has_kept_face(w)) {
          seen[static_cast<std::size_t>(w.idx())] = 1;
          next.push_back(w.idx());
        }
    cut.context.insert(cut.context.end(), next.begin(), next.end());
    ring.swap(next);
  }
  return cut;
}

//! The patch's sizing: at each vertex the mean length of its edges, within [min_fraction·ℓ, ℓ].
//! Around a crossing the pipeline keeps the mesh's own scale too (pipeline.cpp, adapted_sizing),
//! and the kept surface around the cut keeps it by construction.
SizingField patch_sizing(const Mesh& patch, double ell, double min_fraction)
{
  const Eigen::VectorXd mean = vertex_mean_edge_lengths(patch);
  std::vector<double> target(patch.n_vertices());
  for (std::size_t v = 0; v < target.size(); ++v)
    target[v] = std::clamp(mean(static_cast<Eigen::Index>(v)), min_fraction * ell, ell);
  return nearest_vertex_sizing(patch, std::move(target));
}

//! Isotropic remeshing with the boundary (the cut) kept exactly.
RemeshResult remesh_keeping_cut(const Mesh& mesh, const SizingField& sizing, double ell, int iterations)
{
  RemeshOptions remesh;
  remesh.edge_length = ell;
  remesh.iterations = iterations;
  remesh.boundary = BoundaryMode::keep;
  remesh.sizing = sizing;
  return isotropic_remesh(mesh, remesh);
}

//! A rebuilt rim loop matched to a cut loop.
struct LoopPair {
  std::vector<int> cut; //!< vertices in the zip's numbering
  std::vector<int> rim;
};

//! The rim loops of the trimmed rebuild that run along a cut loop, one per cut loop (the others are
//! inner holes). `positions` hold every vertex in the zip's numbering.
std::vector<LoopPair> match_rims_to_cuts(const VertexVectors& positions, const std::vector<std::vector<int>>& cuts,
                                         const std::vector<std::vector<int>>& rims)
{
  if (cuts.empty()) // a patch that holds whole components: nothing to zip a rebuild to
    throw AttemptFailed("the patch holds a whole component, with no cut to join the rebuild to");
  std::vector<LoopPair> pairs(cuts.size());
  std::vector<double> spacing(cuts.size(), 0);
  for (std::size_t c = 0; c < cuts.size(); ++c) {
    pairs[c].cut = cuts[c];
    for (std::size_t i = 0; i < cuts[c].size(); ++i)
      spacing[c] += (positions.row(cuts[c][i]) - positions.row(cuts[c][(i + 1) % cuts[c].size()])).norm();
    spacing[c] /= static_cast<double>(cuts[c].size());
  }
  // Each rim loop near a cut loop is a candidate for it; the longest is its rim, the others (a hole
  // of the rebuild close to the cut) stay inner holes.
  std::vector<double> farthest_of_chosen(cuts.size(), 0);
  std::vector<int> chosen(cuts.size(), -1);
  for (std::size_t r = 0; r < rims.size(); ++r) {
    std::vector<int> votes(cuts.size(), 0);
    std::vector<double> sum(cuts.size(), 0), farthest(cuts.size(), 0);
    for (const int v : rims[r]) {
      std::vector<double> nearest(cuts.size(), std::numeric_limits<double>::infinity());
      for (std::size_t c = 0; c < cuts.size(); ++c)
        for (const int w : cuts[c])
          nearest[c] = std::min(nearest[c], (positions.row(v) - positions.row(w)).norm());
      const auto best = static_cast<std::size_t>(std::min_element(nearest.begin(), nearest.end()) - nearest.begin());
      ++votes[best];
      for (std::size_t c = 0; c < cuts.size(); ++c) {
        sum[c] += nearest[c];
        farthest[c] = std::max(farthest[c], nearest[c]);
      }
    }
    const auto c = static_cast<std::size_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
    if (sum[c] / static_cast<double>(rims[r].size()) > kRimMeanDistance * spacing[c])
      continue;
    if (chosen[c] >= 0 && rims[static_cast<std::size_t>(chosen[c])].size() >= rims[r].size())
      continue;
    chosen[c] = static_cast<int>(r);
    farthest_of_chosen[c] = farthest[c];
  }
  for (std::size_t c = 0; c < cuts.size(); ++c) {
    if (chosen[c] < 0)
      throw AttemptFailed("the rebuild left nothing along a cut loop");
    if (farthest_of_chosen[c] > kRimMaxDistance * spacing[c])
      throw AttemptFailed("a rebuilt rim loop strays from the cut it should join");
    pairs[c].rim = rims[static_cast<std::size_t>(chosen[c])];
  }
  return pairs;
}

//! Closes the boundary loop `loop` (vertices in boundary order) of `mesh` by a fan of triangles
//! around a new vertex at its centroid, which it returns; throws AttemptFailed with `failure` when
//! the loop is not a simple boundary loop.
Mesh::VertexHandle close_with_fan(Mesh& mesh, const std::vector<int>& loop, const char* failure)
{
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const int v : loop)
    centre += to_eigen(mesh.point(mesh.vertex_handle(v)));
  const auto fan = mesh.add_vertex(to_point(centre / static_cast<double>(loop.size())));
  for (std::size_t i = 0; i < loop.size(); ++i)
    if (!mesh.add_face(mesh.vertex_handle(loop[i]), mesh.vertex_handle(loop[(i + 1) % loop.size()]), fan).is_valid())
      throw AttemptFailed(failure);
  return fan;
}

//! Fills the holes of `mesh` that are not its cut loops (Liepa 2003, holes.h): each cut loop is
//! closed by a temporary fan, the holes shorter than `bound` filled, the fans removed.
Mesh fill_inner_holes(const Mesh& input, const std::vector<std::vector<int>>& cuts, double bound, int& filled_count)
{
  Mesh mesh = input;
  std::vector<Mesh::VertexHandle> caps;
  for (const auto& loop : cuts)
    caps.push_back(close_with_fan(mesh, loop, "a cut loop could not be capped (not a simple boundary loop)"));
  HoleFillingOptions holes;
  holes.max_loop_length = bound;
  FilledHoles filled = fill_holes(mesh, holes);
  filled_count = static_cast<int>(std::count_if(filled.loops.begin(), filled.loops.end(),
                                                [](const HoleReport& loop) { return loop.outcome == LoopOutcome::filled; }));
  for (const auto cap : caps)
    filled.mesh.delete_vertex(cap, false);
  filled.mesh.garbage_collection();
  return std::move(filled.mesh);
}

//! Exact coordinates as a map key.
using PointKey = std::array<double, 3>;
PointKey key_of(const Mesh::Point& p) { return {p[0], p[1], p[2]}; }

//! The bounding box of some triangles of a soup.
Eigen::AlignedBox3d box_of(const std::vector<Eigen::Vector3d>& points, const std::vector<std::vector<long long>>& polygons,
                           std::size_t first)
{
  Eigen::AlignedBox3d box;
  for (std::size_t f = first; f < polygons.size(); ++f)
    for (const long long v : polygons[f])
      box.extend(points[static_cast<std::size_t>(v)]);
  return box;
}

//! Do the new triangles of the soup (from `first_new` on) intersect any triangle (exact,
//! self_intersections' rule)? Only triangles whose boxes meet the new ones' box are tested: the
//! kept surface intersects itself nowhere else, the crossings having all been inside the patch.
bool new_faces_intersect(const PolygonSoup& soup, std::size_t first_new)
{
  const Eigen::AlignedBox3d region = box_of(soup.points, soup.polygons, first_new);
  std::vector<int> used(soup.points.size(), -1);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (const auto& polygon : soup.polygons) {
    Eigen::AlignedBox3d box;
    for (const long long v : polygon)
      box.extend(soup.points[static_cast<std::size_t>(v)]);
    if (!box.intersects(region))
      continue;
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      int& index = used[static_cast<std::size_t>(polygon[static_cast<std::size_t>(k)])];
      if (index < 0) {
        index = static_cast<int>(points.size());
        points.push_back(soup.points[static_cast<std::size_t>(polygon[static_cast<std::size_t>(k)])]);
      }
      t[static_cast<std::size_t>(k)] = index;
    }
    triangles.push_back(t);
  }
  return !self_intersections(point_rows(points), triangle_rows(triangles)).empty();
}

//! By vertex of the removal's mesh: whether it lies on a piece that the removal of the
//! intersecting faces cut off from the cut, in a patch component that reaches the cut. Such a
//! piece is surface between crossings (the wall of a neck between the two points where it passed
//! through the axis, a sheet's part inside another), to be dropped, not rebuilt: at a pinch its
//! points are an inside-out tube thinner than ℓ, which the reconstruction stitches to the two
//! ends and the hole filling then fills across. A patch component without a cut vertex (a small
//! component all inside the patch) is rebuilt as before. With a finite `reach`, a piece cut off
//! from the cut is surface between crossings only when none of its vertices is farther than `reach`
//! from every vertex of a removed face: a patch that is not local (the whole surface inside a band,
//! fixed_rim.h) holds whole bodies that a pinch cut off from its cut.
std::vector<char> crossed_over_vertices(const Mesh& patch, const RemovalResult& removal,
                                        double reach = std::numeric_limits<double>::infinity())
{
  int patch_count = 0, piece_count = 0;
  const std::vector<int> patch_component = face_component_ids(patch, &patch_count);
  const std::vector<int> piece = face_component_ids(removal.mesh, &piece_count);
  std::vector<char> component_reaches_cut(static_cast<std::size_t>(patch_count), 0);
  for (const auto f : patch.faces())
    for (const auto v : patch.fv_range(f))
      if (patch.is_boundary(v))
        component_reaches_cut[static_cast<std::size_t>(patch_component[static_cast<std::size_t>(f.idx())])] = 1;
  std::vector<char> piece_reaches_cut(static_cast<std::size_t>(piece_count), 0), piece_in_cut_component(piece_reaches_cut);
  for (const auto f : removal.mesh.faces()) {
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(f.idx())]);
    const int origin = removal.face_origin[static_cast<std::size_t>(f.idx())];
    piece_in_cut_component[p] = component_reaches_cut[static_cast<std::size_t>(patch_component[static_cast<std::size_t>(origin)])];
    for (const auto v : removal.mesh.fv_range(f))
      if (patch.is_boundary(patch.vertex_handle(removal.vertex_origin[static_cast<std::size_t>(v.idx())])))
        piece_reaches_cut[p] = 1;
  }
  if (std::isfinite(reach) && !removal.removed_faces.empty()) {
    std::vector<Eigen::Vector3d> crossing;
    for (const int f : removal.removed_faces)
      for (const auto v : patch.fv_range(patch.face_handle(f)))
        crossing.push_back(to_eigen(patch.point(v)));
    const VertexVectors sites = point_rows(crossing), points = vertex_positions(removal.mesh);
    const std::vector<int> nearest = nearest_points(sites, points);
    for (const auto f : removal.mesh.faces())
      for (const auto v : removal.mesh.fv_range(f))
        if ((points.row(v.idx()) - sites.row(nearest[static_cast<std::size_t>(v.idx())])).norm() > reach)
          piece_reaches_cut[static_cast<std::size_t>(piece[static_cast<std::size_t>(f.idx())])] = 1;
  }
  // A vertex where a crossed-over piece meets a kept one (a pinched vertex) stays.
  std::vector<char> crossed(removal.mesh.n_vertices(), 1);
  for (const auto f : removal.mesh.faces()) {
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(f.idx())]);
    if (!piece_in_cut_component[p] || piece_reaches_cut[p])
      for (const auto v : removal.mesh.fv_range(f))
        crossed[static_cast<std::size_t>(v.idx())] = 0;
  }
  return crossed;
}

//! Stage 4 on each piece of the symmetric k-nearest-neighbour graph of the points apart (k as for
//! the normals; a piece of fewer than k points is left unused, debris): the advancing front then
//! joins only points that sample one surface at the normals' scale, and cannot bridge two ends a
//! pinch left a few ℓ apart (the cone tips of a neck drawn through its axis, whose normals still
//! admit a triangle between them, and whose bridge the hole filling then fills across).
Reconstruction reconstruct_by_piece(const OrientedPoints& oriented, const RetriangulationOptions& options)
{
  const auto n = static_cast<int>(oriented.points.rows());
  const int k = std::min(options.normals.neighbours, n);
  std::vector<int> root(static_cast<std::size_t>(n));
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&](int i) {
    while (root[static_cast<std::size_t>(i)] != i)
      i = root[static_cast<std::size_t>(i)] = root[static_cast<std::size_t>(root[static_cast<std::size_t>(i)])];
    return i;
  };
  const NeighbourTable neighbours = nearest_neighbours(oriented.points, k);
  for (int i = 0; i < n; ++i)
    for (Eigen::Index c = 0; c < neighbours.cols(); ++c)
      root[static_cast<std::size_t>(find(i))] = find(neighbours(i, c));
  std::map<int, std::vector<int>> pieces;
  for (int i = 0; i < n; ++i)
    pieces[find(i)].push_back(i);
  std::vector<std::vector<int>> groups;
  for (auto& [piece_root, members] : pieces)
    if (static_cast<int>(members.size()) >= k)
      groups.push_back(std::move(members));
  return reconstruct_apart(oriented.points, oriented.normals, groups, options.reconstruction);
}

//! Stage 3's points: the patch's but those crossed over, then the context's, each with the
//! surface's own area normal as the reference that signs its jet normal; `outer` marks the cut's
//! and the context's, which the rebuild borrows but does not keep.
struct PatchPoints {
  VertexVectors points, reference;
  std::vector<char> outer;
  int crossed = 0; //!< patch vertices left out as crossed over
};

PatchPoints patch_points(const Mesh& mesh, const Cut& cut, const Mesh& patch, const RemovalResult& removal,
                         double between_crossings_reach)
{
  const std::vector<char> crossed = crossed_over_vertices(patch, removal, between_crossings_reach);
  PatchPoints p;
  p.crossed = static_cast<int>(std::count(crossed.begin(), crossed.end(), 1));
  const auto own = static_cast<Eigen::Index>(removal.mesh.n_vertices()) - p.crossed;
  const auto total = own + static_cast<Eigen::Index>(cut.context.size());
  p.points.resize(total, 3);
  p.reference.resize(total, 3);
  p.outer.assign(static_cast<std::size_t>(total), 0);
  Eigen::Index row = 0;
  for (const auto v : removal.mesh.vertices()) {
    if (crossed[static_cast<std::size_t>(v.idx())])
      continue;
    const auto origin = patch.vertex_handle(removal.vertex_origin[static_cast<std::size_t>(v.idx())]);
    p.points.row(row) = to_eigen(patch.point(origin)).transpose();
    p.reference.row(row) = area_normal(patch, origin).transpose();
    p.outer[static_cast<std::size_t>(row++)] = patch.is_boundary(origin);
  }
  for (const int g : cut.context) {
    const auto v = mesh.vertex_handle(g);
    p.points.row(row) = to_eigen(mesh.point(v)).transpose();
    p.reference.row(row) = area_normal(mesh, v).transpose();
    p.outer[static_cast<std::size_t>(row++)] = 1;
  }
  return p;
}

//! The rebuild without the triangles at the cut or at borrowed points, nor those at a vertex where
//! the rest would meet in more than one fan; throws AttemptFailed when nothing is left.
Mesh trimmed_to_cut(const Reconstruction& rebuilt, const OrientedPoints& oriented, const std::vector<char>& outer)
{
  const auto is_outer = [&](Mesh::VertexHandle v) {
    return outer[static_cast<std::size_t>(
        oriented.source[static_cast<std::size_t>(rebuilt.source[static_cast<std::size_t>(v.idx())])])] != 0;
  };
  std::vector<char> dropped(rebuilt.mesh.n_faces(), 0);
  for (const auto f : rebuilt.mesh.faces())
    for (const auto v : rebuilt.mesh.fv_range(f))
      dropped[static_cast<std::size_t>(f.idx())] = dropped[static_cast<std::size_t>(f.idx())] || is_outer(v);
  separate_split_fans(rebuilt.mesh, dropped);
  std::vector<int> trimmed_index(rebuilt.mesh.n_vertices(), -1);
  std::vector<Eigen::Vector3d> trimmed_points;
  std::vector<std::array<int, 3>> trimmed_faces;
  for (const auto f : rebuilt.mesh.faces()) {
    if (dropped[static_cast<std::size_t>(f.idx())])
      continue;
    std::array<int, 3> t{};
    int k = 0;
    for (const auto v : rebuilt.mesh.fv_range(f)) {
      int& index = trimmed_index[static_cast<std::size_t>(v.idx())];
      if (index < 0) {
        index = static_cast<int>(trimmed_points.size());
        trimmed_points.push_back(to_eigen(rebuilt.mesh.point(v)));
      }
      t[static_cast<std::size_t>(k++)] = index;
    }
    trimmed_faces.push_back(t);
  }
  if (trimmed_faces.empty())
    throw AttemptFailed("nothing of the rebuild is left inside the cut");
  return make_mesh(point_rows(trimmed_points), triangle_rows(trimmed_faces));
}

//! The trimmed rebuild zipped to the patch's cut by a strip (zip_loops), and the cut's loops
//! (in the zipped mesh's numbering) that the strip closed.
struct Zipped {
  Mesh mesh;
  std::vector<std::vector<int>> cuts;
};

Zipped zipped_to_cut(const Mesh& patch, const Mesh& trimmed)
{
  // The trimmed rebuild's vertices first, then the cut's (numbered after them).
  const auto rebuilt_vertices = static_cast<int>(trimmed.n_vertices());
  std::vector<int> zip_index(patch.n_vertices(), -1);
  std::vector<std::vector<int>> cuts;
  for (const auto& loop : boundary_loops(patch))
    cuts.push_back(loop_vertices(patch, loop));
  int cut_vertices = 0;
  for (auto& loop : cuts)
    for (int& v : loop) {
      if (zip_index[static_cast<std::size_t>(v)] < 0)
        zip_index[static_cast<std::size_t>(v)] = rebuilt_vertices + cut_vertices++;
      v = zip_index[static_cast<std::size_t>(v)];
    }
  VertexVectors zx(rebuilt_vertices + cut_vertices, 3);
  zx.topRows(rebuilt_vertices) = vertex_positions(trimmed);
  for (const auto v : patch.vertices())
    if (const int z = zip_index[static_cast<std::size_t>(v.idx())]; z >= 0)
      zx.row(z) = to_eigen(patch.point(v)).transpose();
  std::vector<std::vector<int>> rims;
  for (const auto& loop : boundary_loops(trimmed))
    rims.push_back(loop_vertices(trimmed, loop));
  const std::vector<LoopPair> pairs = match_rims_to_cuts(zx, cuts, rims);
  std::vector<std::array<int, 3>> faces;
  for (const auto f : trimmed.faces()) {
    const auto c = triangle_corners(trimmed, f).index;
    faces.push_back({c[0], c[1], c[2]});
  }
  // Normals at the zip's vertices: the patch's at the cut, the rebuild's at the rim.
  VertexVectors zn = VertexVectors::Zero(zx.rows(), 3);
  for (const auto v : patch.vertices())
    if (const int z = zip_index[static_cast<std::size_t>(v.idx())]; z >= 0)
      zn.row(z) = area_normal(patch, v).transpose();
  for (const auto v : trimmed.vertices())
    zn.row(v.idx()) = area_normal(trimmed, v).transpose();
  Zipped zipped;
  for (const LoopPair& pair : pairs) {
    for (const auto& t : zip_loops(zx, zn, pair.cut, pair.rim))
      faces.push_back(t);
    zipped.cuts.push_back(pair.cut);
  }
  zipped.mesh = make_mesh(zx, triangle_rows(faces));
  return zipped;
}

//! The first of `candidates` (rebuilt patches) that, put in place of the patch with the surface's
//! other faces, crosses none of them; `soup` is then the whole surface. nullptr if none fits.
const RemeshResult* placed_in_surface(const Mesh& mesh, const SurgeryPatch& selection, const Cut& cut,
                                      const std::vector<RemeshResult>& candidates, PolygonSoup& soup)
{
  std::map<PointKey, int> cut_vertex;
  for (const auto v : cut.patch.vertices())
    if (cut.patch.is_boundary(v))
      cut_vertex.emplace(key_of(cut.patch.point(v)), cut.global[static_cast<std::size_t>(v.idx())]);
  std::vector<long long> kept_index(mesh.n_vertices(), -1);
  for (const auto f : mesh.faces())
    if (!selection.in_patch[static_cast<std::size_t>(f.idx())]) {
      std::vector<long long> polygon;
      for (const auto v : mesh.fv_range(f)) {
        long long& index = kept_index[static_cast<std::size_t>(v.idx())];
        if (index < 0) {
          index = static_cast<long long>(soup.points.size());
          soup.points.push_back(to_eigen(mesh.point(v)));
        }
        polygon.push_back(index);
      }
      soup.polygons.push_back(std::move(polygon));
    }
  const std::size_t kept_points = soup.points.size(), first_new = soup.polygons.size();
  for (const RemeshResult& candidate : candidates) {
    soup.points.resize(kept_points);
    soup.polygons.resize(first_new);
    const Mesh& patch_mesh = candidate.mesh;
    std::vector<long long> new_index(patch_mesh.n_vertices(), -1);
    for (const auto v : patch_mesh.vertices()) {
      if (const auto it = cut_vertex.find(key_of(patch_mesh.point(v))); it != cut_vertex.end()) {
        new_index[static_cast<std::size_t>(v.idx())] = kept_index[static_cast<std::size_t>(it->second)];
        continue;
      }
      new_index[static_cast<std::size_t>(v.idx())] = static_cast<long long>(soup.points.size());
      soup.points.push_back(to_eigen(patch_mesh.point(v)));
    }
    for (const auto f : patch_mesh.faces()) {
      std::vector<long long> polygon;
      for (const auto v : patch_mesh.fv_range(f))
        polygon.push_back(new_index[static_cast<std::size_t>(v.idx())]);
      soup.polygons.push_back(std::move(polygon));
    }
    if (!new_faces_intersect(soup, first_new))
      return &candidate;
  }
  return nullptr;
}

//! The sizes below which stage 6 drops a component as debris, at ℓ = `ell`.
ComponentOptions debris_bounds(const RetriangulationOptions& options, double ell)
{
  return {.min_faces = options.min_component_faces, .min_thickness = options.min_component_thickness * ell};
}

//! Stage 6: the first of `candidates` (rebuilt patches with the cut's vertices) that crosses no
//! kept face, put in place of the patch, the result's debris dropped and its boundary loops checked
//! against the input's; fills `r`'s mesh, remeshing counts, components and patch size.
void put_in_place(const Mesh& mesh, const SurgeryPatch& selection, const Cut& cut,
                  const std::vector<RemeshResult>& candidates, const ComponentOptions& debris,
                  int input_boundary_loops, RetriangulationResult& r)
{
  PolygonSoup soup;
  const RemeshResult* placed = placed_in_surface(mesh, selection, cut, candidates, soup);
  if (!placed)
    throw AttemptFailed("the rebuilt patch intersects the surface");
  r.remesh.splits += placed->statistics.splits;
  r.remesh.collapses += placed->statistics.collapses;
  r.remesh.flips += placed->statistics.flips;
  r.remesh.relaxation_reverts += placed->statistics.relaxation_reverts;
  r.remesh.edge_length = r.edge_length;
  ComponentSelection selection_after = keep_components(build_mesh(soup, "local surgery").mesh, debris);
  r.dropped_components += static_cast<int>(selection_after.dropped.size());
  r.mesh = std::move(selection_after.mesh);
  r.open_holes = static_cast<int>(boundary_loops(r.mesh).size());
  if (r.open_holes != input_boundary_loops)
    throw AttemptFailed(fmt::format("the result has {} boundary loops, the input {}", r.open_holes, input_boundary_loops));
  int count = 0;
  face_component_ids(r.mesh, &count);
  r.components_after = count;
  r.rebuilt = true;
  r.patch_faces = selection.faces;
}

//! One attempt on one patch: rebuild it and put it back, or throw (AttemptFailed or any stage's error).
//! `remesh_first`: stage 1 on the patch before the rebuild (the seam is remeshed after it either way,
//! with options.remesh_iterations > 0).
RetriangulationResult rebuild_patch(const Mesh& mesh, const SurgeryPatch& selection, const RetriangulationOptions& options,
                                    double ell, int input_boundary_loops, double hole_bound, bool remesh_first = true,
                                    double between_crossings_reach = std::numeric_limits<double>::infinity())
{
  RetriangulationResult r;
  r.edge_length = ell;
  const ComponentOptions debris = debris_bounds(options, ell);

  // Stage 1 on the patch, its cut fixed.
  auto start = Clock::now();
  const Cut cut = cut_out(mesh, selection);
  const SizingField sizing = patch_sizing(cut.patch, ell, options.min_edge_fraction);
  Mesh patch = cut.patch;
  if (options.remesh_iterations > 0 && remesh_first) {
    RemeshResult remeshed = remesh_keeping_cut(cut.patch, sizing, ell, options.remesh_iterations);
    patch = std::move(remeshed.mesh);
    r.remesh = remeshed.statistics;
  }
  r.seconds.remesh = seconds_since(start);

  // Stage 2.
  start = Clock::now();
  const RemovalResult removal = remove_self_intersections(patch);
  r.intersecting_pairs = static_cast<int>(removal.intersecting_pairs.size());
  r.removed_faces = static_cast<int>(removal.removed_faces.size());
  r.seconds.intersections = seconds_since(start);

  // Stage 3.
  start = Clock::now();
  const PatchPoints sampled = patch_points(mesh, cut, patch, removal, between_crossings_reach);
  const OrientedPoints oriented = normals_oriented_by_reference(sampled.points, sampled.reference, options.normals);
  r.removed_points = sampled.crossed + static_cast<int>(oriented.removed.size());
  r.seconds.normals = seconds_since(start);

  // Stage 4, then the rebuild trimmed to the triangles that touch neither the cut nor the context.
  start = Clock::now();
  const Reconstruction rebuilt = reconstruct_by_piece(oriented, options);
  r.unused_points = static_cast<int>(rebuilt.unused.size());
  ComponentSelection pieces = keep_components(trimmed_to_cut(rebuilt, oriented, sampled.outer), debris);
  r.dropped_components += static_cast<int>(pieces.dropped.size());
  const Mesh& trimmed = pieces.mesh;
  if (trimmed.n_faces() == 0)
    throw AttemptFailed("only debris of the rebuild is left inside the cut");
  r.seconds.reconstruction = seconds_since(start);

  start = Clock::now();
  Zipped zipped = zipped_to_cut(patch, trimmed);
  Mesh rebuilt_patch = std::move(zipped.mesh);

  // Stage 5 on the inner holes.
  if (options.fill_holes)
    rebuilt_patch = fill_inner_holes(rebuilt_patch, zipped.cuts, hole_bound, r.filled_holes);
  r.seconds.holes = seconds_since(start);
  // The seam remeshed with the cut fixed; when that leaves the patch intersecting the surface (a
  // remeshing on a thin gap), the strip as zipped.
  start = Clock::now();
  std::vector<RemeshResult> candidates;
  if (options.remesh_iterations > 0)
    candidates.push_back(remesh_keeping_cut(rebuilt_patch, sizing, ell, options.remesh_iterations));
  candidates.push_back({std::move(rebuilt_patch), {}});
  r.seconds.remesh += seconds_since(start);

  start = Clock::now();
  put_in_place(mesh, selection, cut, candidates, debris, input_boundary_loops, r);
  r.seconds.components = seconds_since(start);
  return r;
}

//! Most vertices of a cut loop that capped_patch caps: the minimum-weight triangulation costs
//! O(n³) (0.3 s at 300, holes.h).
constexpr std::size_t kMaxCappedLoopVertices = 300;

//! Caps for the cut loops of `cut` (Liepa's hole filling, holes.h), as one mesh whose boundary is
//! the cut (its vertices at the cut's exact coordinates). The kept faces next to the cut are the
//! surface each cap is weighed and faired against; the other boundary loops of that collar are
//! closed by temporary fans so that only the cut loops are filled. Empty for a patch of whole
//! components.
Mesh capped_patch(const Mesh& mesh, const SurgeryPatch& selection, const Cut& cut)
{
  std::vector<char> on_cut(mesh.n_vertices(), 0);
  std::set<std::pair<int, int>> cut_edges;
  std::size_t cut_loops = 0;
  for (const auto& loop : boundary_loops(cut.patch)) {
    ++cut_loops;
    if (loop.size() > kMaxCappedLoopVertices)
      throw AttemptFailed(fmt::format("a cut loop of {} vertices is too long to cap", loop.size()));
    for (const auto h : loop) {
      const int a = cut.global[static_cast<std::size_t>(cut.patch.from_vertex_handle(h).idx())];
      const int b = cut.global[static_cast<std::size_t>(cut.patch.to_vertex_handle(h).idx())];
      on_cut[static_cast<std::size_t>(a)] = 1;
      cut_edges.emplace(std::min(a, b), std::max(a, b));
    }
  }
  if (cut_loops == 0)
    return Mesh{}; // whole components: nothing to cap
  // The collar: the kept faces with a corner on the cut.
  const FaceSubset taken = taken_out(mesh, [&](Mesh::FaceHandle f) {
    if (selection.in_patch[static_cast<std::size_t>(f.idx())])
      return false;
    const auto corners = triangle_corners(mesh, f).index;
    return std::any_of(corners.begin(), corners.end(), [&](int v) { return on_cut[static_cast<std::size_t>(v)] != 0; });
  });
  Mesh collar = taken.mesh;
  const std::vector<int>& global = taken.global;
  std::size_t collar_cut_loops = 0;
  for (const auto& loop : boundary_loops(collar)) {
    const bool along_cut = std::all_of(loop.begin(), loop.end(), [&](Mesh::HalfedgeHandle h) {
      const int a = global[static_cast<std::size_t>(collar.from_vertex_handle(h).idx())];
      const int b = global[static_cast<std::size_t>(collar.to_vertex_handle(h).idx())];
      return cut_edges.count({std::min(a, b), std::max(a, b)}) > 0;
    });
    if (along_cut) {
      ++collar_cut_loops;
      continue;
    }
    close_with_fan(collar, loop_vertices(collar, loop),
                   "the surface around the cut is not a simple band, so its loops cannot be capped alone");
  }
  if (collar_cut_loops != cut_loops)
    throw AttemptFailed("the cut loops do not bound the surface kept around them");
  const auto first_cap_face = static_cast<int>(collar.n_faces());
  const FilledHoles filled = fill_holes(collar);
  for (const HoleReport& loop : filled.loops)
    if (loop.outcome != LoopOutcome::filled)
      throw AttemptFailed("a cut loop could not be capped");
  // The caps alone: their faces, the cut's vertices and the vertices the filling added.
  return taken_out(filled.mesh, [&](Mesh::FaceHandle f) { return f.idx() >= first_cap_face; }).mesh;
}

//! Components of the patch with no cut loop: whole components, which capping drops.
int whole_components(const Mesh& patch)
{
  int count = 0;
  const std::vector<int> component = face_component_ids(patch, &count);
  std::vector<char> cut(static_cast<std::size_t>(count), 0);
  for (const auto h : patch.halfedges())
    if (patch.is_boundary(h))
      cut[static_cast<std::size_t>(component[static_cast<std::size_t>(patch.face_handle(patch.opposite_halfedge_handle(h)).idx())])] = 1;
  return static_cast<int>(std::count(cut.begin(), cut.end(), 0));
}

//! A patch replaced by caps of its cut loops (capped_patch), remeshed with the cut fixed, and put
//! back as rebuild_patch puts its rebuild; whole components in the patch are dropped as debris.
//! Throws AttemptFailed (or a stage's error).
RetriangulationResult cap_patch(const Mesh& mesh, const SurgeryPatch& selection, const RetriangulationOptions& options,
                                double ell, int input_boundary_loops)
{
  RetriangulationResult r;
  r.edge_length = ell;
  const ComponentOptions debris = debris_bounds(options, ell);
  auto start = Clock::now();
  const Cut cut = cut_out(mesh, selection);
  Mesh caps = capped_patch(mesh, selection, cut);
  r.removed_faces = selection.faces;
  r.filled_holes = static_cast<int>(boundary_loops(cut.patch).size());
  r.dropped_components = whole_components(cut.patch);
  r.seconds.holes = seconds_since(start);
  start = Clock::now();
  std::vector<RemeshResult> candidates;
  if (options.remesh_iterations > 0 && caps.n_faces() > 0)
    candidates.push_back(remesh_keeping_cut(caps, patch_sizing(cut.patch, ell, options.min_edge_fraction), ell,
                                            options.remesh_iterations));
  candidates.push_back({std::move(caps), {}});
  r.seconds.remesh = seconds_since(start);
  start = Clock::now();
  put_in_place(mesh, selection, cut, candidates, debris, input_boundary_loops, r);
  r.seconds.components = seconds_since(start);
  return r;
}

//! What a patch's rebuild is given besides the patch: ℓ, the input's boundary loops (the result
//! must have as many) and the bound below which inner holes are filled.
struct PatchSetting {
  double ell = 0;
  int boundary_loops = 0;
  double hole_bound = 0;
};

//! The patches of local_surgery and capped_surgery, each twice the radius of the last, until
//! `rebuild` (a patch, the setting, the outcome to count its attempts and failure in → a result or
//! nothing) gives a result; declines as local_surgery.h says.
template <class Rebuild>
LocalSurgery surgery_in_patches(const Mesh& mesh, const std::vector<FacePair>& crossings,
                                const RetriangulationOptions& options, const LocalSurgeryOptions& local,
                                Rebuild&& rebuild)
{
  validate_retriangulation_options(options);
  validate_local_surgery_options(local);
  LocalSurgery outcome;
  if (crossings.empty()) {
    outcome.failure = "nothing intersects";
    return outcome;
  }
  int components = 0;
  const std::vector<int> component = face_component_ids(mesh, &components);
  for (const FacePair& pair : crossings)
    if (component[static_cast<std::size_t>(pair.first)] != component[static_cast<std::size_t>(pair.second)]) {
      outcome.failure = "two components intersect each other (their union is made on the whole surface)";
      return outcome;
    }
  PatchSetting setting;
  setting.ell = options.edge_length > 0 ? options.edge_length : mean_edge_length(mesh);
  const std::vector<double> boundary = boundary_loop_lengths(mesh);
  setting.boundary_loops = static_cast<int>(boundary.size());
  setting.hole_bound = options.max_hole_length > 0 ? options.max_hole_length
                       : boundary.empty()           ? std::numeric_limits<double>::infinity()
                                                    : 0.5 * *std::min_element(boundary.begin(), boundary.end());
  double radius = local.patch_radius * setting.ell;
  int previous_faces = -1;
  for (int attempt = 0; attempt < local.attempts; ++attempt, radius *= 2) {
    const SurgeryPatch patch = surgery_patch(mesh, crossings, radius, options.min_component_faces);
    if (patch.touches_boundary) {
      outcome.failure = "the patch reaches a boundary of the surface";
      return outcome;
    }
    if (patch.faces > local.max_patch_fraction * static_cast<double>(mesh.n_faces())) {
      outcome.failure = fmt::format("the patch would hold {} of the {} faces", patch.faces, mesh.n_faces());
      return outcome;
    }
    if (patch.faces == previous_faces)
      return outcome; // a larger radius takes no more faces: the last failure stands
    previous_faces = patch.faces;
    outcome.patch_radius = radius;
    if (std::optional<RetriangulationResult> r = rebuild(patch, setting, outcome)) {
      r->intersecting_pairs = static_cast<int>(crossings.size());
      r->components_before = components;
      logger().debug("local surgery: {}", retriangulation_summary(*r));
      outcome.result = std::move(r);
      outcome.failure.clear();
      return outcome;
    }
  }
  return outcome;
}

//! One attempt of `rebuild` (→ a result) on `patch`, its failure recorded in `outcome`.
template <class Attempt>
std::optional<RetriangulationResult> attempted(const SurgeryPatch& patch, LocalSurgery& outcome, Attempt&& attempt)
{
  ++outcome.attempts;
  try {
    return attempt();
  } catch (const Error& e) {
    outcome.failure = fmt::format("patch of {} faces: {}", patch.faces, e.what());
    logger().debug("local surgery, attempt {}: {}", outcome.attempts, outcome.failure);
  }
  return std::nullopt;
}

} // namespace

RetriangulationResult rebuild_inside_cut(const Mesh& mesh, const SurgeryPatch& patch, const RetriangulationOptions& options,
                                         const CutRebuild& rebuild)
{
  try {
    return rebuild_patch(mesh, patch, options, rebuild.edge_length, rebuild.boundary_loops, rebuild.hole_bound,
                         rebuild.remesh_first, rebuild.between_crossings_reach);
  } catch (const AttemptFailed& e) {
    throw InvalidMesh(e.what());
  }
}

void validate_local_surgery_options(const LocalSurgeryOptions& o)
{
  if (!(o.patch_radius > 0) || !std::isfinite(o.patch_radius))
    throw InvalidParameter(fmt::format("local surgery: the patch radius must be > 0 (in ℓ), got {}", o.patch_radius));
  if (o.attempts < 1)
    throw InvalidParameter(fmt::format("local surgery: attempts must be ≥ 1, got {}", o.attempts));
  if (!(o.max_patch_fraction > 0 && o.max_patch_fraction <= 1))
    throw InvalidParameter(
        fmt::format("local surgery: the largest patch fraction must be in (0, 1], got {}", o.max_patch_fraction));
}

LocalSurgery local_surgery(const Mesh& mesh, const std::vector<FacePair>& crossings,
                           const RetriangulationOptions& options, const LocalSurgeryOptions& local)
{
  // The patch remeshed first, as the pipeline's stage 1 does; then as it is (a remeshing of a thin
  // neck can leave the rebuild too little room).
  RetriangulationOptions as_it_is = options;
  as_it_is.remesh_iterations = 0;
  const std::array<const RetriangulationOptions*, 2> variants{&options, &as_it_is};
  return surgery_in_patches(mesh, crossings, options, local,
                            [&](const SurgeryPatch& patch, const PatchSetting& set, LocalSurgery& outcome) {
                              for (const RetriangulationOptions* variant : variants) {
                                if (variant == &as_it_is && options.remesh_iterations == 0)
                                  break;
                                if (auto r = attempted(patch, outcome, [&] {
                                      return rebuild_patch(mesh, patch, *variant, set.ell, set.boundary_loops,
                                                           set.hole_bound);
                                    }))
                                  return r;
                              }
                              return std::optional<RetriangulationResult>{};
                            });
}

LocalSurgery capped_surgery(const Mesh& mesh, const std::vector<FacePair>& crossings,
                            const RetriangulationOptions& options, const LocalSurgeryOptions& local)
{
  return surgery_in_patches(mesh, crossings, options, local,
                            [&](const SurgeryPatch& patch, const PatchSetting& set, LocalSurgery& outcome) {
                              return attempted(patch, outcome, [&] {
                                return cap_patch(mesh, patch, options, set.ell, set.boundary_loops);
                              });
                            });
}

} // namespace sdflow
