#include "sdflow/io/triangulate_polygon.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <numeric>

namespace sdflow {

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Eigen::Vector3d>& corners)
{
  const int n = static_cast<int>(corners.size());
  std::vector<std::array<int, 3>> triangles;
  if (n < 3)
    return triangles;
  std::vector<int> remaining(n);
  std::iota(remaining.begin(), remaining.end(), 0);
  auto fan = [&] {
    for (std::size_t k = 1; k + 1 < remaining.size(); ++k)
      triangles.push_back({remaining[0], remaining[k], remaining[k + 1]});
  };

  // Newell's normal (summed about the centroid, for accuracy far from the origin) is the normal of
  // the plane that fits the corners best, and its direction gives the polygon's orientation.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : corners)
    centre += p;
  centre /= n;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i)
    normal += (corners[i] - centre).cross(corners[(i + 1) % n] - centre);
  if (!(normal.norm() > 0)) {
    fan();
    return triangles;
  }
  normal.normalize();
  // (u, v, normal) is right-handed, so the polygon runs counter-clockwise in (u, v).
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  std::vector<Eigen::Vector2d> q(n);
  for (int i = 0; i < n; ++i)
    q[i] = {(corners[i] - centre).dot(u), (corners[i] - centre).dot(v)};
  auto orient = [&](int a, int b, int c) {
    const Eigen::Vector2d ab = q[b] - q[a], ac = q[c] - q[a];
    return ab.x() * ac.y() - ab.y() * ac.x();
  };

  while (remaining.size() > 3) {
    const std::size_t m = remaining.size();
    bool clipped = false;
    for (std::size_t k = 0; k < m && !clipped; ++k) {
      const int a = remaining[(k + m - 1) % m], b = remaining[k], c = remaining[(k + 1) % m];
      if (!(orient(a, b, c) > 0))
        continue;
      // A corner inside the ear or on its border would be cut off (or left on a zero-width spike).
      bool empty = true;
      for (const int r : remaining)
        if (r != a && r != b && r != c && orient(a, b, r) >= 0 && orient(b, c, r) >= 0 && orient(c, a, r) >= 0) {
          empty = false;
          break;
        }
      if (!empty)
        continue;
      triangles.push_back({a, b, c});
      remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped) {
      fan();
      return triangles;
    }
  }
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

} // namespace sdflow

namespace sdflow {

bool polygon_is_simple(const std::vector<Eigen::Vector3d>& corners)
{
  const int n = static_cast<int>(corners.size());
  if (n < 3)
    return false;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : corners)
    centre += p;
  centre /= n;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  double scale = 0;
  for (int i = 0; i < n; ++i) {
    normal += (corners[i] - centre).cross(corners[(i + 1) % n] - centre);
    scale = std::max(scale, (corners[i] - centre).squaredNorm());
  }
  // Newell's normal is twice the projected signed area: none means the outline cancels itself.
  if (!(normal.norm() > 1e-12 * scale))
    return false;
  normal.normalize();
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  std::vector<Eigen::Vector2d> q(n);
  for (int i = 0; i < n; ++i)
    q[i] = {(corners[i] - centre).dot(u), (corners[i] - centre).dot(v)};
  const auto orient = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    const double d = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    return (d > 0) - (d < 0);
  };
  const auto on_segment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
    return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
           p.y() <= std::max(a.y(), b.y());
  };
  const auto meet = [&](int i, int j) {
    const Eigen::Vector2d &a = q[i], &b = q[(i + 1) % n], &c = q[j], &d = q[(j + 1) % n];
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0)
      return true;
    return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
           (o4 == 0 && on_segment(c, d, b));
  };
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1)
        continue; // neighbours through the closing corner
      if (meet(i, j))
        return false;
    }
  return true;
}

} // namespace sdflow
