//! The local feature size by rays along the normals (local_thickness.h), on shapes whose thickness
//! and gaps are known exactly: a sphere is its diameter thick, two spheres face each other across
//! their gap, and a gap within one component counts only when asked.
#include "sdflow/errors.h"
#include "sdflow/spatial/local_thickness.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sdflow {
namespace {

//! An icosphere's vertices lie on the sphere, its faces inside it by at most the sagitta: a ray
//! through the centre meets the far side within this much of the diameter (level 4, radius 1).
constexpr double kChordTolerance = 2e-3;

TEST(LocalThickness, a_sphere_is_its_diameter_thick_and_faces_no_gap)
{
  for (const double radius : {1.0, 1e-3, 1e3}) {
    SCOPED_TRACE(radius);
    const Mesh sphere = analytic::icosphere(4, radius);
    const LocalThickness t = local_thickness(sphere);
    for (const auto v : sphere.vertices()) {
      EXPECT_NEAR(t.inward[v.idx()], 2 * radius, kChordTolerance * radius);
      EXPECT_TRUE(std::isinf(t.outward[v.idx()]));
    }
  }
}

TEST(LocalThickness, two_spheres_face_each_other_across_their_gap)
{
  const double gap = 0.2;
  const Mesh pair = analytic::disjoint_union(analytic::icosphere(4, 1.0),
                                             analytic::icosphere(4, 1.0, Eigen::Vector3d(2 + gap, 0, 0)));
  for (const bool between_components : {false, true}) {
    SCOPED_TRACE(between_components);
    const LocalThickness t = local_thickness(pair, {.gaps_between_components_only = between_components});
    // The first sphere's vertex nearest the second; its normal is radial (eq. 8 is exact on
    // spheres), and the ray along it meets the second sphere at the root of |p + t n − c| = 1.
    int facing = 0;
    for (const auto v : pair.vertices())
      if (v.idx() < static_cast<int>(pair.n_vertices() / 2) && pair.point(v)[0] > pair.point(Mesh::VertexHandle(facing))[0])
        facing = v.idx();
    const Eigen::Vector3d p = to_eigen(pair.point(Mesh::VertexHandle(facing)));
    const Eigen::Vector3d c(2 + gap, 0, 0);
    const Eigen::Vector3d n = p.normalized();
    const double b = n.dot(p - c), exact = -b - std::sqrt(b * b - (p - c).squaredNorm() + 1);
    EXPECT_NEAR(t.outward[facing], exact, 0.05 * gap);
    EXPECT_NEAR(t.feature_size(facing), t.outward[facing], 0);
    EXPECT_NEAR(t.inward[facing], 2.0, 0.01);
  }
}

TEST(LocalThickness, a_gap_within_one_component_counts_unless_only_gaps_between_components_do)
{
  // A torus's inner wall faces its opposite side across the hole: a gap of one component, as the
  // mouth of a concave crease is; the option that counts only gaps between components ignores it.
  const Mesh ring = analytic::torus(96, 48, 2.0, 1.0);
  const LocalThickness all = local_thickness(ring, {.median_over_neighbours = false});
  const LocalThickness between = local_thickness(ring, {.gaps_between_components_only = true});
  double hole = std::numeric_limits<double>::infinity();
  for (const auto v : ring.vertices()) {
    hole = std::min(hole, all.outward[v.idx()]);
    EXPECT_TRUE(std::isinf(between.outward[v.idx()]));
  }
  EXPECT_NEAR(hole, 2 * (2.0 - 1.0), 0.02); // the hole's diameter, across the inner equator
}

TEST(LocalThickness, rejects_an_empty_surface_and_a_negative_reach)
{
  EXPECT_THROW(local_thickness(Mesh{}), InvalidMesh);
  EXPECT_THROW(local_thickness(analytic::icosphere(1), {.max_distance = -1}), InvalidParameter);
}

} // namespace
} // namespace sdflow
