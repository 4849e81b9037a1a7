#pragma once
//! \file mixed_voronoi.h
//! \brief Private to the toolbox: one triangle's share of the mixed Voronoi areas (Meyer, Desbrun,
//! Schröder, Barr 2003), the one code for `mixed_voronoi_areas` (laplacian.h) and `CotangentCache`
//! (cotangent_cache.h), which must sum the same terms in the same order.

#include <Eigen/Core>

#include <array>

namespace sdflow::detail {

//! Adds to `areas` the mixed Voronoi areas of the triangle with corners p (vertex indices `index`):
//! `dots[c]` = (p[c+1] − p[c])·(p[c+2] − p[c]), negative at an obtuse corner, and `twice_area` =
//! |(p[1] − p[0]) × (p[2] − p[0])|. An obtuse triangle gives half its area to the obtuse corner and
//! a quarter to the others; otherwise corner c gets its Voronoi part
//! (|p[c+1] − p[c]|² cot(angle at c+2) + |p[c+2] − p[c]|² cot(angle at c+1)) / 8.
inline void add_mixed_voronoi_areas(const std::array<Eigen::Vector3d, 3>& p, const std::array<int, 3>& index,
                                    const std::array<double, 3>& dots, double twice_area, Eigen::VectorXd& areas)
{
  const double area = 0.5 * twice_area;
  const int obtuse = dots[0] < 0 ? 0 : dots[1] < 0 ? 1 : dots[2] < 0 ? 2 : -1;
  if (obtuse >= 0) {
    for (int c = 0; c < 3; ++c)
      areas[index[c]] += c == obtuse ? area / 2 : area / 4;
    return;
  }
  for (int c = 0; c < 3; ++c) {
    const int n1 = (c + 1) % 3, n2 = (c + 2) % 3;
    const double cot1 = dots[n1] / twice_area, cot2 = dots[n2] / twice_area;
    areas[index[c]] += ((p[n1] - p[c]).squaredNorm() * cot2 + (p[n2] - p[c]).squaredNorm() * cot1) / 8.0;
  }
}

} // namespace sdflow::detail
