#include "sdflow/triangulate_polygon.h"

#include <Eigen/Geometry>

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
