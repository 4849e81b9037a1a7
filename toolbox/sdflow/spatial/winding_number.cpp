#include "sdflow/spatial/winding_number.h"

#include <algorithm>
#include <array>

namespace sdflow {

int winding_number(const Bvh& tree, const Eigen::Vector3d& p)
{
  if (tree.empty())
    return 0;
  // The ray starts a hair off p, in no rational proportion across y and z, so that it passes
  // through no edge or vertex of a mesh whose coordinates are round numbers (a cube's, a grid's).
  const Aabb& bounds = tree.bounds();
  const double scale = std::max({bounds.hi[0] - bounds.lo[0], bounds.hi[1] - bounds.lo[1], bounds.hi[2] - bounds.lo[2]});
  const double y = p.y() + 0.7071067811865476e-10 * scale, z = p.z() + 0.5772156649015329e-10 * scale;
  Aabb ray;
  ray.lo = {p.x(), y, z};
  ray.hi = {std::max(p.x(), bounds.hi[0]), y, z};
  // Twice the signed area of the triangle (u, v, (y, z)) projected along x.
  const auto area = [y, z](const double* u, const double* v) {
    return (v[1] - u[1]) * (z - u[2]) - (v[2] - u[2]) * (y - u[1]);
  };
  int winding = 0;
  tree.for_each_in_box(ray, [&](int t) {
    const std::array<int, 3>& f = tree.triangle(t);
    const double* a = tree.point(f[0]);
    const double* b = tree.point(f[1]);
    const double* c = tree.point(f[2]);
    const double wa = area(b, c), wb = area(c, a), wc = area(a, b);
    const double total = wa + wb + wc; // signed like the normal's x
    const bool inside = (wa >= 0 && wb >= 0 && wc >= 0) || (wa <= 0 && wb <= 0 && wc <= 0);
    if (total == 0 || !inside)
      return;
    const double x = (wa * a[0] + wb * b[0] + wc * c[0]) / total; // where the ray meets the plane
    if (x > p.x())
      winding += total > 0 ? 1 : -1;
  });
  return winding;
}

} // namespace sdflow
