#include "sdflow/retri/zip_loops.h"

#include "sdflow/errors.h"
#include "sdflow/io/validate.h"

#include <fmt/format.h>

#include <limits>

namespace sdflow {
namespace {

Eigen::Vector3d position(const VertexVectors& positions, int i) { return positions.row(i).transpose(); }

//! Index in `loop` of the vertex nearest to p.
std::size_t nearest_on_loop(const VertexVectors& positions, const std::vector<int>& loop, const Eigen::Vector3d& p)
{
  std::size_t best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < loop.size(); ++j)
    if (const double d = (position(positions, loop[j]) - p).squaredNorm(); d < best_distance) {
      best_distance = d;
      best = j;
    }
  return best;
}

} // namespace

std::vector<std::array<int, 3>> zip_loops(const VertexVectors& positions, const VertexVectors& normals,
                                          const std::vector<int>& outer, const std::vector<int>& inner)
{
  const std::size_t n = outer.size(), m = inner.size();
  if (n < 3 || m < 3)
    throw InvalidMesh(fmt::format("zip_loops: loops of {} and {} vertices; each needs at least 3", n, m));
  // Both loops must run the same way: each outer edge against the inner edge at its nearest vertex.
  double agreement = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d a = position(positions, outer[i]), a_next = position(positions, outer[(i + 1) % n]);
    const std::size_t j = nearest_on_loop(positions, inner, a);
    agreement += (a_next - a).dot(position(positions, inner[(j + 1) % m]) - position(positions, inner[j]));
  }
  if (!(agreement > 0))
    throw InvalidMesh("zip_loops: the two loops run opposite ways (their surfaces are oriented inconsistently)");

  const std::size_t start = nearest_on_loop(positions, inner, position(positions, outer[0]));
  const auto a = [&](std::size_t i) { return outer[i % n]; };
  const auto b = [&](std::size_t j) { return inner[(start + j) % m]; };
  const auto distance = [&](int p, int q) { return (position(positions, p) - position(positions, q)).norm(); };
  // Does triangle pqr face along the normals at its corners, with an area validation accepts?
  const double zero_area = BuildOptions{}.zero_area_tolerance;
  const auto faces_along = [&](int p, int q, int r) {
    const Eigen::Vector3d x = position(positions, p), y = position(positions, q), z = position(positions, r);
    return (y - x).cross(z - x).dot(normals.row(p) + normals.row(q) + normals.row(r)) > 0 &&
           !has_zero_area(x, y, z, zero_area);
  };
  std::vector<std::array<int, 3>> strip;
  strip.reserve(n + m);
  std::size_t i = 0, j = 0;
  while (i < n || j < m) {
    bool advance_outer = j == m || (i < n && distance(a(i + 1), b(j)) <= distance(a(i), b(j + 1)));
    if (i < n && j < m) {
      const bool outer_ok = faces_along(a(i + 1), a(i), b(j)), inner_ok = faces_along(b(j), b(j + 1), a(i));
      if (outer_ok != inner_ok)
        advance_outer = outer_ok;
    }
    if (advance_outer) {
      strip.push_back({a(i + 1), a(i), b(j)});
      ++i;
    } else {
      strip.push_back({b(j), b(j + 1), a(i)});
      ++j;
    }
  }
  return strip;
}

} // namespace sdflow
