#include "sdflow/flow/fold_untangling.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace sdflow {
namespace {

//! Rings around the crossing faces tried, one after the other, and sweeps for each.
constexpr int kMaxRings = 3;
constexpr int kSweepsPerRing = 30;
//! Sweeps between two searches for crossings (a search costs about as much as the surface's BVH).
constexpr int kSweepsPerCheck = 5;

//! The vertices of `faces` and `rings` rings of neighbours around them, ascending.
std::vector<int> vertices_around(const Mesh& mesh, const std::vector<int>& faces, int rings)
{
  std::vector<char> taken(mesh.n_vertices(), 0);
  std::vector<int> front;
  for (int f : faces)
    for (Mesh::VertexHandle v : mesh.fv_range(mesh.face_handle(f)))
      if (!taken[v.idx()]) {
        taken[v.idx()] = 1;
        front.push_back(v.idx());
      }
  std::vector<int> all = front;
  for (int r = 0; r < rings; ++r) {
    std::vector<int> next;
    for (int v : front)
      for (Mesh::VertexHandle w : mesh.vv_range(mesh.vertex_handle(v)))
        if (!taken[w.idx()]) {
          taken[w.idx()] = 1;
          next.push_back(w.idx());
        }
    all.insert(all.end(), next.begin(), next.end());
    front = std::move(next);
  }
  std::sort(all.begin(), all.end());
  return all;
}

} // namespace

bool crossings_are_adjacent(const Mesh& mesh, const std::vector<FacePair>& crossings)
{
  if (crossings.empty())
    return false;
  return std::all_of(crossings.begin(), crossings.end(), [&](const FacePair& p) {
    const std::vector<int> near = vertices_around(mesh, {p.first}, 1);
    for (Mesh::VertexHandle v : mesh.fv_range(mesh.face_handle(p.second)))
      if (std::binary_search(near.begin(), near.end(), v.idx()))
        return true;
    return false;
  });
}

FoldUntangling untangle_fold(const Mesh& mesh, const std::vector<FacePair>& crossings, double max_move)
{
  std::vector<int> faces;
  for (const FacePair& p : crossings) {
    faces.push_back(p.first);
    faces.push_back(p.second);
  }
  const VertexVectors start = vertex_positions(mesh);
  const FaceIndices triangles = face_indices(mesh);
  FoldUntangling untangling;
  std::size_t left = crossings.size();
  for (int rings = 1; rings <= kMaxRings; ++rings) {
    const std::vector<int> free = vertices_around(mesh, faces, rings);
    VertexVectors positions = start;
    for (int sweep = 1; sweep <= kSweepsPerRing; ++sweep) {
      // Jacobi sweep: every free vertex to the mean of its neighbours as they were.
      const VertexVectors before = positions;
      for (int v : free) {
        Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
        int count = 0;
        for (Mesh::VertexHandle w : mesh.vv_range(mesh.vertex_handle(v))) {
          sum += before.row(w.idx());
          ++count;
        }
        if (count > 0)
          positions.row(v) = sum / count;
      }
      double moved = 0;
      for (int v : free)
        moved = std::max(moved, (positions.row(v) - start.row(v)).norm());
      if (!(moved <= max_move)) {
        untangling.failure = fmt::format("smoothing {} rings around them moved a vertex {:.3g}, farther than {:.3g}, "
                                         "with {} pairs still crossing",
                                         rings, moved, max_move, left);
        break;
      }
      if (sweep % kSweepsPerCheck != 0)
        continue;
      left = self_intersections(positions, triangles).size();
      if (left == 0) {
        untangling.positions = std::move(positions);
        untangling.rings = rings;
        untangling.iterations = sweep;
        untangling.largest_move = moved;
        untangling.failure.clear();
        return untangling;
      }
      untangling.failure = fmt::format("{} sweeps smoothing {} rings around them left {} pairs crossing", sweep,
                                       rings, left);
    }
  }
  return untangling;
}

} // namespace sdflow
