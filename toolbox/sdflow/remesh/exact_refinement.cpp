#include "sdflow/remesh/exact_refinement.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/angle.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <queue>
#include <utility>
#include <vector>

namespace sdflow {
namespace {

//! Two triangles count as coplanar when the sine of the angle between their normals is below this:
//! a flip between them moves the surface by less than 10⁻¹⁰ of their size, far below what the
//! rounding of coordinates already does, while a crease of a CAD model turns by degrees.
constexpr double kCoplanarSine = 1e-10;
//! A flip is made when the two angles opposite the edge exceed π by more than this (radians):
//! cocircular corners (a square's diagonal) keep their edge, so the flips cannot cycle.
constexpr double kDelaunayMargin = 1e-9;

Eigen::Vector3d point(const Mesh& mesh, Mesh::VertexHandle v) { return to_eigen(mesh.point(v)); }

double length(const Mesh& mesh, Mesh::EdgeHandle e)
{
  const auto h = mesh.halfedge_handle(e, 0);
  return (point(mesh, mesh.to_vertex_handle(h)) - point(mesh, mesh.from_vertex_handle(h))).norm();
}

//! The angle at `apex` of the triangle (apex, p, q).
double angle_at(const Eigen::Vector3d& apex, const Eigen::Vector3d& p, const Eigen::Vector3d& q)
{
  return angle_between(p - apex, q - apex);
}

//! Longest-edge bisection: a priority queue keyed by length, entries checked against the current
//! length when they come out (a split edge keeps its handle for one half).
long split_longest_edges(Mesh& mesh, const ExactRefinementOptions& options, bool& stopped)
{
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry> queue;
  const auto push = [&](Mesh::EdgeHandle e) {
    if (const double l = length(mesh, e); l > options.max_edge_length)
      queue.emplace(l, e.idx());
  };
  for (const auto e : mesh.edges())
    push(e);
  long splits = 0;
  while (!queue.empty()) {
    const auto [stored, index] = queue.top();
    queue.pop();
    const Mesh::EdgeHandle e(index);
    if (length(mesh, e) != stored)
      continue; // split since it was queued: its halves are queued on their own
    if (options.max_vertices > 0 && mesh.n_vertices() >= options.max_vertices) {
      stopped = true;
      break;
    }
    const auto h = mesh.halfedge_handle(e, 0);
    const Eigen::Vector3d mid = 0.5 * (point(mesh, mesh.from_vertex_handle(h)) + point(mesh, mesh.to_vertex_handle(h)));
    const auto v = mesh.add_vertex(to_point(mid));
    mesh.split(e, v);
    ++splits;
    for (const auto around : mesh.ve_range(v))
      push(around);
  }
  return splits;
}

//! Lawson's flips, restricted to edges whose two triangles lie in one plane.
long flip_coplanar_edges(Mesh& mesh)
{
  std::vector<int> queue;
  std::vector<char> queued(mesh.n_edges(), 1);
  for (const auto e : mesh.edges())
    queue.push_back(e.idx());
  long flips = 0;
  // Each flip raises the smallest angle of its quad, so Lawson's flips end; the cap only guards
  // against rounding at cocircular corners beyond kDelaunayMargin.
  const std::size_t cap = 100 * mesh.n_edges() + 100;
  for (std::size_t k = 0; k < queue.size() && k < cap; ++k) {
    const Mesh::EdgeHandle e(queue[k]);
    queued[static_cast<std::size_t>(e.idx())] = 0;
    if (mesh.is_boundary(e))
      continue;
    const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
    const auto a = mesh.from_vertex_handle(h0), b = mesh.to_vertex_handle(h0);
    const auto c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h0));
    const auto d = mesh.to_vertex_handle(mesh.next_halfedge_handle(h1));
    const Eigen::Vector3d pa = point(mesh, a), pb = point(mesh, b), pc = point(mesh, c), pd = point(mesh, d);
    const Eigen::Vector3d n1 = (pb - pa).cross(pc - pa), n2 = (pa - pb).cross(pd - pb);
    if (!(n1.dot(n2) > 0) || n1.cross(n2).norm() > kCoplanarSine * n1.norm() * n2.norm())
      continue;
    if (angle_at(pc, pa, pb) + angle_at(pd, pa, pb) <= std::numbers::pi + kDelaunayMargin || !mesh.is_flip_ok(e))
      continue;
    // After the flip the quad is (c, a, d) and (d, b, c): both must face as the pair did.
    const Eigen::Vector3d n = n1 + n2;
    if (!((pa - pc).cross(pd - pc).dot(n) > 0) || !((pb - pd).cross(pc - pd).dot(n) > 0))
      continue;
    mesh.flip(e);
    ++flips;
    for (const auto h : {mesh.next_halfedge_handle(h0), mesh.prev_halfedge_handle(h0), mesh.next_halfedge_handle(h1),
                         mesh.prev_halfedge_handle(h1)}) {
      const auto side = static_cast<std::size_t>(mesh.edge_handle(h).idx());
      if (!queued[side]) {
        queued[side] = 1;
        queue.push_back(static_cast<int>(side));
      }
    }
  }
  return flips;
}

} // namespace

ExactRefinement refine_exactly(const Mesh& mesh, const ExactRefinementOptions& options)
{
  if (!(options.max_edge_length > 0) || !std::isfinite(options.max_edge_length))
    throw InvalidParameter(
        fmt::format("exact refinement: the edge length bound must be finite and > 0, got {}", options.max_edge_length));
  ExactRefinement r;
  r.mesh = mesh;
  r.splits = split_longest_edges(r.mesh, options, r.stopped);
  r.flips = flip_coplanar_edges(r.mesh);
  return r;
}

} // namespace sdflow
