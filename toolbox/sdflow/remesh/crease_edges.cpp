#include "sdflow/remesh/crease_edges.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/angle.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

namespace sdflow {
namespace {

//! An edge of a crease's triangle within this angle (degrees) of the crease at their common corner
//! runs along it: around a neck resolved by a few edges, such edges turn as much as the crease.
constexpr double kAlongDeg = 75;
//! An edge at the third corner of a crease's triangle within this angle (degrees) of the crease's
//! direction is parallel to it.
constexpr double kParallelDeg = 30;
//! Creases come in lines of at least this many edges (joined at their ends).
constexpr int kMinCreaseEdges = 5;

} // namespace

std::vector<int> crease_edges(const Mesh& mesh, double angle_deg)
{
  if (!(angle_deg > 0 && angle_deg < 180))
    throw InvalidParameter(fmt::format("crease_edges: the crease angle must be in (0°, 180°), got {}°", angle_deg));
  std::vector<Eigen::Vector3d> normal(mesh.n_faces(), Eigen::Vector3d::Zero());
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge_handle(f);
    const Eigen::Vector3d a = to_eigen(mesh.point(mesh.from_vertex_handle(h)));
    const Eigen::Vector3d b = to_eigen(mesh.point(mesh.to_vertex_handle(h)));
    const Eigen::Vector3d c = to_eigen(mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() > 0)
      normal[f.idx()] = n.normalized();
  }
  // The turn of every interior edge, in degrees; a degenerate triangle's edges count as turning
  // sharply (nothing beside them is known to be flat).
  std::vector<double> turn(mesh.n_edges(), 0.0);
  for (const auto e : mesh.edges()) {
    if (mesh.is_boundary(e))
      continue;
    const Eigen::Vector3d& n0 = normal[e.h0().face().idx()];
    const Eigen::Vector3d& n1 = normal[e.h1().face().idx()];
    turn[e.idx()] = n0.squaredNorm() == 0 || n1.squaredNorm() == 0
                        ? 180
                        : angle_between(n0, n1) * 180 / std::numbers::pi;
  }
  // Beside a crease the surface is flat on both sides. The other edges of h's triangle that run
  // along h (within kAlongDeg of it at their common corner) must turn by less than half the crease
  // angle, and so must the edges at the triangle's third corner parallel to h (within
  // kParallelDeg): around a tube a few edges across, the next edge along the tube turns as much,
  // one row away. An edge leaving at a wider angle may be another crease meeting this one at a
  // corner of the shape.
  const double max_turn = angle_deg / 2;
  const double along_cos = std::cos(kAlongDeg * std::numbers::pi / 180);
  const double parallel_cos = std::cos(kParallelDeg * std::numbers::pi / 180);
  const auto flat_beside = [&](Mesh::HalfedgeHandle h) {
    const auto opposite = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    const Eigen::Vector3d a = to_eigen(mesh.point(mesh.from_vertex_handle(h)));
    const Eigen::Vector3d b = to_eigen(mesh.point(mesh.to_vertex_handle(h)));
    const Eigen::Vector3d c = to_eigen(mesh.point(opposite));
    const Eigen::Vector3d along = (b - a).normalized();
    const auto turns = [&](Mesh::HalfedgeHandle g) { return turn[mesh.edge_handle(g).idx()] >= max_turn; };
    if ((along.dot((c - b).normalized()) < -along_cos && turns(mesh.next_halfedge_handle(h))) ||
        (along.dot((c - a).normalized()) > along_cos && turns(mesh.prev_halfedge_handle(h))))
      return false;
    for (const auto g : mesh.voh_range(opposite)) {
      const Eigen::Vector3d d = to_eigen(mesh.point(mesh.to_vertex_handle(g))) - c;
      if (std::abs(along.dot(d)) > parallel_cos * d.norm() && turns(g))
        return false;
    }
    return true;
  };
  std::vector<int> candidates;
  for (const auto e : mesh.edges())
    if (!mesh.is_boundary(e) && turn[e.idx()] > angle_deg && turn[e.idx()] < 180 && flat_beside(e.h0()) &&
        flat_beside(e.h1()))
      candidates.push_back(e.idx());
  // Only lines of them: a sharp edge or two alone is a scan's noise or a coarse tip, which the
  // flow smooths at once.
  std::vector<int> line(mesh.n_vertices());
  std::iota(line.begin(), line.end(), 0);
  const auto root = [&line](int v) {
    while (line[v] != v)
      v = line[v] = line[line[v]];
    return v;
  };
  const auto ends = [&mesh](int e) {
    const auto h = mesh.halfedge_handle(Mesh::EdgeHandle(e), 0);
    return std::array{mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx()};
  };
  for (const int e : candidates) {
    const auto [a, b] = ends(e);
    line[root(a)] = root(b);
  }
  std::vector<int> edges_in_line(mesh.n_vertices(), 0);
  for (const int e : candidates)
    ++edges_in_line[root(ends(e)[0])];
  std::vector<int> creases;
  for (const int e : candidates)
    if (edges_in_line[root(ends(e)[0])] >= kMinCreaseEdges)
      creases.push_back(e);
  return creases;
}

} // namespace sdflow
